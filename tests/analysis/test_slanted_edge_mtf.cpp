// Slanted-edge MTF against the analytic MTF of Gaussian-blurred edges.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "airr/analysis/mtf_metrics.hpp"
#include "airr/analysis/slanted_edge_mtf.hpp"
#include "synthetic_edge.hpp"

namespace aa = airr::analysis;
namespace at = airr::analysis::testing;

namespace {

struct edge_errors {
  double max_mtf_error = 0;    // max |measured - analytic| for f <= 0.5 cycles/pixel
  double mtf50_error_pct = 0;  // signed, percent of the analytic MTF50
};

edge_errors measure(const at::synthetic_edge_params& p, const aa::slanted_edge_params& sp = {}) {
  const aa::mtf_curve curve = aa::slanted_edge_mtf(at::make_slanted_edge(p), sp);
  edge_errors e;
  for (size_t i = 0; i < curve.cycles_per_pixel.size(); ++i) {
    const double f = curve.cycles_per_pixel[i];
    if (f > 0.5) break;
    e.max_mtf_error =
        std::max(e.max_mtf_error, std::abs(curve.mtf[i] - at::analytic_mtf(f, p.sigma_px, p.pixel_integrated)));
  }
  const auto m50 = aa::mtf50(curve);
  const double truth = at::analytic_mtf50(p.sigma_px, p.pixel_integrated);
  e.mtf50_error_pct = m50 ? 100.0 * (m50->cycles_per_pixel - truth) / truth : 1e9;
  return e;
}

const char* sampling_name(bool integrated) { return integrated ? "pixel-integrated" : "point-sampled"; }

}  // namespace

TEST(SlantedEdgeMtf, NoiseFreeGaussianEdgesMatchAnalyticMtf) {
  std::printf("\nnoise-free 5 deg edges, 200x200 px\n");
  std::printf("%-17s %7s %12s %16s %10s\n", "sampling", "sigma", "max |dMTF|", "MTF50 truth c/p", "MTF50 err");
  for (bool integrated : {false, true})
    for (double sigma : {0.7, 1.0, 2.0, 4.0}) {
      at::synthetic_edge_params p;
      p.sigma_px = sigma;
      p.pixel_integrated = integrated;
      const edge_errors e = measure(p);
      std::printf("%-17s %7.2f %12.5f %16.5f %9.3f%%\n", sampling_name(integrated), sigma, e.max_mtf_error,
                  at::analytic_mtf50(sigma, integrated), e.mtf50_error_pct);
      EXPECT_LT(e.max_mtf_error, 0.01) << sampling_name(integrated) << " sigma " << sigma;
      EXPECT_LT(std::abs(e.mtf50_error_pct), 1.0) << sampling_name(integrated) << " sigma " << sigma;
    }
}

TEST(SlantedEdgeMtf, NoisyGaussianEdgesAtSnr50KeepMtf50Within3Percent) {
  const std::vector<std::uint64_t> seeds = {1, 2, 3, 4, 5};
  std::printf("\n5 deg edges, 200x200 px, Gaussian noise sigma = contrast / 50, seeds 1-5\n");
  std::printf("%-17s %7s %16s %16s %16s\n", "sampling", "sigma", "max |dMTF|", "max |MTF50 err|", "mean MTF50 err");
  for (bool integrated : {false, true})
    for (double sigma : {0.7, 1.0, 2.0, 4.0}) {
      double worst_mtf = 0, worst_m50 = 0, mean_m50 = 0;
      for (std::uint64_t seed : seeds) {
        at::synthetic_edge_params p;
        p.sigma_px = sigma;
        p.pixel_integrated = integrated;
        p.noise_sigma = (p.bright - p.dark) / 50.0;
        p.seed = seed;
        const edge_errors e = measure(p);
        worst_mtf = std::max(worst_mtf, e.max_mtf_error);
        worst_m50 = std::max(worst_m50, std::abs(e.mtf50_error_pct));
        mean_m50 += e.mtf50_error_pct / seeds.size();
        EXPECT_LT(std::abs(e.mtf50_error_pct), 3.0)
            << sampling_name(integrated) << " sigma " << sigma << " seed " << seed;
      }
      std::printf("%-17s %7.2f %16.5f %15.3f%% %15.3f%%\n", sampling_name(integrated), sigma, worst_mtf, worst_m50,
                  mean_m50);
    }
}

