#include "airr/models/bead_sheet.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <string>

#include "airr/core/error.hpp"
#include "airr/core/geometry.hpp"
#include "airr/models/dielectric.hpp"
#include "airr/models/diffraction.hpp"
#include "polarized_walk.hpp"

namespace airr {

namespace {

constexpr int max_events = 256;
constexpr long long max_pieces = 100000;  // of a straight stretch, each about a bead spacing long
const double close_packed = pi / (2 * std::sqrt(3.0));

// The first bead the ray p + t d (in the air above the backing) meets at 0 < t < t_end: its
// centre and t. A bead's exposed half is all of it above the backing, so any first root there is
// on it. The stretch is looked at a piece at a time (pieces about a bead spacing long, the beads
// within a radius of each), so a ray that skims the sheet meets its first bead as soon as one
// lies in its way. Empty when none, or after max_pieces.
struct bead_hit {
  double t;
  glm::dvec3 centre;
};
std::optional<bead_hit> first_bead(const bead_sheet_geometry& g, const glm::dvec3& p, const glm::dvec3& d, double t_end,
                                   bool& too_long) {
  const double r = g.diameter_mm / 2, s = g.spacing_mm(), row = s * std::sqrt(3.0) / 2;
  const double across = glm::length(glm::dvec2(d));
  const double step = across > s / t_end ? s / across : t_end;
  const long long pieces = (long long)std::ceil(t_end / step);
  if (pieces > max_pieces) {
    too_long = true;
    return std::nullopt;
  }
  const double eps = 1e-9 * r;
  for (long long k = 0; k < pieces; ++k) {
    const double ta = double(k) * step, tb = std::min(t_end, ta + step);
    const glm::dvec3 a = p + ta * d, b = p + tb * d;
    const double x0 = std::min(a.x, b.x) - r, x1 = std::max(a.x, b.x) + r;
    const double y0 = std::min(a.y, b.y) - r, y1 = std::max(a.y, b.y) + r;
    std::optional<bead_hit> best;
    // Centres (i s + j s / 2, j row): rows j0..j1, and in each row the i whose centre is in [x0, x1].
    for (long long j = (long long)std::floor(y0 / row); j <= (long long)std::ceil(y1 / row); ++j) {
      const double shift = double(j) * s / 2;
      for (long long i = (long long)std::floor((x0 - shift) / s); i <= (long long)std::ceil((x1 - shift) / s); ++i) {
        const glm::dvec3 c(double(i) * s + shift, double(j) * row, -r);
        const glm::dvec3 o = p - c;
        const double bo = glm::dot(d, o), disc = bo * bo - (glm::dot(o, o) - r * r);
        if (disc < 0) continue;
        const double t = -bo - std::sqrt(disc);
        if (t > eps && t < t_end && (!best || t < best->t)) best = bead_hit{t, c};
      }
    }
    // A bead met beyond this piece is met again, first or not, by the pieces it lies near.
    if (best && best->t <= tb) return best;
  }
  return std::nullopt;
}

// Lambertian about n.
glm::dvec3 diffuse_about(const glm::dvec3& n, pcg32& rng) {
  return make_basis(n).to_world(cosine_hemisphere({rng.next_double(), rng.next_double()}));
}

}  // namespace

double bead_sheet_geometry::spacing_mm() const { return diameter_mm * std::sqrt(close_packed / fill_fraction); }

glm::dvec2 bead_cell_point(const bead_sheet_geometry& g, const glm::dvec2& u) {
  const double s = g.spacing_mm();
  return u.x * glm::dvec2(s, 0) + u.y * glm::dvec2(s / 2, s * std::sqrt(3.0) / 2);
}

bead_path trace_bead_sheet(const bead_sheet_geometry& g, const glm::dvec3& wi, const glm::dvec2& entry, pcg32& rng,
                           std::optional<mueller>* polarized) {
  bead_path out;
  if (!(wi.z > 0)) return out;
  std::optional<polarized_walk> light;
  if (polarized) light = polarized_walk::arriving(wi);
  // A mirror backing's reflection, its phases the metal coat's (a diffuse one depolarizes once the
  // light's new direction is drawn).
  const auto off_backing = [&](const glm::dvec3& n, double cos_i, std::complex<double> eta) {
    if (light && !g.diffuse_backing) light->reflect(n, cos_i, eta);
  };
  const double r = g.diameter_mm / 2;
  glm::dvec3 p(entry, 0.0), d = -wi;
  bool in_bead = false;
  glm::dvec3 bead(0.0);  // the centre of the bead the light is in, while it is in one
  double weight = 1;
  int entries = 0, binder = 0;
  for (int event = 0; event < max_events; ++event) {
    if (in_bead) {
      // Across the bead to its surface: the backing below its centre, the air above.
      const glm::dvec3 o = p - bead;
      const double b = glm::dot(d, o);
      const double t = -b + std::sqrt(std::max(0.0, b * b - (glm::dot(o, o) - r * r)));
      p += t * d;
      const glm::dvec3 n = (p - bead) / r;  // outward
      const double cos_out = glm::dot(d, n);
      if (p.z < bead.z) {
        ++out.backing_reflections;
        weight *= g.backing_reflectance;
        off_backing(n, cos_out, metal_coat_index / g.index);
        d = g.diffuse_backing ? diffuse_about(-n, rng) : reflect(d, n);
        if (light && g.diffuse_backing) light->depolarize(d);
        continue;
      }
      if (rng.next_double() < fresnel_dielectric(cos_out, 1 / g.index)) {
        if (light) light->reflect(n, cos_out, 1 / g.index);
        d = reflect(d, n);
        continue;
      }
      const glm::dvec3 leaving = glm::normalize(*refract(d, -n, g.index));
      if (light) light->refract(n, cos_out, 1 / g.index, leaving);
      d = leaving;
      in_bead = false;
      continue;
    }
    // In the air above the backing: a bead, the binder between the beads, or out of the top.
    const double t_end = d.z < 0 ? (-r - p.z) / d.z : d.z > 0 ? (0 - p.z) / d.z : 0.0;
    if (!(t_end > 0)) break;  // running along the sheet
    bool too_long = false;
    const auto hit = first_bead(g, p, d, t_end, too_long);
    if (too_long) break;
    if (hit) {
      p += hit->t * d;
      const glm::dvec3 n = (p - hit->centre) / r;
      const double cos_in = -glm::dot(d, n);
      if (rng.next_double() < fresnel_dielectric(cos_in, g.index)) {
        if (light) light->reflect(n, cos_in, g.index);
        d = reflect(d, n);
        continue;
      }
      const glm::dvec3 entering = glm::normalize(*refract(d, n, 1 / g.index));
      if (light) light->refract(n, cos_in, g.index, entering);
      d = entering;
      bead = hit->centre;
      in_bead = true;
      ++entries;
      continue;
    }
    p += t_end * d;
    if (d.z < 0) {
      ++binder;
      ++out.backing_reflections;
      weight *= g.backing_reflectance;
      off_backing({0, 0, 1}, -d.z, metal_coat_index);
      d = g.diffuse_backing ? diffuse_about({0, 0, 1}, rng) : glm::dvec3(d.x, d.y, -d.z);
      if (light && g.diffuse_backing) light->depolarize(d);
      continue;
    }
    out.wo = d;
    out.shift_mm = glm::dvec2(p) - entry;
    out.weight = weight;
    out.through_bead = entries == 1 && binder == 0;
    if (out.through_bead && g.wavelength_nm > 0) {
      // Through the bead's pupil: a circle of its diameter across the beam. A spread that would
      // send grazing light into the sheet is drawn again (the light leaves, only less spread).
      const basis across = make_basis(out.wo);
      const drawn_light drawn = draw_light(g.light, g.wavelength_nm, rng);
      out.channels = drawn.channels;
      for (int attempt = 0; attempt < 16; ++attempt) {
        const glm::dvec2 f = sample_far_field(aperture{{}, g.diameter_mm}, rng);
        const glm::dvec3 w = glm::normalize(out.wo + drawn.wavelength_nm * 1e-6 * (f.x * across.t + f.y * across.b));
        if (w.z > 0) {
          out.wo = w;
          break;
        }
      }
    }
    if (light) *polarized = light->leaving(out.wo);
    return out;
  }
  out.lost = true;
  out.weight = 0;
  return out;
}

bead_sheet_retro::bead_sheet_retro(const bead_sheet_geometry& g) : g_(g) {
  check_model_numbers("bead_sheet", bead_sheet_retro_kind().fields,
                      {{"diameter_mm", g.diameter_mm},
                       {"index", g.index},
                       {"fill_fraction", g.fill_fraction},
                       {"backing_reflectance", g.backing_reflectance},
                       {"wavelength_nm", g.wavelength_nm}});
}

retro_sample bead_sheet_retro::sample(const glm::dvec3& wi, retro_samples u) const {
  const bead_path path = trace_bead_sheet(g_, wi, bead_cell_point(g_, u.lobe), u.more);
  return {path.wo, path.shift_mm, path.weight, path.through_bead, path.channels};
}

retro_sample bead_sheet_retro::sample_polarized(const glm::dvec3& wi, retro_samples u) const {
  std::optional<mueller> m;
  const bead_path path = trace_bead_sheet(g_, wi, bead_cell_point(g_, u.lobe), u.more, &m);
  // The walk went the sample's way, from the observer's side: the light goes the other.
  if (m) m = reversed_path(*m);
  return {path.wo, path.shift_mm, path.weight, path.through_bead, path.channels, m};
}

const retro_model_kind& bead_sheet_retro_kind() {
  static const retro_model_kind kind = [] {
    retro_model_kind k;
    k.name = "bead_sheet";
    k.help = "Bead sheet traced as geometry: glass spheres half sunk into a mirror or diffuse backing";
    k.fields = {
        number_field("diameter_mm", "mm", 1e-4, 10, 0.06, "Diameter of the glass beads", 0.5),
        number_field("index", "", 1, 3, 1.93, "Refractive index of the glass"),
        number_field("fill_fraction", "", 0.01, 0.9069, 0.8,
                     "Share of the sheet the beads cover (0.9069: close packed)"),
        choice_field("backing", {"mirror", "diffuse"}, "The backing under and between the beads"),
        number_field("backing_reflectance", "", 0, 1, 0.85, "Reflectance of the backing"),
        number_field("wavelength_nm", "nm", 0, 20000, 550,
                     "Wavelength of the diffraction by each bead's pupil (0: none)", 1000),
        spectrum_field(),
    };
    k.make = [](const model_values& v, const model_setting&) -> std::unique_ptr<retro_model> {
      bead_sheet_geometry g;
      g.diameter_mm = v.number("diameter_mm");
      g.index = v.number("index");
      g.fill_fraction = v.number("fill_fraction");
      g.diffuse_backing = v.text("backing") == "diffuse";
      g.backing_reflectance = v.number("backing_reflectance");
      g.wavelength_nm = v.number("wavelength_nm");
      g.light = read_spectrum(v);
      return std::make_unique<bead_sheet_retro>(g);
    };
    return k;
  }();
  return kind;
}

}  // namespace airr
