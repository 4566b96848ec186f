// Scene format version 2: the pose convention, the floating distance, the migration of version 1
// files, and one clear error per kind of bad layout.
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>

#include "airr/core/assets.hpp"
#include "airr/core/error.hpp"
#include "airr/formats/scene_json.hpp"
#include "airr/layout/layout.hpp"
#include "airr/models/emission_profile.hpp"
#include "airr/models/retro_sinc_shift.hpp"
#include "test_helpers.hpp"

using namespace airr;

namespace {

using test::error_of;

void expect_near(const glm::dvec3& a, const glm::dvec3& b, double tol = 1e-12) {
  EXPECT_NEAR(a.x, b.x, tol);
  EXPECT_NEAR(a.y, b.y, tol);
  EXPECT_NEAR(a.z, b.z, tol);
}

// The version 1 files the project shipped, with the directories their relative paths count from.
struct v1_file {
  std::string path, base_dir;
};
std::vector<v1_file> shipped_v1_files() {
  const std::string data = std::string(AIRR_TEST_DATA_DIR) + "/scene_v1/";
  return {{data + "default.json", asset_dir() + "/scenes"},
          {data + "fit_example_setup.json", asset_dir() + "/fit_example"}};
}

scene parse_file(const std::string& path, const std::string& base_dir, const std::vector<scene_override>& o = {}) {
  return parse_scene(read_text_file(path), path, base_dir, o);
}

}  // namespace

TEST(Pose, NormalFollowsTheDocumentedFormula) {
  pose p;
  p.yaw_deg = 25;
  p.pitch_deg = -35;
  p.roll_deg = 70;
  const part_frame f = pose_frame(p, 1, 1);
  const double y = radians(25), x = radians(-35);
  expect_near(f.n, {std::sin(y) * std::cos(x), std::sin(x), std::cos(y) * std::cos(x)});
  // Orthonormal and right-handed: n = u x v.
  expect_near(glm::cross(f.u, f.v), f.n);
  EXPECT_NEAR(glm::dot(f.u, f.v), 0, 1e-12);
  // Roll turns u and v about the normal by the roll angle.
  pose q = p;
  q.roll_deg = 0;
  const part_frame g = pose_frame(q, 1, 1);
  EXPECT_NEAR(glm::dot(f.u, g.u), std::cos(radians(70)), 1e-12);
  EXPECT_NEAR(glm::dot(f.u, g.v), std::sin(radians(70)), 1e-12);
}

TEST(Pose, CanonicalLayoutHasTheVersion1Frames) {
  const scene s;
  const part_frame src = source_frame(s), hm = half_mirror_frame(s), rr = retroreflector_frame(s);
  expect_near(src.center, {0, -150, 0});
  expect_near(src.n, {0, 1, 0});
  expect_near(src.u, {1, 0, 0});
  expect_near(src.v, {0, 0, -1});  // the image's top lies towards -z
  expect_near(hm.n, glm::normalize(glm::dvec3(0, 1, 1)), 1e-15);
  expect_near(rr.center, {0, 0, -150});
  expect_near(rr.n, {0, 0, 1});
  // The aerial image forms at (0, 0, D) with its top up and faces the observer.
  const part_frame a = aerial_image_frame(s);
  expect_near(a.center, {0, 0, 150}, 1e-12);
  expect_near(a.u, {1, 0, 0}, 1e-12);
  expect_near(a.v, {0, 1, 0}, 1e-12);
  expect_near(a.n, {0, 0, 1}, 1e-12);
  EXPECT_NEAR(floating_distance(s), 150, 1e-12);
  const pinhole_camera c = make_camera(s);
  expect_near(c.position, {0, 0, 450}, 1e-12);
  expect_near(c.forward, {0, 0, -1}, 1e-15);
}

