// The half mirror as a glass plate (docs/polarization.md): its faces reflect as the Fresnel
// equations say, its paths add up as an incoherent slab's do, it round-trips through the scene
// file and --set, and bad values are one line naming the file and the field.
#include <cmath>
#include <complex>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "airr/core/geometry.hpp"
#include "airr/formats/scene_json.hpp"
#include "airr/models/plate.hpp"
#include "test_helpers.hpp"

using namespace airr;
using nlohmann::json;

namespace {

// The Fresnel intensity reflectances of s and p light from air onto glass of index n, written
// out here from the textbook (Born and Wolf 1.5.2), not from the product's code.
std::pair<double, double> fresnel_rs_rp(double theta_deg, double n) {
  const double ti = radians(theta_deg);
  const double tt = std::asin(std::sin(ti) / n);
  if (theta_deg == 0) {
    const double r = (n - 1) / (n + 1);
    return {r * r, r * r};
  }
  const double rs = -std::sin(ti - tt) / std::sin(ti + tt);
  const double rp = std::tan(ti - tt) / std::tan(ti + tt);
  return {rs * rs, rp * rp};
}

// An uncoated plate of that thickness and index.
plate_params plate_of(double thickness_mm, double index) {
  plate_params p;
  p.thickness_mm = thickness_mm;
  p.index = index;
  return p;
}

double intensity_s(const plate_path& p) { return std::norm(p.as); }
double intensity_p(const plate_path& p) { return std::norm(p.ap); }

}  // namespace

TEST(Plate, AnUncoatedFaceReflectsAsTheFresnelEquationsSay) {
  const plate_params glass = plate_of(3, 1.5);
  for (double theta = 0; theta <= 80; theta += 5) {
    const auto [rs, rp] = fresnel_rs_rp(theta, 1.5);
    for (bool front : {true, false}) {
      const plate_path near = plate_paths_at(glass, std::cos(radians(theta)), front).reflected[0];
      EXPECT_NEAR(intensity_s(near), rs, 1e-12) << theta;
      EXPECT_NEAR(intensity_p(near), rp, 1e-12) << theta;
      EXPECT_NEAR(near.weight, 0.5 * (rs + rp), 1e-12) << theta;
    }
  }
  const double brewster = degrees(std::atan(1.5));
  const plate_path at_brewster = plate_paths_at(glass, std::cos(radians(brewster)), true).reflected[0];
  EXPECT_LT(intensity_p(at_brewster), 1e-20);
  EXPECT_NEAR(intensity_s(at_brewster), fresnel_rs_rp(brewster, 1.5).first, 1e-12);
}

// A clear plate's paths sum to the incoherent slab's 2R / (1 + R) reflected and (1 - R) / (1 + R)
// transmitted for each of s and p (Born and Wolf 7.6), and the far face's first reflection (the
// double image) lies 2 tan(theta_t) plate thicknesses along the face from the near one's.
TEST(Plate, ItsPathsAddUpAsAnIncoherentSlabs) {
  const plate_params glass = plate_of(3, 1.5);
  for (double theta = 0; theta <= 80; theta += 10) {
    const auto [rs, rp] = fresnel_rs_rp(theta, 1.5);
    const plate_paths paths = plate_paths_at(glass, std::cos(radians(theta)), false);
    double reflected_s = 0, reflected_p = 0, transmitted_s = 0, transmitted_p = 0;
    for (int k = 0; k < plate_orders; ++k) {
      reflected_s += intensity_s(paths.reflected[std::size_t(k)]);
      reflected_p += intensity_p(paths.reflected[std::size_t(k)]);
      transmitted_s += intensity_s(paths.transmitted[std::size_t(k)]);
      transmitted_p += intensity_p(paths.transmitted[std::size_t(k)]);
    }
    const double lost = 1 - (reflected_s + transmitted_s + reflected_p + transmitted_p) / 2;
    std::printf("%4.0f deg: slab R_s %.6f (%.6f), R_p %.6f (%.6f), dropped %.2e\n", theta, reflected_s,
                2 * rs / (1 + rs), reflected_p, 2 * rp / (1 + rp), lost);
    const double tolerance = theta <= 60 ? 1e-9 : 5e-4;
    EXPECT_NEAR(reflected_s, 2 * rs / (1 + rs), tolerance) << theta;
    EXPECT_NEAR(reflected_p, 2 * rp / (1 + rp), tolerance) << theta;
    EXPECT_NEAR(transmitted_s, (1 - rs) / (1 + rs), tolerance) << theta;
    EXPECT_NEAR(transmitted_p, (1 - rp) / (1 + rp), tolerance) << theta;
    EXPECT_GE(lost, -1e-12);
    const double tan_t = std::tan(std::asin(std::sin(radians(theta)) / 1.5));
    EXPECT_NEAR(paths.reflected[1].advance, 2 * tan_t, 1e-12);
    EXPECT_NEAR(paths.transmitted[0].advance, tan_t, 1e-12);
  }
}

