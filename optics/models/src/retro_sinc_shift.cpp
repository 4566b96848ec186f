#include "airr/models/retro_sinc_shift.hpp"

#include <algorithm>
#include <cmath>
#include <typeinfo>

#include "airr/core/error.hpp"
#include "airr/core/files.hpp"
#include "airr/core/geometry.hpp"
#include "airr/models/sinc_lobe.hpp"

namespace airr {

sinc_shift_params resolve_sinc_shift_params(const model_values& v, const model_setting& setting) {
  sinc_shift_params p;
  const std::string preset_name = v.text("preset");
  const auto a = v.optional_number("a_per_mm"), mu = v.optional_number("mu"), c = v.optional_number("c_mm"),
             r = v.optional_number("reference_distance_mm"), n = v.optional_number("shift_index");
  if (!preset_name.empty()) {
    const sheet_preset preset = load_preset(preset_name, setting.base_dir);
    p.theta_deg = preset.theta_deg;
    p.a_per_mm = preset.a_per_mm;
    p.mu = preset.mu;
    p.c_mm = preset.c_mm;
    p.reference_distance_mm = preset.reference_distance_mm;
    p.shift_index = preset.shift_index;
    p.shift_table = preset.shift_table;
    p.polarization = preset.polarization;
  } else if (!a) {
    v.fail("a_per_mm", "needed by the sinc_shift model without a preset");
  }
  if (a) p.a_per_mm = {*a};
  if (mu) p.mu = {*mu};
  if (c) p.c_mm = *c;
  if (r) p.reference_distance_mm = *r;
  if (n) p.shift_index = *n;
  if (const std::string table = v.text("shift_table"); !table.empty())
    p.shift_table = resolve_path(table, setting.base_dir);
  if (v.text("lookup") == "per_render") p.lookup_angle_deg = setting.chief_incidence_deg;
  return p;
}

sinc_shift_params resolve_sinc_shift_params(const retro_model_params& p, const model_setting& setting) {
  return resolve_sinc_shift_params(model_values(p, sinc_shift_retro_kind().fields, "model"), setting);
}

const retro_model_kind& sinc_shift_retro_kind() {
  static const retro_model_kind kind = [] {
    retro_model_kind k;
    k.name = "sinc_shift";
    k.help = "The paper's model: a sinc^2 angular spread and a corner-cube exit shift";
    k.fields = {
        text_field("preset", field_kind::preset,
                   "A sheet preset: a name in assets/presets (rf-ay, rf-an) or a JSON file"),
        optional_number_field("mu", "", 0, 1, false, "Reflectance weight; unset: the preset's mu(theta)"),
        optional_number_field("a_per_mm", "1/mm", 0, 1000, true, "Spread parameter a; unset: the preset's a(theta)",
                              20),
        optional_number_field("c_mm", "mm", 0, 100, false, "Corner size c (0: no exit shift); unset: the preset's c",
                              3),
        optional_number_field("reference_distance_mm", "mm", 0, 1e5, true,
                              "Reference distance R; unset: the preset's, else 300", 1000),
        optional_number_field("shift_index", "", 1, 3, false,
                              "Index in front of the cube corners: the shift table is read at the angle inside; "
                              "unset: the preset's, else 1",
                              2),
        text_field("shift_table", field_kind::path,
                   "Corner-cube shift table (JSON); empty: the preset's, else the shipped table"),
        choice_field("lookup", {"per_ray", "per_render"},
                     "Angle of a, mu and the shift distribution: each ray's incidence (per_ray) or the sheet's "
                     "chief ray for the whole render (per_render, as the paper's fit)"),
    };
    k.make = [](const model_values& v, const model_setting& setting) -> std::unique_ptr<retro_model> {
      sinc_shift_params sp = resolve_sinc_shift_params(v, setting);
      std::shared_ptr<const shift_table> shifts;
      if (sp.c_mm > 0)
        shifts = cached_shift_table(sp.shift_table.empty() ? default_shift_table_path() : sp.shift_table);
      return std::make_unique<sinc_shift_retro>(std::move(sp), std::move(shifts));
    };
    k.derived = [](const model_values& v, const std::string& key, const std::string& base_dir,
                   double theta_deg) -> std::optional<double> {
      try {
        const sinc_shift_params p = resolve_sinc_shift_params(v, {.base_dir = base_dir});
        if (key == "a_per_mm") return interpolate_by_angle(p.theta_deg, p.a_per_mm, theta_deg);
        if (key == "mu") return interpolate_by_angle(p.theta_deg, p.mu, theta_deg);
        if (key == "c_mm") return p.c_mm;
        if (key == "reference_distance_mm") return p.reference_distance_mm;
        if (key == "shift_index") return p.shift_index;
      } catch (const std::exception&) {
      }
      return std::nullopt;
    };
    return k;
  }();
  return kind;
}

sinc_shift_retro::sinc_shift_retro(sinc_shift_params p, std::shared_ptr<const shift_table> shifts)
    : p_(std::move(p)), shifts_(std::move(shifts)) {}

double sinc_shift_retro::a_at(double theta_deg) const {
  return interpolate_by_angle(p_.theta_deg, p_.a_per_mm, p_.lookup_angle_deg.value_or(theta_deg));
}
double sinc_shift_retro::mu_at(double theta_deg) const {
  return interpolate_by_angle(p_.theta_deg, p_.mu, p_.lookup_angle_deg.value_or(theta_deg));
}

sinc_shift_retro::incidence sinc_shift_retro::prepare(const glm::dvec3& wi) const {
  incidence in;
  if (wi.z <= 0) return in;
  const double theta_deg = polar_angle_deg(wi);
  in.lit = true;
  in.frame = make_basis(wi);
  in.k = a_at(theta_deg) * p_.reference_distance_mm;
  in.mu = mu_at(theta_deg);
  if (p_.c_mm > 0 && shifts_) {
    const double outside = radians(p_.lookup_angle_deg.value_or(theta_deg));
    in.rows = shift_rows_at(*shifts_, degrees(std::asin(std::sin(outside) / p_.shift_index)));
  }
  return in;
}

sinc_shift_retro::draw sinc_shift_retro::draw_of(retro_samples u) const {
  draw d;
  d.k_tan_delta = sinc_lobe::instance().sample_k_tan_delta(u.lobe.x, u.more.next_double());
  const double phi = 2.0 * pi * u.lobe.y;
  d.cos_phi = std::cos(phi);
  d.sin_phi = std::sin(phi);
  if (p_.c_mm > 0 && shifts_) {
    d.pick = u.more.next_double();
    d.u_bin = u.shift.x;
    d.u_jitter = u.more.next_double();
    const double psi = 2.0 * pi * u.shift.y;
    d.cos_psi = std::cos(psi);
    d.sin_psi = std::sin(psi);
  }
  return d;
}

retro_sample sinc_shift_retro::sample(const incidence& in, const draw& d, row_shifts& rows) const {
  if (!in.lit) return {};
  const double tan_delta = d.k_tan_delta / in.k;
  const double cos_delta = 1.0 / std::sqrt(1.0 + tan_delta * tan_delta), sin_delta = tan_delta * cos_delta;

  // Rotate the retro direction (wo = wi) by delta at azimuth phi.
  retro_sample s;
  s.wo = in.frame.to_world({sin_delta * d.cos_phi, sin_delta * d.sin_phi, cos_delta});
  if (s.wo.z <= 0) return {};  // sent below the sheet: absorbed

  if (p_.c_mm > 0 && shifts_) {
    const std::size_t row = in.rows.picked(d.pick);
    const auto known = std::find_if(rows.known.begin(), rows.known.begin() + rows.count,
                                    [&](const auto& r) { return r.first == row; });
    double shift = 0;
    if (known != rows.known.begin() + rows.count) {
      shift = known->second;
    } else {
      shift = shift_in_row(*shifts_, row, d.u_bin, d.u_jitter) * p_.c_mm;
      if (rows.count < rows.known.size()) rows.known[rows.count++] = {row, shift};
    }
    s.shift_mm = {shift * d.cos_psi, shift * d.sin_psi};
  }
  s.weight = in.mu;
  return s;
}

retro_sample sinc_shift_retro::sample(const incidence& in, retro_samples u) const {
  if (!in.lit) return {};
  row_shifts rows;
  return sample(in, draw_of(u), rows);
}

retro_sample sinc_shift_retro::sample(const glm::dvec3& wi, retro_samples u) const { return sample(prepare(wi), u); }

retro_sample sinc_shift_retro::sample_polarized(const glm::dvec3& wi, retro_samples u) const {
  retro_sample s = sample(wi, u);
  if (s.weight > 0 && !p_.polarization.empty())
    s.polarization =
        interpolate_by_angle(p_.theta_deg, p_.polarization, p_.lookup_angle_deg.value_or(polar_angle_deg(wi)));
  return s;
}

namespace {
class sinc_shift_incidence final : public retro_at_incidence {
 public:
  sinc_shift_incidence(const sinc_shift_retro& model, const glm::dvec3& wi) : model_(model), in_(model.prepare(wi)) {}
  retro_sample sample(retro_samples u) const override { return model_.sample(in_, u); }

