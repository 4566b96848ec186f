#pragma once
// An image file prepared for measurement: the project's one loader (airr/formats/image.hpp, with
// its linearity rule), seen as OpenCV matrices of doubles with the Rec.709 luminance.
#include <filesystem>
#include <optional>
#include <string>

#include <opencv2/core.hpp>

#include "airr/formats/image.hpp"

namespace airr::analysis {

struct image_read_params {
  image_encoding encoding = image_encoding::automatic;
};

struct linear_image {
  std::filesystem::path path;
  cv::Mat rgb;                         // CV_64FC3, linear RGB (grey files are replicated to three channels)
  cv::Mat luminance;                   // CV_64FC1, Rec.709 luminance of rgb
  std::optional<double> mm_per_pixel;  // from the "airr:mm_per_pixel" attribute, if present
  bool srgb_decoded = false;           // true when code values went through the sRGB curve
  int source_channels = 0;
  std::string source_format;  // e.g. "uint8", "half", "float"
};

// Reads an image by load_image. Throws input_error naming the file on any failure.
linear_image read_linear_image(const std::filesystem::path& path, const image_read_params& params = {});

// An image as CV_64FC3 linear RGB.
cv::Mat to_mat(const image_rgb& img);

// Rec.709 luminance of a CV_64FC3 (or CV_32FC3) linear RGB image, as CV_64FC1.
cv::Mat rec709_luminance(const cv::Mat& rgb);

}  // namespace airr::analysis
