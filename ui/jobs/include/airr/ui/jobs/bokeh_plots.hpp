#pragma once
// The Bokeh tab's data, computed off the UI thread after the other plots: the 2D model PSF, the
// PSF through focus, the spot matrix across the aerial image, and the blur (r50) over a floating
// distance x tilt grid around the design. Each result names the layout generation it shows.
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "airr/analysis/bokeh.hpp"
#include "airr/analysis/psf_grid.hpp"
#include "airr/layout/scene.hpp"
#include "airr/layout/sheet_models.hpp"

namespace airr::ui {

struct bokeh_params {
  std::uint64_t psf_samples = 8000;    // the 2D PSF (the same count and seed as the MTF plot's r50)
  std::uint64_t focus_samples = 4000;  // rays per sheet through focus
  std::uint64_t spot_samples = 4000;   // per point of the spot matrix
  std::uint64_t map_samples = 2000;    // per point of the D x tilt map
  int psf_pixels = 65, spot_pixels = 33;
  int spots = 3;
};

struct bokeh_plots {
  std::uint64_t generation = 0;
  double floating_distance_mm = 0, tilt_deg = 0;  // of the layout shown

  analysis::psf_grid psf;  // a view of the core and near wings
  double r50_mm = 0;
  double psf_ms = 0;

  analysis::through_focus focus;   // offsets -20 .. 20 mm every 4 mm
  std::vector<std::size_t> strip;  // the planes shown as pictures
  double focus_ms = 0;

  analysis::spot_matrix spots;
  double spots_ms = 0;

  std::vector<double> map_d_mm, map_tilt_deg;  // the grid's nodes
  std::vector<double> map_r50_mm;              // row per tilt, D fastest; NaN where the layout fails
  double map_ms = 0;

  std::string error;  // why the PSF views are empty (the map may still be there)
};

// What the worker runs for one layout (synchronously). `stop`, asked between views and map
// points, abandons the work (empty result) when a newer layout waits. `r50_mm`: the model PSF's
// r50 at psf_samples (the MTF plot's), when known; else sampled here.
std::optional<bokeh_plots> compute_bokeh(const scene& s, std::uint64_t generation, const bokeh_params& p = {},
                                         retro_model_list models = {}, const std::function<bool()>& stop = {},
                                         std::optional<double> r50_mm = {});

}  // namespace airr::ui
