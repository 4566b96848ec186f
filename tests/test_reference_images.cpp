// The renders agree with reference images made by an older build (96af0ca, before the speed work
// of issue 53) at high sample counts with seeds of their own (tests/data/reference_images/README.md):
// a faster tracer must not have changed the answer. Each scene is rendered with two seeds, as the
// references were; the squared differences in 4 x 4 pixel bins over their variances (estimated from
// the two seeds' differences) must come to about one, and those of a render 1% brighter (the prism
// sheet's, whose render is noisier: 2%) must not.
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "airr/core/assets.hpp"
#include "airr/formats/image.hpp"
#include "airr/formats/scene_json.hpp"
#include "test_helpers.hpp"

using namespace airr;

namespace {

constexpr int size = 64, bin = 4;

// Two renders of a scene with two seeds, each as a flat RGB array.
struct seed_pair {
  std::vector<float> a, b;
};

seed_pair reference_of(const std::string& name) {
  const std::string dir = std::string(AIRR_TEST_DATA_DIR) + "/reference_images/";
  seed_pair p;
  for (int i = 0; i < 2; ++i) {
    const loaded_image img = load_image(dir + name + "_" + std::to_string(i + 1) + ".exr");
    EXPECT_EQ(img.pixels.width, size);
    EXPECT_EQ(img.pixels.height, size);
    (i == 0 ? p.a : p.b) = img.pixels.rgb;
  }
  return p;
}

seed_pair render_of(const std::string& scene_file, std::vector<scene_override> overrides, std::uint64_t spp) {
  overrides.push_back({"observer.width", std::to_string(size)});
  overrides.push_back({"observer.height", std::to_string(size)});
  scene s = load_scene(airr::asset_dir() + "/scenes/" + scene_file, overrides);
  seed_pair p;
  s.seed = 1;
  p.a = *test::render_to(s, spp).rgb;
  s.seed = 2;
  p.b = *test::render_to(s, spp).rgb;
  return p;
}

// The squared differences of new and reference over 4 x 4 pixel bins (each channel apart), summed,
// over their variances summed: about 1 when the two agree within their noise. A bin's variance is
// estimated from its two seeds' difference, (one - other)^2 / 4 for the mean of the two, so pixels
// whose noise is correlated (the control variate's) are counted right. The ratio's spread is about
// 2 / sqrt(n), n the bins' effective number (the variances' sum squared over their squares' sum).
struct agreement {
  double ratio = 0, effective_bins = 0;
  double limit() const { return 1 + 8 / std::sqrt(effective_bins); }  // four times the spread
};

agreement agreement_of(const seed_pair& now, const seed_pair& ref, double scale_now = 1.0) {
  double squares = 0, variances = 0, variances_squared = 0;
  for (int by = 0; by < size; by += bin) {
    for (int bx = 0; bx < size; bx += bin) {
      for (int c = 0; c < 3; ++c) {
        double n0 = 0, n1 = 0, r0 = 0, r1 = 0;
        for (int y = by; y < by + bin; ++y) {
          for (int x = bx; x < bx + bin; ++x) {
            const std::size_t i = 3 * (std::size_t(y) * size + x) + std::size_t(c);
            n0 += scale_now * now.a[i];
            n1 += scale_now * now.b[i];
            r0 += ref.a[i];
            r1 += ref.b[i];
          }
        }
        const double d = 0.5 * (n0 + n1) - 0.5 * (r0 + r1);
        const double v = 0.25 * ((n0 - n1) * (n0 - n1) + (r0 - r1) * (r0 - r1));
        squares += d * d;
        variances += v;
        variances_squared += v * v;
      }
    }
  }
  if (!(variances > 0)) return {};
  return {squares / variances, variances * variances / variances_squared};
}

// `seen`: a change of the render's brightness the check must see at these sample counts.
void expect_agrees(const std::string& name, const seed_pair& now, double seen) {
  const seed_pair ref = reference_of(name);
  ASSERT_EQ(now.a.size(), ref.a.size());
  const agreement same = agreement_of(now, ref), changed = agreement_of(now, ref, 1 + seen);
  std::printf("%s: squared differences over variances %.3f (limit %.3f, %.0f effective bins); %.0f%% brighter: %.3f\n",
              name.c_str(), same.ratio, same.limit(), same.effective_bins, 100 * seen, changed.ratio);
  EXPECT_GT(same.effective_bins, 10);
  EXPECT_LT(same.ratio, same.limit()) << name << " differs from its reference beyond the noise";
  EXPECT_GT(changed.ratio, changed.limit()) << name << ": the check cannot see a " << 100 * seen << "% change";
}

}  // namespace

TEST(ReferenceImages, TheDefaultSceneAgreesWithTheOldBuild) {
  expect_agrees("default", render_of("default.json", {}, 256), 0.01);
}

TEST(ReferenceImages, TheKioskAgreesWithTheOldBuild) {
  expect_agrees("kiosk", render_of("two_sheet_kiosk.json", {}, 256), 0.01);
}

TEST(ReferenceImages, ThePrismSheetAgreesWithTheOldBuild) {
  expect_agrees("prism_sheet", render_of("default.json", {{"retroreflectors.0.model.type", "prism_sheet"}}, 128), 0.02);
}
