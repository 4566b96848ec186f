#include "airr/models/retro_model.hpp"

#include "airr/core/error.hpp"
#include "airr/models/bead_sheet.hpp"
#include "airr/models/prism_sheet.hpp"
#include "airr/models/retro_microfacet.hpp"
#include "airr/models/retro_sinc_shift.hpp"
#include "airr/models/tile_sheet.hpp"

namespace airr {

std::optional<double> retro_model::pdf(const glm::dvec3&, const glm::dvec3&) const { return std::nullopt; }

namespace {
class forwarded_incidence final : public retro_at_incidence {
 public:
  forwarded_incidence(const retro_model& model, const glm::dvec3& wi) : model_(model), wi_(wi) {}
  retro_sample sample(retro_samples u) const override { return model_.sample(wi_, u); }

 private:
  const retro_model& model_;
  glm::dvec3 wi_;
};
}  // namespace

void retro_at_incidence::sample_group(std::span<const retro_at_incidence* const> at, const retro_samples& u,
                                      std::span<retro_sample> out) const {
  for (std::size_t i = 0; i < at.size(); ++i) out[i] = at[i]->sample(u);
}

std::unique_ptr<const retro_at_incidence> retro_model::at_incidence(const glm::dvec3& wi) const {
  return std::make_unique<forwarded_incidence>(*this, wi);
}
std::optional<double> retro_model::eval(const glm::dvec3&, const glm::dvec3&) const { return std::nullopt; }

const retro_model_kind& ideal_retro_kind() {
  static const retro_model_kind kind = [] {
    retro_model_kind k;
    k.name = "ideal";
    k.help = "Sends light exactly back where it came from";
    k.fields = {number_field("mu", "", 0, 1, 1, "Weight of every retroreflected path")};
    k.make = [](const model_values& v, const model_setting&) -> std::unique_ptr<retro_model> {
      return std::make_unique<ideal_retro>(v.number("mu"));
    };
    return k;
  }();
  return kind;
}

// The registration: every model the scene file can name, in the order the designer lists them.
const std::vector<const retro_model_kind*>& retro_model_kinds() {
  static const std::vector<const retro_model_kind*> kinds = {&ideal_retro_kind(),      &sinc_shift_retro_kind(),
                                                             &microfacet_retro_kind(), &prism_sheet_retro_kind(),
                                                             &bead_sheet_retro_kind(), &tile_sheet_retro_kind()};
  return kinds;
}

const retro_model_kind& find_retro_model_kind(const std::string& name, const std::string& where) {
  std::string names;
  for (const retro_model_kind* k : retro_model_kinds()) {
    if (k->name == name) return *k;
    names += (names.empty() ? "" : ", ") + k->name;
  }
  throw input_error(where + ".type: unknown model '" + name + "' (" + names + ")");
}

retro_model_params with_model_type(const retro_model_params& p, const std::string& type) {
  const retro_model_kind& kind = find_retro_model_kind(type);
  retro_model_params out;
  out.type = type;
  for (const auto& [key, value] : p.values) {
    if (find_field(kind.fields, key)) set_model_value(out, kind.fields, key, value);
  }
  return out;
}

void set_model_value(retro_model_params& p, const std::string& key, std::optional<param_value> value) {
  set_model_value(p, find_retro_model_kind(p.type).fields, key, std::move(value));
}

model_values read_model_values(const retro_model_params& p, const std::string& where) {
  return model_values(p, find_retro_model_kind(p.type, where).fields, where);
}

std::unique_ptr<retro_model> make_retro_model(const retro_model_params& p, const model_setting& setting,
                                              const std::string& where) {
  const retro_model_kind& kind = find_retro_model_kind(p.type, where);
  validate_model_values(p, kind.fields, where);
  return kind.make(model_values(p, kind.fields, where), setting);
}

}  // namespace airr
