// Ambient light from placed sources (spec section 11): the sun, a 0.53 degree disc of given
// illuminance, and luminaires, Lambertian rectangles and discs. The sun seen in the half mirror
// makes a glare spot where the mirrored direction points, R_hm times its luminance; a luminaire
// lights a diffuse card as its solid angle says; each source, each luminaire too, is its own component.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

#include "airr/core/error.hpp"
#include "airr/core/geometry.hpp"
#include "airr/formats/scene_json.hpp"
#include "airr/layout/layout.hpp"
#include "airr/models/plate.hpp"
#include "airr/render/path_expression.hpp"
#include "airr/render/render_session.hpp"
#include "airr/render/tracer.hpp"
#include "plate_mesh.hpp"
#include "test_helpers.hpp"

using namespace airr;

namespace {

render_snapshot render_with_layers(const scene& s, const std::vector<std::string>& layers, std::uint64_t spp) {
  render_session session(
      s,
      {.threads = 2,
       .target_spp = spp,
       .components = true,
       .layers = layers.empty() ? nullptr : std::make_shared<const path_layers>(parse_layer_arguments(layers, s, {}))});
  return session.wait_for(0, spp);
}

struct spot {
  double x = 0, y = 0, total = 0, peak = 0;
};

// The centroid (pixel centres at +0.5), sum and peak of an image's green channel.
spot green_spot(const image_rgb& img) {
  spot s;
  for (int y = 0; y < img.height; ++y) {
    for (int x = 0; x < img.width; ++x) {
      const double v = img.at(x, y)[1];
      s.x += v * (x + 0.5), s.y += v * (y + 0.5), s.total += v;
      s.peak = std::max(s.peak, v);
    }
  }
  if (s.total > 0) s.x /= s.total, s.y /= s.total;
  return s;
}

double mean_green(const image_rgb& img) {
  double sum = 0;
  for (std::size_t i = 1; i < img.rgb.size(); i += 3) sum += img.rgb[i];
  return sum / double(img.rgb.size() / 3);
}

// The white bench with a diffuse card (albedo 0.6, its mesh in `dir`) facing +z at z = 300 between
// the observer and the device, seen from below and in front through a narrow field about its centre
// (1.6 mm across: a luminaire's illuminance falls 0.03% towards its edge).
scene card_scene(const test::temp_dir& dir) {
  test::write_plate(test::plate(2, 300, -60, 60, -60, 60), dir.file("card.glb"));
  scene s = test::white_bench(500, 16);
  s.source.luminance_cd_m2 = 500;
  prop_params card;
  card.name = "card";
  card.mesh = dir.file("card.glb");
  card.surface = prop_surface::diffuse;
  card.albedo = {0.6, 0.6, 0.6};
  s.props.push_back(card);
  s.observer.placement = observer_placement::look_at;
  s.observer.position_mm = {0, -300, 500};
  s.observer.look_at_mm = {0, 0, 300};
  s.observer.fov_deg = 0.25;
  return s;
}

// A disc luminaire (radius 30 mm, 2000 cd/m2) facing down on the card's centre from 50 mm above.
luminaire_params disc_over_card() {
  luminaire_params disc;
  disc.shape = luminaire_shape::disc;
  disc.pose = {.center_mm = {0, 0, 350}, .pitch_deg = 180};  // facing -z
  disc.width_mm = 60;
  disc.luminance_cd_m2 = 2000;
  return disc;
}

// Where the eye sees the sun in the half mirror: the sun's direction mirrored in its plane.
glm::dvec2 glare_pixel(const scene& s) {
  const pinhole_camera cam = make_camera(s);
  const glm::dvec3 seen = reflect(sun_direction(s.environment.sun), half_mirror_frame(s).n);
  return camera_project(cam, cam.position + 100.0 * seen);
}

}  // namespace

