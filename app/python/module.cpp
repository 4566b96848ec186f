// The compiled part of the Python package `airr` (airr/__init__.py re-exports it with the
// documentation): the same libraries as `airr` and `airr-studio`, numpy arrays in and out.
#include <cmath>
#include <filesystem>
#include <optional>
#include <string>

#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include "airr/core/assets.hpp"
#include "airr/core/error.hpp"
#include "airr_version.hpp"
#include "py_calls.hpp"
#include "py_scene.hpp"

namespace py = pybind11;

namespace airr::python {

namespace {

// A Python value as `--set` text: strings as they are, True/False as true/false, NaN and the
// infinities as nan/inf, numbers (numpy's too) and lists as JSON; any other value (bytes, complex,
// objects) is a ValueError naming the key.
std::string set_text(const std::string& key, const py::object& value) {
  if (py::isinstance<py::str>(value)) return value.cast<std::string>();
  if (py::isinstance<py::bool_>(value)) return value.cast<bool>() ? "true" : "false";
  py::object v = value;
  if (py::hasattr(v, "tolist")) v = v.attr("tolist")();  // numpy scalars and arrays
  if (py::isinstance<py::float_>(v)) {
    const double d = v.cast<double>();
    if (std::isnan(d)) return "nan";
    if (std::isinf(d)) return d > 0 ? "inf" : "-inf";
  }
  try {
    return py::module_::import("json").attr("dumps")(v).cast<std::string>();
  } catch (const py::error_already_set&) {
    throw py::value_error(key + ": a " + std::string(py::str(value.get_type().attr("__name__"))) +
                          " cannot be set (a number, text, True/False or a list)");
  }
}

void add_scene(py::module_& m) {
  py::class_<py_scene>(m, "Scene", R"(A layout read from a scene file, changed by `set` as `airr --set` changes it.

Scene.load(path) reads a scene (JSON, or a glTF layout) and checks it as every command does.
set(key, value) applies one `--set key=value` (the same keys: dotted fields such as
"retroreflectors.0.pose.pitch_deg", and the short keys "floating_distance_mm" and "tilt_deg") and
checks the scene again; a bad key or value raises ValueError with the message `airr --set` gives,
and leaves the scene as it was.)")
      .def_static(
          "load", [](const std::filesystem::path& path) { return py_scene::load(path.string()); }, py::arg("path"),
          "Reads and checks a scene file (JSON or glTF layout).")
      .def(
          "set", [](py_scene& s, const std::string& key, const py::object& value) { s.set(key, set_text(key, value)); },
          py::arg("key"), py::arg("value"),
          "Sets a value as `--set key=value` does (a number, text, True/False or a list); raises ValueError as "
          "`airr --set` fails.")
      .def(
          "get",
          [](const py_scene& s, const std::string& key) {
            return py::module_::import("json").attr("loads")(s.get(key).dump());
          },
          py::arg("key"),
          "The value a key names: a number, text, True/False, None (unset), a list or a dict, as the scene's JSON "
          "holds it (e.g. \"tilt_deg\", \"floating_distance_mm\", \"half_mirror.kind\", "
          "\"retroreflectors.0.films\").")
      .def(
          "save",
          [](py_scene& s, const std::optional<std::filesystem::path>& path) {
            s.save(path ? path->string() : s.path());
          },
          py::arg("path") = py::none(),
          "Writes the scene (atomically) to path, or over the file it was read from; relative paths are rewritten "
          "to count from the new file's folder, which is then the scene's file.")
      .def_property_readonly("path", &py_scene::path, "The file the scene was read from (or last saved to).")
      .def_property_readonly(
          "units", [](const py_scene& s) { return std::string(image_units(s.current().source)); },
          "The units of the scene's images: \"cd/m2\" when source.luminance_cd_m2 is set, else \"relative\" "
          "(radiance in units of source.intensity).")
      .def_property_readonly(
          "overrides",
          [](const py_scene& s) {
            py::list out;
            for (const auto& o : s.overrides()) out.append(py::make_tuple(o.key, o.value));
            return out;
          },
          "The (key, value) pairs set since the scene was read, in order.")
      .def("to_json", &py_scene::json_text, "The scene as the JSON text `save` writes.")
      .def("__repr__", [](const py_scene& s) {
        return "<airr.Scene " + s.path() +
               (s.overrides().empty() ? "" : " with " + std::to_string(s.overrides().size()) + " set") + ">";
      });
}

}  // namespace

}  // namespace airr::python

PYBIND11_MODULE(_airr, m) {
  m.doc() = "AIRR Studio's libraries (the package airr re-exports them)";
  m.attr("__version__") = AIRR_VERSION;
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const airr::airr_error& e) {
      PyErr_SetString(PyExc_ValueError, e.what());
    }
  });
  m.def("_set_asset_dir", &airr::set_asset_dir, py::arg("dir"));
  m.def("asset_dir", &airr::asset_dir, "Where the shipped assets (scenes, presets, charts, models) are read from.");
  airr::python::add_scene(m);
  airr::python::add_render_functions(m);
  airr::python::add_measure_functions(m);
  airr::python::add_fit_functions(m);
  airr::python::add_study_functions(m);
}
