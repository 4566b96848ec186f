// The model PSF and the rendered slanted edge measure the same MTF; airr psf and airr sweep.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "airr/optics/assets.hpp"
#include "airr/optics/layout.hpp"
#include "airr/optics/retro_model.hpp"
#include "airr/analysis/image_read.hpp"
#include "airr/analysis/mtf_metrics.hpp"
#include "airr/analysis/psf_mtf.hpp"
#include "airr/analysis/slanted_edge_mtf.hpp"
#include "mtf_routes.hpp"
#include "sweep.hpp"
#include "test_charts.hpp"
#include "test_helpers.hpp"

using namespace airr;

namespace {

double env_or(const char* name, double fallback) {
  const char* v = std::getenv(name);
  return v ? std::atof(v) : fallback;
}

// The default layout, an edge chart fine enough (2048 texels over 50 mm: 0.024 mm) that its own
// blur stays far below the pixel's, and a camera of 0.2 mm pixels framing the chart's centre.
scene two_route_scene(const std::string& chart, const char* preset, double d) {
  const int w = int(env_or("W", 128)), h = int(env_or("H", 64));
  const double pixel_mm = env_or("PX", 0.2);
  scene s = test::uniform_source_scene(50.0, w);
  s.camera.width = w;
  s.camera.height = h;
  s.camera.fov_deg = 2.0 * std::atan(0.5 * h * pixel_mm / s.camera.distance_mm) * 180.0 / M_PI;
  s.source.image = chart;
  s.floating_distance_mm = d;
  s.seed = std::uint64_t(env_or("SEED", 1));
  if (preset) {
    s.retroreflector.model.type = retro_model_type::sinc_shift;
    s.retroreflector.model.preset = preset;
    if (const char* c = std::getenv("CMM")) s.retroreflector.model.c_mm = std::atof(c);
    if (const char* c = std::getenv("AMM")) s.retroreflector.model.a_per_mm = std::atof(c);
  }
  return s;
}

void compare_routes(const char* preset) {
  test::temp_dir dir;
  const std::string chart = dir.file("edge.exr");
  write_image(chart, make_slanted_edge_chart(2048), {});
  const auto spp = std::uint64_t(env_or("SPP", 256));
  for (double d : {150.0, 300.0}) {
    const scene s = two_route_scene(chart, preset, d);
    psf_samples ps = scene_psf(s, 100000);
    if (const double t = env_or("TRUNC", 0); t > 0) {
      psf_samples q = ps; q.offset_mm.clear(); q.weight.clear();
      for (std::size_t i = 0; i < ps.offset_mm.size(); ++i) if (std::abs(ps.offset_mm[i].x) < t) { q.offset_mm.push_back(ps.offset_mm[i]); q.weight.push_back(ps.weight[i]); }
      ps = q;
    }
    if (env_or("FIELD", 0) > 0) {
      const auto model = make_retro_model(s.retroreflector.model, s.base_dir);
      const auto cam = make_camera(s);
      psf_samples q;
      const int k = 9;
      for (int i = 0; i < k; ++i) {
        const double y = ((i + 0.5) / k - 0.5) * cam.height * cam.mm_per_pixel;
        const auto part = sample_psf(s, *model, {.samples = 100000 / k, .seed = s.seed + i}, glm::dvec3(0, y, s.floating_distance_mm));
        q.offset_mm.insert(q.offset_mm.end(), part.offset_mm.begin(), part.offset_mm.end());
        q.weight.insert(q.weight.end(), part.weight.begin(), part.weight.end());
      }
      std::printf("centre-psf mean %.4f\n", psf_route_mtf(ps, make_camera(s).mm_per_pixel).mean_mtf);
      ps = q;
    }
    const mtf_summary psf = psf_route_mtf(ps, make_camera(s).mm_per_pixel);
    const auto t0 = std::chrono::steady_clock::now();
    const auto snap = test::render_to(s, spp);
    const auto t1 = std::chrono::steady_clock::now();
    const mtf_summary edge = edge_route_mtf(s, snap, env_or("ROI", 1.0));
    std::printf("render %.2f s (%.3g rays/s), measure %.2f s\n", std::chrono::duration<double>(t1 - t0).count(), snap.rays / snap.seconds, std::chrono::duration<double>(std::chrono::steady_clock::now() - t1).count());
    std::printf("two routes: %s D %.0f: psf %.4f, edge %.4f, diff %+.4f (mtf50 psf %.3f edge %.3f)\n",
                preset ? preset : "ideal", d, psf.mean_mtf, edge.mean_mtf, edge.mean_mtf - psf.mean_mtf,
                psf.mtf50_lp_per_mm.value_or(0), edge.mtf50_lp_per_mm.value_or(0));
    if (env_or("CURVES", 0) > 0) {
      cv::Mat rgb(snap.height, snap.width, CV_32FC3, const_cast<float*>(snap.rgb->data()));
      const auto c = analysis::slanted_edge_mtf(analysis::rec709_luminance(rgb), {.roi = source_image_roi(s, 1.0)});
      const auto pc = analysis::psf_mtf(ps, {.max_lp_per_mm = 1.0, .points = 11, .pixel_mm = snap.mm_per_pixel});
      std::printf("window %.1f px roi %d\n", c.window_half_width_px, c.roi.width);
      for (int k = 0; k <= 10; ++k) std::printf("  f %.1f psf %.4f edge %.4f\n", pc.lp_per_mm[k], pc.mtf[k], analysis::interpolate_mtf(c, pc.lp_per_mm[k] * snap.mm_per_pixel));
    }
    if (env_or("WINDOWED", 0) > 0) {
      cv::Mat rgb(snap.height, snap.width, CV_32FC3, const_cast<float*>(snap.rgb->data()));
      const auto c = analysis::slanted_edge_mtf(analysis::rec709_luminance(rgb), {.roi = source_image_roi(s, 1.0)});
      const double hw = c.window_half_width_px * snap.mm_per_pixel;
      psf_samples q = ps;
      for (std::size_t i = 0; i < q.weight.size(); ++i) {
        const double t = q.offset_mm[i].x / hw;
        q.weight[i] *= std::abs(t) < 1 ? 0.54 + 0.46 * std::cos(M_PI * t) : 0.0;
      }
      std::printf("windowed psf (hw %.1f mm) mean %.4f diff %+.4f\n", hw, psf_route_mtf(q, snap.mm_per_pixel).mean_mtf, edge.mean_mtf - psf_route_mtf(q, snap.mm_per_pixel).mean_mtf);
    }
    if (env_or("SYNTH", 0) > 0) {
      const double ang = 5.0 * M_PI / 180, px = snap.mm_per_pixel;
      std::vector<std::pair<double, double>> u;
      double tot = 0;
      for (std::size_t i = 0; i < ps.weight.size(); ++i) { u.push_back({std::cos(ang) * ps.offset_mm[i].x - std::sin(ang) * ps.offset_mm[i].y, ps.weight[i]}); tot += ps.weight[i]; }
      std::sort(u.begin(), u.end());
      std::vector<double> keys, cum; double acc = 0;
      for (auto& [k, w] : u) { acc += w; keys.push_back(k); cum.push_back(acc / tot); }
      auto esf = [&](double d) { const auto it = std::lower_bound(keys.begin(), keys.end(), d); const std::size_t i = it - keys.begin(); return i == 0 ? 0.0 : cum[i - 1]; };
      cv::Mat img(snap.height, snap.width, CV_64FC1);
      for (int y = 0; y < snap.height; ++y) for (int x = 0; x < snap.width; ++x) {
        double v = 0;
        for (int j = 0; j < 4; ++j) for (int i = 0; i < 4; ++i) {
          const double xx = (x + (i + 0.5) / 4 - 0.5 * snap.width) * px, yy = (y + (j + 0.5) / 4 - 0.5 * snap.height) * px;
          v += esf(std::cos(ang) * xx + std::sin(ang) * yy);
        }
        img.at<double>(y, x) = v / 16;
      }
      const auto c = analysis::slanted_edge_mtf(img, {.roi = source_image_roi(s, 1.0)});
      std::printf("synthetic edge from psf: mean %.4f (window %.1f px)\n", analysis::mean_mtf(c, px).value, c.window_half_width_px);
    }
    EXPECT_NEAR(edge.mean_mtf, psf.mean_mtf, 0.03) << (preset ? preset : "ideal") << " D " << d;
  }
}

}  // namespace

TEST(TwoRoutes, Ideal) { compare_routes(nullptr); }
TEST(TwoRoutes, RfAy) { compare_routes("rf-ay"); }
TEST(TwoRoutes, RfAn) { compare_routes("rf-an"); }
