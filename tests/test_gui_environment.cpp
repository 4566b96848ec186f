// The device in its room, in the designer under Xvfb: the viewing zone maps the smallest legible
// character and marks the best eye, with the legibility map beside it; a ceiling luminaire shows
// in the layout views, 3D included; the render view shows each luminaire's light as a component
// of its own.
#include <fstream>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "airr/core/assets.hpp"
#include "airr/formats/scene_json.hpp"
#include "gui_test_support.hpp"
#include "test_helpers.hpp"

using namespace airr;
using namespace airr::test::gui;

namespace {

std::string default_scene() { return asset_dir() + "/scenes/default.json"; }

// Warm white pixels: a luminaire's face, shaded (the light paths' yellow has less blue).
int luminaire_pixels(const rgb8_image& img, const std::array<int, 4>& r) {
  int n = 0;
  for (int y = r[1]; y < r[3]; ++y) {
    for (int x = r[0]; x < r[2]; ++x) {
      const unsigned char* p = img.at(x, y);
      n += p[0] > 150 && p[0] >= p[1] && p[1] > 0.85 * p[0] && p[2] > 0.5 * p[0] && p[2] < p[1] - 20;
    }
  }
  return n;
}

// The mean column (0 left, 1 right) of the region's bright pixels, and how many there are.
std::pair<double, int> bright_column(const rgb8_image& img, const std::array<int, 4>& r) {
  double sum = 0;
  int n = 0;
  for (int y = r[1]; y < r[3]; ++y) {
    for (int x = r[0]; x < r[2]; ++x) {
      const unsigned char* p = img.at(x, y);
      if (p[0] + p[1] + p[2] > 3 * 128) sum += double(x - r[0]) / (r[2] - r[0]), ++n;
    }
  }
  return {n ? sum / n : -1, n};
}

}  // namespace

// The full pass's smallest legible character (scripted: it runs to its end before the
// screenshot): a heatmap whose largest heights reach viridis' top, grey where nothing is seen,
// and the best eye marked in red.
TEST(GuiEnvironment, TheViewingZoneMapsTheSmallestLegibleCharacter) {
  test::temp_dir dir;
  const std::string shot = dir.file("zone.png");
  const studio_run run = run_studio(dir, default_scene() + " --zone char-height --frames 10 --screenshot " + shot);
  ASSERT_EQ(run.status, 0) << run.log;
  const rgb8_image img = read_png(shot);
  ASSERT_GT(img.width, 0) << "no screenshot: " << run.log;
  const auto regions = nlohmann::json::parse(std::ifstream(shot + ".json"));
  const auto zone = region(regions, "plot_zone");
  EXPECT_GT(curve_pixels(img, zone, {253, 231, 37}), 20) << "the largest heights";
  EXPECT_GT(curve_pixels(img, zone, {110, 110, 110}), 200) << "nothing seen";
  EXPECT_GT(curve_pixels(img, zone, {255, 90, 90}), 5) << "the best eye";
}

// The zone's legibility map in a lit room: its title (the threshold, the image's and the zone's
// legible share) is too long to share the top line with the y axis's title, and takes a line of
// its own: the two do not overlap, and both lie above the map.
TEST(GuiEnvironment, TheLegibilityMapsTitleKeepsClearOfItsAxisTitle) {
  test::temp_dir dir;
  const std::string shot = dir.file("legible.png");
  const studio_run run =
      run_studio(dir, default_scene() +
                          " --set source.luminance_cd_m2=500 --set environment.room.illuminance_lux=300"
                          " --zone legible-3 --frames 10 --screenshot " +
                          shot);
  ASSERT_EQ(run.status, 0) << run.log;
  const auto regions = nlohmann::json::parse(std::ifstream(shot + ".json"));
  const auto title = region(regions, "plot_zone_title"), axis = region(regions, "plot_zone_y_title"),
             zone = region(regions, "plot_zone");
  ASSERT_GT(title[2], title[0]) << "no title drawn";
  ASSERT_GT(axis[2], axis[0]) << "no y title drawn";
  const bool overlap = title[0] < axis[2] && axis[0] < title[2] && title[1] < axis[3] && axis[1] < title[3];
  EXPECT_FALSE(overlap) << "title " << title[0] << ".." << title[2] << ", y title " << axis[0] << ".." << axis[2];
  EXPECT_LE(title[3], zone[1]);
  EXPECT_LE(axis[3], zone[1]);
}

