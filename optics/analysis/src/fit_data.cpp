#include "airr/analysis/fit_data.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <set>
#include <sstream>

#include <nlohmann/json.hpp>

#include "airr/analysis/edge_file.hpp"
#include "airr/analysis/image_read.hpp"
#include "airr/core/csv_table.hpp"
#include "airr/core/error.hpp"
#include "airr/core/files.hpp"
#include "airr/core/json_reader.hpp"
#include "airr/formats/scene_json.hpp"
#include "airr/layout/layout.hpp"
#include "airr/models/shift_table.hpp"

namespace airr::analysis {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

std::string resolve_file(json_reader& r, const std::string& dir, const std::string& key) {
  const std::string name = r.string(key);
  const std::string path = resolve_path(name, dir);
  std::error_code ec;  // a name the system refuses (too long, say) is not found either
  if (!fs::is_regular_file(path, ec)) r.fail(r.field(key), "file '" + name + "' not found (" + path + ")");
  return path;
}

// The scene a measurement was taken in: the setup at the entry's tilt and floating distance.
void check_entry_layout(const scene& setup, double tilt_deg, double d_mm, const std::string& origin) {
  check_layout(measurement_layout(setup, tilt_deg, d_mm), origin);
}

std::string vector_text(const glm::dvec3& v) {
  return "(" + number_text(v.x, 4) + ", " + number_text(v.y, 4) + ", " + number_text(v.z, 4) + ")";
}

double tilt_of(json_reader& r, const std::string& key = "tilt_deg") {
  const double t = r.number(key);
  if (t < 0 || t >= 90) r.fail(r.field(key), "must be in [0, 90) degrees, got " + number_text(t));
  return t;
}

double distance_of(json_reader& r, double fallback, bool required) {
  const std::optional<double> d =
      required ? std::optional(r.number("floating_distance_mm")) : r.optional_number("floating_distance_mm");
  const double v = d.value_or(fallback);
  if (!(v > 0)) r.fail(r.field("floating_distance_mm"), "must be positive, got " + number_text(v));
  return v;
}

void read_edge_measurement(json_reader& r, mtf_measurement& m) {
  slanted_edge_params params;
  if (r.has("roi")) {
    const json& v = r.raw("roi");
    if (!v.is_array() || v.size() != 4 ||
        !std::all_of(v.begin(), v.end(), [](const json& e) { return e.is_number_integer(); }))
      r.fail(r.field("roi"), "must be [x, y, width, height] in pixels");
    params.roi = cv::Rect(v[0].get<int>(), v[1].get<int>(), v[2].get<int>(), v[3].get<int>());
  }
  edge_file_result e;
  try {
    e = measure_edge_file(m.file, params);
  } catch (const std::runtime_error& err) {
    r.fail(r.field("edge_image"), err.what());
  }
  const std::optional<double> given = r.optional_number("pixel_mm");
  if (given && !(*given > 0)) r.fail(r.field("pixel_mm"), "must be positive for an edge image");
  if (!given && !e.image.mm_per_pixel)
    r.fail(r.field("pixel_mm"), std::string("missing, and ") + m.file + " carries no " + mm_per_pixel_attribute +
                                    " attribute: give the pixel's size on the aerial-image plane in mm");
  m.pixel_mm = given ? *given : *e.image.mm_per_pixel;
  m.lp_per_mm = to_lp_per_mm(e.curve.cycles_per_pixel, m.pixel_mm);
  m.mtf = e.curve.mtf;
  m.window_half_width_mm = e.curve.window_half_width_px * m.pixel_mm;
  m.along_y = e.curve.orientation == edge_orientation::near_horizontal;
}

void read_csv_measurement(json_reader& r, mtf_measurement& m) {
  try {
    read_mtf_csv(m.file, m);
  } catch (const input_error& e) {
    r.fail(r.field("mtf_csv"), e.what());
  }
  if (const auto p = r.optional_number("pixel_mm")) {
    if (*p < 0) r.fail(r.field("pixel_mm"), "must not be negative (0: the curve holds no pixel aperture)");
    m.pixel_mm = *p;
  } else if (m.pixel_mm == 0) {
    r.fail(r.field("pixel_mm"),
           "missing, and " + m.file +
               " has no cycles_per_pixel column to derive it from: give the measuring pixel's size on "
               "the aerial-image plane in mm (0: the curve holds no pixel aperture)");
  }
  if (const auto w = r.optional_number("lsf_window_mm")) {
    if (!(*w > 0)) r.fail(r.field("lsf_window_mm"), "must be positive (leave it out when the LSF was not windowed)");
    m.window_half_width_mm = *w;
  }
}

// One entry of tilt_series or distance_series.
mtf_measurement read_measurement(const json& j, const fit_data& d, const std::string& field, bool distance_series) {
  json_reader r(j, d.fit_json, field);
  mtf_measurement m;
  m.origin = d.fit_json + ": " + field;
  if (distance_series) {
    m.tilt_deg = r.has("tilt_deg") ? tilt_of(r) : 0.0;
    if (m.tilt_deg != 0) r.fail(r.field("tilt_deg"), "the distance series is measured at tilt 0 (c is fitted there)");
  } else {
    m.tilt_deg = tilt_of(r);
  }
  m.floating_distance_mm = distance_of(r, floating_distance(d.setup), distance_series);
  const bool csv = r.has("mtf_csv"), edge = r.has("edge_image");
  if (csv == edge)
    r.fail(r.field(csv ? "edge_image" : "mtf_csv"),
           csv ? "give mtf_csv or edge_image, not both" : "missing (give mtf_csv or edge_image)");
  m.kind = csv ? "mtf_csv" : "edge_image";
  m.file = resolve_file(r, d.dir, m.kind);
  if (csv)
    read_csv_measurement(r, m);
  else
    read_edge_measurement(r, m);
  r.finish();

  const auto in_range =
      std::count_if(m.lp_per_mm.begin(), m.lp_per_mm.end(), [](double f) { return f > 0 && f <= 1.0; });
  if (in_range < 2)
    r.fail(r.field(m.kind),
           m.file + ": the curve has " + std::to_string(in_range) + " frequencies in (0, 1] lp/mm; need at least 2");
  check_entry_layout(d.setup, m.tilt_deg, m.floating_distance_mm, m.origin);
  return m;
}

white_square read_white_square(const json& j, const fit_data& d, const std::string& field) {
  json_reader r(j, d.fit_json, field);
  white_square w;
  w.origin = d.fit_json + ": " + field;
  w.tilt_deg = tilt_of(r);
  w.floating_distance_mm = distance_of(r, floating_distance(d.setup), false);
  w.width_mm = d.setup.source.width_mm;
  w.height_mm = d.setup.source.height_mm;
  if (r.has("square_mm")) {
    const json& v = r.raw("square_mm");
    std::vector<double> size;
    if (v.is_number())
      size = {v.get<double>(), v.get<double>()};
    else if (v.is_array() && v.size() == 2 && v[0].is_number() && v[1].is_number())
      size = {v[0].get<double>(), v[1].get<double>()};
    else
      r.fail(r.field("square_mm"), "must be a side length or [width, height] in mm");
    if (!(size[0] > 0) || !(size[1] > 0) || !std::isfinite(size[0]) || !std::isfinite(size[1]))
      r.fail(r.field("square_mm"), "must be positive and finite");
    if (size[0] > w.width_mm || size[1] > w.height_mm)
      r.fail(r.field("square_mm"), "is larger than the setup scene's source");
    w.width_mm = size[0];
    w.height_mm = size[1];
  }
  w.file = resolve_file(r, d.dir, "image");
  r.finish();

  linear_image img;
  try {
    img = read_linear_image(w.file);
  } catch (const std::runtime_error& err) {
    r.fail(r.field("image"), err.what());
  }
  if (img.luminance.cols != d.setup.observer.width || img.luminance.rows != d.setup.observer.height)
    r.fail(r.field("image"),
           w.file + " is " + std::to_string(img.luminance.cols) + "x" + std::to_string(img.luminance.rows) +
               ", but the setup scene's camera is " + std::to_string(d.setup.observer.width) + "x" +
               std::to_string(d.setup.observer.height) + " (white squares are framed by that camera)");
  for (int y = 0; y < img.luminance.rows; ++y) {
    for (int x = 0; x < img.luminance.cols; ++x) {
      const double v = img.luminance.at<double>(y, x);
      if (!std::isfinite(v))
        r.fail(r.field("image"), w.file + ": pixel (" + std::to_string(x) + ", " + std::to_string(y) + ") is " +
                                     (std::isnan(v) ? "NaN" : "infinite"));
    }
  }
  w.luminance = img.luminance;
  check_entry_layout(d.setup, w.tilt_deg, w.floating_distance_mm, w.origin);
  return w;
}

const json& array_of(json_reader& r, const std::string& key, bool required) {
  static const json empty = json::array();
  if (!r.has(key)) {
    if (required) r.fail(r.field(key), "missing");
    return empty;
  }
  const json& v = r.raw(key);
  if (!v.is_array() || v.empty()) r.fail(r.field(key), "must be a non-empty array");
  return v;
}

}  // namespace