TEST(FloatingDistance, EditingDMovesTheDisplayAndTheImageOnTheirLines) {
  scene s;
  set_floating_distance(s, 240);
  expect_near(source_frame(s).center, {0, -240, 0}, 1e-12);
  expect_near(aerial_image_center(s), {0, 0, 240}, 1e-12);
  // A general layout: D is kept as set, the display moves along its line from the mirror's centre.
  s.half_mirror.pose.pitch_deg = 38;
  s.half_mirror.pose.center_mm = {5, -3, 2};
  s.source.pose.center_mm = {12, -140, 20};
  const glm::dvec3 c = half_mirror_frame(s).center, before = source_frame(s).center;
  set_floating_distance(s, 333);
  EXPECT_NEAR(floating_distance(s), 333, 1e-9);
  const glm::dvec3 after = source_frame(s).center;
  expect_near(glm::normalize(after - c), glm::normalize(before - c), 1e-12);
  // The aerial image is the mirror image: as far from the mirror plane as the display, on the other side.
  const part_frame hm = half_mirror_frame(s);
  EXPECT_NEAR(glm::dot(aerial_image_center(s) - c, hm.n), -glm::dot(after - c, hm.n), 1e-9);
  EXPECT_NE(error_of([&] { set_floating_distance(s, -1); }), "");
  EXPECT_NE(error_of([&] { set_floating_distance(s, std::nan("")); }), "");
}

TEST(Migration, EveryShippedVersion1FileLoads) {
  for (const auto& f : shipped_v1_files()) {
    EXPECT_EQ(nlohmann::json::parse(read_text_file(f.path)).at("version"), 1) << f.path;
    EXPECT_NO_THROW(parse_file(f.path, f.base_dir)) << f.path;
  }
}

TEST(Migration, Version1ToVersion2ToVersion2IsExact) {
  test::temp_dir dir;
  for (const auto& f : shipped_v1_files()) {
    const scene a = parse_file(f.path, f.base_dir);
    const std::string first = dir.file("first.json"), second = dir.file("second.json");
    save_scene(rebase_scene_paths(a, dir.path.string()), first);
    const scene b = load_scene(first);
    save_scene(b, second);
    EXPECT_EQ(read_text_file(first), read_text_file(second)) << f.path;
    EXPECT_TRUE(rebase_scene_paths(b, a.base_dir) == a) << f.path;
    EXPECT_EQ(nlohmann::json::parse(read_text_file(first)).at("version"), 2);
  }
}

TEST(Migration, Version1GeometryIsKept) {
  // D, a source offset, tilt and distance, and the on-axis camera of version 1.
  const nlohmann::json v1 = {
      {"format", "airr-scene"},
      {"version", 1},
      {"floating_distance_mm", 200.0},
      {"source", {{"image", ""}, {"offset_mm", {3.0, 4.0, 5.0}}, {"width_mm", 20.0}}},
      {"retroreflector",
       {{"distance_mm", 170.0},
        {"tilt_deg", 10.0},
        {"model", {{"type", "microfacet"}, {"mu", nullptr}, {"a_per_mm", nullptr}, {"eta", 1.6}, {"preset", ""}}}}},
      {"camera", {{"distance_mm", 250.0}, {"fov_deg", 9.0}, {"width", 64}, {"height", 48}}}};
  const scene s = scene_from_json(v1, "v1.json");
  expect_near(source_frame(s).center, {3, -196, 5}, 1e-12);
  expect_near(source_frame(s).n, {0, 1, 0}, 1e-15);
  const part_frame rr = retroreflector_frame(s);
  expect_near(rr.center, {0, 0, -170});
  expect_near(rr.n, {0, std::sin(radians(10)), std::cos(radians(10))}, 1e-15);
  EXPECT_EQ(s.sheet().model.type, "microfacet");
  EXPECT_EQ(read_model_values(s.sheet().model).number("eta"), 1.6);
  // The camera stayed on the canonical axis, aimed at (0, 0, D).
  const pinhole_camera c = make_camera(s);
  expect_near(c.position, {0, 0, 450}, 1e-12);
  expect_near(c.forward, {0, 0, -1}, 1e-15);
  EXPECT_EQ(c.width, 64);
  EXPECT_EQ(c.height, 48);
  EXPECT_NEAR(c.mm_per_pixel, 2 * 250 * std::tan(radians(4.5)) / 48, 1e-12);
  // Version 1 was as strict as version 2.
  nlohmann::json bad = v1;
  bad["retroreflector"]["tilt"] = 3;
  EXPECT_NE(error_of([&] { scene_from_json(bad, "v1.json"); }).find("v1.json: retroreflector.tilt: unknown key"),
            std::string::npos);
}

