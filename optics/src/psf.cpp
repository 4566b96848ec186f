#include "airr/optics/psf.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>

#include "airr/optics/error.hpp"
#include "airr/optics/layout.hpp"
#include "airr/optics/random.hpp"

namespace airr {

namespace {

// Where the ray meets the part's plane (ahead of the origin), if inside the rectangle.
std::optional<glm::dvec3> hit_part(const part_frame& f, const glm::dvec3& o, const glm::dvec3& d, bool bounded = true) {
  const double denom = glm::dot(d, f.n);
  if (std::abs(denom) < 1e-15) return std::nullopt;
  const double t = glm::dot(f.center - o, f.n) / denom;
  if (t <= 1e-9) return std::nullopt;
  const glm::dvec3 p = o + t * d;
  if (bounded) {
    const glm::dvec2 l = part_local(f, p);
    if (std::abs(l.x) > 0.5 * f.width || std::abs(l.y) > 0.5 * f.height) return std::nullopt;
  }
  return p;
}

glm::dvec3 reflect(const glm::dvec3& d, const glm::dvec3& n) { return d - 2.0 * glm::dot(d, n) * n; }

}  // namespace

double psf_samples::brightness() const {
  double sum = 0;
  for (double w : weight) sum += w;
  return launched ? sum / double(launched) : 0.0;
}

psf_samples sample_psf(const scene& s, const retro_model& model, const psf_params& p) {
  return sample_psf(s, model, p, glm::dvec3(0, 0, s.floating_distance_mm));
}

psf_samples sample_psf(const scene& s, const retro_model& model, const psf_params& p, const glm::dvec3& aerial_point) {
  const part_frame hm = half_mirror_frame(s), rr = retroreflector_frame(s), src = source_frame(s);
  const pinhole_camera cam = make_camera(s);
  const glm::dvec3 d0 = glm::normalize(aerial_point - cam.position);
  const auto p1 = hit_part(hm, cam.position, d0);
  if (!p1) throw input_error("psf: the camera ray through the aerial image misses the half mirror");
  const auto p2 = hit_part(rr, *p1, d0);
  if (!p2 || glm::dot(d0, rr.n) >= 0) throw input_error("psf: the camera ray misses the retroreflector's front");

  // The ideal landing point: exactly back, mirrored down to the source plane.
  const auto q1 = hit_part(hm, *p2, -d0);
  const auto q2 = q1 ? hit_part(src, *q1, reflect(-d0, hm.n), false) : std::nullopt;
  if (!q2) throw input_error("psf: the retroreflected chief ray misses the source plane");
  const glm::dvec3 ideal = *q2;

  psf_samples out;
  out.launched = p.samples;
  out.rr_distance_mm = glm::length(*p2 - aerial_point);
  const glm::dvec3 wi(-glm::dot(d0, rr.u), -glm::dot(d0, rr.v), -glm::dot(d0, rr.n));
  out.incidence_deg = std::acos(std::clamp(wi.z, -1.0, 1.0)) * 180.0 / std::numbers::pi;
  out.offset_mm.reserve(p.samples);
  out.weight.reserve(p.samples);
  const double hm_factor = s.half_mirror.reflectance * s.half_mirror.transmittance;

  for (std::uint64_t i = 0; i < p.samples; ++i) {
    pcg32 rng = sample_rng(i, 0, p.seed);
    retro_randoms r;
    for (auto& u : r.u) u = rng.next_double();
    const retro_sample rs = model.sample(wi, r);
    if (!(rs.weight > 0)) continue;
    const glm::dvec3 dir = rs.wo.x * rr.u + rs.wo.y * rr.v + rs.wo.z * rr.n;
    const glm::dvec3 origin = *p2 + rs.shift_mm.x * rr.u + rs.shift_mm.y * rr.v;
    const auto a = hit_part(hm, origin, dir);
    if (!a) continue;
    const auto b = hit_part(src, *a, reflect(dir, hm.n), false);
    if (!b) continue;
    // The image of a point shows where rays land relative to the ideal point, point-mirrored;
    // source (u, v) map to aerial (x, y).
    const glm::dvec3 delta = *b - ideal;
    out.offset_mm.emplace_back(-glm::dot(delta, src.u), -glm::dot(delta, src.v));
    out.weight.push_back(rs.weight * hm_factor);
  }
  return out;
}

double energy_radius(const psf_samples& psf, double fraction) {
  std::vector<std::pair<double, double>> rw(psf.offset_mm.size());
  double total = 0;
  for (std::size_t i = 0; i < rw.size(); ++i) {
    rw[i] = {glm::length(psf.offset_mm[i]), psf.weight[i]};
    total += psf.weight[i];
  }
  if (total <= 0) return 0;
  std::sort(rw.begin(), rw.end());
  double acc = 0;
  for (const auto& [r, w] : rw) {
    acc += w;
    if (acc >= fraction * total) return r;
  }
  return rw.back().first;
}

}  // namespace airr