TEST(AmbientSources, TheSunMakesItsGlareSpotWhereTheHalfMirrorReflectsItIntoTheEye) {
  // The ideal bench from the default observer; the half mirror (normal (0, 1, 1) / sqrt 2) shows
  // the eye the sky above. A sun at elevation 88.5 deg straight ahead is seen 1.5 deg below the
  // view's centre; moved 10 deg lower, 11.5 deg below.
  scene s = test::white_bench(500, 192);
  s.observer.fov_deg = 30;
  s.environment.sun = {.azimuth_deg = 0, .elevation_deg = 88.5, .illuminance_lux = 100000};
  const double R = s.half_mirror.reflectance;
  const double sun = sun_luminance(s.environment.sun);
  const render_snapshot a = render_with_layers(s, {"glare=A:sun H:r E"}, 16);
  const spot at = green_spot(a.component_image(component_sun));
  const glm::dvec2 expected = glare_pixel(s);
  std::printf("sun at elevation 88.5: spot at (%.3f, %.3f) px, geometry (%.3f, %.3f); peak %.6g cd/m2, R L_sun %.6g\n",
              at.x, at.y, expected.x, expected.y, at.peak, R * sun);
  EXPECT_NEAR(at.x, expected.x, 0.25);
  EXPECT_NEAR(at.y, expected.y, 0.25);
  // A pixel wholly inside the disc (0.16 deg wide, the disc 0.53 deg) sees R L_sun.
  EXPECT_NEAR(at.peak, R * sun, 1e-3 * R * sun);
  // All of it came by the half mirror's reflection.
  EXPECT_NEAR(green_spot(a.layer_image(0)).total, at.total, 1e-6 * at.total);

  s.environment.sun.elevation_deg -= 10;
  const render_snapshot b = render_with_layers(s, {"glare=A:sun H:r E"}, 16);
  const image_rgb moved = b.component_image(component_sun);
  const spot away = green_spot(moved);
  const glm::dvec2 moved_expected = glare_pixel(s);
  std::printf("sun 10 deg lower: spot at (%.3f, %.3f) px, geometry (%.3f, %.3f); at the first spot %.6g\n", away.x,
              away.y, moved_expected.x, moved_expected.y, double(moved.at(int(at.x), int(at.y))[1]));
  EXPECT_NEAR(away.y, moved_expected.y, 0.25);
  // Nothing left within 10 pixels (1.6 deg) of where the spot was.
  for (int y = int(at.y) - 10; y <= int(at.y) + 10; ++y)
    for (int x = int(at.x) - 10; x <= int(at.x) + 10; ++x) EXPECT_EQ(moved.at(x, y)[1], 0.0f) << x << ", " << y;
}

TEST(AmbientSources, ALuminaireLightsADiffuseCardAsItsSolidAngleSays) {
  // A card facing +z at z = 300 between the observer and the device; above its centre, 50 mm
  // out, a disc luminaire of radius 30 mm facing it. On the axis of a Lambertian disc the
  // illuminance is pi L R^2 / (R^2 + h^2), so the card shows albedo L R^2 / (R^2 + h^2).
  test::temp_dir dir;
  scene s = card_scene(dir);
  luminaire_params disc = disc_over_card();
  s.environment.luminaires.push_back(disc);
  check_scene(s, "card under a luminaire");
  const render_snapshot snap = render_with_layers(s, {"lit=A:luminaire0 P:card E"}, 64);
  const double expected = 0.6 * 2000 * 30.0 * 30 / (30.0 * 30 + 50.0 * 50);
  const double lit = mean_green(snap.layer_image(0)),
               component = mean_green(snap.component_image(component_luminaires));
  std::printf("card under a disc luminaire: %.4f cd/m2 (layer), %.4f (component), analytic %.4f\n", lit, component,
              expected);
  EXPECT_NEAR(lit, expected, 0.01 * expected);
  // Nothing else of its light reaches the card's front: the card hides the device from it.
  EXPECT_NEAR(component, lit, 1e-3 * lit);

  // Given by its flux instead, the same luminaire: L = flux / (pi area).
  const double area_m2 = std::numbers::pi * 0.03 * 0.03;
  disc.luminance_cd_m2 = 0;
  disc.flux_lm = 2000 * std::numbers::pi * area_m2;
  EXPECT_NEAR(luminaire_luminance(disc), 2000, 1e-9);
}

// The illuminance at the origin, facing +z, from a Lambertian disc of luminance L, radius R, facing
// -z at (x0, 0, h): L times the integral of cos^2 / r^2 = h^2 / r^4 over the disc (midpoint rule in
// polar coordinates about its centre).
double disc_illuminance(double L, double R, double x0, double h) {
  const int rings = 400, sectors = 800;
  double sum = 0;
  for (int i = 0; i < rings; ++i) {
    const double rho = (i + 0.5) * R / rings;
    for (int j = 0; j < sectors; ++j) {
      const double phi = (j + 0.5) * 2 * std::numbers::pi / sectors, x = x0 + rho * std::cos(phi),
                   y = rho * std::sin(phi), r2 = x * x + y * y + h * h;
      sum += h * h / (r2 * r2) * rho;
    }
  }
  return L * sum * (R / rings) * (2 * std::numbers::pi / sectors);
}

