// The designer for real: under Xvfb the app opens its window on the default scene, applies tilt
// and floating distance from --set, runs frames, writes a screenshot and exits 0. The screenshot's
// render region must show the aerial image and the plot regions must hold drawn curves.
#include <array>
#include <cstdio>
#include <cstdlib>
#include <fstream>

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "airr/core/assets.hpp"
#include "airr/formats/scene_json.hpp"
#include "gltf_builder.hpp"
#include "gui_test_support.hpp"
#include "label_overlap.hpp"
#include "test_helpers.hpp"

using namespace airr;
using namespace airr::test::gui;

TEST(Gui, ScriptedRunShowsTheAerialImageAndPlots) {
  test::temp_dir dir;
  const std::string shot = dir.file("studio.png");
  const studio_run run = run_studio(
      dir, default_scene_path() + " --set tilt_deg=15 --set floating_distance_mm=200 --frames 20 --screenshot " + shot);
  const int status = run.status;
  const std::string& log_text = run.log;
  ASSERT_EQ(status, 0) << log_text;

  const rgb8_image img = read_png(shot);
  ASSERT_GT(img.width, 0) << "no screenshot: " << log_text;
  const auto regions = nlohmann::json::parse(std::ifstream(shot + ".json"));
  EXPECT_EQ(regions.at("width").get<int>(), img.width);

  // The render: not uniform, and the aerial image is brighter than the black around it.
  const auto render = region(regions, "render_image");
  const auto aerial = region(regions, "render_aerial_image");
  const region_stats whole = grey_stats(img, render);
  const region_stats inside = grey_stats(img, aerial);
  const region_stats outside = grey_stats(img, render, &aerial);
  EXPECT_GT(whole.count, 10000);
  EXPECT_GT(whole.stddev, 20.0);
  EXPECT_GT(inside.mean, outside.mean + 40.0) << "inside " << inside.mean << " outside " << outside.mean;

  // Every plot holds a drawn curve in the palette's first colour.
  for (const char* plot : {"plot_mtf", "plot_psf", "plot_sweep"}) {
    EXPECT_GT(curve_pixels(img, region(regions, plot), {80, 160, 255}), 100) << plot;
  }
  // The MTF plot also shows the curve measured on the render (the test chart has a slanted edge).
  EXPECT_GT(curve_pixels(img, region(regions, "plot_mtf"), {255, 150, 60}), 100);
  // The viewing zone: cells where all of the aerial image is seen (viridis' top), cells where none
  // of it is (its bottom), and the observer's white marker.
  const auto zone = region(regions, "plot_zone");
  EXPECT_GT(curve_pixels(img, zone, {253, 231, 37}), 200);
  EXPECT_GT(curve_pixels(img, zone, {68, 1, 84}), 200);
  EXPECT_GT(curve_pixels(img, zone, {255, 255, 255}), 5);
}

// The render view shows one component of the image: the aerial image alone is bright where the
// aerial image forms; the display seen directly is not in view from in front, so it is dark there.
TEST(Gui, TheRenderViewShowsOneComponent) {
  double mean[2] = {0, 0};
  const char* components[2] = {"aerial", "direct"};
  for (int k = 0; k < 2; ++k) {
    test::temp_dir dir;
    const std::string shot = dir.file("component.png");
    const studio_run run =
        run_studio(dir, default_scene_path() + " --component " + components[k] + " --frames 30 --screenshot " + shot);
    const int status = run.status;
    const std::string& log_text = run.log;
    ASSERT_EQ(status, 0) << log_text;
    EXPECT_NE(log_text.find(std::string("component ") + components[k]), std::string::npos) << log_text;
    const rgb8_image img = read_png(shot);
    ASSERT_GT(img.width, 0) << "no screenshot: " << log_text;
    const auto regions = nlohmann::json::parse(std::ifstream(shot + ".json"));
    mean[k] = grey_stats(img, region(regions, "render_aerial_image")).mean;
  }
  EXPECT_GT(mean[0], 60.0);
  EXPECT_LT(mean[1], 25.0);
}