  // One draw for every incidence of this model: the lobe's table, the azimuths' sines and cosines
  // and each table row's shift are worked out once.
  void sample_group(std::span<const retro_at_incidence* const> at, const retro_samples& u,
                    std::span<retro_sample> out) const override {
    const auto ours = [&](const retro_at_incidence* a) {
      return typeid(*a) == typeid(sinc_shift_incidence) &&
             &static_cast<const sinc_shift_incidence*>(a)->model_ == &model_;
    };
    if (!std::all_of(at.begin(), at.end(), ours)) return retro_at_incidence::sample_group(at, u, out);
    const sinc_shift_retro::draw d = model_.draw_of(u);
    sinc_shift_retro::row_shifts rows;
    for (std::size_t i = 0; i < at.size(); ++i) {
      out[i] = model_.sample(static_cast<const sinc_shift_incidence*>(at[i])->in_, d, rows);
    }
  }

 private:
  const sinc_shift_retro& model_;
  sinc_shift_retro::incidence in_;
};
}  // namespace

std::unique_ptr<const retro_at_incidence> sinc_shift_retro::at_incidence(const glm::dvec3& wi) const {
  return std::make_unique<sinc_shift_incidence>(*this, wi);
}

std::optional<double> sinc_shift_retro::pdf(const glm::dvec3& wi, const glm::dvec3& wo) const {
  if (wi.z <= 0 || wo.z <= 0) return 0.0;
  const double cos_delta = std::clamp(glm::dot(wi, wo), -1.0, 1.0);
  const double sin_delta = std::sqrt(std::max(0.0, 1 - cos_delta * cos_delta));
  if (sin_delta <= 0) return std::nullopt;  // the lobe's axis: a density per steradian diverges there
  const double k = a_at(polar_angle_deg(wi)) * p_.reference_distance_mm;
  // p(delta) d(delta) spread uniformly over the azimuth: d(omega) = sin(delta) d(delta) d(phi).
  return sinc_lobe::pdf(std::acos(cos_delta), k) / (2.0 * pi * sin_delta);
}

std::optional<double> sinc_shift_retro::eval(const glm::dvec3& wi, const glm::dvec3& wo) const {
  const auto p = pdf(wi, wo);
  if (!p) return p;
  return *p * mu_at(polar_angle_deg(wi));
}

}  // namespace airr