// Light sampled from a lit card crosses a plate half mirror as the tracer's own paths do: a 3 mm
// uncoated plate between the card and a disc luminaire above it (their light meeting it at 0-31
// deg), the card seen through it from 56 deg. The card shows the plate's transmission along the
// view times the quadrature of the disc's light with the plate's transmission at each point's own
// incidence (the plate's transmission at 45 deg, which the sampled light took before, is 2% less
// than at 0).
TEST(AmbientSources, LightSampledThroughAPlateCrossesItAtItsOwnAngle) {
  test::temp_dir dir;
  scene s = card_scene(dir);
  s.environment.luminaires.push_back(disc_over_card());
  s.half_mirror.kind = half_mirror_kind::plate;
  s.half_mirror.plate.thickness_mm = 3;
  s.half_mirror.plate.index = 1.52;
  s.half_mirror.pose = {.center_mm = {0, 0, 330}, .pitch_deg = 0};  // facing +z, 30 mm over the card
  check_scene(s, "card under a luminaire, behind a plate");
  const plate_params& plate = s.half_mirror.plate;
  const auto passed = [&](double cos_i) { return plate_paths_at(plate, cos_i, true).transmitted_total; };
  // The disc (radius 30, 50 mm over the card's centre), midpoint rule in polar coordinates.
  const int rings = 200, sectors = 400;
  double sum = 0;
  for (int i = 0; i < rings; ++i) {
    const double rho = (i + 0.5) * 30.0 / rings, r2 = rho * rho + 50.0 * 50.0;
    sum += sectors * passed(50 / std::sqrt(r2)) * 2500 / (r2 * r2) * rho;
  }
  const double illuminance = 2000 * sum * (30.0 / rings) * (2 * std::numbers::pi / sectors);
  const double view_cos = 200 / std::hypot(300.0, 200.0);  // from (0, -300, 500) to (0, 0, 300)
  const double expected = passed(view_cos) * 0.6 * illuminance / std::numbers::pi;
  const double at_45 = passed(std::sqrt(0.5)) * passed(view_cos) * 0.6 * 2000 * 900 / (900 + 2500);
  // The sampled light's label holds the plate it crossed on its way to the card.
  const render_snapshot snap =
      render_with_layers(s, {"lit=A:luminaire0 H:t P:card H:t E", "uncrossed=A:luminaire0 P:card H:t E"}, 64);
  const double lit = mean_green(snap.layer_image(0));
  std::printf("card through a plate: %.4f cd/m2, quadrature %.4f, with the plate's 45 deg transmission %.4f\n", lit,
              expected, at_45);
  EXPECT_NEAR(lit, expected, 0.005 * expected);
  EXPECT_GT(std::abs(at_45 / expected - 1), 0.01);  // what the check tells apart
  EXPECT_EQ(mean_green(snap.layer_image(1)), 0.0);
}

// Light sampled from a lit card crosses the half mirror's films as the tracer's own paths do: a
// polarizer film (no leak) on the thin half mirror (T = 0.5) between the card and the disc passes
// half of the disc's unpolarized light; the card, diffuse, sends unpolarized light back through
// both again. The card shows (0.5 x 0.5)^2 of what it shows under the disc alone. The eye also
// sees the disc in the half mirror, through the film twice: 2000 x 0.5 x 0.5 cd/m2. (The layer
// leaves out the light the half mirror's back sends between the card and itself.)
TEST(AmbientSources, LightSampledThroughAPolarizingFilmIsPolarizedByIt) {
  test::temp_dir dir;
  scene s = card_scene(dir);
  s.environment.luminaires.push_back(disc_over_card());
  s.half_mirror.reflectance = s.half_mirror.transmittance = 0.5;
  s.half_mirror.pose = {.center_mm = {0, 0, 330}, .pitch_deg = 0};  // facing +z, 30 mm over the card
  s.half_mirror.films = {film_params{.kind = film_kind::polarizer, .face = part_face::front, .axis_deg = 20}};
  check_scene(s, "card under a luminaire, behind a polarizing film");
  const double expected = 0.25 * 0.25 * 0.6 * 2000 * 30.0 * 30 / (30.0 * 30 + 50.0 * 50);
  const render_snapshot snap =
      render_with_layers(s, {"lit=A:luminaire0 [^P]* P:card H:t E", "seen=A:luminaire0 H:r E"}, 64);
  const double lit = mean_green(snap.layer_image(0)), seen = mean_green(snap.layer_image(1));
  std::printf("card behind a polarizing film: %.4f cd/m2, analytic %.4f; the disc in the half mirror %.4f\n", lit,
              expected, seen);
  EXPECT_NEAR(lit, expected, 0.01 * expected);
  EXPECT_NEAR(seen, 500, 1e-3 * 500);
}