// The legibility map beside the viewing zone: once the full pass exists, the share of the image
// legible at the chosen threshold from each eye stands beside the visible fraction, on the same
// row; at 1.5 far fewer of its eyes read nothing legible (viridis' bottom) than at 25.
TEST(GuiEnvironment, TheLegibilityMapStandsBesideTheViewingZone) {
  test::temp_dir dir;
  int nothing_legible[2] = {0, 0};
  const char* thresholds[2] = {"1.5", "25"};
  for (int k = 0; k < 2; ++k) {
    const std::string shot = dir.file(std::string("beside") + thresholds[k] + ".png");
    const studio_run run =
        run_studio(dir, default_scene() +
                            " --set source.luminance_cd_m2=500 --set environment.room.illuminance_lux=50"
                            " --zone visible --legible-at " +
                            thresholds[k] + " --frames 10 --screenshot " + shot);
    ASSERT_EQ(run.status, 0) << run.log;
    const rgb8_image img = read_png(shot);
    ASSERT_GT(img.width, 0) << run.log;
    const auto regions = nlohmann::json::parse(std::ifstream(shot + ".json"));
    const auto zone = region(regions, "plot_zone"), legibility = region(regions, "plot_zone_legibility");
    EXPECT_GE(legibility[0], zone[2]) << "beside the zone, to its right";
    EXPECT_EQ(legibility[1], zone[1]) << "on the same row";
    EXPECT_GT(curve_pixels(img, zone, {253, 231, 37}), 100) << "the visible fraction, fully seen at the centre";
    nothing_legible[k] = curve_pixels(img, legibility, {68, 1, 84});
  }
  std::printf("eyes' pixels with nothing legible: %d at 1.5, %d at 25\n", nothing_legible[0], nothing_legible[1]);
  EXPECT_LT(nothing_legible[0] + 1000, nothing_legible[1]);
}

// A ceiling panel over the device: drawn in the top view as its outline and in the 3D view as a
// lit face, which the same scene without it lacks.
TEST(GuiEnvironment, ALuminaireShowsInTheLayoutViews) {
  test::temp_dir dir;
  scene s = load_scene(default_scene());
  s.source.image = resolve_scene_path(s, s.source.image);  // the copies live elsewhere
  s.source.luminance_cd_m2 = 500;                          // ambient light needs photometric units
  luminaire_params panel;
  panel.name = "ceiling";
  panel.width_mm = panel.height_mm = 240;
  panel.luminance_cd_m2 = 3000;
  panel.pose = {.center_mm = {0, 260, 0}, .pitch_deg = -90};
  std::ofstream(dir.file("dark.json")) << scene_to_json(s).dump(1);
  s.environment.luminaires.push_back(panel);
  std::ofstream(dir.file("lit.json")) << scene_to_json(s).dump(1);

  int face[2] = {0, 0};
  for (int lit = 0; lit < 2; ++lit) {
    const std::string shot = dir.file(lit ? "lit.png" : "dark.png");
    const studio_run run =
        run_studio(dir, dir.file(lit ? "lit.json" : "dark.json") + " --frames 20 --screenshot " + shot);
    ASSERT_EQ(run.status, 0) << run.log;
    const rgb8_image img = read_png(shot);
    ASSERT_GT(img.width, 0) << run.log;
    const auto regions = nlohmann::json::parse(std::ifstream(shot + ".json"));
    face[lit] = luminaire_pixels(img, region(regions, "layout_3d"));
    const int outline = curve_pixels(img, region(regions, "layout_top"), {255, 240, 150});
    std::printf("%s: %d warm pixels in the 3D view, %d outline pixels in the top view\n", lit ? "lit" : "dark",
                face[lit], outline);
    if (lit) {
      EXPECT_GT(outline, 20) << "the panel's edge in the top view";
    }
  }
  EXPECT_GT(face[1], face[0] + 200) << "the panel's face in the 3D view";
}

// Two small panels facing the observer in front of the device, left and right: the render view's
// component menu offers each luminaire's light, and each shows its own panel alone.
TEST(GuiEnvironment, TheRenderViewShowsEachLuminairesLight) {
  test::temp_dir dir;
  scene s = load_scene(default_scene());
  s.source.image = resolve_scene_path(s, s.source.image);
  s.source.luminance_cd_m2 = 500;
  for (double x : {-10.0, 10.0}) {
    luminaire_params panel;
    panel.width_mm = panel.height_mm = 6;
    panel.luminance_cd_m2 = 3000;
    panel.pose = {.center_mm = {x, 0, 300}};  // facing +z, the observer
    s.environment.luminaires.push_back(panel);
  }
  std::ofstream(dir.file("panels.json")) << scene_to_json(s).dump(1);
  double column[2] = {0, 0};
  for (int k = 0; k < 2; ++k) {
    const std::string shot = dir.file("luminaire" + std::to_string(k) + ".png");
    const studio_run run = run_studio(dir, dir.file("panels.json") + " --component luminaire" + std::to_string(k) +
                                               " --frames 30 --screenshot " + shot);
    ASSERT_EQ(run.status, 0) << run.log;
    EXPECT_NE(run.log.find("component luminaire" + std::to_string(k)), std::string::npos) << run.log;
    const rgb8_image img = read_png(shot);
    ASSERT_GT(img.width, 0) << run.log;
    const auto regions = nlohmann::json::parse(std::ifstream(shot + ".json"));
    const auto [c, n] = bright_column(img, region(regions, "render_image"));
    std::printf("luminaire%d: %d bright pixels about column %.3f of the render view\n", k, n, c);
    EXPECT_GT(n, 50) << "the panel's face";
    column[k] = c;
  }
  EXPECT_LT(column[0], 0.45) << "the left panel alone";
  EXPECT_GT(column[1], 0.55) << "the right panel alone";
}
