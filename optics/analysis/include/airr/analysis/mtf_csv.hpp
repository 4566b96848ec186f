#pragma once

#include <filesystem>
#include <string>

#include "airr/analysis/slanted_edge_mtf.hpp"

namespace airr::analysis {

// CSV text with header "cycles_per_pixel,lp_per_mm,mtf", one row per frequency.
std::string format_mtf_csv(const mtf_curve& curve, double mm_per_pixel);

// Writes format_mtf_csv atomically.
void write_mtf_csv(const std::filesystem::path& path, const mtf_curve& curve, double mm_per_pixel);

}  // namespace airr::analysis
