// Path labels and path expressions (docs/path-expressions.md): the grammar's errors point at the
// character, matching agrees with std::regex on the same language, the four predefined
// expressions partition every label as the tracer's components do and reproduce their images bit
// for bit, and layers that partition the paths add up to the whole image.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <functional>
#include <regex>

#include "airr/core/assets.hpp"
#include "airr/core/error.hpp"
#include "airr/core/random.hpp"
#include "airr/formats/image.hpp"
#include "airr/formats/scene_json.hpp"
#include "airr/render/path_expression.hpp"
#include "airr/render/render_session.hpp"
#include "test_helpers.hpp"

using namespace airr;

namespace {

using test::label_of;

const path_event D{path_event_kind::display}, E{path_event_kind::eye};
path_event H(bool reflected, int order = 0, bool front = true) {
  return {path_event_kind::half_mirror, reflected, front, std::uint16_t(order)};
}
path_event S(int sheet, bool retro) { return {path_event_kind::sheet, retro, false, std::uint16_t(sheet)}; }
path_event P(int prop) { return {path_event_kind::prop, false, false, std::uint16_t(prop)}; }

bool matches(const std::string& expression, const std::vector<path_event>& light_order) {
  return path_expression::parse(expression).matches(label_of(light_order));
}

}  // namespace

TEST(PathExpressions, ErrorsPointAtTheCharacter) {
  const struct {
    const char* text;
    int character;
    const char* says;
  } cases[] = {
      {"", 1, "it is empty"},
      {"D H:q E", 5, "H takes r, t"},
      {"D (H E", 3, "'(' is not closed"},
      {"D E)", 4, "')' without '('"},
      {"D Q E", 3, "expected an event"},
      {"D S0:retr E", 6, "S takes retro or other"},
      {"DH E", 1, "followed by a space or an operator"},
      {"D [H S E", 3, "'[' is not closed"},
      {"D [] E", 4, "an empty set"},
      {"D | | E", 5, "expected an event"},
      {"D:x E", 3, "D takes no qualifier"},
      {"D P:\"hood E", 5, "'\"' is not closed"},
      {"D P# E", 5, "a prop's number"},
  };
  for (const auto& c : cases) {
    try {
      path_expression::parse(c.text);
      ADD_FAILURE() << "parsed: " << c.text;
    } catch (const input_error& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find("path expression '" + std::string(c.text) + "'"), std::string::npos) << what;
      EXPECT_NE(what.find("at character " + std::to_string(c.character) + ":"), std::string::npos) << what;
      EXPECT_NE(what.find(c.says), std::string::npos) << what;
    }
  }
}

TEST(PathExpressions, EventsAndQualifiers) {
  EXPECT_TRUE(matches("D H:r S0:retro H:t E", {D, H(true), S(0, true), H(false), E}));
  EXPECT_FALSE(matches("D H:r S0:retro H:t E", {D, H(true), S(1, true), H(false), E}));
  EXPECT_FALSE(matches("D H:r S0:retro H:t E", {D, H(true), S(0, false), H(false), E}));
  EXPECT_FALSE(matches("D H:r S0:retro H:t E", {D, H(false), S(0, true), H(false), E}));
  EXPECT_TRUE(matches("D H:r1 E", {D, H(true, 1), E}));
  EXPECT_FALSE(matches("D H:r1 E", {D, H(true, 0), E}));
  EXPECT_TRUE(matches("D H:t:back E", {D, H(false, 2, false), E}));
  EXPECT_FALSE(matches("D H:t:front E", {D, H(false, 2, false), E}));
  EXPECT_TRUE(matches("D H S E", {D, H(false), S(3, false), E}));
  EXPECT_TRUE(matches("D P#2 E", {D, P(2), E}));
  EXPECT_FALSE(matches("D P#2 E", {D, P(1), E}));
  // The whole label must match, not a part of it.
  EXPECT_FALSE(matches("D H E", {D, H(true), H(false), E}));
  EXPECT_TRUE(matches("D [^S:retro]* E", {D, H(true), S(0, false), P(0), E}));
  EXPECT_FALSE(matches("D [^S:retro]* E", {D, H(true), S(0, true), E}));
  EXPECT_TRUE(matches("(D|E)+", {D, E, E}));
  EXPECT_TRUE(matches("D H? H? E", {D, E}));
}

