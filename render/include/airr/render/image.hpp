#pragma once
// Linear RGB float images and their files (EXR linear, PNG/JPEG/TIFF sRGB-encoded).
#include <map>
#include <string>
#include <vector>

namespace airr {

struct image_rgb {
  int width = 0;
  int height = 0;
  std::vector<float> rgb;  // row-major from the top-left, 3 floats per pixel

  float* at(int x, int y) { return rgb.data() + 3 * (std::size_t(y) * width + x); }
  const float* at(int x, int y) const { return rgb.data() + 3 * (std::size_t(y) * width + x); }
};

// Loads an image as linear RGB: integer formats are decoded with the sRGB curve, float formats
// (EXR, HDR) are taken as linear; grey is replicated, alpha dropped. Throws input_error.
image_rgb load_image_linear(const std::string& path);

// String metadata written into the file (PNG text chunks, EXR header attributes).
using image_metadata = std::map<std::string, std::string>;

// Writes EXR (float, linear) or PNG (8-bit sRGB after scaling by `exposure`), chosen by the
// extension, atomically (temporary file then rename). Throws input_error.
void write_image(const std::string& path, const image_rgb& img, const image_metadata& meta, float exposure = 1.0f);

// Reads back the string metadata of an image file (only keys starting with "airr:").
image_metadata read_image_metadata(const std::string& path);

float srgb_to_linear(float v);
float linear_to_srgb(float v);

}  // namespace airr
