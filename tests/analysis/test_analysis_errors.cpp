// Bad images give a std::runtime_error that names the problem (and the file, when there is one).
#include <cmath>
#include <fstream>
#include <limits>
#include <string>

#include <gtest/gtest.h>

#include "airr/analysis/edge_file.hpp"
#include "airr/analysis/image_read.hpp"
#include "airr/analysis/slanted_edge_mtf.hpp"
#include "synthetic_edge.hpp"
#include "test_files.hpp"

namespace aa = airr::analysis;
namespace at = airr::analysis::testing;

namespace {

using at::error_of;

std::string mtf_error(const cv::Mat& img, const aa::slanted_edge_params& p = {}) {
  return error_of([&] { aa::slanted_edge_mtf(img, p); });
}

}  // namespace

TEST(SlantedEdgeErrors, FlatImage) {
  EXPECT_NE(mtf_error(cv::Mat(100, 100, CV_64FC1, cv::Scalar(0.5))).find("flat"), std::string::npos);
}

TEST(SlantedEdgeErrors, NoiseWithoutEdge) {
  cv::Mat noise(120, 120, CV_64FC1);
  cv::RNG(7).fill(noise, cv::RNG::NORMAL, 0.5, 0.05);
  EXPECT_NE(mtf_error(noise).find("no edge"), std::string::npos) << mtf_error(noise);
}

TEST(SlantedEdgeErrors, SmoothRampIsNotAnEdge) {
  cv::Mat ramp(120, 120, CV_64FC1);
  for (int y = 0; y < ramp.rows; ++y)
    for (int x = 0; x < ramp.cols; ++x) ramp.at<double>(y, x) = x / 120.0;
  EXPECT_FALSE(mtf_error(ramp).empty());
}

TEST(SlantedEdgeErrors, EdgeAlignedWithPixelAxis) {
  at::synthetic_edge_params p;
  p.angle_deg = 0;
  const std::string e = mtf_error(at::make_slanted_edge(p));
  EXPECT_NE(e.find("tilt"), std::string::npos) << e;
}

TEST(SlantedEdgeErrors, TinyImageAndRoi) {
  at::synthetic_edge_params p;
  p.width = p.height = 12;
  EXPECT_NE(mtf_error(at::make_slanted_edge(p)).find("too small"), std::string::npos);
  aa::slanted_edge_params sp;
  sp.roi = cv::Rect(90, 90, 15, 40);
  EXPECT_NE(mtf_error(at::make_slanted_edge({}), sp).find("too small"), std::string::npos);
}

TEST(SlantedEdgeErrors, RoiOutsideImage) {
  aa::slanted_edge_params sp;
  sp.roi = cv::Rect(150, 150, 100, 100);
  const std::string e = mtf_error(at::make_slanted_edge({}), sp);
  EXPECT_NE(e.find("outside"), std::string::npos) << e;
  sp.roi = cv::Rect(-5, 0, 50, 50);
  EXPECT_NE(mtf_error(at::make_slanted_edge({}), sp).find("outside"), std::string::npos);
}

TEST(SlantedEdgeErrors, NanAndInfinitePixels) {
  cv::Mat img = at::make_slanted_edge({});
  img.at<double>(40, 30) = std::nan("");
  const std::string e = mtf_error(img);
  EXPECT_NE(e.find("NaN"), std::string::npos) << e;
  EXPECT_NE(e.find("(30, 40)"), std::string::npos) << e;
  img.at<double>(40, 30) = std::numeric_limits<double>::infinity();
  EXPECT_NE(mtf_error(img).find("infinite"), std::string::npos);
}

TEST(SlantedEdgeErrors, EmptyAndMultiChannelImages) {
  EXPECT_FALSE(mtf_error(cv::Mat()).empty());
  EXPECT_FALSE(mtf_error(cv::Mat(50, 50, CV_64FC3, cv::Scalar::all(0.5))).empty());
}

TEST(FileErrors, NonexistentFileIsNamed) {
  at::scratch_dir dir("errors");
  const auto path = dir / "missing_edge.exr";
  const std::string e = error_of([&] { aa::read_linear_image(path); });
  EXPECT_NE(e.find("missing_edge.exr"), std::string::npos) << e;
  EXPECT_NE(e.find("no such file"), std::string::npos) << e;
}

TEST(FileErrors, UnreadableFileIsNamed) {
  at::scratch_dir dir("errors");
  const auto path = dir / "garbage_edge.png";
  at::write_bytes(path, "this is not an image at all, just some text\n");
  const std::string e = error_of([&] { aa::read_linear_image(path); });
  EXPECT_NE(e.find("garbage_edge.png"), std::string::npos) << e;
}

TEST(FileErrors, TruncatedPngIsNamed) {
  at::scratch_dir dir("errors");
  const auto good = dir / "good.png";
  cv::Mat codes(64, 64, CV_8UC1);
  cv::RNG(3).fill(codes, cv::RNG::UNIFORM, 0, 255);
  at::write_coded(good, codes);
  std::ifstream in(good, std::ios::binary);
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const auto cut = dir / "cut_edge.png";
  at::write_bytes(cut, bytes.substr(0, bytes.size() / 2));
  const std::string e = error_of([&] { aa::read_linear_image(cut); });
  EXPECT_NE(e.find("cut_edge.png"), std::string::npos) << e;
}

TEST(FileErrors, DirectoryIsNotAnImage) {
  at::scratch_dir dir("errors");
  const std::string e = error_of([&] { aa::read_linear_image(dir.path); });
  EXPECT_NE(e.find("directory"), std::string::npos) << e;
}

TEST(FileErrors, FlatAndNanFilesAreNamedWithTheProblem) {
  at::scratch_dir dir("errors");
  const auto flat = dir / "flat_grey.exr";
  at::write_exr(flat, cv::Mat(64, 64, CV_64FC1, cv::Scalar(0.25)));
  std::string e = error_of([&] { aa::measure_edge_file(flat); });
  EXPECT_NE(e.find("flat_grey.exr"), std::string::npos) << e;
  EXPECT_NE(e.find("flat"), std::string::npos) << e;

  cv::Mat img = at::make_slanted_edge({});
  img.at<double>(10, 20) = std::nan("");
  const auto nan = dir / "nan_edge.exr";
  at::write_exr(nan, img);
  e = error_of([&] { aa::measure_edge_file(nan); });
  EXPECT_NE(e.find("nan_edge.exr"), std::string::npos) << e;
  EXPECT_NE(e.find("NaN"), std::string::npos) << e;

  const auto tiny = dir / "tiny_edge.exr";
  at::synthetic_edge_params p;
  p.width = p.height = 10;
  at::write_exr(tiny, at::make_slanted_edge(p));
  e = error_of([&] { aa::measure_edge_file(tiny); });
  EXPECT_NE(e.find("tiny_edge.exr"), std::string::npos) << e;
  EXPECT_NE(e.find("too small"), std::string::npos) << e;
}

TEST(FileErrors, BadPixelSizeAttributeIsNamed) {
  at::scratch_dir dir("errors");
  const auto path = dir / "bad_attr.exr";
  at::write_exr(path, at::make_slanted_edge({}), at::attribute_kind::string, "0.1mm");
  const std::string e = error_of([&] { aa::read_linear_image(path); });
  EXPECT_NE(e.find("bad_attr.exr"), std::string::npos) << e;
  EXPECT_NE(e.find("airr:mm_per_pixel"), std::string::npos) << e;
}
