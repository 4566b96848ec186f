// The fit of a two-sheet device: measurements synthesised on a device whose second sheet is the
// first's mirror image in the half mirror (both sheets add to every curve and white square) fit
// back to the preset they came from, as one-sheet measurements do; a device whose second sheet is
// placed otherwise is refused, naming the sheet.
#include <gtest/gtest.h>

#include <cstdio>
#include <string>

#include "airr/analysis/fit_data.hpp"
#include "airr/formats/scene_json.hpp"
#include "airr/layout/layout.hpp"
#include "airr/layout/psf.hpp"
#include "airr/layout/sheet_models.hpp"
#include "airr/models/preset.hpp"
#include "test_helpers.hpp"

using namespace airr;

namespace {

// The default bench with a second sheet above the half mirror, the first's mirror image.
scene mirrored_device() {
  scene s;
  s.retroreflectors.push_back(s.sheet());
  s.retroreflectors[1].pose = mirrored_in_half_mirror(s, retroreflector_frame(s, 0));
  return s;
}

}  // namespace

TEST(SheetFit, MirroredSheetFollowsTheTiltAndSeesTheSameIncidence) {
  const scene device = mirrored_device();
  for (double tilt : {0.0, 20.0, 45.0}) {
    scene s = analysis::measurement_layout(device, tilt, 200);
    for (auto& sheet : s.retroreflectors)
      sheet.model = {.type = "sinc_shift", .values = {{"preset", std::string("rf-ay")}}};
    const psf_samples psf = sample_psf(s, make_sheet_models(s), {.samples = 20000, .seed = 1});
    ASSERT_EQ(psf.sheets.size(), 2u);
    ASSERT_TRUE(psf.sheets[1].missed.empty()) << psf.sheets[1].missed;
    EXPECT_TRUE(psf.sheets[1].by_reflection);
    EXPECT_NEAR(psf.sheets[1].incidence_deg, psf.sheets[0].incidence_deg, 1e-6) << "tilt " << tilt;
    EXPECT_NEAR(psf.sheets[1].rr_distance_mm, psf.sheets[0].rr_distance_mm, 1e-6) << "tilt " << tilt;
    EXPECT_NEAR(psf.sheets[0].incidence_deg, tilt, 1e-6);
  }
}

TEST(SheetFit, MirroredTwoSheetDeviceFitsBackToTable2) {
  test::temp_dir dir;
  save_scene(mirrored_device(), dir.file("device.json"));
  const auto synth = test::run_cli("fit --synthesise " + dir.file("data") + " --preset rf-ay --setup " +
                                   dir.file("device.json") + " --samples 400000");
  ASSERT_EQ(synth.exit_code, 0) << synth.out;
  const auto fit = test::run_cli("fit --data " + dir.file("data") + " -o " + dir.file("fitted.json"));
  ASSERT_EQ(fit.exit_code, 0) << fit.out;
  // With one sheet simulated, mu would come out twice the table's.
  test::expect_preset_near_table(load_preset(dir.file("fitted.json")), load_preset("rf-ay"), 0.05);
}

TEST(SheetFit, SecondSheetPlacedOtherwiseIsRefusedByName) {
  test::temp_dir dir;
  scene s = mirrored_device();
  s.retroreflectors[1].pose.center_mm[2] += 20;
  save_scene(s, dir.file("device.json"));
  const auto r = test::run_cli("fit --synthesise " + dir.file("data") + " --setup " + dir.file("device.json"));
  test::expect_one_line_error(r, {"device.json", "retroreflectors[1]", "mirror image"});
}
