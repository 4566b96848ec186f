#pragma once
// What the designer's tests under Xvfb share: running airr-studio with arguments, reading its
// screenshot and the regions it reports, and measuring what a region shows.
#include <array>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include <OpenImageIO/imageio.h>
#include <nlohmann/json.hpp>

#include "test_helpers.hpp"

namespace airr::test::gui {

struct rgb8_image {
  int width = 0, height = 0;
  std::vector<unsigned char> px;
  const unsigned char* at(int x, int y) const { return px.data() + 3 * (std::size_t(y) * width + x); }
};

inline rgb8_image read_png(const std::string& path) {
  auto in = OIIO::ImageInput::open(path);
  if (!in) return {};
  rgb8_image img{in->spec().width, in->spec().height, {}};
  img.px.resize(std::size_t(img.width) * img.height * 3);
  in->read_image(0, 0, 0, 3, OIIO::TypeDesc::UINT8, img.px.data());
  return img;
}

struct region_stats {
  double mean = 0, stddev = 0;
  int count = 0;
};

// Mean and spread of grey level inside r, optionally excluding the rectangle `hole`.
inline region_stats grey_stats(const rgb8_image& img, const std::array<int, 4>& r,
                               const std::array<int, 4>* hole = nullptr) {
  double sum = 0, sum2 = 0;
  int n = 0;
  for (int y = std::max(0, r[1]); y < std::min(img.height, r[3]); ++y) {
    for (int x = std::max(0, r[0]); x < std::min(img.width, r[2]); ++x) {
      if (hole && x >= (*hole)[0] && x < (*hole)[2] && y >= (*hole)[1] && y < (*hole)[3]) continue;
      const unsigned char* p = img.at(x, y);
      const double g = (p[0] + p[1] + p[2]) / 3.0;
      sum += g;
      sum2 += g * g;
      ++n;
    }
  }
  region_stats s;
  s.count = n;
  if (n) {
    s.mean = sum / n;
    s.stddev = std::sqrt(std::max(0.0, sum2 / n - s.mean * s.mean));
  }
  return s;
}

// Pixels close to a curve colour (the plot palette's first two entries).
inline int curve_pixels(const rgb8_image& img, const std::array<int, 4>& r, std::array<int, 3> colour) {
  int n = 0;
  for (int y = std::max(0, r[1]); y < std::min(img.height, r[3]); ++y) {
    for (int x = std::max(0, r[0]); x < std::min(img.width, r[2]); ++x) {
      const unsigned char* p = img.at(x, y);
      if (std::abs(p[0] - colour[0]) + std::abs(p[1] - colour[1]) + std::abs(p[2] - colour[2]) < 60) ++n;
    }
  }
  return n;
}

inline std::array<int, 4> region(const nlohmann::json& j, const char* name) {
  const auto& r = j.at("regions").at(name);
  return {int(r[0].get<double>()) + 1, int(r[1].get<double>()) + 1, int(r[2].get<double>()) - 1,
          int(r[3].get<double>()) - 1};
}

// Runs the designer under Xvfb with `args` (its own config directory); exit status and log.
struct studio_run {
  int status = -1;
  std::string log;
};
inline studio_run run_studio(const test::temp_dir& dir, const std::string& args) {
  const std::string cmd = "XDG_CONFIG_HOME=" + dir.file("config") + " XDG_STATE_HOME=" + dir.file("state") +
                          " xvfb-run -a -s '-screen 0 1600x1000x24' " + std::string(AIRR_STUDIO) + " " + args + " > " +
                          dir.file("log.txt") + " 2>&1";
  studio_run r;
  r.status = std::system(cmd.c_str());
  std::ifstream log(dir.file("log.txt"));
  r.log.assign((std::istreambuf_iterator<char>(log)), std::istreambuf_iterator<char>());
  return r;
}

}  // namespace airr::test::gui
