// PNG line plots: white background, axes, legend, one colour per curve.
#include <cmath>

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

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

// A 2 x 2 grid with values 0, 1/3, 2/3, 1: each cell takes the viridis colour of its value, rows
// run upwards, the marker is drawn at its coordinates, and bad grids are refused.
TEST(PlotPng, HeatmapCellsTakeTheirValuesColoursWithYUp) {
  aa::heatmap_params p;
  p.x_min = 0;
  p.x_max = 10;
  p.y_min = 0;
  p.y_max = 10;
  p.marker = std::pair{10.0, 10.0};
  p.marker_label = "observer";
  const std::vector<double> v = {0.0, 1.0 / 3, 2.0 / 3, 1.0};  // row 0 (y = 0): 0, 1/3
  const cv::Mat img = aa::render_heatmap(v, 2, 2, p);
  ASSERT_EQ(img.cols, p.width);
  ASSERT_EQ(img.rows, p.height);
  cv::Mat codes(1, 4, CV_8U), colours;
  for (int k = 0; k < 4; ++k) codes.at<unsigned char>(k) = static_cast<unsigned char>(std::lround(255 * v[k]));
  cv::applyColorMap(codes, colours, cv::COLORMAP_VIRIDIS);
  // The plot area: 90 px from the left, 140 from the right, 25 from the top, 75 from the bottom.
  const cv::Rect area(90, 25, p.width - 230, p.height - 100);
  const int qx = area.width / 4, qy = area.height / 4;
  const cv::Point lower_left(area.x + qx, area.y + 3 * qy), lower_right(area.x + 3 * qx, area.y + 3 * qy);
  const cv::Point upper_left(area.x + qx, area.y + qy);
  EXPECT_EQ(img.at<cv::Vec3b>(lower_left), colours.at<cv::Vec3b>(0));
  EXPECT_EQ(img.at<cv::Vec3b>(lower_right), colours.at<cv::Vec3b>(1));
  EXPECT_EQ(img.at<cv::Vec3b>(upper_left), colours.at<cv::Vec3b>(2));
  // The marker's white ring sits in the top-right cell, centred on node (10, 10).
  const cv::Rect around(area.x + 3 * qx - 12, area.y + qy - 12, 24, 24);
  EXPECT_GT(count_near(img, around, cv::Scalar(255, 255, 255), 10), 20);
  EXPECT_THROW(aa::render_heatmap({0.0, 1.0}, 2, 2, p), std::runtime_error);
  p.value_max = p.value_min;
  EXPECT_THROW(aa::render_heatmap(v, 2, 2, p), std::runtime_error);
}
