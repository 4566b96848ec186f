#pragma once
// The blur as a designer judges it, from the model alone: the PSF through focus (the bundle cut
// by planes along the chief ray) and across the image (a spot matrix of model PSFs).
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "airr/analysis/psf_grid.hpp"
#include "airr/layout/psf.hpp"
#include "airr/layout/psf_focus.hpp"
#include "airr/layout/scene.hpp"
#include "airr/layout/sheet_models.hpp"

namespace airr::analysis {

struct focus_plane {
  double offset_mm = 0;
  double r50_mm = 0, r80_mm = 0;
  double peak_per_mm2 = 0;  // the picture's largest density, of a PSF of unit weight
  psf_grid grid;            // of unit weight, a view (psf_picture_half_width); every plane on the same grid
};

struct through_focus {
  std::vector<focus_plane> planes;
  double best_offset_mm = 0;  // where r50 is smallest (a parabola through the smallest and its neighbours)
  std::vector<psf_sheet_share> sheets;
};

// Throws input_error when no sheet's bundle returns (see sample_focus_bundle).
through_focus compute_through_focus(const scene& s, const retro_model_list& models, const std::vector<double>& offsets,
                                    const focus_params& p, int grid_size);

struct field_spot {
  int col = 0, row = 0;       // in the matrix, row 0 at the top as the observer sees it
  glm::dvec3 point{0};        // on the aerial image
  double x_mm = 0, y_mm = 0;  // from the aerial image's centre, the observer's right and up
  double r50_mm = 0, brightness = 0, incidence_deg = 0;
  psf_grid grid;       // a view (psf_picture_half_width); every spot on the same grid
  std::string missed;  // why no sheet is reached from here (then the rest is unset)
};

struct spot_matrix {
  int n = 0;
  std::vector<field_spot> spots;  // row-major
};

// Model PSFs at n x n points spread evenly over the central `field_fraction` of the aerial
// image (n >= 1; the centre is one of them when n is odd). Throws input_error for n outside
// [1, 9] or a fraction outside (0, 1].
spot_matrix compute_spot_matrix(const scene& s, const retro_model_list& models, int n, const psf_params& p,
                                int grid_size, double field_fraction = 0.9);

}  // namespace airr::analysis