TEST(PathExpressions, PropNamesAreBoundToTheScene) {
  scene s;
  s.props.resize(2);
  s.props[0].name = "hood";
  s.props[1].name = "front plate";
  const path_expression e = path_expression::parse("D P:\"front plate\" E").bound(s, true);
  EXPECT_TRUE(e.matches(label_of({D, P(1), E})));
  EXPECT_FALSE(e.matches(label_of({D, P(0), E})));
  EXPECT_FALSE(path_expression::parse("D P:hood E").matches(label_of({D, P(0), E})));  // not bound yet
  EXPECT_THROW(path_expression::parse("D P:lid E").bound(s, true), input_error);
  EXPECT_FALSE(path_expression::parse("D P:lid E").bound(s, false).matches(label_of({D, P(0), E})));
}

// Random expressions over a few events against std::regex on the same language: each event a
// letter, each expression's event the class of letters it accepts.
TEST(PathExpressions, MatchingAgreesWithStdRegex) {
  const std::vector<path_event> alphabet = {D, E, H(true), H(false), H(true, 1), S(0, true), S(1, false), P(0)};
  const std::vector<std::string> atoms = {"D", "E", "H", "H:r", "H:t", "H:r1", "S", "S0:retro", "S:other", "P", "."};
  pcg32 rng(7, 11);
  const auto pick = [&](std::size_t n) { return std::size_t(rng.next_double() * double(n)); };
  const auto letters_of = [&](const std::string& atom) {
    std::string cls;
    const path_expression e = path_expression::parse(atom);
    for (std::size_t i = 0; i < alphabet.size(); ++i)
      if (e.matches(label_of({alphabet[i]}))) cls += char('a' + i);
    return "[" + cls + "]";
  };
  // Grows an expression and its regex side by side.
  std::function<std::pair<std::string, std::string>(int)> grow = [&](int depth) -> std::pair<std::string, std::string> {
    const std::size_t kind = depth <= 0 ? 0 : pick(5);
    if (kind == 0 || kind == 4) {
      const std::string a = atoms[pick(atoms.size())];
      return {a, letters_of(a)};
    }
    const auto [x, rx] = grow(depth - 1);
    if (kind == 1) {
      const auto [y, ry] = grow(depth - 1);
      return {x + " " + y, rx + ry};
    }
    if (kind == 2) {
      const auto [y, ry] = grow(depth - 1);
      return {"(" + x + " | " + y + ")", "(" + rx + "|" + ry + ")"};
    }
    const char* op[] = {"*", "+", "?"};
    const std::string o = op[pick(3)];
    return {"(" + x + ")" + o, "(" + rx + ")" + o};
  };
  int checked = 0, matched = 0;
  for (int t = 0; t < 300; ++t) {
    const auto [text, rx] = grow(4);
    const path_expression e = path_expression::parse(text);
    const std::regex re(rx);
    for (int u = 0; u < 40; ++u) {
      std::vector<path_event> events;
      std::string letters;
      for (std::size_t n = pick(7); n > 0; --n) {
        const std::size_t i = pick(alphabet.size());
        events.push_back(alphabet[i]);
        letters += char('a' + i);
      }
      const bool expected = std::regex_match(letters, re);
      ASSERT_EQ(e.matches(label_of(events)), expected) << text << " on " << letters;
      ++checked;
      matched += expected;
    }
  }
  std::printf("%d labels checked, %d matched\n", checked, matched);
  EXPECT_GT(matched, checked / 20);
}

// The predefined expressions give every label exactly the component the tracer's counts give it.
TEST(PathExpressions, ComponentsPartitionTheLabels) {
  const path_layers layers = component_layers();
  const std::vector<path_event> middle = {H(true), H(false), H(true, 1), S(0, true), S(1, false), P(0)};
  pcg32 rng(3, 5);
  // Ambient light, by any path, is its own component: the room's, the sun's, the luminaires'.
  const std::array<std::pair<path_event, int>, 4> ambient_sources = {{
      {{path_event_kind::ambient, false, false, ambient_room}, component_room},
      {{path_event_kind::ambient, false, false, ambient_sun}, component_sun},
      {{path_event_kind::ambient, false, false, ambient_first_luminaire}, component_luminaires},
      {{path_event_kind::ambient, false, false, ambient_first_luminaire + 7}, component_luminaires},
  }};
  for (int t = 0; t < 5000; ++t) {
    const bool ambient = t % 5 == 0;
    const auto& source = ambient_sources[std::size_t(t / 5) % ambient_sources.size()];
    std::vector<path_event> events = {ambient ? source.first : D};
    int retro = 0, scattered = 0, reflections = 0;
    for (std::size_t n = std::size_t(rng.next_double() * 6); n > 0; --n) {
      const path_event e = middle[std::size_t(rng.next_double() * double(middle.size()))];
      events.push_back(e);
      retro += e.kind == path_event_kind::sheet && e.taken;
      scattered += e.kind == path_event_kind::prop || (e.kind == path_event_kind::sheet && !e.taken);
      reflections += e.kind == path_event_kind::half_mirror && e.taken;
    }
    events.push_back(E);
    const int expected = ambient            ? source.second
                         : retro > 0        ? component_aerial
                         : scattered > 0    ? component_rest
                         : reflections == 0 ? component_direct
                         : reflections == 1 ? component_reflection
                                            : component_rest;
    ASSERT_EQ(layers.select(label_of(events)), std::uint64_t(1) << expected) << label_text(label_of(events));
  }
}