void read_mtf_csv(const std::string& path, mtf_measurement& m) {
  const csv_table t = read_csv_table(path);
  const int c_lp = t.column("lp_per_mm"), c_mtf = t.column("mtf"), c_cpp = t.column("cycles_per_pixel");
  if (c_lp < 0)
    throw input_error(path +
                      ": no lp_per_mm column in the header (the `airr mtf` format is cycles_per_pixel,lp_per_mm,mtf)");
  if (c_mtf < 0)
    throw input_error(path + ": no mtf column in the header (the `airr mtf` format is cycles_per_pixel,lp_per_mm,mtf)");

  std::vector<double> cpp;
  m.lp_per_mm.clear();
  m.mtf.clear();
  for (std::size_t i = 0; i < t.rows.size(); ++i) {
    const auto& row = t.rows[i];
    const double f = row[std::size_t(c_lp)];
    if (f < 0) throw input_error(t.where(i) + ": lp_per_mm: negative frequency");
    if (!m.lp_per_mm.empty() && !(f > m.lp_per_mm.back()))
      throw input_error(t.where(i) + ": lp_per_mm: frequencies must ascend");
    m.lp_per_mm.push_back(f);
    m.mtf.push_back(row[std::size_t(c_mtf)]);
    if (c_cpp >= 0) cpp.push_back(row[std::size_t(c_cpp)]);
  }
  if (m.lp_per_mm.size() < 2) throw input_error(path + ": needs at least 2 rows of data");

  // The measuring pixel follows from the two frequency columns.
  m.pixel_mm = 0;
  if (c_cpp >= 0) {
    for (std::size_t i = 0; i < cpp.size(); ++i) {
      if (m.lp_per_mm[i] <= 0) continue;
      const double p = cpp[i] / m.lp_per_mm[i];
      if (m.pixel_mm == 0)
        m.pixel_mm = p;
      else if (std::abs(p - m.pixel_mm) > 1e-3 * m.pixel_mm)
        throw input_error(path + ": cycles_per_pixel and lp_per_mm disagree on the pixel size (" +
                          number_text(m.pixel_mm) + " and " + number_text(p) + " mm)");
    }
    if (!(m.pixel_mm > 0)) throw input_error(path + ": cycles_per_pixel: must be positive where lp_per_mm is");
  }
}

