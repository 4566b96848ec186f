// MTF50, mean MTF over (0, 1] lp/mm and the CSV report.
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "airr/analysis/mtf_csv.hpp"
#include "airr/analysis/mtf_metrics.hpp"
#include "airr/analysis/slanted_edge_mtf.hpp"
#include "synthetic_edge.hpp"
#include "test_files.hpp"

namespace aa = airr::analysis;
namespace at = airr::analysis::testing;

namespace {

// Simpson's rule average of the analytic MTF over (0, upper] lp/mm.
double analytic_mean(double sigma_px, bool integrated, double mm_per_pixel, double upper_lp_per_mm) {
  const int n = 2000;
  const double h = upper_lp_per_mm / n;
  double sum = 0;
  for (int i = 0; i <= n; ++i) {
    const double w = (i == 0 || i == n) ? 1 : (i % 2 ? 4 : 2);
    sum += w * at::analytic_mtf(i * h * mm_per_pixel, sigma_px, integrated);
  }
  return sum * h / 3.0 / upper_lp_per_mm;
}

aa::mtf_curve sampled_curve(double sigma_px, double step, double top) {
  aa::mtf_curve c;
  for (double f = 0; f <= top + 1e-12; f += step) {
    c.cycles_per_pixel.push_back(f);
    c.mtf.push_back(at::gaussian_mtf(f, sigma_px));
  }
  return c;
}

}  // namespace

TEST(MeanMtf, GaussianEdgeMatchesAveragedAnalyticCurve) {
  std::printf("\nmean MTF over (0, 1] lp/mm, 5 deg edge 200x200 px\n%-17s %6s %8s %10s %10s\n", "sampling", "sigma",
              "mm/px", "measured", "analytic");
  for (bool integrated : {false, true})
    for (const auto& [sigma, mm] :
         {std::pair{2.0, 0.1}, std::pair{1.0, 0.3}, std::pair{4.0, 0.04}, std::pair{0.7, 0.5}}) {
      at::synthetic_edge_params p;
      p.sigma_px = sigma;
      p.pixel_integrated = integrated;
      const auto curve = aa::slanted_edge_mtf(at::make_slanted_edge(p));
      const auto mean = aa::mean_mtf(curve, mm);
      const double truth = analytic_mean(sigma, integrated, mm, 1.0);
      std::printf("%-17s %6.2f %8.3f %10.5f %10.5f\n", integrated ? "pixel-integrated" : "point-sampled", sigma, mm,
                  mean.value, truth);
      EXPECT_FALSE(mean.clamped);
      EXPECT_DOUBLE_EQ(mean.upper_lp_per_mm, 1.0);
      EXPECT_NEAR(mean.value, truth, 0.01) << "sigma " << sigma << " mm/px " << mm;
    }
}

TEST(MeanMtf, ClampsToNyquistWhenPixelsAreCoarse) {
  at::synthetic_edge_params p;
  p.sigma_px = 0.7;
  const auto curve = aa::slanted_edge_mtf(at::make_slanted_edge(p));
  // 1 mm pixels: Nyquist is 0.5 lp/mm.
  const auto mean = aa::mean_mtf(curve, 1.0);
  EXPECT_TRUE(mean.clamped);
  EXPECT_DOUBLE_EQ(mean.upper_lp_per_mm, 0.5);
  EXPECT_NEAR(mean.value, analytic_mean(0.7, false, 1.0, 0.5), 0.01);
}

TEST(MeanMtf, RejectsBadPixelSize) {
  const auto curve = sampled_curve(1.0, 0.01, 1.0);
  EXPECT_THROW(aa::mean_mtf(curve, 0.0), std::runtime_error);
  EXPECT_THROW(aa::mean_mtf(curve, -1.0), std::runtime_error);
  EXPECT_THROW(aa::mean_mtf(curve, std::nan("")), std::runtime_error);
}

TEST(Mtf50, InterpolatesTheFirstCrossing) {
  const auto curve = sampled_curve(1.0, 0.001, 1.0);
  const auto m50 = aa::mtf50(curve, 0.02);
  ASSERT_TRUE(m50);
  const double truth = std::sqrt(std::log(2.0) / (2.0 * M_PI * M_PI));
  EXPECT_NEAR(m50->cycles_per_pixel, truth, 1e-5);
  EXPECT_NEAR(m50->lp_per_mm, truth / 0.02, 1e-3);
}

TEST(Mtf50, EmptyWhenTheCurveStaysAboveHalf) {
  aa::mtf_curve c;
  c.cycles_per_pixel = {0.0, 0.5, 1.0};
  c.mtf = {1.0, 0.8, 0.6};
  EXPECT_FALSE(aa::mtf50(c));
}