TEST(AmbientSources, EachLuminaireIsItsOwnComponent) {
  // The card of the test above under two discs: one on its axis, one beside it and higher, of
  // other sizes and luminances. Each luminaire's own component shows the card as that disc
  // alone lights it, the two add up to the luminaires' component, and each is the light of its
  // path event's expression.
  test::temp_dir dir;
  scene s = card_scene(dir);
  luminaire_params above, beside;
  above.shape = beside.shape = luminaire_shape::disc;
  above.pose = {.center_mm = {0, 0, 350}, .pitch_deg = 180};  // facing -z
  above.width_mm = 60;
  above.luminance_cd_m2 = 2000;
  beside.pose = {.center_mm = {70, 0, 360}, .pitch_deg = 180};  // clear of the first seen from the card
  beside.width_mm = 30;
  beside.luminance_cd_m2 = 3000;
  s.environment.luminaires = {above, beside};
  check_scene(s, "card under two luminaires");
  render_session session(s, {.threads = 2,
                             .target_spp = 64,
                             .components = true,
                             .layers = std::make_shared<const path_layers>(
                                 parse_layer_arguments({"first=A:luminaire0 .* E", "second=A:luminaire1 .* E"}, s, {})),
                             .final_images_only = true});
  const render_snapshot snap = session.wait_for(0, 64);
  const std::vector<image_rgb> parts = snap.component_images();
  ASSERT_EQ(parts.size(), std::size_t(component_count + 2));
  EXPECT_EQ(snap.component_image_names().back(), "luminaire1");
  const std::vector<image_rgb> own(parts.end() - 2, parts.end());
  const double first = mean_green(own[0]), second = mean_green(own[1]);
  const double expected_first = 0.6 / std::numbers::pi * disc_illuminance(2000, 30, 0, 50),
               expected_second = 0.6 / std::numbers::pi * disc_illuminance(3000, 15, 70, 60);
  std::printf("card under two discs: %.4f and %.4f cd/m2 (components), analytic %.4f and %.4f\n", first, second,
              expected_first, expected_second);
  EXPECT_NEAR(expected_first, 0.6 * 2000 * 30.0 * 30 / (30.0 * 30 + 50.0 * 50), 1e-4 * expected_first);
  EXPECT_NEAR(first, expected_first, 0.01 * expected_first);
  EXPECT_NEAR(second, expected_second, 0.02 * expected_second);
  const image_rgb all = snap.component_image(component_luminaires);
  for (std::size_t i = 0; i < all.rgb.size(); ++i) {
    EXPECT_NEAR(own[0].rgb[i] + own[1].rgb[i], all.rgb[i], 1e-5f * all.rgb[i]) << i;
    EXPECT_EQ(own[0].rgb[i], snap.layer_image(0).rgb[i]) << i;
    EXPECT_EQ(own[1].rgb[i], snap.layer_image(1).rgb[i]) << i;
  }
}

TEST(AmbientSources, ALuminaireSeenFromItsFrontShowsItsLuminanceAndFromItsBackNothing) {
  scene s = test::white_bench(500, 8);
  s.observer.fov_deg = 2;
  luminaire_params panel;
  panel.pose = {.center_mm = {0, 0, 400}};  // facing +z, the observer at z = 450
  panel.width_mm = panel.height_mm = 40;
  panel.luminance_cd_m2 = 1234;
  s.environment.luminaires.push_back(panel);
  const render_snapshot front = render_with_layers(s, {}, 4);
  EXPECT_NEAR(mean_green(front.component_image(component_luminaires)), 1234, 1e-3);
  // Its back hides the device and shows nothing.
  s.environment.luminaires[0].pose.yaw_deg = 180;
  const render_snapshot back = render_with_layers(s, {}, 4);
  EXPECT_EQ(mean_green(back.component_image(component_luminaires)), 0.0);
  // (The aerial image is the model image's less its traced correction: zero within rounding.)
  EXPECT_NEAR(mean_green(back.component_image(component_aerial)), 0.0, 1e-3);
}

