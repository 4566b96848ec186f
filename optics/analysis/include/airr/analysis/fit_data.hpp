#pragma once
// A fit data directory (assets/fit_example/README.md): fit.json naming the measurement setup
// (an airr scene), measured MTF curves per tilt and per floating distance (CSV in the `airr mtf`
// format, or slanted-edge images) and optional white-square images for the brightness.
// Loading reads and measures every file, so a fit starts only from complete, valid data.
#include <optional>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "airr/layout/scene.hpp"

namespace airr::analysis {

// One measured MTF curve and what a simulation must include to compare with it.
struct mtf_measurement {
  std::string origin;  // "DIR/fit.json: tilt_series[2]", for messages
  std::string file;    // the CSV or image, resolved
  std::string kind;    // "mtf_csv" or "edge_image"
  double tilt_deg = 0;
  double floating_distance_mm = 150;
  std::vector<double> lp_per_mm;  // ascending, starting at or above 0
  std::vector<double> mtf;
  double pixel_mm = 0;              // the measuring pixel on the aerial-image plane; 0: no aperture
  double window_half_width_mm = 0;  // Hamming window the measurement put on the LSF; 0: none
  bool along_y = false;             // a near-horizontal edge measures the blur along y
};

// A photo of a white square shown centred on the source, framed by the setup scene's camera.
struct white_square {
  std::string origin;
  std::string file;
  double tilt_deg = 0;
  double floating_distance_mm = 150;
  double width_mm = 0;  // of the square on the source
  double height_mm = 0;
  cv::Mat luminance;  // CV_64FC1, camera size, radiance in the units of the source intensity
};

struct fit_data {
  std::string dir;       // the data directory
  std::string fit_json;  // its fit.json
  std::string name;
  std::string note;
  std::string scene_path;
  scene setup;                                   // the measurement setup (checked)
  std::vector<mtf_measurement> tilt_series;      // one per tilt, ascending, tilt 0 included
  std::vector<mtf_measurement> distance_series;  // tilt 0, ascending D, at least 2 distinct D
  std::vector<white_square> white_squares;       // one per tilt, ascending; may be empty
  std::optional<double> mu;                      // fit.json "mu", used when there are no white squares
  // fit.json "shift_table" (resolved): the sheet's own shift distributions, which the fit simulates
  // with and the preset names; empty: the shipped corner cube's.
  std::string shift_table;

  // Every file the data names (scene, CSVs, images), for provenance.
  std::vector<std::string> files() const;
};

inline constexpr const char* fit_data_format = "airr-fit-data";
inline constexpr int fit_data_version = 1;

// Throws airr::input_error "FILE: FIELD: problem" naming what is missing or wrong.
fit_data load_fit_data(const std::string& dir);

// The device a measurement was taken on: the setup with its first sheet at pitch `tilt_deg` and
// the display at floating distance `floating_distance_mm`. A device may have more sheets if each
// is the first sheet's mirror image in the half mirror (so that every sheet sees the aerial
// image's centre at the first sheet's incidence, which the fit's per-tilt a and mu describe);
// they follow the first sheet's tilt.
scene measurement_layout(const scene& setup, double tilt_deg, double floating_distance_mm);

// Throws input_error "<origin>: retroreflectors[i]: ..." for a sheet after the first that is not
// the first sheet's mirror image in the half mirror.
void check_fit_sheets(const scene& setup, const std::string& origin);

// A CSV in the `airr mtf` format: header naming lp_per_mm and mtf (cycles_per_pixel optional).
// Fills lp_per_mm, mtf and, when the CSV has cycles_per_pixel, pixel_mm. Throws input_error.
void read_mtf_csv(const std::string& path, mtf_measurement& m);

}  // namespace airr::analysis