// The luminance view: a 500 cd/m2 white display on the ideal bench makes an aerial image of
// L R T = 125 cd/m2, the top of the scale at 0 EV (viridis' yellow), on a black surround (its
// purple); the scale bar beside the image, labelled in cd/m2.
TEST(Gui, TheLuminanceViewShowsCdPerM2InFalseColour) {
  test::temp_dir dir;
  const std::string shot = dir.file("luminance.png");
  const studio_run run = run_studio(dir, asset_dir() +
                                             "/scenes/ideal_bench.json --set source.image= --set "
                                             "source.luminance_cd_m2=500 --luminance-view --frames 30 --screenshot " +
                                             shot);
  ASSERT_EQ(run.status, 0) << run.log;
  const rgb8_image img = read_png(shot);
  ASSERT_GT(img.width, 0) << "no screenshot: " << run.log;
  const auto notes = nlohmann::json::parse(std::ifstream(shot + ".json"));
  EXPECT_EQ(notes["render_view"]["units"], "cd/m2");
  EXPECT_EQ(notes["render_view"]["luminance_view"], true);
  EXPECT_NEAR(notes["render_view"]["scale_top"].get<double>(), 125, 1e-3);
  const auto aerial = region(notes, "render_aerial_image");
  const int area = (aerial[2] - aerial[0]) * (aerial[3] - aerial[1]);
  const int yellow = curve_pixels(img, aerial, {253, 231, 37});
  std::printf("luminance view: %d of the aerial image's %d pixels at the scale's top\n", yellow, area);
  EXPECT_GT(yellow, area / 2);
  const auto image = region(notes, "render_image");
  EXPECT_GT(curve_pixels(img, image, {68, 1, 84}), area / 2) << "the black surround at the scale's bottom";
  const auto scale = region(notes, "luminance_scale");
  EXPECT_GT(curve_pixels(img, scale, {253, 231, 37}), 20);
  EXPECT_GT(curve_pixels(img, scale, {68, 1, 84}), 20);
}

// The contrast view: the room's surround (no aerial image) at the scale's bottom; over the aerial
// image the contrast (125 + 0.75 L) / (0.75 L) of the ideal bench, higher in a dimmer room, so
// further up viridis (whose green rises along it).
TEST(Gui, TheContrastViewShowsTheAerialImageAgainstTheRoom) {
  test::temp_dir dir;
  std::vector<double> green;
  for (const char* lux : {"100", "3000"}) {
    const std::string shot = dir.file(std::string("contrast_") + lux + ".png");
    const studio_run run = run_studio(dir, asset_dir() +
                                               "/scenes/ideal_bench.json --set source.image= --set "
                                               "source.luminance_cd_m2=500 --set environment.room.illuminance_lux=" +
                                               lux + " --contrast-view --frames 30 --screenshot " + shot);
    ASSERT_EQ(run.status, 0) << run.log;
    const rgb8_image img = read_png(shot);
    ASSERT_GT(img.width, 0) << "no screenshot: " << run.log;
    const auto notes = nlohmann::json::parse(std::ifstream(shot + ".json"));
    EXPECT_EQ(notes["render_view"]["contrast_view"], true);
    const auto aerial = region(notes, "render_aerial_image");
    // The aerial image's middle half, away from its border.
    const int qx = (aerial[2] - aerial[0]) / 4, qy = (aerial[3] - aerial[1]) / 4;
    double sum = 0;
    int n = 0;
    for (int y = aerial[1] + qy; y < aerial[3] - qy; ++y) {
      for (int x = aerial[0] + qx; x < aerial[2] - qx; ++x) {
        sum += img.at(x, y)[1];
        ++n;
      }
    }
    green.push_back(sum / std::max(1, n));
    const auto scale = region(notes, "contrast_scale");
    EXPECT_GT(curve_pixels(img, scale, {253, 231, 37}), 20) << lux;
    std::printf("contrast view at %s lx: mean green %.1f over the aerial image's middle\n", lux, green.back());
  }
  EXPECT_GT(green[0], green[1] + 30);  // contrast 6.2 at 100 lx against 1.17 at 3,000 lx
}