namespace {

// The default layout seen from 30 degrees above with a wide field and a sheet of `model` (an RF-AN
// preset or the prism sheet, which sends some light back without retroreflecting it), or from
// between the sheet and the half mirror, where the display's reflection is seen.
scene looking_down(const std::string& model = "rf-an") {
  std::vector<scene_override> o = {{"observer.elevation_deg", "30"},
                                   {"observer.fov_deg", "60"},
                                   {"observer.width", "48"},
                                   {"observer.height", "48"}};
  if (model != "prism") {
    o.push_back({"retroreflectors.0.model.type", "\"sinc_shift\""});
    o.push_back({"retroreflectors.0.model.preset", "\"" + model + "\""});
  }
  scene s = load_scene(ideal_bench_scene_path(), o);
  if (model == "prism") s.sheet().model = retro_model_params{"prism_sheet", {{"wavelength_nm", 0.0}}};
  return s;
}
// The ideal bench with its display turned over above the half mirror, on the observer's side:
// the observer sees the display's reflection in the half mirror.
scene display_above() {
  scene s = looking_down("rf-an");
  s.observer.elevation_deg = 0;
  s.observer.fov_deg = 30;
  s.source.pose.center_mm = {0, 150, 0};
  s.source.pose.pitch_deg = -90;
  return s;
}
scene wide(const std::string& name) {
  return load_scene(asset_dir() + "/scenes/" + name + ".json",
                    {{"observer.fov_deg", "60"}, {"observer.width", "48"}, {"observer.height", "48"}});
}

render_snapshot render_layers(const scene& s, const path_layers& layers, bool components, std::uint64_t spp) {
  render_session session(s, {.threads = 2,
                             .target_spp = spp,
                             .components = components,
                             .layers = std::make_shared<const path_layers>(layers)});
  session.wait_for(0, spp);
  return session.snapshot();
}

}  // namespace

TEST(PathLayers, PredefinedExpressionsReproduceTheComponentsBitForBit) {
  std::vector<double> energy(component_count, 0.0);
  scene kiosk_in_a_room = wide("two_sheet_kiosk");
  kiosk_in_a_room.source.luminance_cd_m2 = 500;
  kiosk_in_a_room.environment.room.illuminance_lux = 500;
  luminaire_params ceiling;
  ceiling.pose = {.center_mm = {0, 600, 300}, .pitch_deg = -90};
  ceiling.luminance_cd_m2 = 3000;
  kiosk_in_a_room.environment.luminaires.push_back(ceiling);
  // From 30 degrees above, the half mirror shows the sky at an elevation of 60 degrees straight
  // ahead: a sun there makes a glare spot.
  scene bench_in_the_sun = looking_down();
  bench_in_the_sun.source.luminance_cd_m2 = 500;
  bench_in_the_sun.environment.sun = {.azimuth_deg = 0, .elevation_deg = 60, .illuminance_lux = 20000};
  for (const scene& s : {looking_down(), looking_down("prism"), display_above(), kiosk_in_a_room, bench_in_the_sun}) {
    const render_snapshot snap = render_layers(s, component_layers(), true, 8);
    ASSERT_TRUE(snap.components);
    ASSERT_TRUE(snap.layers);
    ASSERT_EQ(snap.layer_names.size(), std::size_t(component_count + 1));
    EXPECT_EQ(snap.layer_names.back(), "unmatched");
    for (int k = 0; k < component_count; ++k) {
      EXPECT_EQ(snap.layer_names[std::size_t(k)], component_names[k]);
      const image_rgb layer = snap.layer_image(std::size_t(k)), component = snap.component_image(k);
      ASSERT_EQ(layer.rgb.size(), component.rgb.size());
      double e = 0;
      for (float v : component.rgb) e += v;
      energy[std::size_t(k)] += e;
      EXPECT_TRUE(std::equal(layer.rgb.begin(), layer.rgb.end(), component.rgb.begin(), [](float a, float b) {
        return std::memcmp(&a, &b, sizeof a) == 0;
      })) << component_names[k];
      std::printf("%s: energy %.6g, the same as the component's to the bit\n", component_names[k], e);
    }
    const image_rgb unmatched = snap.layer_image(component_count);
    EXPECT_EQ(*std::max_element(unmatched.rgb.begin(), unmatched.rgb.end()), 0.0f);
  }
  for (int k = 0; k < component_count; ++k) EXPECT_GT(energy[std::size_t(k)], 0) << component_names[k];
}

