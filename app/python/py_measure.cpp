// airr.psf, airr.mtf and airr.read_image: the model PSF and its MTF, the slanted-edge MTF of an
// image, and the project's image loader, into numpy arrays and dicts.
#include <cstdio>
#include <filesystem>
#include <limits>
#include <optional>
#include <string>

#include <pybind11/numpy.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include "airr/analysis/image_read.hpp"
#include "airr/analysis/mtf_metrics.hpp"
#include "airr/analysis/psf_grid.hpp"
#include "airr/analysis/psf_mtf.hpp"
#include "airr/analysis/similarity.hpp"
#include "airr/analysis/slanted_edge_mtf.hpp"
#include "airr/core/error.hpp"
#include "airr/layout/layout.hpp"
#include "airr/measure/mtf_routes.hpp"
#include "py_arrays.hpp"
#include "py_calls.hpp"
#include "py_scene.hpp"

namespace py = pybind11;

namespace airr::python {

namespace {

py::dict psf(const py_scene& ps, std::uint64_t samples, bool pixel, double max_lp_per_mm, int points, int image_pixels,
             std::optional<double> extent_mm) {
  if (samples < 100 || samples > 100000000) throw input_error("psf: samples must be in [100, 100000000]");
  if (!(max_lp_per_mm > 0) || points < 2) throw input_error("psf: max_lp_per_mm must be > 0 and points >= 2");
  if (image_pixels < 3 || image_pixels > 4095 || image_pixels % 2 == 0)
    throw input_error("psf: image_pixels must be odd, in [3, 4095] (the middle pixel is the ideal point)");
  if (extent_mm && !(*extent_mm > 0)) throw input_error("psf: extent_mm must be > 0");
  const scene& s = ps.current();
  py::dict out;
  {
    py::gil_scoped_release released;
    const retro_model_list models = make_sheet_models(s);
    const double pixel_mm = pixel ? make_camera(s).mm_per_pixel : 0.0;
    // As `airr psf` computes them: the curve and summary from the stratified samples, the 2D
    // picture from independent ones.
    const psf_samples p = scene_psf(s, models, samples);
    const auto curve = analysis::psf_mtf(p, {.max_lp_per_mm = max_lp_per_mm, .points = points, .pixel_mm = pixel_mm});
    const mtf_summary m = psf_route_mtf(p, pixel_mm);
    const double r50 = energy_radius(p);
    const legible_character legible =
        psf_legible_character(s, p, std::numeric_limits<double>::infinity(), legibility_criterion{});
    const psf_samples loose = sample_psf(s, models, {.samples = samples, .seed = s.seed, .stratified = false});
    const double half = extent_mm ? *extent_mm : analysis::psf_picture_half_width(loose, true);
    const analysis::psf_grid grid = analysis::psf_to_grid(loose, image_pixels, 2 * half / image_pixels);
    py::gil_scoped_acquire held;
    out["lp_per_mm"] = to_array(curve.lp_per_mm);
    out["mtf"] = to_array(curve.mtf);
    out["pixel_mm"] = pixel_mm;
    out["r50_mm"] = r50;
    out["mean_mtf"] = m.mean_mtf;
    out["mtf50_lp_per_mm"] = m.mtf50_lp_per_mm ? py::object(py::float_(*m.mtf50_lp_per_mm)) : py::none();
    out["brightness"] = p.brightness();
    out["luminance_cd_m2"] =
        in_cd_m2(s.source) ? py::object(py::float_(p.brightness() * s.source.luminance_cd_m2)) : py::none();
    out["char_height_mm"] = legible.height_mm;
    out["char_height_arcmin"] = legible.arcmin;
    out["launched"] = p.launched;
    out["reached"] = p.offset_mm.size();
    cv::Mat density(grid.size, grid.size, CV_64FC1, const_cast<double*>(grid.density.data()));
    out["image"] = to_array(density);
    out["image_mm_per_pixel"] = grid.mm_per_pixel;
  }
  return out;
}

// An image given as a path or a numpy array (H x W grey, or H x W x 3 linear RGB): its luminance,
// and its pixel size when the file holds one.
struct given_image {
  cv::Mat luminance;
  std::optional<double> mm_per_pixel;
};

given_image image_of(const py::object& image, const std::string& what) {
  if (py::isinstance<py::str>(image) || py::hasattr(image, "__fspath__")) {
    const std::string path = py::str(py::module_::import("os").attr("fspath")(image));
    const analysis::linear_image read = analysis::read_linear_image(path);
    return {read.luminance, read.mm_per_pixel};
  }
  const auto a = image.cast<py::array_t<double, py::array::c_style | py::array::forcecast>>();
  const int rows = a.ndim() >= 2 ? int(a.shape(0)) : 0, cols = a.ndim() >= 2 ? int(a.shape(1)) : 0;
  if (a.ndim() == 2) return {cv::Mat(rows, cols, CV_64FC1, const_cast<double*>(a.data())).clone(), {}};
  if (a.ndim() == 3 && a.shape(2) == 3)
    return {analysis::rec709_luminance(cv::Mat(rows, cols, CV_64FC3, const_cast<double*>(a.data()))), {}};
  throw input_error(what + ": the image must be height x width (grey) or height x width x 3 (linear RGB)");
}

py::dict mtf(const py::object& image, std::optional<double> mm_per_pixel, std::optional<std::vector<int>> roi,
             int oversampling, double max_cycles_per_pixel) {
  const given_image given = image_of(image, "mtf");
  const cv::Mat& lum = given.luminance;
  const std::optional<double> pixel = mm_per_pixel ? mm_per_pixel : given.mm_per_pixel;
  analysis::slanted_edge_params p;
  p.oversampling = oversampling;
  p.max_cycles_per_pixel = max_cycles_per_pixel;
  if (roi) {
    if (roi->size() != 4) throw input_error("mtf: roi is (x, y, width, height)");
    p.roi = cv::Rect((*roi)[0], (*roi)[1], (*roi)[2], (*roi)[3]);
  }
  if (pixel && !(*pixel > 0)) throw input_error("mtf: mm_per_pixel must be > 0");
  analysis::mtf_curve c;
  try {
    py::gil_scoped_release released;
    c = analysis::slanted_edge_mtf(lum, p);
  } catch (const airr_error&) {
    throw;
  } catch (const std::runtime_error& e) {
    throw measurement_error(std::string("mtf: ") + e.what());
  }
  py::dict out;
  out["cycles_per_pixel"] = to_array(c.cycles_per_pixel);
  out["mtf"] = to_array(c.mtf);
  out["lp_per_mm"] = pixel ? py::object(to_array(analysis::to_lp_per_mm(c.cycles_per_pixel, *pixel))) : py::none();
  out["mm_per_pixel"] = pixel ? py::object(py::float_(*pixel)) : py::none();
  const auto m50 = analysis::mtf50(c, pixel.value_or(0));
  out["mtf50_cycles_per_pixel"] = m50 ? py::object(py::float_(m50->cycles_per_pixel)) : py::none();
  out["mtf50_lp_per_mm"] = m50 && pixel ? py::object(py::float_(m50->lp_per_mm)) : py::none();
  out["mean_mtf"] = pixel ? py::object(py::float_(analysis::mean_mtf(c, *pixel).value)) : py::none();
  out["edge_angle_deg"] = c.edge_angle_deg;
  out["edge"] = c.orientation == analysis::edge_orientation::near_vertical ? "vertical" : "horizontal";
  out["roi"] = py::make_tuple(c.roi.x, c.roi.y, c.roi.width, c.roi.height);
  return out;
}

py::dict compare(const py::object& a, const py::object& b, std::optional<double> data_range) {
  const given_image x = image_of(a, "compare"), y = image_of(b, "compare");
  if (x.luminance.size() != y.luminance.size())
    throw input_error("compare: the images differ in size: " + std::to_string(x.luminance.cols) + "x" +
                      std::to_string(x.luminance.rows) + " and " + std::to_string(y.luminance.cols) + "x" +
                      std::to_string(y.luminance.rows));
  if (data_range && !(*data_range > 0)) throw input_error("compare: data_range must be > 0");
  analysis::ssim_params p;
  p.data_range = data_range ? *data_range : analysis::auto_data_range(x.luminance, y.luminance);
  py::dict out;
  try {
    out["ssim"] = analysis::ssim(x.luminance, y.luminance, p);
    const auto ms = analysis::ms_ssim(x.luminance, y.luminance, p);
    out["ms_ssim"] = ms.value;
    out["ms_ssim_scales"] = ms.scales;
  } catch (const airr_error&) {
    throw;
  } catch (const std::runtime_error& e) {
    throw measurement_error(std::string("compare: ") + e.what());
  }
  out["data_range"] = p.data_range;
  return out;
}

py::dict read_image(const std::filesystem::path& path) {
  loaded_image img = load_image(path.string());
  py::dict out;
  out["pixels"] = to_array(img.pixels);
  out["mm_per_pixel"] = img.mm_per_pixel ? py::object(py::float_(*img.mm_per_pixel)) : py::none();
  out["srgb_decoded"] = img.srgb_decoded;
  out["format"] = img.format;
  return out;
}

void write_image_file(const std::filesystem::path& file,
                      const py::array_t<float, py::array::c_style | py::array::forcecast>& a, float exposure,
                      std::optional<double> mm_per_pixel) {
  const std::string path = file.string();
  if (a.ndim() != 3 || a.shape(2) != 3) throw input_error(path + ": write_image takes a height x width x 3 array");
  if (!(exposure > 0)) throw input_error(path + ": exposure must be > 0");
  image_rgb img{int(a.shape(1)), int(a.shape(0)), std::vector<float>(a.data(), a.data() + a.size())};
  image_metadata meta{{"airr:generator", "airr Python module"}};
  if (mm_per_pixel) {
    if (!(*mm_per_pixel > 0)) throw input_error(path + ": mm_per_pixel must be > 0");
    char text[64];
    std::snprintf(text, sizeof text, "%.17g", *mm_per_pixel);
    meta[mm_per_pixel_attribute] = text;
  }
  py::gil_scoped_release released;
  write_image(path, img, meta, exposure);
}

}  // namespace

void add_measure_functions(py::module_& m) {
  m.def("psf", &psf, py::arg("scene"), py::kw_only(), py::arg("samples") = 100000, py::arg("pixel") = true,
        py::arg("max_lp_per_mm") = 2.0, py::arg("points") = 101, py::arg("image_pixels") = 129,
        py::arg("extent_mm") = py::none(),
        R"(The model PSF of the scene at the aerial image's centre (no tracer), as `airr psf` computes it.

Returns a dict: "lp_per_mm" and "mtf" (the MTF curve, float64 arrays, with the camera pixel's
aperture unless pixel=False), "pixel_mm", "r50_mm" (50%-energy radius), "mean_mtf" (over (0, 1]
lp/mm), "mtf50_lp_per_mm" (None when the MTF stays above 0.5), "brightness" (aerial radiance per
unit source radiance), "luminance_cd_m2" (the aerial image's luminance, brightness times the
display's source.luminance_cd_m2; None in relative units), "char_height_mm" and
"char_height_arcmin" (the smallest legible character from the observer in the dark,
docs/ambient-light.md), "launched" and "reached" (samples), and the 2D PSF: "image", an
image_pixels x image_pixels float64 array of density per mm^2 (x right, y up, row 0 the top; it
integrates to the brightness that falls inside it), "image_mm_per_pixel" (the picture spans
extent_mm either side of the ideal point; default the square holding 99.8% of the PSF).)");
  m.def("mtf", &mtf, py::arg("image"), py::kw_only(), py::arg("mm_per_pixel") = py::none(), py::arg("roi") = py::none(),
        py::arg("oversampling") = 4, py::arg("max_cycles_per_pixel") = 1.0,
        R"(The slanted-edge MTF of an image holding one straight edge, as `airr mtf` measures it.

image: a path (EXR, PNG, TIFF...: read by the project's loader, 8-bit files sRGB-decoded) or a
numpy array, height x width (grey) or height x width x 3 (linear RGB; measured on its Rec.709
luminance). mm_per_pixel: the pixel's size (default: the file's airr:mm_per_pixel, if any).
roi: (x, y, width, height) of the edge's region (default the whole image).

Returns a dict: "cycles_per_pixel" and "mtf" (float64 arrays), "lp_per_mm" (None without a pixel
size), "mm_per_pixel", "mtf50_cycles_per_pixel", "mtf50_lp_per_mm", "mean_mtf" (over (0, 1]
lp/mm; None without a pixel size), "edge_angle_deg", "edge" ("vertical" or "horizontal"), "roi".)");
  m.def("compare", &compare, py::arg("a"), py::arg("b"), py::kw_only(), py::arg("data_range") = py::none(),
        R"(How alike two images of the same size are, as `airr compare` scores them: SSIM (Gaussian
window 11, sigma 1.5) and MS-SSIM on the linear Rec.709 luminance.

a, b: paths or numpy arrays (as for mtf). data_range: the pixel values' range L (default max -
min over both). Returns a dict: "ssim", "ms_ssim", "ms_ssim_scales", "data_range".)");
  m.def("write_image", &write_image_file, py::arg("path"), py::arg("pixels"), py::kw_only(), py::arg("exposure") = 1.0f,
        py::arg("mm_per_pixel") = py::none(),
        R"(Writes a linear height x width x 3 image (atomically): EXR as float, PNG as sRGB scaled by
exposure. mm_per_pixel is stored as the file's airr:mm_per_pixel (what mtf and the fit read).)");
  m.def("read_image", &read_image, py::arg("path"),
        R"(Reads an image file with the project's loader (the rule every command follows: float and
16-bit files linear, 8-bit files sRGB-decoded unless tagged linear).

Returns a dict: "pixels" (float32 array, height x width x 3, linear), "mm_per_pixel" (from the
file's airr:mm_per_pixel, or None), "srgb_decoded", "format" (the file's pixel type).)");
}

}  // namespace airr::python