// The viewing zone's full pass from the designer (scripted: it runs to its end before the
// screenshot): the brightness map is 1 (viridis' top) at the best eyes and grey where nothing is seen.
TEST(Gui, TheFullViewingZoneShowsBrightness) {
  test::temp_dir dir;
  const std::string shot = dir.file("zone.png");
  const studio_run run =
      run_studio(dir, default_scene_path() + " --zone brightness --frames 10" + " --screenshot " + shot);
  const int status = run.status;
  const std::string& log_text = run.log;
  ASSERT_EQ(status, 0) << log_text;
  const rgb8_image img = read_png(shot);
  ASSERT_GT(img.width, 0) << "no screenshot: " << log_text;
  const auto regions = nlohmann::json::parse(std::ifstream(shot + ".json"));
  const auto zone = region(regions, "plot_zone");
  EXPECT_GT(curve_pixels(img, zone, {253, 231, 37}), 20);
  EXPECT_GT(curve_pixels(img, zone, {110, 110, 110}), 200);
}

TEST(Gui, AnEditShowsTheModelImageFirst) {
  // Right after an edit the render view shows the model image (its first look, or at view quality: before any traced
  // sample), and it already shows the aerial image where the edited layout puts it.
  test::temp_dir dir;
  const std::string shot = dir.file("edit.png");
  const studio_run run =
      run_studio(dir, default_scene_path() +
                          " --frames 10 --edit tilt_deg=20 --edit floating_distance_mm=180 --screenshot-after 0"
                          " --screenshot " +
                          shot);
  const int status = run.status;
  const std::string& log_text = run.log;
  ASSERT_EQ(status, 0) << log_text;
  EXPECT_NE(log_text.find("the render view shows the model image"), std::string::npos) << log_text;

  const rgb8_image img = read_png(shot);
  ASSERT_GT(img.width, 0) << "no screenshot: " << log_text;
  const auto regions = nlohmann::json::parse(std::ifstream(shot + ".json"));
  const auto render = region(regions, "render_image");
  const auto aerial = region(regions, "render_aerial_image");
  const region_stats inside = grey_stats(img, aerial);
  const region_stats outside = grey_stats(img, render, &aerial);
  EXPECT_GT(inside.mean, outside.mean + 40.0) << "inside " << inside.mean << " outside " << outside.mean;
}

TEST(Gui, BadSceneFailsBeforeOpeningAWindow) {
  test::temp_dir dir;
  const std::string bad = dir.file("bad.json");
  std::ofstream(bad) << "{";
  const std::string cmd = std::string(AIRR_STUDIO) + " " + bad + " > " + dir.file("log.txt") + " 2>&1";
  EXPECT_NE(std::system(cmd.c_str()), 0);
  std::ifstream log(dir.file("log.txt"));
  std::string line;
  std::getline(log, line);
  EXPECT_NE(line.find("malformed JSON"), std::string::npos) << line;
}

TEST(Gui, FontsAndSizesFollowTheContentScale) {
  // The same window at 96 and at 192 dpi (Xft.dpi, read by GLFW): every panel doubles in size.
  test::temp_dir dir;
  auto run = [&](int dpi, const std::string& shot) {
    const std::string script = dir.file("run" + std::to_string(dpi) + ".sh");
    std::ofstream(script) << "echo 'Xft.dpi: " << dpi << "' | xrdb -nocpp -merge\n"
                          << "XDG_CONFIG_HOME=" << dir.file("config" + std::to_string(dpi))
                          << " XDG_STATE_HOME=" << dir.file("state" + std::to_string(dpi)) << " " << AIRR_STUDIO << " "
                          << default_scene_path() << " --frames 10 --screenshot " << shot << "\n";
    // -noreset keeps the resource database alive between xrdb and the app.
    const std::string cmd = "xvfb-run -a -s '-noreset -screen 0 3400x2200x24' bash " + script + " > " +
                            dir.file("log" + std::to_string(dpi) + ".txt") + " 2>&1";
    return std::system(cmd.c_str());
  };
  ASSERT_EQ(run(96, dir.file("s1.png")), 0);
  ASSERT_EQ(run(192, dir.file("s2.png")), 0);
  const auto r1 = nlohmann::json::parse(std::ifstream(dir.file("s1.png.json")));
  const auto r2 = nlohmann::json::parse(std::ifstream(dir.file("s2.png.json")));
  EXPECT_EQ(r2.at("width").get<int>(), 2 * r1.at("width").get<int>());
  for (const char* name : {"plot_mtf", "render_image"}) {
    const auto& a = r1.at("regions").at(name);
    const auto& b = r2.at("regions").at(name);
    const double w1 = a[2].get<double>() - a[0].get<double>(), w2 = b[2].get<double>() - b[0].get<double>();
    EXPECT_NEAR(w2 / w1, 2.0, 0.1) << name;
  }
}

