#pragma once

#include <filesystem>

#include "airr/analysis/image_read.hpp"
#include "airr/analysis/slanted_edge_mtf.hpp"

namespace airr::analysis {

struct edge_file_result {
  linear_image image;
  mtf_curve curve;
};

// Reads an image and measures its slanted-edge MTF on the luminance; every error names the file.
edge_file_result measure_edge_file(const std::filesystem::path& path, const slanted_edge_params& params = {},
                                   const image_read_params& read_params = {});

}  // namespace airr::analysis