// Version 1's default scene had the ideal sheet: today's ideal bench.
TEST(Migration, IdealBenchIsTheVersion1DefaultScene) {
  const auto f = shipped_v1_files().front();
  scene migrated = parse_file(f.path, f.base_dir);
  const scene shipped = load_scene(ideal_bench_scene_path());
  migrated.base_dir = shipped.base_dir;
  EXPECT_TRUE(migrated == shipped);
}

// The designer opens on a real sheet (RF-Ay, from its preset), so the first image shows the blur;
// the ideal bench is the same layout with the ideal retroreflector (mu = 1).
TEST(ShippedScenes, DefaultSheetIsRfAyAndIdealBenchSheetIsIdeal) {
  const scene shipped = load_scene(default_scene_path());
  ASSERT_EQ(shipped.retroreflectors.size(), 1u);
  EXPECT_EQ(shipped.sheet().model.type, "sinc_shift");
  EXPECT_EQ(read_model_values(shipped.sheet().model).text("preset"), "rf-ay");
  // Nothing but the preset is set: a and mu per tilt and c are RF-Ay's (Table 2; first entry: tilt 0).
  EXPECT_EQ(shipped.sheet().model.values.size(), 1u);
  const sinc_shift_params p = resolve_sinc_shift_params(shipped.sheet().model, {.base_dir = shipped.base_dir});
  ASSERT_EQ(p.a_per_mm.size(), 10u);
  EXPECT_DOUBLE_EQ(p.a_per_mm.front(), 9.9302);
  EXPECT_DOUBLE_EQ(p.mu.front(), 0.33505);
  EXPECT_DOUBLE_EQ(p.c_mm, 0.94966);

  const scene ideal = load_scene(ideal_bench_scene_path());
  ASSERT_EQ(ideal.retroreflectors.size(), 1u);
  EXPECT_EQ(ideal.sheet().model.type, "ideal");
  EXPECT_EQ(read_model_values(ideal.sheet().model).number("mu"), 1.0);
  // Otherwise the same layout.
  scene same = ideal;
  same.sheet().model = shipped.sheet().model;
  EXPECT_TRUE(same == shipped);
}

// ---------------------------------------------------------------- bad layouts

TEST(BadLayout, IntersectingPartsNameTheFileAndThePart) {
  test::temp_dir dir;
  scene s = test::uniform_source_scene(20);
  s.sheet().pose.center_mm[2] = -50;  // inside the mirror's reach (its top edge is at z = -106)
  save_scene(s, dir.file("s.json"));
  EXPECT_EQ(error_of([&] { load_scene(dir.file("s.json")); }),
            dir.file("s.json") + ": retroreflectors[0]: layout: the half mirror and the retroreflector intersect");
  s = test::uniform_source_scene(20);
  s.retroreflectors.push_back(s.sheet());  // two sheets in the same place
  save_scene(s, dir.file("s.json"));
  EXPECT_EQ(error_of([&] { load_scene(dir.file("s.json")); }),
            dir.file("s.json") + ": retroreflectors[1]: layout: sheet 0 and sheet 1 intersect");
}

TEST(BadLayout, ObserverInsideAPart) {
  test::temp_dir dir;
  scene s = test::uniform_source_scene(20);
  s.observer.placement = observer_placement::look_at;
  s.observer.position_mm = {10, 0, -150.5};  // in the sheet
  s.observer.look_at_mm = {0, 0, 150};
  save_scene(s, dir.file("s.json"));
  const std::string e = error_of([&] { load_scene(dir.file("s.json")); });
  EXPECT_EQ(e, dir.file("s.json") + ": observer: the observer is inside the retroreflector");
}

TEST(BadLayout, ObserverBehindTheHalfMirror) {
  test::temp_dir dir;
  scene s = test::uniform_source_scene(20);
  s.observer.elevation_deg = -80;  // below the mirror plane, on the display's side
  s.observer.distance_mm = 600;
  save_scene(s, dir.file("s.json"));
  const std::string e = error_of([&] { load_scene(dir.file("s.json")); });
  EXPECT_NE(e.find(dir.file("s.json") + ": observer: behind the half mirror"), std::string::npos) << e;
  EXPECT_NE(e.find("no aerial image can be seen"), std::string::npos) << e;
}

