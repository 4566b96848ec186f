// A model image moved to another placement of its layout (remap_model_image): to its own
// placement it is the model image itself, for a drag's step it is close to the moved placement's
// own model image, and it refuses what it cannot move.
#include <cstdio>

#include <gtest/gtest.h>

#include "airr/formats/image.hpp"
#include "airr/layout/sheet_models.hpp"
#include "airr/render/layout_model_image.hpp"
#include "test_helpers.hpp"

using namespace airr;

namespace {

std::shared_ptr<const image_rgb> display_of(const scene& s) {
  return cached_image_pixels(resolve_scene_path(s, s.source.image));
}

std::shared_ptr<const layout_model_image> view_of(const scene& s) {
  return compute_layout_model_image(s, make_sheet_models(s), display_of(s).get(), model_image_params::for_view());
}

}  // namespace

TEST(Placement, DifferInPlacementAloneSeesPosesAndTheObserversPlacement) {
  const scene a = test::chart_scene("rf-ay", 64, 20);
  scene b = a;
  EXPECT_TRUE(differ_in_placement_alone(a, b));
  b.sheet().pose.pitch_deg += 0.5;
  b.source.pose.center_mm[1] -= 2;
  b.half_mirror.pose.yaw_deg += 1;
  b.observer.azimuth_deg += 3;
  b.observer.position_mm[0] += 5;
  EXPECT_TRUE(differ_in_placement_alone(a, b));
  for (const auto& change : std::vector<std::function<void(scene&)>>{
           [](scene& s) { s.source.intensity *= 2; }, [](scene& s) { s.source.width_mm += 1; },
           [](scene& s) { s.sheet().model.values["preset"] = std::string("rf-an"); },
           [](scene& s) { s.observer.width += 1; }, [](scene& s) { s.observer.fov_deg += 1; },
           [](scene& s) { s.half_mirror.reflectance = 0.4; }, [](scene& s) { s.retroreflectors.push_back(s.sheet()); },
           [](scene& s) { s.seed += 1; }}) {
    scene c = b;
    change(c);
    EXPECT_FALSE(differ_in_placement_alone(a, c));
  }
}

TEST(ModelImageRemap, ToItsOwnPlacementItIsTheModelImageItself) {
  const scene s = test::chart_scene("rf-ay", 96, 20);
  const auto view = view_of(s);
  ASSERT_TRUE(view);
  ASSERT_EQ(view->sheets.size(), 1u);
  EXPECT_TRUE(view->sheets[0]->correlations);
  const image_rgb same = remap_layout_model_image(*view, s, model_image_params::for_view());
  ASSERT_EQ(same.rgb.size(), view->image.rgb.size());
  EXPECT_TRUE(same.rgb == view->image.rgb);  // the same paths read the same grids, bit for bit
}

// Each small move of one part (a drag's step): the moved image is far closer to the new
// placement's own model image than the image before the move, or than the coarse first look.
TEST(ModelImageRemap, ASmallMoveIsCloseToTheMovedPlacementsModelImage) {
  const scene a = test::chart_scene("rf-ay", 256, 20);
  const auto from = view_of(a);
  ASSERT_TRUE(from);
  const std::vector<std::pair<std::string, std::function<void(scene&)>>> moves = {
      {"tilt +0.5 deg", [](scene& s) { s.sheet().pose.pitch_deg += 0.5; }},
      {"tilt -0.5 deg", [](scene& s) { s.sheet().pose.pitch_deg -= 0.5; }},
      {"observer 0.5 deg up", [](scene& s) { s.observer.elevation_deg += 0.5; }},
      {"observer 1 deg round", [](scene& s) { s.observer.azimuth_deg += 1; }}};
  for (const auto& [name, move] : moves) {
    scene b = a;
    move(b);
    const auto truth = view_of(b);
    ASSERT_TRUE(truth) << name;
    const image_rgb moved = remap_layout_model_image(*from, b, model_image_params::for_view());
    ASSERT_EQ(moved.rgb.size(), truth->image.rgb.size()) << name;
    const double err = test::relative_rms_of_signal(moved.rgb, truth->image.rgb);
    const double stale = test::relative_rms_of_signal(from->image.rgb, truth->image.rgb);
    const double coarse = test::relative_rms_of_signal(
        model_image_first_look(b, make_sheet_models(b), display_of(b).get()).rgb, truth->image.rgb);
    std::printf("%-22s moved %.2f%%, unmoved %.2f%%, coarse first look %.2f%%\n", name.c_str(), 100 * err, 100 * stale,
                100 * coarse);
    EXPECT_LT(err, 0.01) << name;
    EXPECT_LT(err, 0.5 * stale) << name;
    EXPECT_LT(err, 0.2 * coarse) << name;
  }
}

