// airr.render: the scene traced as `airr render` traces it, into numpy arrays.
#include <atomic>
#include <chrono>
#include <cstdint>
#include <future>
#include <memory>
#include <optional>

#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include "airr/core/error.hpp"
#include "airr/render/memory_need.hpp"
#include "airr/render/path_expression.hpp"
#include "airr/render/ray_file.hpp"
#include "airr/render/render_session.hpp"
#include "airr/render/tracer.hpp"
#include "py_arrays.hpp"
#include "py_calls.hpp"
#include "py_job.hpp"
#include "py_scene.hpp"

namespace py = pybind11;

namespace airr::python {

namespace {

py::object render(const py_scene& ps, std::uint64_t spp, std::optional<std::uint64_t> seed, bool components,
                  std::optional<py::dict> layers, int threads, py::object progress) {
  if (spp < 1 || spp > (1u << 24))
    throw input_error("render: spp must be in [1, 16777216] (is " + std::to_string(spp) + ")");
  if (threads < 0 || threads > 1024) throw input_error("render: threads must be in [0, 1024]");
  scene s = ps.current();
  if (seed) s.seed = *seed;
  // The layers as `airr render --layer NAME=EXPR` takes them, in the dict's order.
  std::shared_ptr<const path_layers> path_layers;
  if (layers) {
    std::vector<std::string> arguments;
    for (const auto& [name, expression] : *layers) {
      const std::string n = py::str(name), e = py::str(expression);
      arguments.push_back(n + "=" + e);
    }
    std::vector<std::string> taken;
    if (components) taken = component_layer_names(int(s.environment.luminaires.size()));
    path_layers = std::make_shared<const airr::path_layers>(parse_layer_arguments(arguments, s, taken));
  }
  python_job job(std::move(progress));
  render_snapshot snap;
  {
    py::gil_scoped_release released;
    // As `airr render` sets it up, so that the same scene and seed give the same image. The
    // session is built on another thread (its opening model image takes a second or more) while
    // this one watches for Ctrl+C, which cancels the build.
    std::atomic<bool> build_cancel{false};
    const session_params params{.threads = threads,
                                .target_spp = spp,
                                .components = components,
                                .layers = path_layers,
                                .build_cancel = &build_cancel,
                                .final_images_only = true};
    check_render_memory(s, params);  // refused before anything is allocated
    auto building = std::async(std::launch::async, [&] { return std::make_unique<render_session>(s, params); });
    while (building.wait_for(std::chrono::milliseconds(50)) != std::future_status::ready)
      if (!job.keep_going(0.0)) build_cancel = true;
    const std::unique_ptr<render_session> session = building.get();
    if (!job.stopped())
      snap = render_to_spp(
          *session, spp, [&](std::uint64_t done) { return job.keep_going(double(done) / double(spp)); },
          std::chrono::milliseconds(50));
  }
  job.finish();
  py::array_t<float> image = to_array(snap.image());
  if (!components && !path_layers) return image;
  py::dict parts;
  const std::vector<image_rgb> split = snap.component_images();
  const std::vector<std::string> names = snap.component_image_names();
  for (std::size_t k = 0; components && k < split.size(); ++k) parts[py::str(names[k])] = to_array(split[k]);
  for (std::size_t k = 0; k < snap.layer_names.size(); ++k)
    parts[py::str(snap.layer_names[k])] = to_array(snap.layer_image(k));
  return py::make_tuple(image, parts);
}

py::dict record_rays(const py_scene& ps, const py::object& file, std::uint64_t spp, std::optional<std::uint64_t> seed,
                     const std::string& select, std::uint64_t limit, int threads, py::object progress) {
  if (spp < 1 || spp > (1u << 24))
    throw input_error("record_rays: spp must be in [1, 16777216] (is " + std::to_string(spp) + ")");
  if (threads < 0 || threads > 1024) throw input_error("record_rays: threads must be in [0, 1024]");
  const std::string path = py::str(py::module_::import("os").attr("fspath")(file));
  scene s = ps.current();
  if (seed) s.seed = *seed;
  const ray_file_params p{.select = select, .segment_limit = limit, .spp = spp, .threads = threads};
  check_ray_file(path, s, p);
  python_job job(std::move(progress));
  ray_record r;
  {
    py::gil_scoped_release released;
    r = airr::record_rays(s, p, [&](double done) { return job.keep_going(done); });
    if (!job.stopped()) write_ray_file(path, s, p, r);
  }
  job.finish();
  py::dict out;
  out["paths"] = r.paths.size();
  out["segments"] = r.segments.size();
  out["selected"] = r.selected;
  out["complete"] = r.complete;
  return out;
}

}  // namespace

void add_render_functions(py::module_& m) {
  m.def("record_rays", &record_rays, py::arg("scene"), py::arg("path"), py::kw_only(), py::arg("spp") = 64,
        py::arg("seed") = py::none(), py::arg("select") = ".*", py::arg("limit") = 1000000, py::arg("threads") = 0,
        py::arg("progress") = py::none(),
        R"(Write the ray file of a render, as `airr render --rays PATH --rays-select SELECT --rays-limit LIMIT`.

Traces the paths a render of the scene with the same spp and seed traces and keeps those the path
expression `select` selects (docs/path-expressions.md), segment by segment in the light's order,
until `limit` segments are kept; read the file with airr.read_rays (format: docs/ray-file.md).
Returns {"paths", "segments", "selected", "complete"}: the paths and segments written, the paths
selected, and whether every selected path was written. A bad expression, a limit out of range or
a file the disk could not hold raises ValueError before anything is traced.)");
  m.def("render", &render, py::arg("scene"), py::kw_only(), py::arg("spp") = 64, py::arg("seed") = py::none(),
        py::arg("components") = false, py::arg("layers") = py::none(), py::arg("threads") = 0,
        py::arg("progress") = py::none(),
        R"(Render the scene with the tracer, as `airr render` does.

Returns the linear image as a float32 array of shape (height, width, 3): the same pixels `airr
render SCENE -o out.exr --spp N [--seed S]` writes for the same scene. With components=True
returns (image, components), components a dict of the image's parts ("aerial", "direct",
"reflection", "rest", "room", "sun", "luminaires"), arrays of the same shape that add up to the image,
and each luminaire's own ("luminaire0", "luminaire1", ...), which add up to "luminaires". With layers, a dict
{name: path expression} (docs/path-expressions.md), as `airr render --layer NAME=EXPR`: returns
(image, parts), parts holding each layer's light and "unmatched" (the paths no layer selects),
and the components when asked too; a bad expression raises ValueError pointing at the character.

spp: samples per pixel. seed: overrides the scene's seed. threads: worker threads (0: all
cores). progress: called with the fraction done (0 to 1, increasing); an exception it raises
stops the render and reaches the caller. The render runs without the GIL; Ctrl+C stops it
within a fraction of a second (KeyboardInterrupt).)");
}

}  // namespace airr::python