TEST(Gui, FitFromTheDesignerAppliesThePreset) {
  // The designer runs the fit on the shipped example (RF-Ay's synthetic measurements), applies
  // the result and saves the scene: the scene's model now points at a preset close to Table 2.
  test::temp_dir dir;
  const std::string scene_out = dir.file("fitted.json");
  const studio_run run = run_studio(
      dir, default_scene_path() + " --fit " + asset_dir() + "/fit_example --frames 5 --save-as " + scene_out);
  const int status = run.status;
  const std::string& log_text = run.log;
  ASSERT_EQ(status, 0) << log_text;
  const auto scene_json = nlohmann::json::parse(std::ifstream(scene_out));
  const auto& model = scene_json.at("retroreflectors").at(0).at("model");
  EXPECT_EQ(model.at("type"), "sinc_shift");
  const auto preset = nlohmann::json::parse(std::ifstream(model.at("preset").get<std::string>()));
  EXPECT_NEAR(preset.at("c_mm").get<double>(), 0.94966, 0.05 * 0.94966);
  EXPECT_NEAR(preset.at("a_per_mm")[0].get<double>(), 9.93020, 0.05 * 9.93020);
  EXPECT_NEAR(preset.at("mu")[9].get<double>(), 0.10973, 0.05 * 0.10973);
}

TEST(Gui, PredictedPresetFromTheSheetsModelIsApplied) {
  // The designer predicts a preset for a prism sheet traced as geometry (the shipped RF-AN-like
  // sheet, fewer samples than the default), applies it and saves the scene: the sheet's model is
  // now the sinc-shift model with the predicted preset, whose a at tilt 0 lies near the 0.727 per mm
  // `airr predict-preset` gives with its default samples (a matched to the mean MTF).
  test::temp_dir dir;
  const std::string scene_out = dir.file("predicted.json"), shot = dir.file("studio.png");
  const std::string sheet =
      " --set retroreflectors.0.model.type=prism_sheet --set retroreflectors.0.model.pitch_mm=0.16"
      " --set retroreflectors.0.model.index=1.5046 --set retroreflectors.0.model.coating=metal"
      " --set retroreflectors.0.model.face_reflectance=0.83";
  const studio_run run = run_studio(dir, default_scene_path() + sheet +
                                             " --predict-preset --predict-samples 100000 --frames 5 --save-as " +
                                             scene_out + " --screenshot " + shot);
  ASSERT_EQ(run.status, 0) << run.log;
  const auto scene_json = nlohmann::json::parse(std::ifstream(scene_out));
  const auto& model = scene_json.at("retroreflectors").at(0).at("model");
  EXPECT_EQ(model.at("type"), "sinc_shift");
  const auto preset = nlohmann::json::parse(std::ifstream(model.at("preset").get<std::string>()));
  EXPECT_EQ(preset.at("provenance").at("source"), "airr predict-preset");
  EXPECT_EQ(preset.at("provenance").at("sheet").at("model").at("pitch_mm"), 0.16);
  EXPECT_NEAR(preset.at("a_per_mm")[0].get<double>(), 0.727, 0.07);
  EXPECT_TRUE(std::filesystem::exists(dir.file("config/airr-studio/predictions/prism_sheet_bench/fit.json")));
  // A second prediction keeps the first's preset and measurements.
  const studio_run again =
      run_studio(dir, default_scene_path() + sheet + " --predict-preset --predict-samples 20000 --frames 2 --save-as " +
                          dir.file("again.json"));
  ASSERT_EQ(again.status, 0) << again.log;
  const auto again_json = nlohmann::json::parse(std::ifstream(dir.file("again.json")));
  EXPECT_NE(again_json.at("retroreflectors").at(0).at("model").at("preset"), model.at("preset"));
  EXPECT_TRUE(std::filesystem::exists(model.at("preset").get<std::string>()));
  EXPECT_TRUE(std::filesystem::exists(dir.file("config/airr-studio/predictions/prism_sheet_bench-2/fit.json")));
  EXPECT_GT(read_png(shot).width, 0);
}

