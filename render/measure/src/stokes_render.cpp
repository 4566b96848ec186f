#include "airr/measure/stokes_render.hpp"

#include <cmath>

#include "airr/render/render_session.hpp"

namespace airr {

stokes_images render_stokes(const scene& s, std::uint64_t spp, int threads,
                            const std::function<void(int, std::uint64_t)>& progress) {
  stokes_images out;
  for (int i = 0; i < 4; ++i) {
    render_session session(s, {.threads = threads, .target_spp = spp, .stokes = i});
    const render_snapshot snap = render_to_spp(session, spp, [&](std::uint64_t done) {
      if (progress) progress(i, done);
      return true;
    });
    out.s[std::size_t(i)] = snap.image();
    out.spp = snap.spp;
  }
  out.degree = out.s[0];
  for (std::size_t k = 0; k < out.degree.rgb.size(); ++k) {
    const double s0 = out.s[0].rgb[k], s1 = out.s[1].rgb[k], s2 = out.s[2].rgb[k], s3 = out.s[3].rgb[k];
    out.degree.rgb[k] = s0 > 0 ? float(std::sqrt(s1 * s1 + s2 * s2 + s3 * s3) / s0) : 0.0f;
  }
  return out;
}

}  // namespace airr
