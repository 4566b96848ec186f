#include "airr/measure/ghost_table.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <mutex>
#include <numeric>
#include <sstream>

#include "airr/core/color.hpp"
#include "airr/core/error.hpp"
#include "airr/core/files.hpp"
#include "airr/layout/layout.hpp"
#include "airr/measure/aerial_outline.hpp"
#include "airr/render/memory_need.hpp"
#include "airr/render/parallel_rows.hpp"
#include "airr/render/render_session.hpp"
#include "airr/render/tracer.hpp"

namespace airr {

namespace {

double luminance(const float* v) { return rec709_luminance(v[0], v[1], v[2]); }

// The census: every label's light over the observer's image, at p.census_spp.
std::map<std::string, census_class> census(const scene& s, const ghost_params& p) {
  embree_device device;
  tracer_scene ts;
  build_tracer_scene(ts, device, s);
  std::map<std::string, census_class> all;
  std::mutex m;
  const std::atomic<bool> never{false};
  detail::parallel_rows(ts.camera.height, p.threads, [&](int y0, int y1) {
    std::map<std::string, census_class> mine;
    std::uint64_t rays = 0;
    census_rows(ts, y0, y1, 0, p.census_spp, mine, p.cancel ? *p.cancel : never, rays);
    std::lock_guard lock(m);
    for (const auto& [text, c] : mine) all.try_emplace(text, census_class{c.label}).first->second.light += c.light;
  });
  return all;
}

// Whether a typed expression's paths are retroreflected: every label of the census it selects
// is, and it selects one.
bool retroreflected_class(const path_expression& e, const std::map<std::string, census_class>& seen) {
  bool any = false;
  for (const auto& [text, c] : seen) {
    if (!e.matches(c.label)) continue;
    if (!aerial_image_path(c.label)) return false;
    any = true;
  }
  return any;
}

// The observer moved `offset` mm along its camera's right, still aimed at its target, so that
// what it looks at stays in its field.
scene eye_moved(const scene& s, double offset) {
  const pinhole_camera cam = make_camera(s);
  const glm::dvec3 at = observer_target(s);
  scene e = s;
  e.observer.placement = observer_placement::look_at;
  const glm::dvec3 pos = cam.position + offset * cam.right;
  e.observer.position_mm = {pos.x, pos.y, pos.z};
  e.observer.look_at_mm = {at.x, at.y, at.z};
  return e;
}

struct eye_view {
  render_snapshot snap;
  pinhole_camera cam;
};

eye_view render_eye(const scene& s, const std::shared_ptr<const path_layers>& layers, const ghost_params& p) {
  session_params sp{.threads = p.threads, .target_spp = p.spp, .layers = layers};
  check_render_memory(s, sp);
  render_session session(s, sp);
  return {render_to_spp(session, p.spp, [&](std::uint64_t) { return !(p.cancel && *p.cancel); }), make_camera(s)};
}

// How far along the centre camera's view the point lies that the two eyes see at pixels `pl`
// and `pr`: the middle of the shortest segment between their rays (NaN when the rays diverge).
double distance_by_parallax(const pinhole_camera& centre, const eye_view& l, const eye_view& r, const glm::dvec2& pl,
                            const glm::dvec2& pr) {
  if (!std::isfinite(pl.x) || !std::isfinite(pr.x)) return ghost_class::nan;
  const glm::dvec3 d1 = camera_direction(l.cam, pl.x, pl.y), d2 = camera_direction(r.cam, pr.x, pr.y);
  const glm::dvec3 w = l.cam.position - r.cam.position;
  const double a = glm::dot(d1, d1), b = glm::dot(d1, d2), c = glm::dot(d2, d2), d = glm::dot(d1, w),
               e = glm::dot(d2, w);
  const double den = a * c - b * b;
  if (!(den > 1e-15)) return ghost_class::nan;
  const double t1 = (b * e - c * d) / den, t2 = (a * e - b * d) / den;
  if (t1 <= 0 || t2 <= 0) return ghost_class::nan;
  const glm::dvec3 point = 0.5 * (l.cam.position + t1 * d1 + r.cam.position + t2 * d2);
  return glm::dot(point - centre.position, centre.forward);
}

}  // namespace

ghost_table compute_ghost_table(const scene& s, const ghost_params& p,
                                const std::function<void(const std::string&, double)>& progress) {
  if (p.top < 1 || p.top > max_path_layers - 1)
    throw input_error("ghosts: --top must be 1 to " + std::to_string(max_path_layers - 1));
  if (p.census_spp < 1 || p.spp < 1) throw input_error("ghosts: samples per pixel must be at least 1");
  if (std::size_t(p.top) + p.expressions.size() > std::size_t(max_path_layers))
    throw input_error("ghosts: at most " + std::to_string(max_path_layers) + " classes (--top and the expressions)");
  for (const std::string& e : p.expressions) path_expression::parse(e).bound(s, true);  // before the census
  if (!(p.baseline_mm > 0) || p.baseline_mm > 1000) throw input_error("ghosts: the baseline must be in (0, 1000] mm");
  const auto start = std::chrono::steady_clock::now();
  const auto say = [&](const std::string& stage, double f) {
    if (progress) progress(stage, f);
  };
  say("census", 0);
  const std::map<std::string, census_class> seen = census(s, p);
  ghost_table t;
  t.labels_seen = seen.size();
  std::vector<std::pair<double, std::string>> ranked;
  double all = 0;
  for (const auto& [label, c] : seen) {
    const double l = rec709_luminance(c.light.x, c.light.y, c.light.z);
    all += l;
    ranked.push_back({l, label});
  }
  std::sort(ranked.begin(), ranked.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
  if (ranked.size() > std::size_t(p.top)) ranked.resize(std::size_t(p.top));
  const std::size_t found = ranked.size();
  for (const std::string& e : p.expressions) ranked.push_back({-1, e});  // their census share from the render
  const auto stopped = [&] { return p.cancel && p.cancel->load(); };
  if (stopped()) return {};

  // Each class a layer; the brightest retroreflected one is the aerial image the others are
  // placed against.
  auto layers = std::make_shared<path_layers>();
  std::vector<bool> retro(ranked.size());
  std::size_t aerial_layer = ranked.size();
  for (std::size_t i = 0; i < ranked.size(); ++i) {
    layers->layers.push_back({"c" + std::to_string(i), path_expression::parse(ranked[i].second).bound(s, true)});
    retro[i] = i < found ? aerial_image_path(seen.at(ranked[i].second).label)
                         : retroreflected_class(layers->layers.back().expression, seen);
    if (aerial_layer == ranked.size() && i < found && retro[i]) aerial_layer = i;
  }

  const double b = p.baseline_mm;
  say("observer", 0.1);
  const eye_view centre = render_eye(s, layers, p);
  if (stopped()) return {};
  say("left eye", 0.4);
  const eye_view left = render_eye(eye_moved(s, -0.5 * b), layers, p);
  if (stopped()) return {};
  say("right eye", 0.7);
  const eye_view right = render_eye(eye_moved(s, 0.5 * b), layers, p);
  if (stopped()) return {};

  const std::array<glm::dvec2, 4> outline = aerial_outline(s, centre.cam);
  const image_rgb whole = centre.snap.image();
  double whole_inside = 0, whole_all = 0;
  int inside = 0;
  for (int y = 0; y < whole.height; ++y) {
    for (int x = 0; x < whole.width; ++x) {
      whole_all += luminance(whole.at(x, y));
      if (!inside_quad(outline, x + 0.5, y + 0.5)) continue;
      whole_inside += luminance(whole.at(x, y));
      ++inside;
    }
  }
  const auto place = [&](std::size_t k, glm::dvec2& c, double& distance) {
    c = luminance_centroid(centre.snap.layer_image(k));
    distance = distance_by_parallax(centre.cam, left, right, luminance_centroid(left.snap.layer_image(k)),
                                    luminance_centroid(right.snap.layer_image(k)));
  };
  if (aerial_layer < ranked.size()) place(aerial_layer, t.aerial_centroid, t.aerial_distance_mm);
  for (std::size_t i = 0; i < ranked.size(); ++i) {
    ghost_class g;
    g.expression = ranked[i].second;
    g.aerial = retro[i];
    g.typed = i >= found;
    g.census_share = all > 0 ? ranked[i].first / all : 0;
    g.image = centre.snap.layer_image(i);
    double in = 0, everywhere = 0;
    for (int y = 0; y < g.image.height; ++y) {
      for (int x = 0; x < g.image.width; ++x) {
        const double l = luminance(g.image.at(x, y));
        g.peak = std::max(g.peak, l);
        everywhere += l;
        if (inside_quad(outline, x + 0.5, y + 0.5)) in += l;
      }
    }
    if (g.typed) g.census_share = whole_all > 0 ? everywhere / whole_all : 0;  // from the render instead
    g.outline_luminance = inside ? in / inside : 0;
    g.share = whole_inside > 0 ? in / whole_inside : 0;
    place(i, g.centroid, g.distance_mm);
    if (std::isfinite(g.centroid.x) && std::isfinite(t.aerial_centroid.x))
      g.separation_arcmin = separation_arcmin(centre.cam, t.aerial_centroid, g.centroid);
    t.classes.push_back(std::move(g));
  }
  std::stable_sort(t.classes.begin(), t.classes.end(), [](const ghost_class& a, const ghost_class& b) {
    return a.outline_luminance > b.outline_luminance;
  });
  t.by_peak.resize(t.classes.size());
  std::iota(t.by_peak.begin(), t.by_peak.end(), 0);
  std::stable_sort(t.by_peak.begin(), t.by_peak.end(),
                   [&](std::size_t a, std::size_t b) { return t.classes[a].peak > t.classes[b].peak; });
  t.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  say("done", 1);
  return t;
}

void write_ghost_csv(const ghost_table& t, const std::string& path) {
  std::vector<std::size_t> peak_rank(t.classes.size());
  for (std::size_t r = 0; r < t.by_peak.size(); ++r) peak_rank[t.by_peak[r]] = r + 1;
  std::ostringstream out;
  out.precision(8);
  out << "rank_by_light,rank_by_peak,expression,aerial,census_share,outline_luminance,share_in_outline,peak_luminance,"
         "centroid_x_px,centroid_y_px,separation_arcmin,distance_mm,depth_from_aerial_mm\n";
  for (std::size_t i = 0; i < t.classes.size(); ++i) {
    const ghost_class& g = t.classes[i];
    out << i + 1 << ',' << peak_rank[i] << ",\"" << g.expression << "\"," << (g.aerial ? 1 : 0) << ',' << g.census_share
        << ',' << g.outline_luminance << ',' << g.share << ',' << g.peak << ',' << g.centroid.x << ',' << g.centroid.y
        << ',' << g.separation_arcmin << ',' << g.distance_mm << ',' << g.distance_mm - t.aerial_distance_mm << '\n';
  }
  write_file_atomic(path, out.str());
}

}  // namespace airr
