#include "airr/analysis/image_read.hpp"
#include "airr/core/error.hpp"

#include <stdexcept>

#include "airr/core/color.hpp"

namespace airr::analysis {

cv::Mat to_mat(const image_rgb& img) {
  cv::Mat out(img.height, img.width, CV_64FC3);
  for (int y = 0; y < img.height; ++y) {
    auto* row = out.ptr<cv::Vec3d>(y);
    for (int x = 0; x < img.width; ++x) {
      const float* p = img.at(x, y);
      row[x] = cv::Vec3d(p[0], p[1], p[2]);
    }
  }
  return out;
}

cv::Mat rec709_luminance(const cv::Mat& rgb) {
  if (rgb.channels() != 3) throw measurement_error("rec709_luminance needs a three-channel image");
  cv::Mat rgb64;
  rgb.convertTo(rgb64, CV_64FC3);
  cv::Mat lum(rgb64.size(), CV_64FC1);
  for (int y = 0; y < rgb64.rows; ++y) {
    const auto* src = rgb64.ptr<cv::Vec3d>(y);
    auto* dst = lum.ptr<double>(y);
    for (int x = 0; x < rgb64.cols; ++x) dst[x] = airr::rec709_luminance(src[x][0], src[x][1], src[x][2]);
  }
  return lum;
}

linear_image read_linear_image(const std::filesystem::path& path, const image_read_params& params) {
  loaded_image loaded = load_image(path.string(), params.encoding);
  linear_image out;
  out.path = path;
  out.rgb = to_mat(loaded.pixels);
  out.luminance = rec709_luminance(out.rgb);
  out.mm_per_pixel = loaded.mm_per_pixel;
  out.srgb_decoded = loaded.srgb_decoded;
  out.source_channels = loaded.channels;
  out.source_format = loaded.format;
  return out;
}

}  // namespace airr::analysis
