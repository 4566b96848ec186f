#pragma once
// The ghost table (docs/path-expressions.md): which light paths reach the eye, ranked by their
// light inside the aerial image's outline and by their peak, each placed by the parallax between
// two eyes: how far from the eye its image forms and how far, in arcmin, from the aerial image.
#include <atomic>
#include <cstdint>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "airr/formats/image.hpp"
#include "airr/layout/scene.hpp"

namespace airr {

struct ghost_params {
  std::uint64_t census_spp = 4;  // samples per pixel of the census that finds the path classes
  std::uint64_t spp = 64;        // of each eye's render of the classes found
  int top = 8;                   // the classes measured: those with the most light in the census
  double baseline_mm = 65;       // between the two eyes, either side of the observer
  int threads = 0;               // 0: all cores
  // Path expressions measured as classes too, after the census's (the designer's typed layers).
  std::vector<std::string> expressions{};
  const std::atomic<bool>* cancel = nullptr;  // set: the table stops and comes back empty
};

struct ghost_class {
  std::string expression;  // the class's label, a path expression selecting it alone
  // Its paths were retroreflected (a typed class: every path of the census it selects was): a
  // share of the aerial image itself.
  bool aerial = false;
  bool typed = false;       // one of ghost_params::expressions (else a label the census found)
  double census_share = 0;  // of all the light the census saw (typed: of the observer's render)
  // Mean luminance inside the aerial image's outline, and its share of the whole image's there.
  double outline_luminance = 0, share = 0;
  double peak = 0;  // the luminance of its brightest pixel
  static constexpr double nan = std::numeric_limits<double>::quiet_NaN();
  glm::dvec2 centroid{nan};        // luminance-weighted, in the observer's pixels
  double separation_arcmin = nan;  // from the aerial image's centroid, as the observer sees them
  double distance_mm = nan;        // from the observer, along its view, by the eyes' parallax
  image_rgb image;                 // as the observer sees it
};

struct ghost_table {
  std::vector<ghost_class> classes;  // by outline luminance, highest first
  std::vector<std::size_t> by_peak;  // indices into classes, highest peak first
  // The aerial image (the retroreflected class with the most light) placed the same way.
  glm::dvec2 aerial_centroid{ghost_class::nan};
  double aerial_distance_mm = ghost_class::nan;
  std::size_t labels_seen = 0;  // distinct labels the census met
  double seconds = 0;
};

// Throws input_error for parameters out of range (and what a render of the scene throws).
// `progress(stage, fraction)` as it goes.
ghost_table compute_ghost_table(const scene& s, const ghost_params& p = {},
                                const std::function<void(const std::string&, double)>& progress = {});

// The table as CSV (rank by light, rank by peak, expression, the numbers), written atomically.
void write_ghost_csv(const ghost_table& t, const std::string& path);

}  // namespace airr
