#include "airr/analysis/image_read.hpp"

#include "airr/optics/srgb.hpp"

#include <charconv>
#include <cmath>
#include <stdexcept>
#include <system_error>
#include <vector>

#include <OpenImageIO/imageio.h>

namespace airr::analysis {

namespace {

[[noreturn]] void fail(const std::filesystem::path& path, const std::string& problem) {
  throw std::runtime_error(path.string() + ": " + problem);
}

// Parses the pixel-size attribute, written as a decimal string (or stored as a number).
std::optional<double> read_mm_per_pixel(const std::filesystem::path& path,
                                        const OIIO::ImageSpec& spec) {
  const OIIO::ParamValue* p = spec.find_attribute(mm_per_pixel_attribute);
  if (!p) return std::nullopt;
  double value = 0;
  std::string text;
  if (p->type() == OIIO::TypeString) {
    text = p->get_string();
    const char* begin = text.data();
    const char* end = begin + text.size();
    while (begin != end && *begin == ' ') ++begin;
    while (end != begin && end[-1] == ' ') --end;
    auto [ptr, ec] = std::from_chars(begin, end, value);
    if (ec != std::errc{} || ptr != end) value = std::nan("");
  } else if (p->type().basetype == OIIO::TypeDesc::FLOAT ||
             p->type().basetype == OIIO::TypeDesc::DOUBLE ||
             p->type().basetype == OIIO::TypeDesc::HALF ||
             p->type().basetype == OIIO::TypeDesc::INT) {
    value = p->get_float();
    text = std::to_string(value);
  } else {
    fail(path, std::string("attribute ") + mm_per_pixel_attribute + " has unsupported type " +
                   p->type().c_str());
  }
  if (!std::isfinite(value) || value <= 0)
    fail(path, std::string("attribute ") + mm_per_pixel_attribute +
                   " is not a positive number ('" + text + "')");
  return value;
}

}  // namespace

double srgb_to_linear(double code) { return srgb_decode(code); }

double linear_to_srgb(double linear) { return srgb_encode(linear); }

cv::Mat rec709_luminance(const cv::Mat& rgb) {
  if (rgb.channels() != 3) throw std::runtime_error("rec709_luminance needs a three-channel image");
  cv::Mat rgb64;
  rgb.convertTo(rgb64, CV_64FC3);
  cv::Mat lum(rgb64.size(), CV_64FC1);
  for (int y = 0; y < rgb64.rows; ++y) {
    const auto* src = rgb64.ptr<cv::Vec3d>(y);
    auto* dst = lum.ptr<double>(y);
    for (int x = 0; x < rgb64.cols; ++x)
      dst[x] = 0.2126 * src[x][0] + 0.7152 * src[x][1] + 0.0722 * src[x][2];
  }
  return lum;
}

linear_image read_linear_image(const std::filesystem::path& path, const image_read_params& params) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) fail(path, "no such file");
  if (std::filesystem::is_directory(path, ec)) fail(path, "is a directory, not an image");

  auto in = OIIO::ImageInput::open(path.string());
  if (!in) {
    std::string why = OIIO::geterror();
    if (why.empty()) why = "unknown format";
    fail(path, "cannot read image: " + why);
  }
  const OIIO::ImageSpec& spec = in->spec();
  if (spec.width <= 0 || spec.height <= 0 || spec.nchannels <= 0)
    fail(path, "image has no pixels");
  if (spec.depth > 1) fail(path, "volume images are not supported");

  linear_image out;
  out.path = path;
  out.source_channels = spec.nchannels;
  out.source_format = spec.format.c_str();
  out.mm_per_pixel = read_mm_per_pixel(path, spec);

  const int nch = spec.nchannels;
  std::vector<float> data(static_cast<size_t>(spec.width) * spec.height * nch);
  if (!in->read_image(0, 0, 0, nch, OIIO::TypeDesc::FLOAT, data.data())) {
    std::string why = in->geterror();
    fail(path, "cannot read pixels: " + (why.empty() ? std::string("truncated or corrupt file") : why));
  }
  in->close();

  const auto base = spec.format.basetype;
  const bool is_float = base == OIIO::TypeDesc::FLOAT || base == OIIO::TypeDesc::HALF ||
                        base == OIIO::TypeDesc::DOUBLE;
  out.srgb_decoded = !is_float && !params.linear_input;

  // Channels: grey, grey + alpha, RGB, RGBA (alpha and extra channels are ignored).
  const bool colour = nch >= 3;
  out.rgb.create(spec.height, spec.width, CV_64FC3);
  for (int y = 0; y < spec.height; ++y) {
    auto* row = out.rgb.ptr<cv::Vec3d>(y);
    for (int x = 0; x < spec.width; ++x) {
      const float* px = &data[(static_cast<size_t>(y) * spec.width + x) * nch];
      cv::Vec3d v = colour ? cv::Vec3d(px[0], px[1], px[2]) : cv::Vec3d(px[0], px[0], px[0]);
      if (out.srgb_decoded)
        for (int c = 0; c < 3; ++c) v[c] = srgb_to_linear(v[c]);
      row[x] = v;
    }
  }
  out.luminance = rec709_luminance(out.rgb);
  return out;
}

}  // namespace airr::analysis