std::vector<std::string> fit_data::files() const {
  std::vector<std::string> out = {fit_json, scene_path};
  for (const auto& m : tilt_series) out.push_back(m.file);
  for (const auto& m : distance_series) out.push_back(m.file);
  for (const auto& w : white_squares) out.push_back(w.file);
  if (!shift_table.empty()) out.push_back(shift_table);
  std::sort(out.begin() + 2, out.end());
  out.erase(std::unique(out.begin() + 2, out.end()), out.end());
  return out;
}

scene measurement_layout(const scene& setup, double tilt_deg, double floating_distance_mm) {
  scene s = setup;
  s.sheet().pose.pitch_deg = tilt_deg;
  airr::set_floating_distance(s, floating_distance_mm);
  const pose mirrored = mirrored_in_half_mirror(s, retroreflector_frame(s, 0));
  for (std::size_t i = 1; i < s.retroreflectors.size(); ++i) s.retroreflectors[i].pose = mirrored;
  return s;
}

void check_fit_sheets(const scene& setup, const std::string& origin) {
  const part_frame mirrored = pose_frame(mirrored_in_half_mirror(setup, retroreflector_frame(setup, 0)), 1, 1);
  for (std::size_t i = 1; i < setup.retroreflectors.size(); ++i) {
    const part_frame f = retroreflector_frame(setup, i);
    if (glm::length(f.center - mirrored.center) > 1e-3 || glm::dot(f.n, mirrored.n) < 1 - 1e-9) {
      throw input_error(origin + ": retroreflectors[" + std::to_string(i) +
                        "]: the fit simulates every sheet with the first sheet's a and mu at each tilt, so a "
                        "device's other sheets must be the first sheet's mirror image in the half mirror (centre " +
                        vector_text(mirrored.center) + " mm, facing " + vector_text(mirrored.n) +
                        "); measure the sheet on a one-sheet bench, or mirror it");
    }
  }
}

