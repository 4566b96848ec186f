#pragma once
// The bokeh views of `airr psf`: the 2D model PSF as an image and a picture, the PSF through
// focus, and the spot matrix across the aerial image.
#include <cstdint>
#include <string>
#include <vector>

#include "airr/layout/psf.hpp"
#include "airr/layout/scene.hpp"
#include "airr/layout/sheet_models.hpp"

struct psf_picture_options {
  std::string image;         // EXR (or any format write_image takes) of the density, mm per pixel in its metadata
  std::string png;           // log-scaled picture
  int pixels = 0;            // per side; 0: 129 for pictures, for the image enough that r50 spans 4 pixels (<= 1025)
  double half_width_mm = 0;  // 0: the square holding 99.8% of the PSF
};

// The tracer's PSF beside the model's (--traced): a disc on the display, rendered.
struct traced_options {
  bool on = false;
  double disc_mm = 0.2;
  std::uint64_t spp = 256;
};

struct focus_options {
  std::string range;  // "start:end:step" in mm; empty: none
  std::string csv, plot, strip;
};

struct field_options {
  int n = 0;  // 0: none
  std::string csv, png;
};

// With `traced.on` both files use the picture's grid: the image then holds the model PSF there
// (its share of the brightness in the metadata) and layers model_disc, traced and difference.
void write_psf_pictures(const airr::scene& s, const airr::psf_samples& psf, const psf_picture_options& o,
                        const traced_options& traced);
// `offsets` as parse_focus_offsets reads them from o.range.
void run_through_focus(const airr::scene& s, const airr::retro_model_list& models, const std::vector<double>& offsets,
                       std::uint64_t samples, int pixels, const focus_options& o);
void run_spot_matrix(const airr::scene& s, const airr::retro_model_list& models, std::uint64_t samples, int pixels,
                     const field_options& o);
