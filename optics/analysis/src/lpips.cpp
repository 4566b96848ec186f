#include "airr/analysis/lpips.hpp"
#include "airr/core/color.hpp"
#include "airr/core/error.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include <opencv2/dnn.hpp>
#include <opencv2/imgproc.hpp>

#include "airr/analysis/image_read.hpp"
#include "airr/analysis/onnx_inputs.hpp"

namespace airr::analysis {

namespace {

std::string shape_text(const onnx_input& in) {
  if (!in.shape_known) return "unknown";
  std::string s = "[";
  for (size_t i = 0; i < in.shape.size(); ++i) {
    if (i) s += " x ";
    s += in.shape[i] > 0 ? std::to_string(in.shape[i]) : std::string("?");
  }
  return s + "]";
}

// sRGB-encoded values scaled to [-1, 1], as an N x 3 x H x W float blob.
cv::Mat to_blob(const cv::Mat& rgb, cv::Size size) {
  cv::Mat linear;
  rgb.convertTo(linear, CV_64FC3);
  if (linear.size() != size) cv::resize(linear, linear, size, 0, 0, cv::INTER_AREA);
  cv::Mat encoded(linear.size(), CV_32FC3);
  for (int y = 0; y < linear.rows; ++y) {
    const auto* src = linear.ptr<cv::Vec3d>(y);
    auto* dst = encoded.ptr<cv::Vec3f>(y);
    for (int x = 0; x < linear.cols; ++x)
      for (int c = 0; c < 3; ++c) {
        const double v = srgb_encode(std::clamp(src[x][c], 0.0, 1.0));
        dst[x][c] = static_cast<float>(2.0 * v - 1.0);
      }
  }
  return cv::dnn::blobFromImage(encoded, 1.0, cv::Size(), cv::Scalar(), false, false, CV_32F);
}

}  // namespace

lpips_result lpips(const cv::Mat& a_rgb, const cv::Mat& b_rgb, const std::filesystem::path& model_path) {
  if (a_rgb.empty() || b_rgb.empty()) throw measurement_error("cannot compare an empty image");
  if (a_rgb.channels() != 3 || b_rgb.channels() != 3)
    throw measurement_error("LPIPS compares three-channel RGB images");
  if (a_rgb.size() != b_rgb.size())
    throw measurement_error("images differ in size: " + std::to_string(a_rgb.cols) + "x" + std::to_string(a_rgb.rows) +
                            " vs " + std::to_string(b_rgb.cols) + "x" + std::to_string(b_rgb.rows));

  const std::string where = model_path.string() + ": ";
  const std::vector<onnx_input> inputs = read_onnx_inputs(model_path);
  if (inputs.size() != 2) {
    std::string names;
    for (const auto& in : inputs) names += (names.empty() ? "" : ", ") + in.name + " " + shape_text(in);
    throw measurement_error(where + "an LPIPS model takes two images (N x 3 x H x W), this one has " +
                            std::to_string(inputs.size()) + " input(s)" +
                            (names.empty() ? std::string() : ": " + names));
  }
  lpips_result result;
  result.input_size = a_rgb.size();
  for (const auto& in : inputs) {
    const bool nchw = !in.shape_known || (in.shape.size() == 4 && (in.shape[0] == -1 || in.shape[0] == 1) &&
                                          (in.shape[1] == -1 || in.shape[1] == 3));
    if (!nchw)
      throw measurement_error(where + "input '" + in.name + "' has shape " + shape_text(in) +
                              ", expected N x 3 x H x W with N = 1");
    if (in.shape_known && in.shape[2] > 0 && in.shape[3] > 0)
      result.input_size = cv::Size(static_cast<int>(in.shape[3]), static_cast<int>(in.shape[2]));
  }
  result.resized = result.input_size != a_rgb.size();

  cv::dnn::Net net;
  try {
    net = cv::dnn::readNetFromONNX(model_path.string());
  } catch (const cv::Exception& e) {
    throw measurement_error(where + "the model cannot be loaded: " + e.err);
  }
  if (net.empty()) throw measurement_error(where + "the model cannot be loaded");

  cv::Mat out;
  try {
    net.setInput(to_blob(a_rgb, result.input_size), inputs[0].name);
    net.setInput(to_blob(b_rgb, result.input_size), inputs[1].name);
    out = net.forward();
  } catch (const cv::Exception& e) {
    throw measurement_error(where + "running the model failed: " + e.err);
  }
  if (out.empty() || out.depth() != CV_32F) throw measurement_error(where + "the model returned no float output");
  // A spatial distance map is averaged to one value.
  const auto* v = out.ptr<float>();
  double sum = 0;
  for (size_t i = 0; i < out.total(); ++i) sum += v[i];
  result.value = sum / static_cast<double>(out.total());
  if (!std::isfinite(result.value)) throw measurement_error(where + "the model returned NaN or inf");
  return result;
}

}  // namespace airr::analysis