// A housing prop (an open box around the device) appears in the side and top views as its box and
// in the 3D view, which shows the parts shaded (the sheet's green) and the light paths (yellow).
TEST(Gui, HousingPropShowsInTheLayoutViews) {
  test::temp_dir dir;
  test::gltf_builder b;
  const float x0 = -0.18f, x1 = 0.18f, y0 = -0.2f, y1 = 0.17f, z0 = -0.2f, z1 = 0.09f;
  const std::vector<float> p = {x0, y0, z0, x1, y0, z0, x1, y1, z0, x0, y1, z0,
                                x0, y0, z1, x1, y0, z1, x1, y1, z1, x0, y1, z1};
  const int mesh = b.add_mesh(
      {{b.add_positions(p),
        b.add_indices({0, 2, 1, 0, 3, 2, 0, 1, 5, 0, 5, 4, 3, 6, 2, 3, 7, 6, 0, 4, 7, 0, 7, 3, 1, 2, 6, 1, 6, 5}, 5121),
        -1}});
  b.add_node({{"name", "Housing"}, {"mesh", mesh}});
  b.write(dir.file("housing.glb"), test::gltf_builder::storage::glb);
  nlohmann::json j = scene_to_json(load_scene(default_scene_path()));
  j["source"]["image"] = asset_dir() + "/charts/test_chart.png";
  j["props"] = {{{"name", "housing"}, {"mesh", dir.file("housing.glb")}, {"surface", "absorber"}}};
  std::ofstream(dir.file("housed.json")) << j.dump(1);

  const std::string shot = dir.file("studio.png");
  const studio_run run = run_studio(dir, dir.file("housed.json") + " --frames 20 --screenshot " + shot);
  ASSERT_EQ(run.status, 0) << run.log;
  const rgb8_image img = read_png(shot);
  ASSERT_GT(img.width, 0) << run.log;
  const auto regions = nlohmann::json::parse(std::ifstream(shot + ".json"));
  for (const char* view : {"layout_side", "layout_top"}) {
    EXPECT_GT(curve_pixels(img, region(regions, view), {230, 160, 80}), 100) << view << ": the housing's box";
  }
  const auto view3d = region(regions, "layout_3d");
  const region_stats stats = grey_stats(img, view3d);
  EXPECT_GT(stats.stddev, 5.0) << "the 3D view draws something";
  int green = 0;
  for (int y = view3d[1]; y < view3d[3]; ++y) {
    for (int x = view3d[0]; x < view3d[2]; ++x) {
      const unsigned char* q = img.at(x, y);
      green += q[1] > q[0] + 15 && q[1] > q[2] + 12;
    }
  }
  EXPECT_GT(green, 100) << "the sheet, shaded green, seen through the housing";
  EXPECT_GT(curve_pixels(img, view3d, {255, 209, 89}), 10) << "the light paths";
}

