// LPIPS through an ONNX file: errors for missing, garbage and mis-shaped models, and the data path
// (sRGB encoding, [-1, 1] scaling, NCHW, two inputs) checked with a hand-built distance network.
#include <cmath>
#include <string>

#include <gtest/gtest.h>

#include "airr/analysis/image_read.hpp"
#include "airr/analysis/lpips.hpp"
#include "airr/analysis/onnx_inputs.hpp"
#include "airr/core/color.hpp"
#include "onnx_builder.hpp"
#include "test_files.hpp"

namespace aa = airr::analysis;
namespace at = airr::analysis::testing;
using at::error_of;
namespace onnx = airr::analysis::testing::onnx;

namespace {

cv::Mat colour_pattern(int w, int h, double phase) {
  cv::Mat img(h, w, CV_64FC3);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      img.at<cv::Vec3d>(y, x) = {0.5 + 0.4 * std::sin(0.3 * x + phase), 0.2 + 0.1 * std::cos(0.2 * y),
                                 (x + y) % 7 == 0 ? 1.5 : 0.05};  // 1.5 is clipped to white
  return img;
}

// The distance the hand-built network should return: mean over pixels and channels of
// (2 srgb(a) - 2 srgb(b))^2 with values clipped to [0, 1].
double expected_distance(const cv::Mat& a, const cv::Mat& b) {
  double sum = 0;
  for (int y = 0; y < a.rows; ++y)
    for (int x = 0; x < a.cols; ++x)
      for (int c = 0; c < 3; ++c) {
        const double ea = airr::srgb_encode(std::clamp(a.at<cv::Vec3d>(y, x)[c], 0.0, 1.0));
        const double eb = airr::srgb_encode(std::clamp(b.at<cv::Vec3d>(y, x)[c], 0.0, 1.0));
        sum += std::pow(2.0 * ea - 2.0 * eb, 2);
      }
  return sum / (a.total() * 3.0);
}

}  // namespace

TEST(Lpips, MissingModelFileIsNamed) {
  at::scratch_dir dir("lpips");
  const cv::Mat a = colour_pattern(32, 32, 0);
  const std::string e = error_of([&] { aa::lpips(a, a, dir / "alex_missing.onnx"); });
  EXPECT_NE(e.find("alex_missing.onnx"), std::string::npos) << e;
  EXPECT_NE(e.find("no such file"), std::string::npos) << e;
}

TEST(Lpips, GarbageModelFileIsNamed) {
  at::scratch_dir dir("lpips");
  const cv::Mat a = colour_pattern(32, 32, 0);
  for (const std::string& bytes : {std::string("hello, I am not a neural network\n"), std::string(),
                                   std::string("\x08\x07\x3a\xff\xff\xff\x0f", 7)}) {
    const auto path = dir / "garbage_model.onnx";
    at::write_bytes(path, bytes);
    const std::string e = error_of([&] { aa::lpips(a, a, path); });
    EXPECT_NE(e.find("garbage_model.onnx"), std::string::npos) << e;
    EXPECT_NE(e.find("not an ONNX model"), std::string::npos) << e;
  }
}

TEST(Lpips, ReadsGraphInputs) {
  at::scratch_dir dir("lpips");
  at::write_bytes(dir / "m.onnx", onnx::squared_difference_model(24, -1));
  const auto inputs = aa::read_onnx_inputs(dir / "m.onnx");
  ASSERT_EQ(inputs.size(), 2u);
  EXPECT_EQ(inputs[0].name, "image_a");
  EXPECT_EQ(inputs[1].name, "image_b");
  EXPECT_EQ(inputs[0].shape, (std::vector<std::int64_t>{1, 3, 24, -1}));
}

TEST(Lpips, HandBuiltDistanceNetworkGivesTheExpectedValue) {
  at::scratch_dir dir("lpips");
  const auto path = dir / "squared_difference.onnx";
  at::write_bytes(path, onnx::squared_difference_model(24, 40));
  const cv::Mat a = colour_pattern(40, 24, 0.0), b = colour_pattern(40, 24, 0.7);
  const auto r = aa::lpips(a, b, path);
  EXPECT_FALSE(r.resized);
  EXPECT_NEAR(r.value, expected_distance(a, b), 1e-4 * expected_distance(a, b));
  EXPECT_NEAR(aa::lpips(a, a, path).value, 0.0, 1e-9);
}

TEST(Lpips, FixedModelSizeResizesTheImages) {
  at::scratch_dir dir("lpips");
  const auto path = dir / "small.onnx";
  at::write_bytes(path, onnx::squared_difference_model(16, 16));
  const cv::Mat a(64, 64, CV_64FC3, cv::Scalar::all(0.2)), b(64, 64, CV_64FC3, cv::Scalar::all(0.8));
  const auto r = aa::lpips(a, b, path);
  EXPECT_TRUE(r.resized);
  EXPECT_EQ(r.input_size, cv::Size(16, 16));
  const double d = 2.0 * (airr::srgb_encode(0.8) - airr::srgb_encode(0.2));
  EXPECT_NEAR(r.value, d * d, 1e-4);
}

TEST(Lpips, OtherInputArrangementsAreReported) {
  at::scratch_dir dir("lpips");
  const cv::Mat a = colour_pattern(16, 16, 0);

  onnx::graph_spec one;  // a single input
  one.inputs = {onnx::tensor_info("x", {1, 3, 16, 16})};
  one.nodes = {onnx::node({"x"}, {"y"}, "GlobalAveragePool")};
  one.outputs = {onnx::tensor_info("y", {1, 3, 1, 1})};
  at::write_bytes(dir / "one_input.onnx", onnx::model(one));
  std::string e = error_of([&] { aa::lpips(a, a, dir / "one_input.onnx"); });
  EXPECT_NE(e.find("one_input.onnx"), std::string::npos) << e;
  EXPECT_NE(e.find("two"), std::string::npos) << e;

  onnx::graph_spec nhwc;  // channels last
  nhwc.inputs = {onnx::tensor_info("a", {1, 16, 16, 3}), onnx::tensor_info("b", {1, 16, 16, 3})};
  nhwc.nodes = {onnx::node({"a", "b"}, {"y"}, "Sub")};
  nhwc.outputs = {onnx::tensor_info("y", {1, 16, 16, 3})};
  at::write_bytes(dir / "nhwc.onnx", onnx::model(nhwc));
  e = error_of([&] { aa::lpips(a, a, dir / "nhwc.onnx"); });
  EXPECT_NE(e.find("nhwc.onnx"), std::string::npos) << e;
  EXPECT_NE(e.find("N x 3 x H x W"), std::string::npos) << e;
}

TEST(Lpips, ImagesMustMatch) {
  at::scratch_dir dir("lpips");
  at::write_bytes(dir / "m.onnx", onnx::squared_difference_model(-1, -1));
  EXPECT_THROW(aa::lpips(colour_pattern(16, 16, 0), colour_pattern(17, 16, 0), dir / "m.onnx"), std::runtime_error);
  EXPECT_THROW(aa::lpips(cv::Mat(16, 16, CV_64FC1), cv::Mat(16, 16, CV_64FC1), dir / "m.onnx"), std::runtime_error);
}
