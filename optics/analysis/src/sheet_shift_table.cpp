#include "airr/analysis/sheet_shift_table.hpp"

#include <algorithm>
#include <vector>

#include <tbb/parallel_for.h>

#include "airr/analysis/fit_data.hpp"
#include "airr/core/error.hpp"
#include "airr/core/random.hpp"
#include "airr/layout/layout.hpp"
#include "airr/layout/psf.hpp"
#include "airr/models/prism_sheet.hpp"
#include "airr/models/retro_model.hpp"

namespace airr::analysis {

namespace {

constexpr std::uint64_t block_samples = 10000;

// Numbers per row: the histogram's bins, the retroreflected weight, the weighted sum of the paths'
// Mueller matrices (16, row-major).
std::size_t row_width(const sheet_shift_params& p) { return std::size_t(p.bins) + 1 + 16; }

// One row: the weighted histogram of |shift| / unit over the light retroreflected at wi, the
// retroreflected weight and the weighted Mueller sum. Blocks are summed in order, so the row is
// the same on any number of threads.
std::vector<double> trace_row(const retro_model& model, const glm::dvec3& wi, double unit_mm,
                              const sheet_shift_params& p, std::uint64_t row) {
  const std::uint64_t blocks = (p.samples + block_samples - 1) / block_samples;
  const std::size_t width = row_width(p), weight_at = std::size_t(p.bins);
  std::vector<std::vector<double>> block_bins(blocks, std::vector<double>(width, 0.0));
  tbb::parallel_for(std::uint64_t(0), blocks, [&](std::uint64_t b) {
    std::vector<double>& h = block_bins[b];
    pcg32 rng(p.seed + b, 2 * row + 1);
    const std::uint64_t n = std::min(block_samples, p.samples - b * block_samples);
    for (std::uint64_t i = 0; i < n; ++i) {
      retro_samples u{.lobe = {rng.next_double(), rng.next_double()},
                      .shift = {rng.next_double(), rng.next_double()},
                      .more = pcg32(p.seed + b * block_samples + i, 2 * row + 2)};
      const retro_sample s = model.sample_polarized(wi, u);
      if (!(s.weight > 0) || !s.retroreflected) continue;
      const double shift = glm::length(s.shift_mm) / unit_mm;
      h[std::size_t(std::clamp(int(shift / p.s_max * p.bins), 0, p.bins - 1))] += s.weight;
      h[weight_at] += s.weight;
      const mueller m = s.polarization.value_or(mueller::identity());
      for (std::size_t k = 0; k < 16; ++k) h[weight_at + 1 + k] += s.weight * m.m[k / 4][k % 4];
    }
  });
  std::vector<double> sum(width, 0.0);
  for (const auto& h : block_bins)
    for (std::size_t k = 0; k < sum.size(); ++k) sum[k] += h[k];
  return sum;
}

}  // namespace

std::optional<double> sheet_shift_unit_mm(const retro_model_params& model, const std::string& base_dir) {
  if (model.type != "prism_sheet") return std::nullopt;
  const auto built = make_retro_model(model, {.base_dir = base_dir}, "model");
  return dynamic_cast<const prism_sheet_retro&>(*built).geometry().cube_edge_mm();
}

traced_sheet trace_sheet_shift_table(const retro_model_params& model, const std::string& base_dir, const scene& bench,
                                     double unit_mm, const sheet_shift_params& p, const item_share& share) {
  if (!(unit_mm > 0) || !(p.step_deg > 0) || p.bins < 1 || p.samples < 1)
    throw input_error("sheet shift table: the unit, step, bins and samples must be positive");
  const auto built = make_retro_model(model, {.base_dir = base_dir}, "model");
  std::vector<double> tilts;
  for (int i = 0; i * p.step_deg <= p.max_deg + 1e-9; ++i) tilts.push_back(i * p.step_deg);

  const std::size_t width = row_width(p);
  const std::vector<double> rows = run_items(share, tilts.size(), width, [&](std::size_t i, double* out) {
    const scene s = measurement_layout(bench, tilts[i], 150);
    const psf_chief_ray chief = chief_ray_through(s, aerial_image_center(s));
    const std::vector<double> h = trace_row(*built, chief.wi, unit_mm, p, i);
    std::copy(h.begin(), h.end(), out);
  });

  traced_sheet out;
  shift_table& t = out.shifts;
  t.s_max = p.s_max;
  for (std::size_t i = 0; i < tilts.size(); ++i) {
    const double* h = rows.data() + i * width;
    const double kept = h[p.bins];
    if (!(kept > 0))
      throw input_error("sheet shift table: the sheet retroreflects nothing at tilt " + number_text(tilts[i]) + " deg");
    std::vector<double> row(h, h + p.bins);
    for (double& v : row) v /= kept;
    t.theta_deg.push_back(tilts[i]);
    t.probability.push_back(std::move(row));
    t.retro_fraction.push_back(std::min(1.0, kept / double(p.samples)));
    mueller m;
    for (std::size_t k = 0; k < 16; ++k) m.m[k / 4][k % 4] = h[std::size_t(p.bins) + 1 + k] / kept;
    out.polarization.push_back(m);
  }
  t.provenance = {{"source", "the sheet's explicit model on the bench (sheet_shift_table.hpp)"},
                  {"model", model.type},
                  {"unit_mm", unit_mm},
                  {"samples_per_row", p.samples},
                  {"seed", p.seed}};
  finalize_shift_table(t);
  return out;
}

}  // namespace airr::analysis