TEST(PathLayers, APartitionAddsUpToTheWholeImage) {
  path_layers layers;
  layers.layers.push_back({"aerial0", path_expression::parse("D .* S0:retro .* E")});
  layers.layers.push_back({"others", path_expression::parse("D [^S0:retro]* E")});
  layers.layers.push_back({"via_reflection", path_expression::parse("D .* H:r .* E")});  // overlaps both
  const render_snapshot snap = render_layers(looking_down(), layers, false, 8);
  ASSERT_TRUE(snap.layers);
  ASSERT_EQ(snap.layer_names.size(), 4u);
  const image_rgb a = snap.layer_image(0), b = snap.layer_image(1), r = snap.layer_image(2), u = snap.layer_image(3);
  const double peak = *std::max_element(snap.rgb->begin(), snap.rgb->end());
  double worst = 0, aerial = 0, others = 0, reflected = 0;
  for (std::size_t i = 0; i < snap.rgb->size(); ++i) {
    worst = std::max(worst, std::abs(double(a.rgb[i]) + b.rgb[i] - (*snap.rgb)[i]));
    aerial += a.rgb[i];
    others += b.rgb[i];
    reflected += r.rgb[i];
    EXPECT_EQ(u.rgb[i], 0.0f);
  }
  std::printf("aerial0 + others = image within %.3g of its peak; energies %.6g %.6g, via a reflection %.6g\n",
              worst / peak, aerial, others, reflected);
  EXPECT_LT(worst, 1e-5 * peak);
  EXPECT_GT(aerial, 0);
  EXPECT_GT(others, 0);
  EXPECT_GT(reflected, 0);
}

TEST(PathLayers, LayerArgumentsAreChecked) {
  const scene s = looking_down();
  EXPECT_EQ(parse_layer_arguments({"a=D .* E", "b=D H:t E"}, s).layers.size(), 2u);
  const auto says = [&](const std::vector<std::string>& args, const std::string& what,
                        const std::vector<std::string>& taken = {}) {
    try {
      parse_layer_arguments(args, s, taken);
      ADD_FAILURE() << "accepted " << args.front();
    } catch (const input_error& e) {
      EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << e.what();
    }
  };
  says({"a=D .* E", "a=D E"}, "the layer a is named twice");
  says({"D .* E"}, "expected NAME=EXPRESSION");
  says({"a b=D E"}, "a layer's name is letters");
  says({"unmatched=D E"}, "'unmatched' names the paths");
  says({"a=D (E"}, "at character 3");
  says({"a=D P:lid E"}, "no prop named 'lid'");
  says({"rest=D E"}, "rest names another of the render's outputs", {"aerial", "direct", "reflection", "rest"});
  EXPECT_EQ(parse_layer_arguments({"rest=D E"}, s).layers.size(), 1u);
  // The command line's outputs: the components with --components, the Stokes images with --stokes.
  test::temp_dir dir;
  const std::string scene = test::scene_file(dir, [](nlohmann::json& j) { j["observer"]["width"] = 8; });
  const std::string out = dir.file("taken.exr");
  test::expect_one_line_error(test::run_cli("render " + scene + " -o " + out + " --components --layer 'direct=D E'"),
                              {"--layer 'direct=D E'", "another of the render's outputs"});
  test::expect_one_line_error(test::run_cli("render " + scene + " -o " + out + " --stokes --layer 'dop=D E'"),
                              {"--layer 'dop=D E'", "another of the render's outputs"});
  EXPECT_FALSE(std::filesystem::exists(out));
}