TEST(SlantedEdgeMtf, ReportsEdgeAngleAndOrientation) {
  for (double angle : {5.0, -5.0, 8.0, -3.0})
    for (bool horizontal : {false, true}) {
      at::synthetic_edge_params p;
      p.angle_deg = angle;
      p.horizontal = horizontal;
      const auto curve = aa::slanted_edge_mtf(at::make_slanted_edge(p));
      EXPECT_EQ(curve.orientation,
                horizontal ? aa::edge_orientation::near_horizontal : aa::edge_orientation::near_vertical);
      // The synthetic edge runs along dx/dy = tan(angle) (vertical) or dy/dx = tan(angle).
      EXPECT_NEAR(curve.edge_angle_deg, angle, 0.02) << "angle " << angle << " horizontal " << horizontal;
    }
}

TEST(SlantedEdgeMtf, BothOrientationsAndPolaritiesGiveTheSameMtf) {
  const double truth = at::analytic_mtf50(1.5, true);
  for (bool horizontal : {false, true})
    for (bool rising : {true, false}) {
      at::synthetic_edge_params p;
      p.sigma_px = 1.5;
      p.pixel_integrated = true;
      p.horizontal = horizontal;
      p.rising = rising;
      p.width = 180;
      p.height = 240;
      const auto curve = aa::slanted_edge_mtf(at::make_slanted_edge(p));
      EXPECT_EQ(curve.rising, rising);
      const auto m50 = aa::mtf50(curve);
      ASSERT_TRUE(m50);
      EXPECT_NEAR(m50->cycles_per_pixel, truth, 0.01 * truth) << "horizontal " << horizontal << " rising " << rising;
    }
}

TEST(SlantedEdgeMtf, RoiSelectsOneEdgeOfSeveral) {
  // Left half: a sharp edge; right half: a blurred one. Each ROI must see only its own.
  at::synthetic_edge_params sharp, soft;
  sharp.width = soft.width = 120;
  sharp.height = soft.height = 160;
  sharp.sigma_px = 0.8;
  soft.sigma_px = 3.0;
  soft.offset_px = 10;  // off-centre inside its region
  cv::Mat img(160, 240, CV_64FC1);
  at::make_slanted_edge(sharp).copyTo(img(cv::Rect(0, 0, 120, 160)));
  at::make_slanted_edge(soft).copyTo(img(cv::Rect(120, 0, 120, 160)));
  for (const auto& [roi, sigma] :
       {std::pair{cv::Rect(0, 0, 120, 160), 0.8}, std::pair{cv::Rect(120, 0, 120, 160), 3.0}}) {
    aa::slanted_edge_params sp;
    sp.roi = roi;
    const auto curve = aa::slanted_edge_mtf(img, sp);
    EXPECT_EQ(curve.roi, roi);
    const auto m50 = aa::mtf50(curve);
    ASSERT_TRUE(m50);
    const double truth = at::analytic_mtf50(sigma, false);
    EXPECT_NEAR(m50->cycles_per_pixel, truth, 0.01 * truth) << "sigma " << sigma;
  }
}

TEST(SlantedEdgeMtf, AcceptsSinglePrecisionImages) {
  at::synthetic_edge_params p;
  p.sigma_px = 2;
  cv::Mat f32;
  at::make_slanted_edge(p).convertTo(f32, CV_32F);
  const auto m50 = aa::mtf50(aa::slanted_edge_mtf(f32));
  ASSERT_TRUE(m50);
  EXPECT_NEAR(m50->cycles_per_pixel, at::analytic_mtf50(2, false), 0.01 * at::analytic_mtf50(2, false));
}

TEST(SlantedEdgeMtf, FrequencyAxisStartsAtZeroAndReachesOneCyclePerPixel) {
  const auto curve = aa::slanted_edge_mtf(at::make_slanted_edge({}));
  ASSERT_GT(curve.cycles_per_pixel.size(), 100u);
  EXPECT_EQ(curve.cycles_per_pixel.front(), 0.0);
  EXPECT_DOUBLE_EQ(curve.mtf.front(), 1.0);
  EXPECT_NEAR(curve.cycles_per_pixel.back(), 1.0, 0.01);
  EXPECT_TRUE(std::is_sorted(curve.cycles_per_pixel.begin(), curve.cycles_per_pixel.end()));
  EXPECT_DOUBLE_EQ(curve.nyquist_cycles_per_pixel, 0.5);
}

TEST(SlantedEdgeMtf, ConvertsToLinePairsPerMm) {
  const auto lp = aa::to_lp_per_mm({0.0, 0.1, 0.5}, 0.05);
  ASSERT_EQ(lp.size(), 3u);
  EXPECT_DOUBLE_EQ(lp[0], 0.0);
  EXPECT_DOUBLE_EQ(lp[1], 2.0);
  EXPECT_DOUBLE_EQ(lp[2], 10.0);
  EXPECT_THROW(aa::to_lp_per_mm({0.1}, 0.0), std::runtime_error);
}
