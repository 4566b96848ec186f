// Film events (docs/path-expressions.md): the films on each face the light crosses are an event of
// their own, around their part's event in the light's order; expressions that name no film read
// labels without them, so the components and every film-blind expression select what they did;
// the modelled path written with its films carries the control variate; the ray file's segments
// leave parts, not films.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <map>

#include "airr/core/assets.hpp"
#include "airr/core/error.hpp"
#include "airr/formats/scene_json.hpp"
#include "airr/layout/layout.hpp"
#include "airr/render/path_expression.hpp"
#include "airr/render/ray_file.hpp"
#include "airr/render/render_session.hpp"
#include "airr/render/tracer.hpp"
#include "test_helpers.hpp"

using namespace airr;

namespace {

using test::label_of;

bool matches(const std::string& expression, const std::vector<path_event>& light_order) {
  return path_expression::parse(expression).matches(label_of(light_order));
}

const path_event D{path_event_kind::display}, E{path_event_kind::eye};
const path_event H_r{path_event_kind::half_mirror, true, false, 0}, H_t{path_event_kind::half_mirror, false, false, 0};
const path_event S0{path_event_kind::sheet, true, false, 0};
path_event F(std::uint16_t whose, bool front) { return {path_event_kind::film, false, front, whose}; }

bool same_bits(const image_rgb& a, const image_rgb& b) {
  return a.rgb.size() == b.rgb.size() && std::equal(a.rgb.begin(), a.rgb.end(), b.rgb.begin(), [](float x, float y) {
           return std::memcmp(&x, &y, sizeof x) == 0;
         });
}

// The shipped p-AIRR device (a quarter-wave film on its sheet's front), small, with a retarder
// on the display's front and one on the half mirror's `half_mirror_face`.
scene filmed_p_airr(part_face half_mirror_face) {
  scene s = load_scene(asset_dir() + "/scenes/p_airr.json", {{"observer.width", "24"}, {"observer.height", "24"}});
  s.source.films.push_back({.kind = film_kind::retarder, .face = part_face::front, .axis_deg = 0});
  s.half_mirror.films.push_back({.kind = film_kind::retarder, .face = half_mirror_face, .axis_deg = 30});
  return s;
}

render_snapshot render_layers(const scene& s, const std::vector<std::string>& expressions, bool components) {
  path_layers layers = expressions.empty() ? component_layers() : path_layers{};
  for (std::size_t k = 0; k < expressions.size(); ++k)
    layers.layers.push_back({"l" + std::to_string(k), path_expression::parse(expressions[k])});
  render_session session(
      s,
      {.threads = 2, .target_spp = 8, .components = components, .layers = std::make_shared<const path_layers>(layers)});
  session.wait_for(0, 8);
  return session.snapshot();
}

}  // namespace

TEST(FilmEvents, WrittenReadAndLeftOutByExpressionsNamingNoFilm) {
  EXPECT_EQ(event_text(F(films_on_display, true)), "F:D:front");
  EXPECT_EQ(event_text(F(films_on_half_mirror, false)), "F:H:back");
  EXPECT_EQ(event_text(F(films_on_first_sheet + 1, true)), "F:S1:front");
  const std::vector<path_event> filmed = {D,  F(films_on_display, true),     H_r, F(films_on_first_sheet, true),
                                          S0, F(films_on_first_sheet, true), H_t, F(films_on_half_mirror, true),
                                          E};
  // Every event's own text selects the label it came from.
  EXPECT_TRUE(matches(label_text(label_of(filmed)), filmed));
  EXPECT_TRUE(matches("D F:D H:r F:S0:front S0:retro F:S0 H:t F:H:front E", filmed));
  EXPECT_FALSE(matches("D F:D H:r F:S0:front S0:retro F:S0 H:t F:H:back E", filmed));
  EXPECT_FALSE(matches("D F:D H:r F:S1 S0:retro F:S0 H:t F:H E", filmed));
  EXPECT_TRUE(matches("D .* F:S .* E", filmed));
  EXPECT_FALSE(matches("D .* F:S2 .* E", filmed));
  EXPECT_FALSE(matches("D [^F]* E", filmed));  // names films: sees them
  // Naming none, an expression reads the label without its films.
  EXPECT_TRUE(matches("D H:r S0:retro H:t E", filmed));
  EXPECT_TRUE(matches("D . . . E", filmed));
  EXPECT_FALSE(matches("D . . . . E", filmed));
  for (const auto& [text, says] : std::map<std::string, std::string>{{"D F:Q E", "F takes its part"},
                                                                     {"D F:D:H E", "a film's part is named once"},
                                                                     {"D F:S12345 E", "F takes"}}) {
    try {
      path_expression::parse(text);
      ADD_FAILURE() << "parsed: " << text;
    } catch (const input_error& e) {
      EXPECT_NE(std::string(e.what()).find(says), std::string::npos) << e.what();
    }
  }
}

