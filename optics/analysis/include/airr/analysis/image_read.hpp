#pragma once

#include <filesystem>
#include <optional>
#include <string>

#include <opencv2/core.hpp>

namespace airr::analysis {

struct image_read_params {
  // Treat 8- and 16-bit code values as linear instead of decoding the sRGB curve.
  bool linear_input = false;
};

struct linear_image {
  std::filesystem::path path;
  cv::Mat rgb;        // CV_64FC3, linear RGB (grey files are replicated to three channels)
  cv::Mat luminance;  // CV_64FC1, Rec.709 luminance of rgb
  std::optional<double> mm_per_pixel;  // from the "airr:mm_per_pixel" attribute, if present
  bool srgb_decoded = false;           // true when integer code values went through the sRGB curve
  int source_channels = 0;
  std::string source_format;           // e.g. "uint8", "half", "float"
};

// Name of the metadata attribute the renderer writes with the pixel size on the aerial-image plane.
inline constexpr const char* mm_per_pixel_attribute = "airr:mm_per_pixel";

// Reads EXR, PNG, TIFF or JPEG. Float files are taken as linear; integer files are decoded with
// the sRGB transfer curve unless params.linear_input is set. Throws std::runtime_error naming
// the file on any failure.
linear_image read_linear_image(const std::filesystem::path& path,
                               const image_read_params& params = {});

// sRGB transfer curve, code value in [0, 1] to linear, and its inverse.
double srgb_to_linear(double code);
double linear_to_srgb(double linear);

// Rec.709 luminance of a CV_64FC3 (or CV_32FC3) linear RGB image, as CV_64FC1.
cv::Mat rec709_luminance(const cv::Mat& rgb);

}  // namespace airr::analysis
