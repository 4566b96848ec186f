#include "airr/measure/test_charts.hpp"

#include <cmath>
#include <numbers>

namespace airr {

static void fill(image_rgb& img, int x0, int y0, int x1, int y1, float v) {
  for (int y = std::max(0, y0); y < std::min(img.height, y1); ++y) {
    for (int x = std::max(0, x0); x < std::min(img.width, x1); ++x) {
      float* p = img.at(x, y);
      p[0] = p[1] = p[2] = v;
    }
  }
}

// Fraction of the pixel (x, y) on the white side of a line at angle_deg from vertical through (cx, cy).
static float edge_coverage(int x, int y, double cx, double cy, double angle_deg) {
  const double a = angle_deg * std::numbers::pi / 180.0;
  const int n = 8;  // supersamples per side, so the edge is antialiased like a real print
  int white = 0;
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      const double px = x + (i + 0.5) / n - cx, py = y + (j + 0.5) / n - cy;
      if (px * std::cos(a) + py * std::sin(a) < 0) ++white;
    }
  }
  return float(white) / float(n * n);
}

image_rgb make_slanted_edge_chart(int size, double angle_deg) {
  image_rgb img{size, size, std::vector<float>(std::size_t(size) * size * 3)};
  for (int y = 0; y < size; ++y) {
    for (int x = 0; x < size; ++x) {
      float* p = img.at(x, y);
      p[0] = p[1] = p[2] = edge_coverage(x, y, 0.5 * size, 0.5 * size, angle_deg);
    }
  }
  return img;
}

image_rgb make_test_chart(int size) {
  image_rgb img{size, size, std::vector<float>(std::size_t(size) * size * 3, 0.0f)};
  const int h = size / 2, q = size / 4;
  // Top left: slanted edge.
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < h; ++x) {
      float* p = img.at(x, y);
      p[0] = p[1] = p[2] = edge_coverage(x, y, 0.5 * h, 0.5 * h, 5.0);
    }
  }
  // Top right: vertical bar groups with periods of 32, 16, 8 and 4 texels.
  const int periods[] = {32, 16, 8, 4};
  for (int g = 0; g < 4; ++g) {
    const int y0 = 8 + g * (h - 16) / 4, y1 = y0 + (h - 16) / 4 - 8;
    for (int x = h + 8; x < size - 8; ++x) {
      if ((x - h - 8) % periods[g] < periods[g] / 2) fill(img, x, y0, x + 1, y1, 1.0f);
    }
  }
  // Bottom left: a white square and an "F".
  fill(img, q / 4, h + q / 4, q / 4 + q / 2, h + q / 4 + q / 2, 1.0f);
  const int fx = q + q / 4, fy = h + q / 4, fw = q / 2, fs = q / 8;
  fill(img, fx, fy, fx + fs, fy + 2 * q - q / 2, 1.0f);       // stem
  fill(img, fx, fy, fx + fw + fs, fy + fs, 1.0f);             // top bar
  fill(img, fx, fy + q / 2, fx + fw, fy + q / 2 + fs, 1.0f);  // middle bar
  // Bottom right: checkerboard of 16-texel squares.
  for (int y = h; y < size; ++y) {
    for (int x = h; x < size; ++x) {
      if (((x - h) / 16 + (y - h) / 16) % 2 == 0) fill(img, x, y, x + 1, y + 1, 1.0f);
    }
  }
  // A one-texel frame around the whole chart.
  fill(img, 0, 0, size, 1, 1.0f);
  fill(img, 0, size - 1, size, size, 1.0f);
  fill(img, 0, 0, 1, size, 1.0f);
  fill(img, size - 1, 0, size, size, 1.0f);
  return img;
}

}  // namespace airr
