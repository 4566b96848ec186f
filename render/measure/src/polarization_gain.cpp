#include "airr/measure/polarization_gain.hpp"

#include <vector>

#include "airr/core/color.hpp"
#include "airr/core/error.hpp"
#include "airr/render/render_session.hpp"
#include "airr/render/tracer.hpp"

namespace airr {

scene with_plain_half_mirror(const scene& s) {
  scene plain = s;
  plain.half_mirror.kind = half_mirror_kind::half_mirror;
  plain.half_mirror.reflectance = plain.half_mirror.transmittance = 0.5;
  plain.source.films.clear();
  plain.half_mirror.films.clear();
  for (auto& r : plain.retroreflectors) r.films.clear();
  return plain;
}

namespace {

// The aerial component's luminance, pixel by pixel.
std::vector<double> aerial_luminance(const scene& s, std::uint64_t spp, int threads) {
  render_session session(s, {.threads = threads, .target_spp = spp, .components = true});
  const render_snapshot snap = render_to_spp(session, spp);
  const image_rgb img = snap.component_image(component_aerial);
  std::vector<double> y(std::size_t(img.width) * img.height);
  for (int row = 0; row < img.height; ++row) {
    for (int x = 0; x < img.width; ++x) {
      const float* p = img.at(x, row);
      y[std::size_t(row) * img.width + x] = rec709_luminance(p[0], p[1], p[2]);
    }
  }
  return y;
}

}  // namespace

polarization_gain measure_polarization_gain(const scene& s, std::uint64_t spp, int threads,
                                            const std::function<void(int)>& progress) {
  if (progress) progress(0);
  const std::vector<double> plain = aerial_luminance(with_plain_half_mirror(s), spp, threads);
  if (progress) progress(1);
  const std::vector<double> own = aerial_luminance(s, spp, threads);
  if (progress) progress(2);
  polarization_gain g;
  g.spp = spp;
  for (std::size_t i = 0; i < plain.size(); ++i) {
    g.aerial += own[i];
    g.half_mirror += plain[i];
  }
  if (!(g.half_mirror > 0))
    throw measurement_error("gain: with a plain half mirror the layout shows no aerial image in view");
  return g;
}

}  // namespace airr
