#include "airr/models/emission_profile.hpp"

#include <filesystem>

#include "airr/core/csv_table.hpp"
#include "airr/core/error.hpp"
#include "airr/core/files.hpp"
#include "airr/core/interpolate.hpp"

namespace airr {

double emission_profile::at(double theta_deg) const { return interpolate_linear(angle_deg, relative, theta_deg); }

emission_profile read_emission_profile(const std::string& path) {
  const csv_table t = read_csv_table(path);
  const int ca = t.column("angle_deg"), cl = t.column("relative_luminance");
  if (ca < 0 || cl < 0) throw input_error(path + ": expected the header angle_deg,relative_luminance");
  emission_profile p;
  for (std::size_t i = 0; i < t.rows.size(); ++i) {
    const double a = t.rows[i][std::size_t(ca)], l = t.rows[i][std::size_t(cl)];
    if (i == 0 && a != 0) throw input_error(t.where(i) + ": angle_deg: the first row must be at 0");
    if (i > 0 && !(a > p.angle_deg.back())) throw input_error(t.where(i) + ": angle_deg: angles must ascend");
    if (a > 90) throw input_error(t.where(i) + ": angle_deg: must be at most 90");
    if (l < 0) throw input_error(t.where(i) + ": relative_luminance: must not be negative");
    if (i == 0 && !(l > 0)) throw input_error(t.where(i) + ": relative_luminance: must be positive at 0");
    p.angle_deg.push_back(a);
    p.relative.push_back(l);
  }
  if (p.angle_deg.size() < 2) throw input_error(path + ": needs at least 2 rows (angles 0 and more)");
  const double l0 = p.relative.front();
  for (double& l : p.relative) l /= l0;
  return p;
}

std::shared_ptr<const emission_profile> load_emission_profile(const std::string& path) {
  static file_cache<emission_profile> cache;
  return cache.get(path, path, [&] { return std::make_shared<const emission_profile>(read_emission_profile(path)); });
}

}  // namespace airr