TEST(BadLayout, DegeneratePoses) {
  test::temp_dir dir;
  const scene s = test::uniform_source_scene(20);
  save_scene(s, dir.file("s.json"));
  const std::string path = dir.file("s.json");
  EXPECT_EQ(error_of([&] { load_scene(path, {parse_override("half_mirror.width_mm=0")}); }),
            path + " (with --set): half_mirror.width_mm: must be positive (is 0)");
  EXPECT_NE(error_of([&] {
              load_scene(path, {parse_override("source.pose.yaw_deg=nan")});
            }).find("--set source.pose.yaw_deg: must be a finite number"),
            std::string::npos);
  EXPECT_NE(error_of([&] {
              load_scene(path, {parse_override("retroreflectors.0.pose.roll_deg=1e9")});
            }).find("retroreflectors[0].pose.roll_deg: must be in [-360"),
            std::string::npos);
  // A NaN written into the file (not JSON; some writers produce it) is malformed JSON, named.
  std::ofstream(dir.file("nan.json"))
      << R"({"format": "airr-scene", "version": 2, "source": {"pose": {"yaw_deg": NaN}}})";
  EXPECT_NE(error_of([&] { load_scene(dir.file("nan.json")); }).find("nan.json: malformed JSON"), std::string::npos);
  // No sheet at all.
  nlohmann::json j = scene_to_json(s);
  j["retroreflectors"] = nlohmann::json::array();
  std::ofstream(dir.file("none.json")) << j.dump();
  EXPECT_NE(error_of([&] { load_scene(dir.file("none.json")); }).find("retroreflectors: must be an array of 1 to 8"),
            std::string::npos);
  // An observer aimed at itself.
  EXPECT_NE(error_of([&] {
              load_scene(
                  path, {parse_override("observer.placement=look_at"), parse_override("observer.position_mm=[0,0,400]"),
                         parse_override("observer.look_at_mm=[0,0,400]")});
            }).find("observer.look_at_mm: must differ from observer.position_mm"),
            std::string::npos);
}

TEST(BadLayout, ModelFieldsAreCheckedByTheirDescriptions) {
  test::temp_dir dir;
  save_scene(test::uniform_source_scene(20), dir.file("s.json"));
  const std::string path = dir.file("s.json");
  const std::string e = error_of([&] {
    load_scene(path, {parse_override("retroreflectors.0.model.type=microfacet"),
                      parse_override("retroreflectors.0.model.eta=7")});
  });
  EXPECT_EQ(e, path + " (with --set): retroreflectors[0].model.eta: must be in [1, 3] (is 7)");
  const std::string e2 = error_of([&] {
    load_scene(path, {parse_override("retroreflectors.0.model.type=sinc_shift"),
                      parse_override("retroreflectors.0.model.a_per_mm=0")});
  });
  EXPECT_EQ(e2, path + " (with --set): retroreflectors[0].model.a_per_mm: must be in (0, 1000] (is 0)");
  // Switching the model drops the old model's fields, so the switch itself is valid.
  const scene s = load_scene(path, {parse_override("retroreflectors.0.model.type=microfacet")});
  EXPECT_EQ(s.sheet().model.type, "microfacet");
  EXPECT_TRUE(s.sheet().model.values.empty());
}

TEST(SincLookup, ChoiceIsCheckedAndSaved) {
  test::temp_dir dir;
  save_scene(test::uniform_source_scene(20), dir.file("s.json"));
  const std::string path = dir.file("s.json");
  const std::string e = error_of([&] {
    load_scene(path, {parse_override("retroreflectors.0.model.type=sinc_shift"),
                      parse_override("retroreflectors.0.model.preset=rf-ay"),
                      parse_override("retroreflectors.0.model.lookup=per_pixel")});
  });
  EXPECT_EQ(e,
            path + " (with --set): retroreflectors[0].model.lookup: unknown value 'per_pixel' (per_ray, per_render)");
  const scene s = load_scene(path, {parse_override("retroreflectors.0.model.type=sinc_shift"),
                                    parse_override("retroreflectors.0.model.preset=rf-ay"),
                                    parse_override("retroreflectors.0.model.lookup=per_render")});
  save_scene(s, dir.file("t.json"));
  EXPECT_EQ(load_scene(dir.file("t.json")).sheet().model.values.at("lookup"), param_value(std::string("per_render")));
}

