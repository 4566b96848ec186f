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
constexpr std::array<metric_name, design_metric_count> metric_names = {{
    {design_metric::visible_fraction, "visible_fraction", true},
    {design_metric::mean_mtf, "mean_mtf", true},
    {design_metric::mtf50_lp_per_mm, "mtf50_lp_per_mm", true},
    {design_metric::r50_mm, "r50_mm", true},
    {design_metric::brightness, "brightness", true},
    {design_metric::stray_light, "stray_light", true},
    {design_metric::ghost_ratio, "ghost_ratio", true},
    {design_metric::ghost_separation_arcmin, "ghost_separation_arcmin", true},
    {design_metric::luminance_cd_m2, "luminance_cd_m2", true},
    {design_metric::contrast, "contrast", true},
    {design_metric::legible_share, "legible_share", true},
    {design_metric::char_height_mm, "char_height_mm", true},
    {design_metric::size_x_mm, "size_x_mm", false},
    {design_metric::size_y_mm, "size_y_mm", false},
    {design_metric::size_z_mm, "size_z_mm", false},
    {design_metric::prop_cut_mm, "prop_cut_mm", false},
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

// The metric, and the expression that a ghost metric needs and no other takes.
design_metric read_metric(json_reader& r, std::string& expression) {
  const std::string name = r.string("metric");
  const auto m = design_metric_named(name);
  if (!m) r.fail(r.field("metric"), "unknown metric '" + name + "' (" + design_metric_names() + ")");
  if (metric_takes_expression(*m)) {
    expression = r.string("expression");
    if (expression.empty()) r.fail(r.field("expression"), "must not be empty");
  } else if (r.has("expression")) {
    r.fail(r.field("expression"), "only ghost_ratio and ghost_separation_arcmin take a path expression");
  }
  return *m;
}

// "over" and, for share_above, its "threshold".
over_eyes read_over(json_reader& r, double& threshold) {
  std::string over = "mean";
  r.string("over", over);
  if (over != "mean" && over != "min" && over != "share_above")
    r.fail(r.field("over"), "must be \"mean\", \"min\" or \"share_above\"");
  if (over != "share_above") return over == "min" ? over_eyes::min : over_eyes::mean;
  threshold = r.number("threshold");
  return over_eyes::share_above;
}

// "eye_zone": {"shape": "plane" or "sphere", "distance_mm", "x": [lo, hi], "y": [lo, hi], "n": [nx, ny]}.
static legibility_criterion read_legibility(json_reader r) {
  legibility_criterion c;
  const auto in = [&](const char* key, double& v, double lo, double hi) {
    r.number(key, v);
    if (!(v >= lo && v <= hi))
      r.fail(r.field(key), "must be in [" + number_text(lo) + ", " + number_text(hi) + "] (is " + number_text(v) + ")");
  };
  in("cycles_per_height", c.cycles_per_height, 0.5, 10);
  in("modulation", c.modulation, 1e-3, 1);
  in("min_arcmin", c.min_arcmin, 0, 600);
  r.finish();
  return c;
}

eye_grid read_eye_zone(json_reader z) {
  eye_grid g;
  std::string shape = "plane";
  z.string("shape", shape);
  if (shape != "plane" && shape != "sphere") z.fail(z.field("shape"), "must be \"plane\" or \"sphere\"");
  g.kind = shape == "sphere" ? eye_grid::shape::sphere : eye_grid::shape::plane;
  z.number("distance_mm", g.distance_mm);
  auto pair = [&](const char* key) {
    const std::vector<double> v = z.number_array(key);
    if (v.size() != 2) z.fail(z.field(key), "must be [first, last]");
    return v;
  };
  const std::vector<double> x = pair("x"), y = pair("y"), n = pair("n");
  g.x_min = x[0], g.x_max = x[1], g.y_min = y[0], g.y_max = y[1];
  if (n[0] != std::floor(n[0]) || n[1] != std::floor(n[1]) || n[0] < 1 || n[1] < 1 || n[0] * n[1] > 400)
    z.fail(z.field("n"), "must be [nx, ny], whole numbers, at most 400 eyes in all");
  g.nx = int(n[0]), g.ny = int(n[1]);
  try {
    check_eye_grid(g);
  } catch (const input_error& e) {
    z.fail(z.field("x"), e.what());
  }
  z.finish();
  return g;
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

bool metric_takes_expression(design_metric m) {
  return m == design_metric::ghost_ratio || m == design_metric::ghost_separation_arcmin;
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

namespace {

// The spec in j; its scene is `base` when given, else the file its "scene" names (relative to
// base_dir).
design_spec read_design_spec(const nlohmann::json& j, const std::string& path, const std::string& base_dir,
                             const scene* base) {
  json_reader r(j, path, "");
  std::string format;
  r.string("format", format);
  if (format != design_format) r.fail("format", std::string("expected \"") + design_format + "\"");
  int version = 0;
  r.integer("version", version);
  if (version != design_version) r.fail("version", "unsupported version " + std::to_string(version));
  design_spec spec;
  spec.path = path;
  if (base) {
    spec.base = *base;
    if (r.has("scene")) r.string("scene", spec.scene_path);
  } else {
    spec.scene_path = resolve_path(r.string("scene"), base_dir);
    try {
      spec.base = load_scene(spec.scene_path);
    } catch (const input_error& e) {
      r.fail("scene", e.what());
    }
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
  }
  if (r.has("eye_zone")) spec.eye_zone = read_eye_zone(r.child("eye_zone"));
  r.number("legible_contrast", spec.legible_contrast);
  if (!(spec.legible_contrast >= 1 && spec.legible_contrast <= 1e6))
    r.fail("legible_contrast", "must be in [1, 1e6] (is " + number_text(spec.legible_contrast) + ")");
  if (r.has("legibility")) spec.legibility = read_legibility(r.child("legibility"));
  if (spec.eyes_mm.empty() && !spec.eye_zone) spec.eyes_mm.push_back(observer_position(spec.base));
  each_object(r, "objectives", true, [&](json_reader& o, std::size_t) {
    design_objective obj;
    obj.metric = read_metric(o, obj.expression);
    obj.over = read_over(o, obj.threshold);
    const std::string goal = o.string("goal");
    if (goal != "maximise" && goal != "minimise") o.fail(o.field("goal"), "must be \"maximise\" or \"minimise\"");
    obj.maximise = goal == "maximise";
    o.number("weight", obj.weight);
    if (!(obj.weight > 0)) o.fail(o.field("weight"), "must be positive");
    spec.objectives.push_back(obj);
  });
  each_object(r, "constraints", false, [&](json_reader& c, std::size_t) {
    design_constraint con;
    con.metric = read_metric(c, con.expression);
    con.over = read_over(c, con.threshold);
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
    t.integer("samples", spec.tolerance.samples, 10, 1000000);
    t.integer("seed", spec.tolerance.seed);
    t.finish();
  }
  if (r.has("search")) {
    json_reader s = r.child("search");
    s.integer("seed", spec.search.seed);
    s.integer("global_evaluations", spec.search.global_evaluations, 1, 100000);
    s.integer("local_evaluations", spec.search.local_evaluations, 0, 100000);
    s.integer("psf_samples", spec.search.psf_samples, std::uint64_t(1000), std::uint64_t(100000000));
    s.finish();
  }
  if (r.has("pareto")) {
    json_reader f = r.child("pareto");
    f.require("points");
    f.integer("points", spec.front.points, 3, 101);
    if (spec.objectives.size() != 2) f.fail(f.field("points"), "a Pareto front needs exactly two objectives");
    f.finish();
  }
  r.finish();
  return spec;
}

const char* goal_name(bool maximise) { return maximise ? "maximise" : "minimise"; }
const char* over_name(over_eyes o) {
  return o == over_eyes::min ? "min" : o == over_eyes::share_above ? "share_above" : "mean";
}

}  // namespace

design_spec load_design_spec(const std::string& path) {
  return read_design_spec(read_json_file(path), path, std::filesystem::absolute(path).parent_path().string(), nullptr);
}

design_spec parse_design_spec(const std::string& text, const std::string& origin, const scene& base) {
  return read_design_spec(parse_json(text, origin), origin, "", &base);
}

std::string design_spec_text(const design_spec& spec) {
  nlohmann::ordered_json j;
  j["format"] = design_format;
  j["version"] = design_version;
  if (!spec.scene_path.empty()) j["scene"] = spec.scene_path;
  j["variables"] = nlohmann::ordered_json::array();
  for (const design_variable& v : spec.variables)
    j["variables"].push_back({{"key", v.key}, {"min", v.min}, {"max", v.max}});
  j["eyes_mm"] = nlohmann::ordered_json::array();
  for (const glm::dvec3& e : spec.eyes_mm) j["eyes_mm"].push_back({e.x, e.y, e.z});
  if (const auto& z = spec.eye_zone) {
    j["eye_zone"] = {{"shape", z->kind == eye_grid::shape::sphere ? "sphere" : "plane"},
                     {"distance_mm", z->distance_mm},
                     {"x", {z->x_min, z->x_max}},
                     {"y", {z->y_min, z->y_max}},
                     {"n", {z->nx, z->ny}}};
  }
  if (spec.legible_contrast != 3) j["legible_contrast"] = spec.legible_contrast;
  if (spec.legibility != legibility_criterion{}) {
    j["legibility"] = {{"cycles_per_height", spec.legibility.cycles_per_height},
                       {"modulation", spec.legibility.modulation},
                       {"min_arcmin", spec.legibility.min_arcmin}};
  }
  j["objectives"] = nlohmann::ordered_json::array();
  for (const design_objective& o : spec.objectives) {
    nlohmann::ordered_json obj = {{"metric", to_string(o.metric)}};
    if (metric_takes_expression(o.metric)) obj["expression"] = o.expression;
    obj["goal"] = goal_name(o.maximise);
    obj["over"] = over_name(o.over);
    obj["weight"] = o.weight;
    if (o.over == over_eyes::share_above) obj["threshold"] = o.threshold;
    j["objectives"].push_back(obj);
  }
  j["constraints"] = nlohmann::ordered_json::array();
  for (const design_constraint& c : spec.constraints) {
    nlohmann::ordered_json o = {{"metric", to_string(c.metric)}};
    if (metric_takes_expression(c.metric)) o["expression"] = c.expression;
    o["over"] = over_name(c.over);
    if (c.over == over_eyes::share_above) o["threshold"] = c.threshold;
    if (c.min) o["min"] = *c.min;
    if (c.max) o["max"] = *c.max;
    j["constraints"].push_back(o);
  }
  j["search"] = {{"seed", spec.search.seed},
                 {"global_evaluations", spec.search.global_evaluations},
                 {"local_evaluations", spec.search.local_evaluations},
                 {"psf_samples", spec.search.psf_samples}};
  if (spec.front.points > 0) j["pareto"] = {{"points", spec.front.points}};
  j["tolerances"] = nlohmann::ordered_json::array();
  for (const design_tolerance& t : spec.tolerances) {
    nlohmann::ordered_json o = {{"key", t.key}, {"distribution", t.uniform ? "uniform" : "normal"}};
    o[t.uniform ? "half_width" : "sd"] = t.size;
    o["percent"] = t.percent;
    j["tolerances"].push_back(o);
  }
  j["tolerance"] = {{"samples", spec.tolerance.samples}, {"seed", spec.tolerance.seed}};
  return j.dump(2) + "\n";
}

std::vector<glm::dvec3> design_eyes(const design_spec& spec) {
  std::vector<glm::dvec3> eyes = spec.eyes_mm;
  if (const auto& z = spec.eye_zone) {
    for (int j = 0; j < z->ny; ++j) {
      for (int i = 0; i < z->nx; ++i) eyes.push_back(eye_position(spec.base, *z, z->x_at(i), z->y_at(j)));
    }
  }
  return eyes;
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