// Moves beyond the strict limits (a drag faster than view images are made): within the lenient
// ones the moved image is still far closer to the new placement's own model image than the coarse
// first look, which is what a first look falls back to otherwise.
TEST(ModelImageRemap, LenientLimitsMoveFartherStillCloserThanTheCoarseLook) {
  const scene a = test::chart_scene("rf-ay", 128, 0);
  const auto from = view_of(a);
  ASSERT_TRUE(from);
  const model_image_params p = model_image_params::for_view();
  for (const double step : {1.0, 1.5, 2.0, 4.0, 5.0}) {
    scene b = a;
    b.sheet().pose.pitch_deg += step;
    const auto truth = view_of(b);
    ASSERT_TRUE(truth) << step;
    EXPECT_TRUE(remap_layout_model_image(*from, b, p).rgb.empty()) << step;  // beyond the strict limits
    const image_rgb moved = remap_layout_model_image(*from, b, p, nullptr, remap_limits::lenient());
    ASSERT_EQ(moved.rgb.size(), truth->image.rgb.size()) << step;
    const double err = test::relative_rms_of_signal(moved.rgb, truth->image.rgb);
    const double coarse = test::relative_rms_of_signal(
        model_image_first_look(b, make_sheet_models(b), display_of(b).get()).rgb, truth->image.rgb);
    std::printf("tilt +%.1f deg: moved %.2f%%, coarse first look %.2f%%\n", step, 100 * err, 100 * coarse);
    EXPECT_LT(err, 0.03) << step;
    EXPECT_LT(err, 0.3 * coarse) << step;
  }
  scene far = a;
  far.sheet().pose.pitch_deg += 9;
  EXPECT_TRUE(remap_layout_model_image(*from, far, p, nullptr, remap_limits::lenient()).rgb.empty());
}

TEST(ModelImageRemap, RefusesWhatItCannotMove) {
  const scene a = test::chart_scene("rf-ay", 64, 20);
  const auto from = view_of(a);
  ASSERT_TRUE(from);
  const model_image_params p = model_image_params::for_view();
  for (const auto& change : std::vector<std::function<void(scene&)>>{
           [](scene& s) { s.sheet().pose.pitch_deg += 5; },      // bins' angles move by more than a degree
           [](scene& s) { s.sheet().pose.center_mm[2] -= 20; },  // the path to the display grows by 10%
           [](scene& s) { s.observer.distance_mm *= 1.5; },      // the pixels' footprint grows
           [](scene& s) { s.source.intensity *= 2; },            // not a placement
           [](scene& s) { s.sheet().model.values["preset"] = std::string("rf-an"); }}) {  // not a placement
    scene b = a;
    change(b);
    EXPECT_TRUE(remap_layout_model_image(*from, b, p).rgb.empty());
  }
  // A model image that kept no correlations (the control variate's) cannot be moved.
  const auto quick = compute_layout_model_image(a, make_sheet_models(a), display_of(a).get(),
                                                model_image_params::for_image(64, 64, true));
  ASSERT_TRUE(quick);
  EXPECT_FALSE(quick->sheets[0]->correlations);
  EXPECT_TRUE(remap_model_image(*quick->sheets[0], a, p).rgb.empty());
  // Cancelled, it gives nothing.
  const std::atomic<bool> cancel{true};
  EXPECT_TRUE(remap_layout_model_image(*from, a, p, &cancel).rgb.empty());
}
