// Photometric units: a display whose white is given in cd/m2 makes the layout's images cd/m2. The
// aerial image's luminance is then L R T for the ideal sheet, the model PSF's brightness times L
// for a real sheet, and `airr psf` prints the luminance the tracer renders, emission profile and
// all. (A white display's RGB channels are equal, so each is its luminance, CIE Y.)
#include <gtest/gtest.h>

#include <cstdio>
#include <regex>

#include "airr/core/assets.hpp"
#include "airr/formats/image.hpp"
#include "airr/formats/scene_json.hpp"
#include "airr/layout/layout.hpp"
#include "airr/layout/psf.hpp"
#include "airr/layout/sheet_models.hpp"
#include "test_helpers.hpp"

using namespace airr;

namespace {

// The number `airr psf` prints after "aerial image luminance: ".
double printed_luminance(const std::string& out) {
  std::smatch m;
  if (!std::regex_search(out, m, std::regex("aerial image luminance: ([0-9.eE+-]+) cd/m2"))) return -1;
  return std::stod(m[1]);
}

}  // namespace

TEST(PhotometricUnits, IdealSheetsAerialImageIsTheDisplaysLuminanceTimesRT) {
  const scene s = test::white_bench(500);
  ASSERT_TRUE(in_cd_m2(s.source));
  EXPECT_STREQ(image_units(s.source), "cd/m2");
  const double at_defaults = test::traced_aerial_at_centre(s, 16, 4);
  std::printf("ideal sheet, 500 cd/m2 display: aerial image %.4f cd/m2 (L R T = 125)\n", at_defaults);
  EXPECT_NEAR(at_defaults, 500 * 0.5 * 0.5, 0.005 * 125);

  scene other = s;
  other.half_mirror.reflectance = 0.7;
  other.half_mirror.transmittance = 0.2;
  other.source.intensity = 3;  // not used once the luminance is set
  const double other_rt = test::traced_aerial_at_centre(other, 16, 4);
  EXPECT_NEAR(other_rt, 500 * 0.7 * 0.2, 0.005 * 70);

  // Relative units stay: without a luminance the image is in units of `intensity`.
  const scene relative = test::white_bench(0);
  EXPECT_STREQ(image_units(relative.source), "relative");
  EXPECT_NEAR(test::traced_aerial_at_centre(relative, 16, 4), 10 * 0.25, 0.005 * 2.5);
}

TEST(PhotometricUnits, TheLuminanceRoundTripsAndIsChecked) {
  test::temp_dir dir;
  const std::string path = dir.file("bench.json");
  save_scene(test::white_bench(500), path);
  EXPECT_EQ(load_scene(path).source.luminance_cd_m2, 500);
  // A scene in relative units does not write the field.
  EXPECT_FALSE(scene_to_json(test::white_bench(0), json_form::saved)["source"].contains("luminance_cd_m2"));
  const auto bad = test::run_cli("psf " + path + " --samples 1000 --set source.luminance_cd_m2=-5");
  test::expect_one_line_error(bad, {"source.luminance_cd_m2", "-5"});
  const auto text = test::run_cli("psf " + path + " --samples 1000 --set source.luminance_cd_m2=bright");
  test::expect_one_line_error(text, {"source.luminance_cd_m2"});
  const auto sweep =
      test::run_cli("sweep " + path + " --vary tilt=0:10:10 --psf --samples 2000 -o " + dir.file("s.csv"));
  ASSERT_EQ(sweep.exit_code, 0) << sweep.out;
  EXPECT_NE(sweep.out.find("the aerial image's luminance is it x 500 cd/m2"), std::string::npos) << sweep.out;
  // The render's file names its units.
  const std::string exr = dir.file("render.exr");
  const auto r =
      test::run_cli("render " + path + " -o " + exr + " --spp 2 --set observer.width=16 --set observer.height=16");
  ASSERT_EQ(r.exit_code, 0) << r.out;
  EXPECT_EQ(read_image_metadata(exr).at("airr:units"), "cd/m2");
  const auto rel =
      test::run_cli("render " + path + " -o " + exr +
                    " --spp 2 --set observer.width=16 --set observer.height=16 --set source.luminance_cd_m2=0");
  ASSERT_EQ(rel.exit_code, 0) << rel.out;
  EXPECT_EQ(read_image_metadata(exr).at("airr:units"), "relative");
}

// A measured sheet (RF-Ay's preset): the tracer's aerial image at the centre (the 2 x 2 pixels
// there: the luminance changes by 1.6% from the centre to 6 mm off it, as the eye's angle to the
// sheet changes) is the model PSF's brightness times the display's luminance, within 1%.
TEST(PhotometricUnits, RealSheetsAerialImageIsTheModelsBrightnessTimesTheLuminance) {
  scene s = test::white_bench(500, 96);
  s.sheet().model = {.type = "sinc_shift", .values = {{"preset", std::string("rf-ay")}}};
  const double model = sample_psf(s, make_sheet_models(s), {.samples = 400000, .seed = 5}).brightness() * 500;
  const double traced = test::traced_aerial_at_centre(s, 256, 1);
  std::printf("RF-Ay, 500 cd/m2 display: traced aerial %.4f cd/m2, model PSF %.4f cd/m2 (%+.2f%%)\n", traced, model,
              100 * (traced / model - 1));
  EXPECT_NEAR(traced, model, 0.01 * model);
}

// The shipped kiosk emits by its LCD's profile; what `airr psf` prints is what the tracer renders
// at the aerial image's centre, within 1%.
TEST(PhotometricUnits, KioskPrintedLuminanceIsTheTracersAtTheCentre) {
  const std::string kiosk = asset_dir() + "/scenes/two_sheet_kiosk.json";
  const std::vector<scene_override> sets = {
      {"source.image", ""}, {"source.luminance_cd_m2", "500"}, {"observer.width", "96"}, {"observer.height", "96"}};
  test::temp_dir dir;
  std::string args = "psf " + kiosk + " --samples 1000000 -o " + dir.file("mtf.csv");
  for (const auto& o : sets) args += " --set " + o.key + "=" + o.value;
  const auto r = test::run_cli(args);
  ASSERT_EQ(r.exit_code, 0) << r.out;
  const double printed = printed_luminance(r.out);
  ASSERT_GT(printed, 0) << r.out;
  const scene s = load_scene(kiosk, sets);
  ASSERT_FALSE(s.source.emission_profile.empty());
  const double traced = test::traced_aerial_at_centre(s, 256, 1);
  std::printf("kiosk, 500 cd/m2 LCD: printed %.4f cd/m2, traced %.4f cd/m2 (%+.2f%%)\n", printed, traced,
              100 * (traced / printed - 1));
  EXPECT_NEAR(traced, printed, 0.01 * printed);
}
