#include "airr/analysis/edge_file.hpp"

#include <stdexcept>

namespace airr::analysis {

edge_file_result measure_edge_file(const std::filesystem::path& path, const slanted_edge_params& params,
                                   const image_read_params& read_params) {
  edge_file_result result;
  result.image = read_linear_image(path, read_params);  // names the file itself
  try {
    result.curve = slanted_edge_mtf(result.image.luminance, params);
  } catch (const std::runtime_error& e) {
    throw std::runtime_error(path.string() + ": " + e.what());
  }
  return result;
}

}  // namespace airr::analysis