TEST(InterpolateMtf, IsLinearBetweenSamplesAndZeroBeyond) {
  aa::mtf_curve c;
  c.cycles_per_pixel = {0.0, 0.1, 0.2};
  c.mtf = {1.0, 0.6, 0.2};
  EXPECT_DOUBLE_EQ(aa::interpolate_mtf(c, 0.05), 0.8);
  EXPECT_DOUBLE_EQ(aa::interpolate_mtf(c, 0.15), 0.4);
  EXPECT_DOUBLE_EQ(aa::interpolate_mtf(c, 0.0), 1.0);
  EXPECT_DOUBLE_EQ(aa::interpolate_mtf(c, 0.3), 0.0);
}

TEST(MtfCsv, HasHeaderAndOneRowPerFrequency) {
  aa::mtf_curve c;
  c.cycles_per_pixel = {0.0, 0.25, 0.5};
  c.mtf = {1.0, 0.5, 0.125};
  std::istringstream in(aa::format_mtf_csv(c, 0.05));
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line, "cycles_per_pixel,lp_per_mm,mtf");
  std::getline(in, line);
  EXPECT_EQ(line, "0,0,1");
  std::getline(in, line);
  EXPECT_EQ(line, "0.25,5,0.5");
  std::getline(in, line);
  EXPECT_EQ(line, "0.5,10,0.125");
  EXPECT_FALSE(std::getline(in, line));
}

TEST(MtfCsv, WritesAtomicallyAndReplacesOldFile) {
  at::scratch_dir dir("csv");
  const auto path = dir / "mtf.csv";
  at::write_bytes(path, "old contents\n");
  aa::mtf_curve c;
  c.cycles_per_pixel = {0.0, 0.5};
  c.mtf = {1.0, 0.25};
  aa::write_mtf_csv(path, c, 0.1);
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  EXPECT_EQ(text.str(), "cycles_per_pixel,lp_per_mm,mtf\n0,0,1\n0.5,5,0.25\n");
  EXPECT_FALSE(std::filesystem::exists(dir / "mtf.csv.tmp"));
  EXPECT_THROW(aa::write_mtf_csv(dir / "no_such_dir" / "mtf.csv", c, 0.1), std::runtime_error);
}

TEST(MtfSigma, HalvesPredictTheSpreadOfTheFullEstimate) {
  // Thirty renders, each the mean of two independent noisy halves of a slanted edge: the sigma
  // the halves predict matches the spread of the full image's MTF over the thirty.
  const int renders = 30;
  at::synthetic_edge_params p;
  p.sigma_px = 1.5;
  p.noise_sigma = 0.04;
  std::vector<std::vector<double>> full;
  std::vector<double> predicted_var;
  std::vector<double> cycles;
  for (int r = 0; r < renders; ++r) {
    p.seed = 2 * r + 1;
    const cv::Mat a = at::make_slanted_edge(p);
    p.seed = 2 * r + 2;
    const cv::Mat b = at::make_slanted_edge(p);
    const cv::Mat mean = 0.5 * (a + b);
    const aa::mtf_curve ca = aa::slanted_edge_mtf(a), cb = aa::slanted_edge_mtf(b), cm = aa::slanted_edge_mtf(mean);
    ASSERT_EQ(ca.mtf.size(), cm.mtf.size());
    ASSERT_EQ(cb.mtf.size(), cm.mtf.size());
    const std::vector<double> sigma = aa::mtf_sigma_from_halves(ca.mtf, cb.mtf);
    if (predicted_var.empty()) predicted_var.assign(sigma.size(), 0.0), cycles = cm.cycles_per_pixel;
    for (std::size_t i = 0; i < sigma.size(); ++i) predicted_var[i] += sigma[i] * sigma[i] / renders;
    full.push_back(cm.mtf);
  }
  double predicted = 0, measured = 0;
  int count = 0;
  for (std::size_t i = 0; i < cycles.size(); ++i) {
    if (cycles[i] < 0.05 || cycles[i] > 0.5) continue;
    double m = 0, m2 = 0;
    for (const auto& c : full) m += c[i] / renders, m2 += c[i] * c[i] / renders;
    measured += m2 - m * m;
    predicted += predicted_var[i];
    ++count;
  }
  ASSERT_GT(count, 10);
  const double ratio = std::sqrt(predicted / measured);
  std::printf("MTF sigma from halves / spread over %d renders: %.3f (%d frequencies)\n", renders, ratio, count);
  EXPECT_GT(ratio, 0.8);
  EXPECT_LT(ratio, 1.25);
}

TEST(MtfSigma, ReadableUpToStopsAtTheFirstNoisyFrequency) {
  const std::vector<double> f{0, 0.5, 1, 1.5, 2}, sigma{0.01, 0.02, 0.05, 0.01, 0.01};
  EXPECT_DOUBLE_EQ(airr::analysis::readable_up_to(f, sigma, 0.03), 0.5);
  EXPECT_DOUBLE_EQ(airr::analysis::readable_up_to(f, {0.1, 0, 0, 0, 0}, 0.03), 0.0);
  EXPECT_DOUBLE_EQ(airr::analysis::readable_up_to(f, {0, 0, 0, 0, 0}, 0.03), 2.0);
}
