#pragma once

#include <filesystem>

#include <opencv2/core.hpp>

namespace airr::analysis {

struct lpips_result {
  double value = 0;
  cv::Size input_size;   // size the images were fed at
  bool resized = false;  // the model has a fixed input size different from the images
};

// LPIPS distance between two linear RGB images (CV_64FC3 or CV_32FC3, same size) using an ONNX
// model that takes two N x 3 x H x W inputs of sRGB-encoded values scaled to [-1, 1] and returns
// the distance (a map is averaged). Throws std::runtime_error naming the model file when it is
// missing, unreadable or has a different input arrangement.
lpips_result lpips(const cv::Mat& a_rgb, const cv::Mat& b_rgb, const std::filesystem::path& model_path);

}  // namespace airr::analysis
