#include "airr/models/plate.hpp"

#include <algorithm>
#include <cmath>

#include "airr/core/geometry.hpp"
#include "airr/models/dielectric.hpp"

namespace airr {

namespace {

using complex = std::complex<double>;

// A face's amplitude ratios for light arriving from outside (air into glass) and from inside,
// transmissions scaled so that their squares are the intensities passed.
struct face_amplitudes {
  complex rs, rp, ts, tp;
};

face_amplitudes coated(const coating_params& c, double cos_i, double eta) {
  if (c.kind == coating_kind::partial_mirror) {
    return {-std::sqrt(c.rs), std::polar(std::sqrt(c.rp), radians(c.phase_deg)), std::sqrt(c.ts), std::sqrt(c.tp)};
  }
  if (c.kind == coating_kind::anti_reflection) {
    const double r = std::sqrt(c.residual), t = std::sqrt(1 - c.residual);
    return {-r, r, t, t};
  }
  const fresnel_coefficients f = fresnel_amplitudes(cos_i, eta);
  // Transmitted intensity |t|^2 Re(eta cos_t) / cos_i: its square root goes into the amplitude.
  const double energy = cos_i > 0 ? std::max(0.0, (eta * f.cos_t).real()) / cos_i : 0.0;
  return {f.rs, f.rp, f.ts * std::sqrt(energy), f.tp * std::sqrt(energy)};
}

plate_path path_of(complex as, complex ap, double advance) {
  return {as, ap, 0.5 * (std::norm(as) + std::norm(ap)), advance};
}

}  // namespace

plate_paths plate_paths_at(const plate_params& p, double cos_i, bool at_front) {
  cos_i = std::clamp(cos_i, 0.0, 1.0);
  const double sin_t = std::sqrt(1 - cos_i * cos_i) / p.index;
  const double cos_t = std::sqrt(1 - sin_t * sin_t);
  const coating_params& near = at_front ? p.front : p.back;
  const coating_params& far = at_front ? p.back : p.front;
  const face_amplitudes near_out = coated(near, cos_i, p.index), near_in = coated(near, cos_t, 1 / p.index);
  const face_amplitudes far_in = coated(far, cos_t, 1 / p.index);

  plate_paths out;
  out.tan_t = sin_t / cos_t;
  // Into the glass and to the far face; each round trip reflects once at each face inside.
  complex s = near_out.ts, pp = near_out.tp;
  out.reflected[0] = path_of(near_out.rs, near_out.rp, 0);
  for (int k = 0; k < plate_orders; ++k) {
    out.transmitted[std::size_t(k)] = path_of(s * far_in.ts, pp * far_in.tp, (2 * k + 1) * out.tan_t);
    s *= far_in.rs;
    pp *= far_in.rp;
    if (k + 1 < plate_orders)
      out.reflected[std::size_t(k + 1)] = path_of(s * near_in.ts, pp * near_in.tp, 2 * (k + 1) * out.tan_t);
    s *= near_in.rs;
    pp *= near_in.rp;
  }
  for (int k = 0; k < plate_orders; ++k) {
    out.reflected_total += out.reflected[std::size_t(k)].weight;
    out.transmitted_total += out.transmitted[std::size_t(k)].weight;
  }
  return out;
}

}  // namespace airr
