// airr.fit: the sheet fit of `airr fit`, from a fit data directory to a preset.
#include <filesystem>
#include <optional>
#include <string>

#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include "airr/analysis/fit_data.hpp"
#include "airr/analysis/sheet_fit.hpp"
#include "airr/core/error.hpp"
#include "airr/models/preset.hpp"
#include "py_arrays.hpp"
#include "py_calls.hpp"
#include "py_job.hpp"

namespace py = pybind11;

namespace airr::python {

namespace {

py::dict fit(const std::filesystem::path& data_dir, std::optional<std::filesystem::path> output, std::uint64_t samples,
             std::uint64_t seed, py::object progress) {
  analysis::fit_params p;
  p.psf_samples = samples;
  p.seed = seed;
  python_job job(std::move(progress));
  std::optional<analysis::fit_result> r;
  {
    py::gil_scoped_release released;
    const analysis::fit_data data = analysis::load_fit_data(data_dir.string());
    try {
      r = analysis::fit_sheet(data, p, [&](const analysis::fit_progress& f) { return job.keep_going(f.fraction); });
    } catch (const analysis::fit_cancelled&) {
    }
  }
  job.finish();
  if (!r) throw std::logic_error("fit: cancelled without a reason");
  if (output) save_preset(r->preset, output->string());
  py::dict out;
  out["name"] = r->preset.name;
  out["theta_deg"] = to_array(r->preset.theta_deg);
  out["a_per_mm"] = to_array(r->preset.a_per_mm);
  out["mu"] = to_array(r->preset.mu);
  out["c_mm"] = r->preset.c_mm;
  out["reference_distance_mm"] = r->preset.reference_distance_mm;
  out["simulations"] = r->report.simulations;
  out["preset"] = to_python(preset_to_json(r->preset));
  return out;
}

}  // namespace

void add_fit_functions(py::module_& m) {
  m.def("fit", &fit, py::arg("data_dir"), py::kw_only(), py::arg("output") = py::none(), py::arg("samples") = 200000,
        py::arg("seed") = 1, py::arg("progress") = py::none(),
        R"(Fits the sinc-shift model's a and mu per tilt and c to a sheet's measurements, as `airr fit` does.

data_dir: a fit data directory (fit.json with its MTF curves, edge images and white squares;
see assets/fit_example). output: the preset file to write (atomically), if any. samples, seed:
the model PSF's per simulation. progress: called with the fraction done; an exception it raises
(or Ctrl+C) stops the fit and reaches the caller.

Returns a dict: "name", "theta_deg", "a_per_mm", "mu" (arrays per tilt), "c_mm",
"reference_distance_mm", "simulations", and "preset", the preset as written (with its
provenance: the data, the losses, the settings).)");
}

}  // namespace airr::python
