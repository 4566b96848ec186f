#include "airr/optics/retro_model.hpp"

#include <map>
#include <mutex>

#include "airr/optics/error.hpp"
#include "airr/optics/files.hpp"
#include "airr/optics/retro_microfacet.hpp"
#include "airr/optics/retro_sinc_shift.hpp"
#include "airr/optics/scene.hpp"

namespace airr {

// Shift tables are shared between models built from the same file.
static std::shared_ptr<const shift_table> cached_shift_table(const std::string& path) {
  static std::mutex mutex;
  static std::map<std::string, std::shared_ptr<const shift_table>> cache;
  std::lock_guard lock(mutex);
  auto& entry = cache[path];
  if (!entry) entry = std::make_shared<const shift_table>(load_shift_table(path));
  return entry;
}

std::optional<double> retro_model::pdf(const glm::dvec3&, const glm::dvec3&) const { return std::nullopt; }
std::optional<double> retro_model::eval(const glm::dvec3&, const glm::dvec3&) const { return std::nullopt; }

std::unique_ptr<retro_model> make_retro_model(const retro_model_params& p, const std::string& base_dir) {
  switch (p.type) {
    case retro_model_type::ideal:
      return std::make_unique<ideal_retro>(p.mu.value_or(1.0));
    case retro_model_type::sinc_shift: {
      sinc_shift_params sp = resolve_sinc_shift_params(p, base_dir);
      std::shared_ptr<const shift_table> shifts;
      if (sp.c_mm > 0) {
        shifts = cached_shift_table(p.shift_table.empty() ? default_shift_table_path()
                                                          : resolve_path(p.shift_table, base_dir));
      }
      return std::make_unique<sinc_shift_retro>(std::move(sp), std::move(shifts));
    }
    case retro_model_type::microfacet:
      return std::make_unique<microfacet_retro>(p);
  }
  throw input_error("retroreflector.model.type: unknown model");
}

}  // namespace airr