// At 1600 x 1000, the shipped scenes' layout views: no label overprints another label, a part's
// outline or other text, each stays inside its view (label_overlap.hpp's own measure, on the
// rectangles the designer drew), and the 3D view has half the layout window.
TEST(Gui, LayoutLabelsNeverOverprintInTheShippedScenes) {
  for (const char* name : {"default.json", "two_sheet_kiosk.json"}) {
    test::temp_dir dir;
    const std::string shot = dir.file("studio.png");
    const studio_run run = run_studio(dir, asset_dir() + "/scenes/" + name + " --frames 10 --screenshot " + shot);
    ASSERT_EQ(run.status, 0) << run.log;
    const auto j = nlohmann::json::parse(std::ifstream(shot + ".json"));
    ASSERT_EQ(j.at("width").get<int>(), 1600);
    for (const char* view : {"side", "top"}) {
      const auto& v = j.at("layout_views").at(view);
      std::vector<std::pair<std::string, test::rect4>> labels;
      for (const auto& l : v.at("labels")) labels.push_back({l.at("text"), l.at("box").get<test::rect4>()});
      const auto lines = v.at("outlines").get<std::vector<test::segment4>>();
      const auto marks = v.at("marks").get<std::vector<test::rect4>>();
      const test::rect4 canvas = j.at("regions").at(std::string("layout_") + view).get<test::rect4>();
      const test::label_overlaps o = test::measure_label_overlaps(labels, lines, marks, canvas);
      std::string what;
      for (const auto& w : o.what) what += "\n  " + w;
      EXPECT_GE(labels.size(), 5u) << name << " " << view;
      EXPECT_EQ(o.label_pairs + o.label_lines + o.label_marks + o.outside, 0) << name << " " << view << ":" << what;
      std::printf("%s, %s view: %zu labels, %zu outline segments, %d overlaps\n", name, view, labels.size(),
                  lines.size(), o.label_pairs + o.label_lines + o.label_marks + o.outside);
    }
    // "add the second sheet" is offered while the layout has one sheet, not beside the kiosk's two.
    EXPECT_EQ(j.at("regions").contains("button_add_second_sheet"), std::string(name) == "default.json") << name;
    const auto r3 = j.at("regions").at("layout_3d").get<test::rect4>();
    const auto rs = j.at("regions").at("layout_side").get<test::rect4>();
    std::printf("%s: 3D view %.0f x %.0f px, side view %.0f x %.0f px\n", name, r3[2] - r3[0], r3[3] - r3[1],
                rs[2] - rs[0], rs[3] - rs[1]);
    EXPECT_GE(r3[2] - r3[0], 350.0);
    EXPECT_GE((r3[2] - r3[0]) * (r3[3] - r3[1]), 1.9 * (rs[2] - rs[0]) * (rs[3] - rs[1]));
  }
}