TEST(AmbientSources, SunAndLuminairesAreSavedAndBadValuesAreClearErrors) {
  test::temp_dir dir;
  scene s = test::white_bench(500, 8);
  s.environment.sun = {.azimuth_deg = 30, .elevation_deg = 40, .illuminance_lux = 50000};
  luminaire_params panel;
  panel.name = "ceiling";
  panel.pose = {.center_mm = {0, 800, 200}, .pitch_deg = -90};
  panel.flux_lm = 3000;
  s.environment.luminaires.push_back(panel);
  const std::string path = dir.file("lit.json");
  save_scene(s, path);
  EXPECT_EQ(load_scene(path).environment, s.environment);
  const glm::dvec3 d = sun_direction(s.environment.sun);
  EXPECT_NEAR(d.y, std::sin(40 * std::numbers::pi / 180), 1e-12);
  // The sun's disc times its luminance gives its illuminance back.
  const double half = 0.265 * std::numbers::pi / 180;
  EXPECT_NEAR(sun_luminance(s.environment.sun) * 2 * std::numbers::pi * (1 - std::cos(half)), 50000, 1e-6);

  const auto fails = [&](const std::string& set, const std::vector<std::string>& words) {
    const auto r = test::run_cli("render " + path + " -o " + dir.file("x.png") + " --spp 1 --set " + set);
    std::vector<std::string> all = {path};
    all.insert(all.end(), words.begin(), words.end());
    test::expect_one_line_error(r, all);
  };
  fails("environment.sun.elevation_deg=-5", {"environment.sun.elevation_deg", "below the horizon"});
  fails("environment.sun.illuminance_lux=-1", {"environment.sun.illuminance_lux"});
  fails("environment.sun.illuminance_lux=1e7", {"environment.sun.illuminance_lux"});
  fails("environment.luminaires.0.width_mm=0", {"environment.luminaires[0].width_mm"});
  fails("environment.luminaires.0.luminance_cd_m2=-3", {"environment.luminaires[0].luminance_cd_m2"});
  fails("environment.luminaires.0.luminance_cd_m2=100", {"environment.luminaires[0]", "not both"});
  fails("environment.luminaires.0.shape=star", {"environment.luminaires[0].shape", "star"});

  // The sun, the luminaires and the one luminaire's own as components of `airr render`.
  for (const char* component : {"sun", "luminaires", "luminaire0"}) {
    const auto ok = test::run_cli("render " + path + " -o " + dir.file("part.exr") + " --spp 1 --component " +
                                  component + " --set observer.width=8 --set observer.height=8");
    EXPECT_EQ(ok.exit_code, 0) << ok.out;
  }
  const auto none = test::run_cli("render " + path + " -o " + dir.file("part.exr") +
                                  " --spp 1 --component luminaire1 --set observer.width=8 --set observer.height=8");
  EXPECT_NE(none.exit_code, 0);
  EXPECT_NE(none.out.find("the scene has 1 luminaire"), std::string::npos) << none.out;
}

TEST(AmbientSources, PathExpressionsNameTheSunAndEachLuminaire) {
  EXPECT_EQ(event_text({path_event_kind::ambient, false, false, ambient_sun}), "A:sun");
  EXPECT_EQ(event_text({path_event_kind::ambient, false, false, ambient_first_luminaire + 3}), "A:luminaire3");
  path_label l;
  l.push({path_event_kind::eye});
  l.push({path_event_kind::half_mirror, true, true, 0});
  l.push({path_event_kind::ambient, false, false, ambient_first_luminaire + 3});
  EXPECT_TRUE(path_expression::parse("A:luminaire3 H:r E").matches(l));
  EXPECT_TRUE(path_expression::parse("A:luminaire .* E").matches(l));
  EXPECT_FALSE(path_expression::parse("A:luminaire2 .* E").matches(l));
  EXPECT_FALSE(path_expression::parse("A:sun .* E").matches(l));
  EXPECT_THROW(path_expression::parse("A:moon E"), input_error);
}
