#include "fuzz_targets.hpp"

#include <unistd.h>

#include <algorithm>
#include <charconv>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <vector>

#include "airr/analysis/fit_data.hpp"
#include "airr/analysis/onnx_inputs.hpp"
#include "airr/core/csv_table.hpp"
#include "airr/core/error.hpp"
#include "airr/core/files.hpp"
#include "airr/formats/design_spec.hpp"
#include "airr/formats/gltf_layout.hpp"
#include "airr/formats/image.hpp"
#include "airr/formats/mesh_step.hpp"
#include "airr/formats/prop_mesh.hpp"
#include "airr/formats/scene_json.hpp"
#include "airr/formats/sheet_json.hpp"
#include "airr/models/preset.hpp"
#include "airr/models/shift_table.hpp"
#include "airr/render/path_expression.hpp"
#include "airr/render/render_shards.hpp"
#include "cluster/partial_file.hpp"

namespace airr::fuzz {

namespace fs = std::filesystem;

// A folder of this process's own for the files the loaders read (they take paths), and for the
// cache glTF images are extracted into (XDG_CACHE_HOME); removed at exit.
struct work_folder {
  fs::path path = fs::temp_directory_path() / ("airr-fuzz-" + std::to_string(::getpid()));
  work_folder() {
    fs::create_directories(path);
    ::setenv("XDG_CACHE_HOME", path.c_str(), 1);
  }
  ~work_folder() {
    std::error_code ec;
    fs::remove_all(path, ec);
  }
};
static const fs::path& work_dir() {
  static const work_folder folder;
  return folder.path;
}

static std::string write_input(const std::string& name, std::string_view bytes) {
  const fs::path p = work_dir() / name;
  std::ofstream(p, std::ios::binary).write(bytes.data(), std::streamsize(bytes.size()));
  return p.string();
}

// Whether the loader read the input (false: it refused it with the project's error).
template <class F>
static bool expecting_input_errors(F&& f) {
  try {
    f();
    return true;
  } catch (const airr_error&) {
    return false;  // the answer to bad input
  }
}

// Scenes and fit data name their files relative to themselves, as assets/ holds them: the model,
// the charts and the display profile go to models/, charts/ and displays/, and the fit example's
// measurements and setup scene to fit/, where the fit.json an input becomes sits beside them.
// Copied once.
static void copy_assets_beside() {
  static const bool copied = [] {
    const fs::path assets = AIRR_ASSETS_DIR;
    for (const char* file :
         {"models/panel.gltf", "charts/test_chart.png", "charts/slanted_edge.png", "displays/lcd_typical.csv"}) {
      fs::create_directories((work_dir() / file).parent_path());
      fs::copy_file(assets / file, work_dir() / file, fs::copy_options::overwrite_existing);
    }
    fs::create_directories(work_dir() / "fit");
    for (const auto& e : fs::directory_iterator(assets / "fit_example"))
      if (e.path().filename() != "fit.json")
        fs::copy_file(e.path(), work_dir() / "fit" / e.path().filename(), fs::copy_options::overwrite_existing);
    return true;
  }();
  (void)copied;
}

bool scene_json(std::string_view bytes) {
  copy_assets_beside();
  return expecting_input_errors(
      [&] { parse_scene(std::string(bytes), "fuzz.json", (work_dir() / "scenes").string()); });
}

bool gltf(std::string_view bytes) {
  const std::string path = write_input(bytes.substr(0, 4) == "glTF" ? "fuzz.glb" : "fuzz.gltf", bytes);
  const bool mesh = expecting_input_errors([&] { load_prop_mesh(path, ""); });
  const bool layout = expecting_input_errors([&] {
    if (!gltf_has_layout_roles(path)) throw input_error("no layout roles");
    gltf_layout_document(path);
  });
  return mesh || layout;
}

bool step(std::string_view bytes) {
  const std::string path = write_input("fuzz.step", bytes);
  return expecting_input_errors([&] { load_step_mesh(path, "", 0.5); });
}

bool path_expression(std::string_view bytes) {
  return expecting_input_errors([&] {
    scene s;
    s.props.resize(1);
    s.props[0].name = "hood";
    const auto e = airr::path_expression::parse(bytes).bound(s, false);
    // Labels of every kind of event, and one as long as a path may be.
    path_label aerial, longest;
    for (const path_event ev :
         {path_event{path_event_kind::eye}, path_event{path_event_kind::half_mirror, false, true, 0},
          path_event{path_event_kind::sheet, true, false, 0}, path_event{path_event_kind::half_mirror, true, true, 1},
          path_event{path_event_kind::prop, false, false, 0}, path_event{path_event_kind::display}})
      aerial.push(ev);
    for (int i = 0; i < max_path_events; ++i)
      longest.push({i == 0 ? path_event_kind::eye : path_event_kind::half_mirror, bool(i & 1), bool(i & 2), 0});
    e.matches(aerial);
    e.matches(longest);
    e.matches(path_label{});
  });
}

bool preset(std::string_view bytes) {
  return expecting_input_errors([&] { load_preset(write_input("preset.json", bytes)); });
}

bool sheet_json(std::string_view bytes) {
  return expecting_input_errors([&] { load_sheet(write_input("sheet.json", bytes)); });
}

bool shift_table(std::string_view bytes) {
  return expecting_input_errors([&] { load_shift_table(write_input("table.json", bytes)); });
}

bool fit_json(std::string_view bytes) {
  copy_assets_beside();
  write_input("fit/fit.json", bytes);
  return expecting_input_errors([&] { analysis::load_fit_data((work_dir() / "fit").string()); });
}

bool csv(std::string_view bytes) {
  return expecting_input_errors([&] { read_csv_table(write_input("table.csv", bytes)); });
}

// The extension a user's file of that content would have (the image library picks its reader by
// the name first).
static std::string image_name(std::string_view bytes) {
  const auto starts = [&](std::string_view magic) { return bytes.substr(0, magic.size()) == magic; };
  if (starts("v/1\x01")) return "image.exr";
  if (starts("II*") || starts("MM\0*")) return "image.tif";
  if (starts("\xff\xd8")) return "image.jpg";
  return "image.png";
}

// Mutated headers within the loader's own limit would make most runs allocate and convert
// hundreds of megabytes; a lower limit keeps them cheap and exercises the same code.
constexpr std::int64_t fuzz_image_pixel_limit = 1 << 16;

bool image(std::string_view bytes) {
  return expecting_input_errors(
      [&] { load_image(write_input(image_name(bytes), bytes), image_encoding::automatic, fuzz_image_pixel_limit); });
}

bool onnx(std::string_view bytes) {
  return expecting_input_errors([&] { analysis::read_onnx_inputs(write_input("model.onnx", bytes)); });
}

bool design_spec(std::string_view bytes) {
  static const scene kiosk = load_scene(std::string(AIRR_ASSETS_DIR) + "/scenes/two_sheet_kiosk.json");
  return expecting_input_errors([&] { parse_design_spec(std::string(bytes), "spec.json", kiosk); });
}

bool partial(std::string_view bytes) {
  return expecting_input_errors([&] { read_partial(write_input("part.json", bytes)); });
}

// Splits text into lines (without their ends).
static std::vector<std::string_view> lines_of(std::string_view text) {
  std::vector<std::string_view> out;
  while (!text.empty()) {
    const std::size_t end = text.find('\n');
    out.push_back(text.substr(0, end));
    text = end == std::string_view::npos ? std::string_view() : text.substr(end + 1);
  }
  return out;
}

bool render_shard(std::string_view bytes) {
  return expecting_input_errors([&] {
    std::vector<render_shard_header> headers;
    shard_roll roll;
    std::vector<std::string_view> block;
    const auto finish_block = [&] {
      if (block.empty()) return;
      const std::string path = "shard" + std::to_string(headers.size()) + ".exr";
      int width = 0, rows = 0;
      const char* at = block[0].data();
      const char* const end = at + block[0].size();
      const auto w = std::from_chars(at, end, width);
      const auto r = std::from_chars(w.ptr < end ? w.ptr + 1 : end, end, rows);
      if (w.ec != std::errc() || r.ec != std::errc()) throw input_error(path + ": no pixels");
      image_metadata meta;
      std::vector<std::string> layers;
      for (std::size_t k = 1; k < block.size(); ++k) {
        const std::string_view line = block[k];
        if (line.substr(0, 6) == "layer ") {
          layers.emplace_back(line.substr(6));
        } else if (const std::size_t eq = line.find('='); eq != std::string_view::npos) {
          meta[std::string(line.substr(0, eq))] = std::string(line.substr(eq + 1));
        }
      }
      render_shard_header h = check_shard_header(path, meta, width, rows, layers);
      if (!headers.empty()) {
        if (const std::string differs = shard_mismatch(headers.front(), h); !differs.empty())
          throw input_error(path + ": " + differs);
      }
      roll.add(path, h.place);
      headers.push_back(std::move(h));
      block.clear();
    };
    for (const std::string_view line : lines_of(bytes)) {
      if (line.empty())
        finish_block();
      else
        block.push_back(line);
    }
    finish_block();
    if (headers.empty()) throw input_error("no shards");
    roll.check_complete(headers.front().place.count);
  });
}

bool scene_set(std::string_view bytes) {
  static const std::string path = std::string(AIRR_ASSETS_DIR) + "/scenes/default.json";
  static const std::string scene_text = read_text_file(path);
  const std::size_t end = bytes.find('\n');
  const scene_override set{std::string(bytes.substr(0, end)),
                           end == std::string_view::npos ? std::string() : std::string(bytes.substr(end + 1))};
  return expecting_input_errors(
      [&] { parse_scene(scene_text, path, std::string(AIRR_ASSETS_DIR) + "/scenes", {set}); });
}

bool run(const std::string& target, std::string_view bytes) {
  if (target == "scene_json") return scene_json(bytes);
  if (target == "gltf") return gltf(bytes);
  if (target == "preset") return preset(bytes);
  if (target == "sheet_json") return sheet_json(bytes);
  if (target == "shift_table") return shift_table(bytes);
  if (target == "fit_json") return fit_json(bytes);
  if (target == "csv") return csv(bytes);
  if (target == "image") return image(bytes);
  if (target == "onnx") return onnx(bytes);
  if (target == "design_spec") return design_spec(bytes);
  if (target == "partial") return partial(bytes);
  if (target == "render_shard") return render_shard(bytes);
  if (target == "scene_set") return scene_set(bytes);
  if (target == "step") return step(bytes);
  if (target == "path_expression") return path_expression(bytes);
  throw std::invalid_argument("no fuzz target named " + target);
}

}  // namespace airr::fuzz