// The Bokeh tab: its 2D PSF's bright core spans the r50 that `airr psf` prints for the scene (the
// picture is bright inside 0.8 r50 and dim at 1.7 to 1.9 r50, beyond the edge of even a flat disc,
// which holds half its energy within 0.71 of its radius; read through the plot's mm range), and
// an edit of the tilt moves the D x tilt map's design marker and changes the PSF.
TEST(Gui, BokehTabShowsThePsfAndFollowsAnEdit) {
  struct shown {
    nlohmann::json bokeh;
    rgb8_image img;
  };
  auto run = [](const test::temp_dir& dir, const std::string& extra) {
    const std::string shot = dir.file("bokeh.png");
    const studio_run r =
        run_studio(dir, default_scene_path() + " --plots bokeh --frames 10" + extra + " --screenshot " + shot);
    EXPECT_EQ(r.status, 0) << r.log;
    EXPECT_NE(r.log.find("bokeh views (generation"), std::string::npos) << r.log;
    return shown{nlohmann::json::parse(std::ifstream(shot + ".json")).at("bokeh"), read_png(shot)};
  };
  auto printed_r50 = [](const std::string& sets) {
    const test::temp_dir dir;
    const auto r = test::run_cli("psf " + default_scene_path() + " --samples 8000 -o " + dir.file("p.csv") + sets);
    const auto at = r.out.find("50%-energy radius: ");
    return at == std::string::npos ? -1.0 : std::stod(r.out.substr(at + 19));
  };
  const test::temp_dir before_dir, after_dir;
  const shown before = run(before_dir, "");
  const shown after = run(after_dir, " --edit tilt_deg=30 --export-bokeh " + after_dir.file("views.png"));
  ASSERT_FALSE(before.bokeh.is_null());
  ASSERT_FALSE(after.bokeh.is_null());
  for (const shown* s : {&before, &after}) EXPECT_TRUE(s->bokeh.at("current").get<bool>()) << s->bokeh.dump();

  EXPECT_NEAR(before.bokeh.at("r50_mm").get<double>(), printed_r50(""), 1e-4);
  EXPECT_NEAR(after.bokeh.at("r50_mm").get<double>(), printed_r50(" --set tilt_deg=30"), 1e-4);
  EXPECT_GT(std::abs(after.bokeh.at("r50_mm").get<double>() - before.bokeh.at("r50_mm").get<double>()), 0.01);

  for (const shown* s : {&before, &after}) {
    const auto& area = s->bokeh.at("psf_area");
    const auto& x_mm = s->bokeh.at("psf_x_mm");
    const double x0 = area[0].get<double>(), y0 = area[1].get<double>(), x1 = area[2].get<double>(),
                 y1 = area[3].get<double>();
    const double mm_per_px = (x_mm[1].get<double>() - x_mm[0].get<double>()) / (x1 - x0);
    const double cx = 0.5 * (x0 + x1), cy = 0.5 * (y0 + y1), r50_px = s->bokeh.at("r50_mm").get<double>() / mm_per_px;
    ASSERT_GT(r50_px, 8.0) << "the picture shows r50 over too few pixels";
    double inner = 0, outer = 0;
    int n_inner = 0, n_outer = 0;
    for (int y = int(y0) + 1; y < int(y1); ++y) {
      for (int x = int(x0) + 1; x < int(x1); ++x) {
        const double r = std::hypot(x + 0.5 - cx, y + 0.5 - cy) / r50_px;
        const unsigned char* p = s->img.at(x, y);
        const double g = (p[0] + p[1] + p[2]) / 3.0;
        if (r < 0.8) inner += g, ++n_inner;
        if (r > 1.7 && r < 1.9) outer += g, ++n_outer;
      }
    }
    std::printf("tilt %g: r50 %.4f mm over %.1f px; grey inside 0.8 r50 %.1f, at 1.7-1.9 r50 %.1f\n",
                s->bokeh.at("marker_d_tilt")[1].get<double>(), s->bokeh.at("r50_mm").get<double>(), r50_px,
                inner / std::max(n_inner, 1), outer / std::max(n_outer, 1));
    ASSERT_GT(n_inner, 50);
    ASSERT_GT(n_outer, 50);
    EXPECT_GT(inner / n_inner, outer / n_outer + 30)
        << "inside 0.8 r50 " << inner / n_inner << ", beyond 1.5 r50 " << outer / n_outer;
  }

  // The design marker: at tilt 0, then at tilt 30 (higher on the map) at the same D.
  EXPECT_NEAR(before.bokeh.at("marker_d_tilt")[1].get<double>(), 0.0, 1e-9);
  EXPECT_NEAR(after.bokeh.at("marker_d_tilt")[1].get<double>(), 30.0, 1e-9);
  EXPECT_NEAR(after.bokeh.at("marker")[0].get<double>(), before.bokeh.at("marker")[0].get<double>(), 1.0);
  EXPECT_LT(after.bokeh.at("marker")[1].get<double>(), before.bokeh.at("marker")[1].get<double>() - 20);
  const auto& m = after.bokeh.at("marker");
  const unsigned char* p = after.img.at(int(m[0].get<double>()), int(m[1].get<double>()));
  EXPECT_GT(p[0] + p[1] + p[2], 600) << "the marker is drawn white where the JSON says";

  // The export: five pictures and the plot data with the bokeh views' numbers of the edited layout.
  for (const char* name : {"views.png", "views_focus.png", "views_strip.png", "views_spots.png", "views_map.png"})
    EXPECT_GT(read_png(after_dir.file(name)).width, 300) << name;
  std::ifstream csv(after_dir.file("views.csv"));
  const std::string text((std::istreambuf_iterator<char>(csv)), std::istreambuf_iterator<char>());
  for (const char* curve : {"through_focus_r50(offset_mm)", "psf2d_middle_row(mm)", "blur_map_r50_at_tilt_30"})
    EXPECT_NE(text.find(curve), std::string::npos) << curve;
}
