#include "airr/analysis/mtf_csv.hpp"

#include <cstdio>

#include "airr/formats/scene_json.hpp"

namespace airr::analysis {

std::string format_mtf_csv(const mtf_curve& curve, double mm_per_pixel) {
  const std::vector<double> lp_per_mm = to_lp_per_mm(curve.cycles_per_pixel, mm_per_pixel);
  std::string out = "cycles_per_pixel,lp_per_mm,mtf\n";
  char line[96];
  for (size_t i = 0; i < curve.cycles_per_pixel.size(); ++i) {
    std::snprintf(line, sizeof line, "%.8g,%.8g,%.8g\n", curve.cycles_per_pixel[i], lp_per_mm[i], curve.mtf[i]);
    out += line;
  }
  return out;
}

void write_mtf_csv(const std::filesystem::path& path, const mtf_curve& curve, double mm_per_pixel) {
  airr::write_file_atomic(path.string(), format_mtf_csv(curve, mm_per_pixel));
}

}  // namespace airr::analysis