fit_data load_fit_data(const std::string& dir_text) {
  fit_data d;
  d.dir = fs::path(dir_text).lexically_normal().string();
  std::error_code ec;
  if (!fs::is_directory(d.dir, ec))
    throw input_error(dir_text + ": not a directory (expected a fit data directory holding fit.json)");
  d.fit_json = (fs::path(d.dir) / "fit.json").string();
  if (!fs::is_regular_file(d.fit_json, ec))
    throw input_error(d.fit_json + ": missing (a fit data directory needs fit.json; see assets/fit_example/README.md)");
  const json j = read_json_file(d.fit_json);
  json_reader r(j, d.fit_json, "");
  if (r.string("format") != fit_data_format)
    r.fail(r.field("format"), std::string("expected \"") + fit_data_format + "\"");
  const double version = r.number("version");
  if (version != fit_data_version) r.fail(r.field("version"), "unsupported version " + number_text(version));
  d.name = r.has("name") ? r.string("name") : fs::path(d.dir).filename().string();
  if (r.has("note")) d.note = r.string("note");

  d.scene_path = resolve_file(r, d.dir, "scene");
  d.setup = load_scene(d.scene_path);
  check_fit_sheets(d.setup, d.scene_path);

  const json& tilts = array_of(r, "tilt_series", true);
  for (std::size_t i = 0; i < tilts.size(); ++i)
    d.tilt_series.push_back(read_measurement(tilts[i], d, "tilt_series[" + std::to_string(i) + "]", false));
  const json& distances = array_of(r, "distance_series", true);
  for (std::size_t i = 0; i < distances.size(); ++i)
    d.distance_series.push_back(read_measurement(distances[i], d, "distance_series[" + std::to_string(i) + "]", true));
  if (r.has("white_squares")) {
    const json& whites = array_of(r, "white_squares", false);
    for (std::size_t i = 0; i < whites.size(); ++i)
      d.white_squares.push_back(read_white_square(whites[i], d, "white_squares[" + std::to_string(i) + "]"));
  }
  d.mu = r.optional_number("mu");
  if (d.mu && (*d.mu < 0 || *d.mu > 1)) r.fail(r.field("mu"), "must be in [0, 1]");
  if (d.mu && !d.white_squares.empty())
    r.fail(r.field("mu"), "give white_squares (mu is fitted) or mu (mu is fixed), not both");
  if (r.has("shift_table")) {
    // Absolute: the fit's scenes resolve it against the setup's folder.
    d.shift_table = absolute_path(resolve_file(r, d.dir, "shift_table"));
    cached_shift_table(d.shift_table);  // read now: a bad table is named before the fit starts
  }
  r.finish();

  auto by_tilt = [](const auto& a, const auto& b) { return a.tilt_deg < b.tilt_deg; };
  std::stable_sort(d.tilt_series.begin(), d.tilt_series.end(), by_tilt);
  std::stable_sort(d.white_squares.begin(), d.white_squares.end(), by_tilt);
  std::stable_sort(d.distance_series.begin(), d.distance_series.end(),
                   [](const auto& a, const auto& b) { return a.floating_distance_mm < b.floating_distance_mm; });
  for (std::size_t i = 1; i < d.tilt_series.size(); ++i) {
    if (d.tilt_series[i].tilt_deg == d.tilt_series[i - 1].tilt_deg)
      r.fail(r.field("tilt_series"), "tilt " + number_text(d.tilt_series[i].tilt_deg) + " deg appears twice");
  }
  if (d.tilt_series.front().tilt_deg != 0)
    r.fail(r.field("tilt_series"), "no measurement at tilt 0 (a(0) and c are fitted there)");
  std::set<double> distinct;
  for (const auto& m : d.distance_series) distinct.insert(m.floating_distance_mm);
  if (distinct.size() < 2)
    r.fail(r.field("distance_series"), "needs at least 2 different floating distances for the slope of mean MTF (has " +
                                           std::to_string(distinct.size()) + ")");
  for (std::size_t i = 0; i < d.white_squares.size(); ++i) {
    const double t = d.white_squares[i].tilt_deg;
    if (i > 0 && t == d.white_squares[i - 1].tilt_deg)
      r.fail(r.field("white_squares"), "tilt " + number_text(t) + " deg appears twice");
    if (std::none_of(d.tilt_series.begin(), d.tilt_series.end(), [&](const auto& m) { return m.tilt_deg == t; }))
      r.fail(r.field("white_squares"),
             "tilt " + number_text(t) +
                 " deg has no tilt_series entry (the preset tabulates mu at the tilt series' angles)");
  }
  return d;
}

}  // namespace airr::analysis