TEST(PathLayers, RenderWritesEachLayerWithItsExpression) {
  test::temp_dir dir;
  const std::string scene = test::scene_file(dir, [](nlohmann::json& j) {
    j["observer"]["width"] = 32;
    j["observer"]["height"] = 24;
  });
  const std::string out = dir.file("layers.exr");
  const auto r = test::run_cli("render " + scene + " -o " + out +
                               " --spp 2 --layer 'aerial0=D .* S0:retro .* E' --layer 'other=D [^S0:retro]* E'");
  ASSERT_EQ(r.exit_code, 0) << r.out;
  const image_metadata meta = read_image_metadata(out);
  EXPECT_EQ(meta.at("airr:layer:aerial0"), "D .* S0:retro .* E");
  EXPECT_EQ(meta.at("airr:layer:other"), "D [^S0:retro]* E");
  const image_rgb whole = load_image(out).pixels;
  const image_rgb a = load_image_layer(out, "aerial0"), b = load_image_layer(out, "other"),
                  u = load_image_layer(out, "unmatched");
  ASSERT_EQ(a.rgb.size(), whole.rgb.size());
  double worst = 0, peak = 0;
  for (std::size_t i = 0; i < whole.rgb.size(); ++i) {
    worst = std::max(worst, std::abs(double(a.rgb[i]) + b.rgb[i] + u.rgb[i] - whole.rgb[i]));
    peak = std::max(peak, double(whole.rgb[i]));
  }
  EXPECT_GT(peak, 0);
  EXPECT_LT(worst, 1e-5 * peak);

  // A bad expression: one line pointing at the character, nothing written.
  const std::string bad = dir.file("bad.exr");
  test::expect_one_line_error(test::run_cli("render " + scene + " -o " + bad + " --layer 'x=D H:q E'"),
                              {"path expression 'D H:q E'", "at character 5"});
  EXPECT_FALSE(std::filesystem::exists(bad));
  test::expect_one_line_error(test::run_cli("render " + scene + " -o " + bad + " --layer 'x=D E' --layer 'x=E'"),
                              {"the layer x is named twice"});
  EXPECT_FALSE(std::filesystem::exists(bad));
}

// The aerial image's one path class, written exactly (its faces too), carries the control variate:
// it is the aerial component to the bit, and nothing is left unmatched by it and the rest.
TEST(PathLayers, TheModelledPathsExactLabelCarriesTheControlVariate) {
  scene s = looking_down();
  s.observer.elevation_deg = 0;
  s.observer.fov_deg = 14;
  path_layers layers;
  layers.layers.push_back({"exact", path_expression::parse("D H:r0:back S0:retro H:t0:back E")});
  layers.layers.push_back(component_layers().layers.front());
  const render_snapshot snap = render_layers(s, layers, false, 8);
  ASSERT_TRUE(snap.layers);
  const image_rgb exact = snap.layer_image(0), aerial = snap.layer_image(1);
  double energy = 0;
  for (float v : exact.rgb) energy += v;
  EXPECT_GT(energy, 0);
  EXPECT_TRUE(std::equal(exact.rgb.begin(), exact.rgb.end(), aerial.rgb.begin(),
                         [](float a, float b) { return std::memcmp(&a, &b, sizeof a) == 0; }));
}

// Shards of a render with layers merge into the one-process render's layers, bit for bit.
TEST(PathLayers, ShardsOfALayeredRenderMergeIntoTheWhole) {
  test::temp_dir dir;
  const std::string scene = test::scene_file(dir, [](nlohmann::json& j) {
    j["observer"]["width"] = 24;
    j["observer"]["height"] = 20;
  });
  const std::string layers = " --spp 2 --seed 5 --layer 'a0=D .* S0:retro .* E' --layer 'rest=D [^S0:retro]* E'";
  ASSERT_EQ(test::run_cli("render " + scene + " -o " + dir.file("whole.exr") + layers).exit_code, 0);
  for (const char* shard : {"0/2", "1/2"}) {
    const auto r = test::run_cli("render " + scene + " -o " + dir.file(std::string("s") + shard[0] + ".exr") + layers +
                                 " --shard " + shard);
    ASSERT_EQ(r.exit_code, 0) << r.out;
  }
  const auto m = test::run_cli("merge " + dir.file("s0.exr") + " " + dir.file("s1.exr") + " -o " + dir.file("m.exr"));
  ASSERT_EQ(m.exit_code, 0) << m.out;
  for (const char* name : {"a0", "rest", "unmatched"}) {
    const image_rgb whole = load_image_layer(dir.file("whole.exr"), name),
                    merged = load_image_layer(dir.file("m.exr"), name);
    EXPECT_EQ(whole.rgb, merged.rgb) << name;
  }
  EXPECT_EQ(read_image_metadata(dir.file("m.exr")).at("airr:layer:a0"), "D .* S0:retro .* E");
}