// Coatings: a partial mirror reflects what it is given with its phase, an anti-reflection coat
// passes the rest; a plate whose near face is coated so and far face is not shows the glass's
// own Fresnel reflection as its double image.
TEST(Plate, CoatingsReflectWhatTheyAreGiven) {
  plate_params p = plate_of(2, 1.52);
  p.back = {.kind = coating_kind::partial_mirror, .rs = 0.6, .rp = 0.4, .ts = 0.3, .tp = 0.5, .phase_deg = 30};
  p.front = {.kind = coating_kind::anti_reflection, .residual = 0.01};
  const plate_paths at_back = plate_paths_at(p, std::cos(radians(45)), false);
  EXPECT_NEAR(intensity_s(at_back.reflected[0]), 0.6, 1e-12);
  EXPECT_NEAR(intensity_p(at_back.reflected[0]), 0.4, 1e-12);
  // The phase of p against s beyond an ideal mirror's (rs = -1, rp = 1).
  EXPECT_NEAR(std::arg(at_back.reflected[0].ap / -at_back.reflected[0].as), radians(30), 1e-12);
  // Through the partial mirror (0.3 of s), off the coat inside (0.01), and out again (0.3).
  EXPECT_NEAR(intensity_s(at_back.reflected[1]), 0.3 * 0.01 * 0.3, 1e-12);
  EXPECT_NEAR(intensity_s(at_back.transmitted[0]), 0.3 * 0.99, 1e-12);

  const plate_paths at_front = plate_paths_at(p, std::cos(radians(45)), true);
  EXPECT_NEAR(at_front.reflected[0].weight, 0.01, 1e-12);
  EXPECT_NEAR(intensity_s(at_front.reflected[1]), 0.99 * 0.6 * 0.99, 1e-12);
}

TEST(Plate, ItRoundTripsThroughTheSceneFileAndSet) {
  test::temp_dir dir;
  scene s = test::uniform_source_scene(20);
  s.half_mirror.kind = half_mirror_kind::plate;
  s.half_mirror.plate = plate_of(4, 1.6);
  s.half_mirror.plate.back = {.kind = coating_kind::partial_mirror, .rs = 0.55, .rp = 0.45, .ts = 0.4, .tp = 0.5};
  s.half_mirror.plate.front = {.kind = coating_kind::anti_reflection, .residual = 0.005};
  derive_half_mirror_light(s.half_mirror);
  EXPECT_TRUE(scene_polarizes(s));
  // The main reflection of unpolarized light at 45 deg on the back face, and all that passes.
  EXPECT_NEAR(s.half_mirror.reflectance, 0.5, 1e-12);
  // Straight through, and once round inside (the coat's 0.005, the mirror's 0.55 and 0.45); the
  // second round trip adds 3e-6.
  EXPECT_NEAR(s.half_mirror.transmittance, 0.5 * 0.995 * (0.4 * (1 + 0.005 * 0.55) + 0.5 * (1 + 0.005 * 0.45)), 1e-5);
  save_scene(s, dir.file("plate.json"));
  scene back = load_scene(dir.file("plate.json"));
  back.base_dir = s.base_dir;
  EXPECT_EQ(back, s);

  const std::string path = test::scene_file(dir, [](json&) {});
  const scene set =
      load_scene(path, {parse_override("half_mirror.kind=plate"), parse_override("half_mirror.plate.thickness_mm=6"),
                        parse_override("half_mirror.plate.front.coating=partial_mirror")});
  EXPECT_EQ(set.half_mirror.kind, half_mirror_kind::plate);
  EXPECT_DOUBLE_EQ(set.half_mirror.plate.thickness_mm, 6);
  EXPECT_EQ(set.half_mirror.plate.front.kind, coating_kind::partial_mirror);
  const auto [rs, rp] = fresnel_rs_rp(45, 1.52);
  EXPECT_NEAR(set.half_mirror.reflectance, (rs + rp) / 2, 1e-12);
}

TEST(Plate, BadValuesAreOneLineNamingTheFileAndTheField) {
  test::temp_dir dir;
  const auto plate = [](json p) {
    return [p](json& j) {
      j["half_mirror"]["kind"] = "plate";
      j["half_mirror"]["plate"] = p;
    };
  };
  const std::vector<std::pair<std::function<void(json&)>, std::string>> cases = {
      {[](json& j) { j["half_mirror"]["kind"] = "plate"; }, "half_mirror.plate: missing"},
      {plate({{"thickness_mm", 400}}),
       "half_mirror.plate.thickness_mm: the plate (400 mm) must be thinner than its width (300 mm)"},
      {plate({{"thickness_mm", 0}}), "half_mirror.plate.thickness_mm: must be positive (is 0)"},
      {plate({{"index", 0.5}}), "half_mirror.plate.index: must be in [1, 4] (is 0.5)"},
      {plate({{"index", "glass"}}), "half_mirror.plate.index: must be a number"},
      {plate({{"front", {{"coating", "gold"}}}}),
       "half_mirror.plate.front.coating: unknown value 'gold' (uncoated, partial_mirror, anti_reflection)"},
      {plate({{"back", {{"coating", "partial_mirror"}, {"rs", 0.7}, {"ts", 0.5}}}}),
       "half_mirror.plate.back.ts: rs + ts must not exceed 1"},
      {plate({{"back", {{"coating", "partial_mirror"}, {"rp", 1.2}}}}),
       "half_mirror.plate.back.rp: must be in [0, 1] (is 1.2)"},
      {plate({{"front", {{"coating", "anti_reflection"}, {"residual", 0.9}}}}),
       "half_mirror.plate.front.residual: must be in [0, 0.5] (is 0.9)"},
      {plate({{"front", {{"coating", "uncoated"}, {"reflectance", 0.1}}}}),
       "half_mirror.plate.front.reflectance: unknown key"},
  };
  for (const auto& [edit, expected] : cases) {
    const std::string path = test::scene_file(dir, edit);
    const std::string e = test::error_of([&] { load_scene(path); });
    EXPECT_NE(e.find(path + ": " + expected), std::string::npos) << "expected: " << expected << "\n     got: " << e;
    EXPECT_EQ(e.find('\n'), std::string::npos) << e;
  }
  const std::string path = test::scene_file(dir, plate({{"thickness_mm", 3}}));
  const std::string e = test::error_of([&] { load_scene(path, {parse_override("half_mirror.plate.index=nan")}); });
  EXPECT_NE(e.find("half_mirror.plate.index"), std::string::npos) << e;
}
