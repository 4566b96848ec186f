#include "airr/formats/design_spec.hpp"

#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include <nlohmann/json.hpp>

#include "airr/core/error.hpp"
#include "airr/core/files.hpp"
#include "airr/core/json_reader.hpp"
#include "airr/formats/scene_json.hpp"
#include "airr/layout/layout.hpp"

namespace airr {

namespace {

constexpr const char* design_format = "airr-design";
constexpr int design_version = 1;

struct metric_name {
  design_metric metric;
  const char* name;
  bool at_eye;
};
constexpr std::array<metric_name, 8> metric_names = {{
    {design_metric::visible_fraction, "visible_fraction", true},
    {design_metric::mean_mtf, "mean_mtf", true},
    {design_metric::mtf50_lp_per_mm, "mtf50_lp_per_mm", true},
    {design_metric::r50_mm, "r50_mm", true},
    {design_metric::brightness, "brightness", true},
    {design_metric::size_x_mm, "size_x_mm", false},
    {design_metric::size_y_mm, "size_y_mm", false},
    {design_metric::size_z_mm, "size_z_mm", false},
}};

// Each element of the array at `key` (required when `required`), read as an object.
template <class Read>
void each_object(json_reader& r, const std::string& key, bool required, Read read) {
  if (!r.has(key)) {
    if (required) r.fail(r.field(key), "missing");
    return;
  }
  const nlohmann::json& a = r.raw(key);
  if (!a.is_array()) r.fail(r.field(key), "must be an array of objects");
  if (required && a.empty()) r.fail(r.field(key), "must not be empty");
  for (std::size_t i = 0; i < a.size(); ++i) {
    json_reader item(a[i], r.origin(), r.field(key) + "[" + std::to_string(i) + "]");
    read(item, i);
    item.finish();
  }
}

design_metric read_metric(json_reader& r) {
  const std::string name = r.string("metric");
  const auto m = design_metric_named(name);
  if (!m) r.fail(r.field("metric"), "unknown metric '" + name + "' (" + design_metric_names() + ")");
  return *m;
}

over_eyes read_over(json_reader& r) {
  std::string over = "mean";
  r.string("over", over);
  if (over != "mean" && over != "min") r.fail(r.field("over"), "must be \"mean\" or \"min\"");
  return over == "min" ? over_eyes::min : over_eyes::mean;
}

}  // namespace

const char* to_string(design_metric m) {
  for (const metric_name& n : metric_names)
    if (n.metric == m) return n.name;
  return "?";
}

std::optional<design_metric> design_metric_named(const std::string& name) {
  for (const metric_name& n : metric_names)
    if (name == n.name) return n.metric;
  return std::nullopt;
}

bool metric_at_eye(design_metric m) {
  for (const metric_name& n : metric_names)
    if (n.metric == m) return n.at_eye;
  return false;
}

std::string design_metric_names() {
  std::string out;
  for (const metric_name& n : metric_names) out += (out.empty() ? "" : ", ") + std::string(n.name);
  return out;
}

design_spec load_design_spec(const std::string& path) {
  const nlohmann::json j = read_json_file(path);
  json_reader r(j, path, "");
  std::string format;
  r.string("format", format);
  if (format != design_format) r.fail("format", std::string("expected \"") + design_format + "\"");
  int version = 0;
  r.integer("version", version);
  if (version != design_version) r.fail("version", "unsupported version " + std::to_string(version));
  design_spec spec;
  spec.path = path;
  const std::string base_dir = std::filesystem::absolute(path).parent_path().string();
  spec.scene_path = resolve_path(r.string("scene"), base_dir);
  try {
    spec.base = load_scene(spec.scene_path);
  } catch (const input_error& e) {
    r.fail("scene", e.what());
  }
  each_object(r, "variables", false, [&](json_reader& v, std::size_t) {
    design_variable var;
    var.key = v.string("key");
    var.min = v.number("min");
    var.max = v.number("max");
    if (!(var.min < var.max)) v.fail(v.field("max"), "the range is empty: max must exceed min");
    try {
      with_overrides(spec.base, {design_override(var.key, 0.5 * (var.min + var.max))}, "--set");
    } catch (const input_error& e) {
      v.fail(v.field("key"), std::string("not a value of the scene (") + e.what() + ")");
    }
    spec.variables.push_back(var);
  });
  if (r.has("eyes_mm")) {
    const nlohmann::json& eyes = r.raw("eyes_mm");
    if (!eyes.is_array() || eyes.empty()) r.fail("eyes_mm", "must be a non-empty array of [x, y, z] positions");
    for (std::size_t i = 0; i < eyes.size(); ++i) {
      const std::string where = "eyes_mm[" + std::to_string(i) + "]";
      if (!eyes[i].is_array() || eyes[i].size() != 3) r.fail(where, "must be [x, y, z] in mm");
      glm::dvec3 e(0);
      for (int k = 0; k < 3; ++k) {
        if (!eyes[i][std::size_t(k)].is_number()) r.fail(where, "must be [x, y, z] in mm");
        e[k] = eyes[i][std::size_t(k)].get<double>();
        if (!std::isfinite(e[k])) r.fail(where, "must be finite");
      }
      spec.eyes_mm.push_back(e);
    }
  } else {
    spec.eyes_mm.push_back(observer_position(spec.base));
  }
  each_object(r, "objectives", true, [&](json_reader& o, std::size_t) {
    design_objective obj;
    obj.metric = read_metric(o);
    obj.over = read_over(o);
    const std::string goal = o.string("goal");
    if (goal != "maximise" && goal != "minimise") o.fail(o.field("goal"), "must be \"maximise\" or \"minimise\"");
    obj.maximise = goal == "maximise";
    o.number("weight", obj.weight);
    if (!(obj.weight > 0)) o.fail(o.field("weight"), "must be positive");
    spec.objectives.push_back(obj);
  });
  each_object(r, "constraints", false, [&](json_reader& c, std::size_t) {
    design_constraint con;
    con.metric = read_metric(c);
    con.over = read_over(c);
    con.min = c.optional_number("min");
    con.max = c.optional_number("max");
    if (!con.min && !con.max) c.fail(c.field("metric"), "a constraint needs a min, a max or both");
    if (con.min && con.max && !(*con.min <= *con.max)) c.fail(c.field("max"), "must not be below min");
    spec.constraints.push_back(con);
  });
  each_object(r, "tolerances", false, [&](json_reader& t, std::size_t) {
    design_tolerance tol;
    tol.key = t.string("key");
    std::string distribution = "normal";
    t.string("distribution", distribution);
    if (distribution != "normal" && distribution != "uniform")
      t.fail(t.field("distribution"), "must be \"normal\" or \"uniform\"");
    tol.uniform = distribution == "uniform";
    tol.size = t.number(tol.uniform ? "half_width" : "sd");
    if (!(tol.size > 0)) t.fail(t.field(tol.uniform ? "half_width" : "sd"), "must be positive");
    t.boolean("percent", tol.percent);
    try {
      scene_number(spec.base, tol.key);
    } catch (const input_error& e) {
      t.fail(t.field("key"), std::string("not a number of the scene (") + e.what() + ")");
    }
    spec.tolerances.push_back(tol);
  });
  if (r.has("tolerance")) {
    json_reader t = r.child("tolerance");
    t.integer("samples", spec.tolerance.samples);
    t.integer("seed", spec.tolerance.seed);
    if (spec.tolerance.samples < 10 || spec.tolerance.samples > 1000000)
      t.fail(t.field("samples"), "must be 10 to 1000000");
    t.finish();
  }
  if (r.has("search")) {
    json_reader s = r.child("search");
    s.integer("seed", spec.search.seed);
    s.integer("global_evaluations", spec.search.global_evaluations);
    s.integer("local_evaluations", spec.search.local_evaluations);
    s.integer("psf_samples", spec.search.psf_samples);
    if (spec.search.global_evaluations < 1 || spec.search.global_evaluations > 100000)
      s.fail(s.field("global_evaluations"), "must be 1 to 100000");
    if (spec.search.local_evaluations < 0 || spec.search.local_evaluations > 100000)
      s.fail(s.field("local_evaluations"), "must be 0 to 100000");
    if (spec.search.psf_samples < 1000 || spec.search.psf_samples > 100000000)
      s.fail(s.field("psf_samples"), "must be 1000 to 100000000");
    s.finish();
  }
  if (r.has("pareto")) {
    json_reader f = r.child("pareto");
    f.require("points");
    f.integer("points", spec.front.points);
    if (spec.front.points < 3 || spec.front.points > 101) f.fail(f.field("points"), "must be 3 to 101");
    if (spec.objectives.size() != 2) f.fail(f.field("points"), "a Pareto front needs exactly two objectives");
    f.finish();
  }
  r.finish();
  return spec;
}

scene_override design_override(const std::string& key, double v) {
  char buffer[40];
  std::snprintf(buffer, sizeof buffer, "%.17g", v);
  return {key, buffer};
}

scene design_scene(const design_spec& spec, const std::vector<double>& x) {
  std::vector<scene_override> set;
  for (std::size_t i = 0; i < spec.variables.size() && i < x.size(); ++i)
    set.push_back(design_override(spec.variables[i].key, x[i]));
  scene s = with_overrides(spec.base, set, spec.path);
  validate_scene(s, spec.path);
  check_layout(s, spec.path);
  return s;
}

}  // namespace airr