// The angle a per-render lookup uses: the sheet's tilt in the canonical layout, for a sheet beyond
// the half mirror (lit through it) the angle to the display's centre.
TEST(SincLookup, SheetChiefIncidenceIsTheTiltOnTheBenchAndFollowsTheDisplayBeyondTheMirror) {
  scene s = test::uniform_source_scene(20);
  for (double tilt : {0.0, 5.0, 20.0, 45.0}) {
    s.sheet().pose.pitch_deg = tilt;
    EXPECT_NEAR(sheet_chief_incidence_deg(s), tilt, 1e-9);
  }
  s.sheet().pose.pitch_deg = 0;
  s.retroreflectors.push_back(s.sheet());
  s.retroreflectors[1].pose = {.center_mm = {0, 160, 0}, .pitch_deg = -90};  // above the mirror, facing down
  EXPECT_NEAR(sheet_chief_incidence_deg(s, 1), 0.0, 1e-9);
  s.source.pose.center_mm = {0, -150, 40};  // the display towards the viewer: 40 mm off the sheet's axis
  EXPECT_NEAR(sheet_chief_incidence_deg(s, 1), degrees(std::atan2(40.0, 310.0)), 1e-9);
  // The first sheet sees the display's mirror image, which moved with it.
  EXPECT_NEAR(sheet_chief_incidence_deg(s, 0), degrees(std::atan2(40.0, 300.0)), 1e-9);

  // A per-render sheet looks a and mu up there for every ray; a per-ray sheet at each ray's angle.
  s.sheet().model = with_model_type(s.sheet().model, "sinc_shift");
  set_model_value(s.sheet().model, "preset", std::string("rf-ay"));
  const auto per_ray = make_sheet_model(s);
  set_model_value(s.sheet().model, "lookup", std::string("per_render"));
  const auto per_render = make_sheet_model(s);
  const auto& ray = dynamic_cast<const sinc_shift_retro&>(*per_ray);
  const auto& render = dynamic_cast<const sinc_shift_retro&>(*per_render);
  const double chief = sheet_chief_incidence_deg(s);
  for (double theta : {0.0, 10.0, 30.0}) {
    EXPECT_EQ(render.a_at(theta), ray.a_at(chief));
    EXPECT_EQ(render.mu_at(theta), ray.mu_at(chief));
  }
  EXPECT_NE(ray.a_at(0), ray.a_at(chief));
}

TEST(EmissionProfile, BadFilesNameTheLineAndTheProblem) {
  test::temp_dir dir;
  auto write = [&](const std::string& text) {
    std::ofstream(dir.file("p.csv")) << text;
    return dir.file("p.csv");
  };
  EXPECT_NE(error_of([&] {
              read_emission_profile(write("angle_deg,relative_luminance\n10,1\n20,0.5\n"));
            }).find("line 2: angle_deg: the first row must be at 0"),
            std::string::npos);
  EXPECT_NE(error_of([&] {
              read_emission_profile(write("angle_deg,relative_luminance\n0,1\n20,x\n"));
            }).find("line 3: relative_luminance: 'x' is not a number"),
            std::string::npos);
  EXPECT_NE(error_of([&] {
              read_emission_profile(write("angle_deg,relative_luminance\n0,1\n30,0.5\n20,0.6\n"));
            }).find("line 4: angle_deg: angles must ascend"),
            std::string::npos);
  EXPECT_NE(error_of([&] { read_emission_profile(write("angle,lum\n0,1\n")); }).find("expected the header"),
            std::string::npos);
  const emission_profile p = read_emission_profile(write("angle_deg,relative_luminance\n0,2\n40,1\n80,0\n"));
  EXPECT_DOUBLE_EQ(p.at(0), 1);
  EXPECT_DOUBLE_EQ(p.at(20), 0.75);
  EXPECT_DOUBLE_EQ(p.at(89), 0);
  // The shipped example is valid and falls off steeply.
  const emission_profile lcd = read_emission_profile(asset_dir() + "/displays/lcd_typical.csv");
  EXPECT_LT(lcd.at(60), 0.2);
}
