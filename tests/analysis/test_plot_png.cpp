// PNG line plots: white background, axes, legend, one colour per curve.
#include <cmath>

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>

#include "airr/analysis/plot_png.hpp"
#include "test_files.hpp"

namespace aa = airr::analysis;
namespace at = airr::analysis::testing;

namespace {

std::vector<aa::plot_series> two_curves(bool labelled) {
  aa::plot_series a, b;
  for (int i = 0; i <= 100; ++i) {
    const double f = i * 0.05;
    a.x.push_back(f);
    a.y.push_back(std::exp(-0.3 * f * f));
    b.x.push_back(f);
    b.y.push_back(std::exp(-1.0 * f * f));
  }
  if (labelled) {
    a.label = "sharp";
    b.label = "blurred";
  }
  return {a, b};
}

int count_near(const cv::Mat& img, const cv::Rect& area, const cv::Scalar& bgr, int tol) {
  int n = 0;
  for (int y = area.y; y < area.y + area.height; ++y)
    for (int x = area.x; x < area.x + area.width; ++x) {
      const auto p = img.at<cv::Vec3b>(y, x);
      if (std::abs(p[0] - bgr[0]) <= tol && std::abs(p[1] - bgr[1]) <= tol && std::abs(p[2] - bgr[2]) <= tol) ++n;
    }
  return n;
}

}  // namespace

TEST(PlotPng, WritesAReadablePlotWithAxesCurvesAndLegend) {
  at::scratch_dir dir("plot");
  const auto path = dir / "mtf.png";
  aa::plot_params p;
  p.title = "test plot";
  aa::write_plot_png(path, two_curves(true), p);
  EXPECT_FALSE(std::filesystem::exists(dir / "mtf.png.tmp"));
  const cv::Mat img = cv::imread(path.string(), cv::IMREAD_COLOR);
  ASSERT_FALSE(img.empty());
  EXPECT_EQ(img.size(), cv::Size(p.width, p.height));
  const cv::Rect all(0, 0, img.cols, img.rows);
  // White background in the corners, black axes and text, both curve colours present.
  EXPECT_EQ(img.at<cv::Vec3b>(2, 2), cv::Vec3b(255, 255, 255));
  EXPECT_EQ(img.at<cv::Vec3b>(img.rows - 3, img.cols - 3), cv::Vec3b(255, 255, 255));
  EXPECT_GT(count_near(img, all, {0, 0, 0}, 10), 500);
  EXPECT_GT(count_near(img, all, aa::plot_palette_colour(0), 8), 200);
  EXPECT_GT(count_near(img, all, aa::plot_palette_colour(1), 8), 200);
  EXPECT_NE(aa::plot_palette_colour(0), aa::plot_palette_colour(1));
}

TEST(PlotPng, LegendAppearsOnlyForLabelledSeries) {
  // The curves stay in the lower part of the top-right corner, so dark pixels there are legend.
  const cv::Mat with = aa::render_plot(two_curves(true));
  const cv::Mat without = aa::render_plot(two_curves(false));
  const cv::Rect corner(with.cols - 300, 30, 260, 60);
  EXPECT_GT(count_near(with, corner, {0, 0, 0}, 60), 100);
  EXPECT_EQ(count_near(without, corner, {0, 0, 0}, 60), 0);
}

TEST(PlotPng, HasTickLabelsBelowAndLeftOfTheAxes) {
  const cv::Mat img = aa::render_plot(two_curves(false));
  // Bottom margin (tick labels and x title) and left margin (tick labels and y title) hold text.
  EXPECT_GT(count_near(img, cv::Rect(100, img.rows - 70, img.cols - 150, 65), {0, 0, 0}, 60), 200);
  EXPECT_GT(count_near(img, cv::Rect(0, 40, 85, img.rows - 140), {0, 0, 0}, 60), 200);
}

TEST(PlotPng, RejectsMismatchedSeriesAndBadPaths) {
  aa::plot_series bad;
  bad.x = {0, 1};
  bad.y = {0};
  EXPECT_THROW(aa::render_plot({bad}), std::runtime_error);
  EXPECT_THROW(aa::write_plot_png("/nonexistent_dir_for_airr_test/plot.png", two_curves(true)), std::runtime_error);
}