// The aerial image's paths, from the census of a render: the display's films as the light leaves
// it, the half mirror's on the faces the light arrives on and leaves by (it meets the half mirror's
// back, by reflection, then crosses it from the back to the front), the sheet's both ways.
TEST(FilmEvents, TheTracerLabelsTheFacesOfFilmsTheLightCrosses) {
  const std::map<part_face, std::string> expected = {
      {part_face::front, "D F:D:front H:r0:back F:S0:front S0:retro F:S0:front H:t0:back F:H:front E"},
      {part_face::back, "D F:D:front F:H:back H:r0:back F:H:back F:S0:front S0:retro F:S0:front F:H:back H:t0:back E"}};
  for (const auto& [face, label] : expected) {
    embree_device device;
    tracer_scene ts;
    ts.use_model_image = false;
    ts.layers = std::make_shared<path_layers>();
    build_tracer_scene(ts, device, filmed_p_airr(face));
    std::map<std::string, census_class> classes;
    const std::atomic<bool> never{false};
    std::uint64_t rays = 0;
    census_rows(ts, 0, ts.camera.height, 0, 2, classes, never, rays);
    const auto brightest = std::max_element(classes.begin(), classes.end(), [](const auto& a, const auto& b) {
      return a.second.light.y < b.second.light.y;
    });
    ASSERT_NE(brightest, classes.end());
    EXPECT_EQ(brightest->first, label);
    std::printf("films on the half mirror's %s: %zu classes, the brightest %s\n",
                face == part_face::front ? "front" : "back", classes.size(), brightest->first.c_str());
  }
}

TEST(FilmEvents, FilmBlindExpressionsAndTheControlVariateKeepTheirPaths) {
  const scene s = filmed_p_airr(part_face::front);
  // The predefined expressions name no film: still the components, to the bit.
  const render_snapshot snap = render_layers(s, {}, true);
  ASSERT_TRUE(snap.components && snap.layers);
  for (int k = 0; k < component_count; ++k)
    EXPECT_TRUE(same_bits(snap.layer_image(std::size_t(k)), snap.component_image(k))) << component_names[k];
  // The modelled path written without and with its films: each render's one layer takes the control
  // variate, the same image to the bit (with the films left out of the modelled label, the second
  // would go without it).
  const image_rgb plain = render_layers(s, {"D H:r0:back S0:retro H:t0:back E"}, false).layer_image(0);
  const image_rgb filmed =
      render_layers(s, {"D F:D:front H:r0:back F:S0:front S0:retro F:S0:front H:t0:back F:H:front E"}, false)
          .layer_image(0);
  double energy = 0;
  for (float v : plain.rgb) energy += v;
  EXPECT_GT(energy, 0);
  EXPECT_TRUE(same_bits(plain, filmed));
}

TEST(FilmEvents, RayFileSegmentsLeavePartsNotFilms) {
  const ray_record r = record_rays(filmed_p_airr(part_face::back), {.select = ".*", .spp = 1, .threads = 2});
  ASSERT_GT(r.paths.size(), 10u);
  for (const ray_path& p : r.paths) {
    const ray_segment* g = r.segments.data() + p.first_segment;
    ASSERT_GE(p.segment_count, 1u);
    EXPECT_EQ(g[0].event.kind, path_event_kind::display);
    for (std::uint32_t j = 0; j < p.segment_count; ++j) EXPECT_NE(g[j].event.kind, path_event_kind::film);
    // The aerial image's path: display, half mirror, sheet, half mirror, eye.
    if (p.segment_count == 4) {
      EXPECT_EQ(g[2].event.kind, path_event_kind::sheet);
    }
  }
}
