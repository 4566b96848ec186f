// Housings from mechanical CAD: a hood drawn and exported as STEP by FreeCAD (tests/step/make_hood.py)
// read as a prop, its size, place, window and hole where FreeCAD put them; units and colours as the
// file states them; damaged files as clear errors.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <regex>
#include <sstream>

#include <nlohmann/json.hpp>

#include "airr/core/files.hpp"
#include "airr/formats/mesh_gltf.hpp"
#include "airr/formats/mesh_step.hpp"
#include "airr/formats/prop_mesh.hpp"
#include "airr/formats/scene_json.hpp"
#include "error_of.hpp"
#include "test_helpers.hpp"

namespace airr {
namespace {

constexpr double top_z = 100;  // the hood's top wall, where the window and the hole are
constexpr double hole_x = 20, hole_y = 20, hole_radius = 10;

struct freecad_hood {
  std::string path;
  glm::dvec3 lo, hi;  // FreeCAD's bounding box
};

// The hood made once by FreeCAD for every test here (a few seconds).
const freecad_hood& hood() {
  static const test::temp_dir dir;
  static const freecad_hood made = [] {
    freecad_hood h{dir.file("hood.step"), {}, {}};
    const test::command_result r =
        test::run_command("HOOD_STEP='" + h.path + "' freecadcmd '" AIRR_SOURCE_DIR "/tests/step/make_hood.py' 2>&1");
    EXPECT_EQ(r.exit_code, 0) << r.out;
    const std::size_t at = r.out.rfind("{\"min\"");
    if (at == std::string::npos) {
      ADD_FAILURE() << "FreeCAD printed no bounding box:\n" << r.out;
      return h;
    }
    const auto box = nlohmann::json::parse(r.out.substr(at, r.out.find('\n', at) - at));
    h.lo = {box["min"][0], box["min"][1], box["min"][2]};
    h.hi = {box["max"][0], box["max"][1], box["max"][2]};
    return h;
  }();
  return made;
}

std::string hood_with(const test::temp_dir& dir, const std::string& name,
                      const std::function<std::string(std::string)>& edit) {
  const std::string path = dir.file(name);
  write_file_atomic(path, edit(read_text_file(hood().path)));
  return path;
}

// Whether the point (x, y) of the top wall's plane lies on one of the mesh's triangles there.
bool top_covers(const triangle_mesh& m, double x, double y) {
  for (std::size_t t = 0; t + 2 < m.indices.size(); t += 3) {
    const glm::vec3 a = m.positions[m.indices[t]], b = m.positions[m.indices[t + 1]], c = m.positions[m.indices[t + 2]];
    if (std::abs(a.z - top_z) > 1e-3 || std::abs(b.z - top_z) > 1e-3 || std::abs(c.z - top_z) > 1e-3) continue;
    auto side = [&](glm::vec3 p, glm::vec3 q) { return (q.x - p.x) * (y - p.y) - (q.y - p.y) * (x - p.x); };
    const double s0 = side(a, b), s1 = side(b, c), s2 = side(c, a);
    if ((s0 >= 0 && s1 >= 0 && s2 >= 0) || (s0 <= 0 && s1 <= 0 && s2 <= 0)) return true;
  }
  return false;
}

// The angles (radians, sorted) of the top wall's vertices on the cable hole's rim.
std::vector<double> hole_rim_angles(const triangle_mesh& m) {
  std::vector<double> angles;
  for (const glm::vec3& p : m.positions) {
    const double r = std::hypot(p.x - hole_x, p.y - hole_y);
    if (std::abs(p.z - top_z) < 1e-3 && std::abs(r - hole_radius) < 0.01) {
      angles.push_back(std::atan2(p.y - hole_y, p.x - hole_x));
    }
  }
  std::sort(angles.begin(), angles.end());
  angles.erase(std::unique(angles.begin(), angles.end(), [](double a, double b) { return b - a < 1e-6; }),
               angles.end());
  return angles;
}

TEST(StepHousing, TheHoodFreeCadDrewHasItsSizeAndPlace) {
  const freecad_hood& h = hood();
  const triangle_mesh m = load_step_mesh(h.path, "", 0.05);
  const mesh_bounds b = bounds_of(m);
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(b.lo[k], h.lo[k], 1e-3) << "axis " << k;
    EXPECT_NEAR(b.hi[k], h.hi[k], 1e-3) << "axis " << k;
  }
  EXPECT_NEAR(h.hi.x - h.lo.x, 200, 1e-6);  // FreeCAD's own figure, as drawn
}

TEST(StepHousing, TheWindowsEdgesAreWhereFreeCadPutThem) {
  const triangle_mesh m = load_step_mesh(hood().path, "", 0.05);
  const double d = 0.05;  // each edge found within this of where it was drawn
  EXPECT_FALSE(top_covers(m, 100, 75)) << "the window's middle";
  for (double y : {40.0, 75.0, 110.0}) {
    EXPECT_TRUE(top_covers(m, 40 - d, y)) << y;
    EXPECT_FALSE(top_covers(m, 40 + d, y)) << y;
    EXPECT_FALSE(top_covers(m, 160 - d, y)) << y;
    EXPECT_TRUE(top_covers(m, 160 + d, y)) << y;
  }
  for (double x : {45.0, 100.0, 155.0}) {
    EXPECT_TRUE(top_covers(m, x, 35 - d)) << x;
    EXPECT_FALSE(top_covers(m, x, 35 + d)) << x;
    EXPECT_FALSE(top_covers(m, x, 115 - d)) << x;
    EXPECT_TRUE(top_covers(m, x, 115 + d)) << x;
  }
  EXPECT_TRUE(top_covers(m, 180, 75)) << "the top beside the window";
  EXPECT_FALSE(top_covers(m, 201, 75)) << "beyond the hood";
}

TEST(StepHousing, TheHolesRimStaysWithinTheTessellationTolerance) {
  std::size_t previous = 0, rim_points_at_1mm = 0;
  for (double tolerance : {1.0, 0.2, 0.05, 0.01}) {
    const triangle_mesh m = load_step_mesh(hood().path, "", tolerance);
    const std::vector<double> angles = hole_rim_angles(m);
    ASSERT_GE(angles.size(), 3u) << tolerance;
    double widest = angles.front() + 2 * M_PI - angles.back();
    for (std::size_t i = 1; i < angles.size(); ++i) widest = std::max(widest, angles[i] - angles[i - 1]);
    // The chord's farthest distance from the arc it replaces (its sagitta).
    const double sagitta = hole_radius * (1 - std::cos(widest / 2));
    EXPECT_LE(sagitta, tolerance + 1e-6) << tolerance << " mm: " << angles.size() << " rim points";
    // Open CASCADE's angular limit (0.5 rad) may ask for more points than a coarse tolerance.
    EXPECT_GE(angles.size(), previous) << tolerance;
    if (tolerance == 0.01) {
      EXPECT_GT(angles.size(), rim_points_at_1mm);
    }
    if (tolerance == 1.0) rim_points_at_1mm = angles.size();
    previous = angles.size();
    // Inside the polygon the rim's chords make: open; just outside the circle: the wall.
    for (double a = 0.1; a < 2 * M_PI; a += 0.5) {
      const double inside = hole_radius - sagitta - 1e-3, outside = hole_radius + 1e-3;
      EXPECT_FALSE(top_covers(m, hole_x + inside * std::cos(a), hole_y + inside * std::sin(a))) << tolerance;
      EXPECT_TRUE(top_covers(m, hole_x + outside * std::cos(a), hole_y + outside * std::sin(a))) << tolerance;
    }
  }
}

TEST(StepHousing, LengthsAreInTheFilesUnit) {
  const test::temp_dir dir;
  const std::string mm_unit = "( LENGTH_UNIT() NAMED_UNIT(*) SI_UNIT(.MILLI.,.METRE.) )";
  auto with_unit = [&](const std::string& name, const std::string& unit, const std::string& extra) {
    return hood_with(dir, name, [&](std::string text) {
      const std::size_t at = text.find(mm_unit);
      EXPECT_NE(at, std::string::npos);
      if (at != std::string::npos) text.replace(at, mm_unit.size(), unit);
      text.insert(text.find("ENDSEC;", text.find("DATA;")), extra);
      return text;
    });
  };
  const std::string inches =
      with_unit("inches.step", "( CONVERSION_BASED_UNIT('INCH',#9001) LENGTH_UNIT() NAMED_UNIT(#9002) )",
                "#9001 = LENGTH_MEASURE_WITH_UNIT(LENGTH_MEASURE(25.4),#9003);\n"
                "#9002 = DIMENSIONAL_EXPONENTS(1.,0.,0.,0.,0.,0.,0.);\n"
                "#9003 = ( LENGTH_UNIT() NAMED_UNIT(*) SI_UNIT(.MILLI.,.METRE.) );\n");
  const std::string metres = with_unit("metres.stp", "( LENGTH_UNIT() NAMED_UNIT(*) SI_UNIT($,.METRE.) )", "");
  const mesh_bounds in = bounds_of(load_step_mesh(inches, "", 0.05));
  EXPECT_NEAR(in.hi.x, 200 * 25.4, 1e-2);
  EXPECT_NEAR(in.hi.z, 100 * 25.4, 1e-2);
  const mesh_bounds m = bounds_of(load_step_mesh(metres, "", 0.05));
  EXPECT_NEAR(m.hi.y, 150 * 1000, 1);
}

TEST(StepHousing, ColoursAndProductNamesComeFromTheFile) {
  const test::temp_dir dir;
  // A colour for the solid as CAD programs write it (AP214 presentation style), and a product name.
  const std::string coloured = hood_with(dir, "coloured.step", [](std::string text) {
    std::smatch solid, context;
    std::regex_search(text, solid, std::regex("#(\\d+) = MANIFOLD_SOLID_BREP"));
    std::regex_search(text, context, std::regex("ADVANCED_BREP_SHAPE_REPRESENTATION\\([^#]*#[^#]*#\\d+\\),#(\\d+)\\)"));
    EXPECT_FALSE(solid.empty() || context.empty());
    const std::string style =
        "#9010 = COLOUR_RGB('',1.,0.5,0.);\n"
        "#9011 = FILL_AREA_STYLE_COLOUR('',#9010);\n"
        "#9012 = FILL_AREA_STYLE('',(#9011));\n"
        "#9013 = SURFACE_STYLE_FILL_AREA(#9012);\n"
        "#9014 = SURFACE_SIDE_STYLE('',(#9013));\n"
        "#9015 = SURFACE_STYLE_USAGE(.BOTH.,#9014);\n"
        "#9016 = PRESENTATION_STYLE_ASSIGNMENT((#9015));\n"
        "#9017 = STYLED_ITEM('color',(#9016),#" +
        solid[1].str() +
        ");\n"
        "#9018 = MECHANICAL_DESIGN_GEOMETRIC_PRESENTATION_REPRESENTATION('',(#9017),#" +
        context[1].str() + ");\n";
    text.insert(text.find("ENDSEC;", text.find("DATA;")), style);
    return std::regex_replace(text, std::regex("PRODUCT\\('Open CASCADE STEP translator [^']*',\\s*'[^']*'"),
                              "PRODUCT('Hood','Hood'");
  });
  const triangle_mesh m = load_step_mesh(coloured, "", 0.05);
  ASSERT_EQ(m.materials.size(), 1u);
  ASSERT_EQ(m.triangle_materials.size(), m.indices.size() / 3);
  // STEP's colours are display (sRGB) values; a mesh's base colour is linear, as glTF's.
  EXPECT_NEAR(m.materials[0].base_color.r, 1.0, 1e-4);
  EXPECT_NEAR(m.materials[0].base_color.g, 0.21404, 1e-3);
  EXPECT_NEAR(m.materials[0].base_color.b, 0.0, 1e-4);
  EXPECT_EQ(m.materials[0].metallic, 0.0f);
  prop_params p;
  p.surface = prop_surface::material;
  const surface_response s = prop_surface_of(p, m, 0);
  EXPECT_EQ(s.kind, prop_surface::diffuse);

  EXPECT_EQ(load_step_mesh(coloured, "Hood", 0.05).indices, m.indices);
  EXPECT_EQ(test::error_of([&] { load_step_mesh(coloured, "Lid", 0.05); }), coloured + ": no product named Lid");
  // A file without colours: no materials, as a glTF mesh without them.
  EXPECT_TRUE(load_step_mesh(hood().path, "", 0.05).materials.empty());
}

TEST(StepHousing, DamagedFilesAreClearErrors) {
  const test::temp_dir dir;
  const std::string text = read_text_file(hood().path);
  const std::string empty = dir.file("empty.step"), half = dir.file("half.step"), shapeless = dir.file("none.stp"),
                    prose = dir.file("prose.step");
  write_file_atomic(empty, "");
  write_file_atomic(half, text.substr(0, text.size() / 2));
  write_file_atomic(prose, "This housing was drawn in a CAD program.\n");
  write_file_atomic(shapeless, text.substr(0, text.find("DATA;")) + "DATA;\nENDSEC;\nEND-ISO-10303-21;\n");
  // What the fuzzer found would crash the reader: a direction turned to garbage, a vertex naming a
  // point that is not there, a point whose type is garbled, an oriented edge built on itself, an
  // entity defined twice. Each file is refused, naming what is wrong.
  const auto mangled = [&](const std::string& name, const std::string& find, std::size_t offset,
                           const std::string& insert, std::size_t erase = 0) {
    std::string t = text;
    const std::size_t at = t.find(find);
    EXPECT_NE(at, std::string::npos) << find;
    if (at != std::string::npos) t.replace(at + offset, erase, insert);
    write_file_atomic(dir.file(name), t);
    return dir.file(name);
  };
  const std::string garbled = mangled("garbled.step", "= DIRECTION(", 0, "2212Geom_Surface(", 12),
                    dangling = mangled("dangling.step", "VERTEX_POINT('',#", 17, "9999"),
                    untyped = mangled("untyped.step", "= CARTESIAN_POINT(", 8, "\xff\xff", 6),
                    twice = mangled("twice.step", "DATA;", 5, "\n#1 = CARTESIAN_POINT('',(0.,0.,0.));");
  std::string looped = text;
  const std::size_t edge = looped.find("= ORIENTED_EDGE('',*,*,#");
  ASSERT_NE(edge, std::string::npos);
  const std::size_t self = looped.rfind('#', edge), target = edge + std::string("= ORIENTED_EDGE('',*,*,").size();
  const std::string self_id = looped.substr(self, looped.find_first_of(" =", self) - self);
  looped.replace(target, looped.find(',', target) - target, self_id);
  write_file_atomic(dir.file("looped.step"), looped);
  const std::string cycle = dir.file("looped.step");
  // The same loop behind a name whose last quote doubles: the reader ends the string at the quote
  // before the comma and reads the loop; a scan taking '' as one quote would skip it.
  std::string hidden_text = looped;
  hidden_text.replace(edge + std::string("= ORIENTED_EDGE(").size(), 2, "'it''");
  write_file_atomic(dir.file("hidden.step"), hidden_text);
  const std::string hidden = dir.file("hidden.step");
  // A line whose vector's direction is the line: references that go round in a loop.
  std::string ring_text = text;
  const std::size_t line = ring_text.find("= LINE('',#");
  ASSERT_NE(line, std::string::npos);
  const std::size_t line_id = ring_text.rfind('#', line), point_ref = ring_text.find(",#", line) + 1,
                    vector_ref = ring_text.find(",#", point_ref) + 1;
  const std::string line_name = ring_text.substr(line_id, ring_text.find_first_of(" =", line_id) - line_id),
                    vector_name = ring_text.substr(vector_ref, ring_text.find(')', vector_ref) - vector_ref);
  const std::string vector_start = vector_name + " = VECTOR('',";
  const std::size_t direction = ring_text.find(vector_start) + vector_start.size();
  ring_text.replace(direction, ring_text.find(',', direction) - direction, line_name);
  write_file_atomic(dir.file("ring.step"), ring_text);
  const std::string ring = dir.file("ring.step");
  // A direction with no ratios: the reader's own check reads the list it left unset.
  std::string hollow_text = text;
  const std::size_t ratios = hollow_text.find("= DIRECTION('',(") + std::string("= DIRECTION('',(").size();
  hollow_text.erase(ratios, hollow_text.find(')', ratios) - ratios);
  write_file_atomic(dir.file("hollow.step"), hollow_text);
  const std::string hollow = dir.file("hollow.step");
  EXPECT_NE(test::error_of([&] { load_step_mesh(garbled, "", 0.05); }).find("which the file does not define"),
            std::string::npos);
  EXPECT_NE(test::error_of([&] { load_step_mesh(dangling, "", 0.05); }).find("9999"), std::string::npos);
  EXPECT_NE(test::error_of([&] { load_step_mesh(untyped, "", 0.05); }).find("Line "), std::string::npos);
  EXPECT_NE(test::error_of([&] { load_step_mesh(cycle, "", 0.05); }).find("oriented edge"), std::string::npos);
  EXPECT_NE(test::error_of([&] { load_step_mesh(hidden, "", 0.05); }).find("oriented edge"), std::string::npos);
  const std::string ring_error = test::error_of([&] { load_step_mesh(ring, "", 0.05); });
  EXPECT_NE(ring_error.find("refers back to " + line_name), std::string::npos) << ring_error;
  EXPECT_NE(test::error_of([&] { load_step_mesh(hollow, "", 0.05); }).find("a DIRECTION, has an empty list"),
            std::string::npos);
  EXPECT_NE(test::error_of([&] { load_step_mesh(twice, "", 0.05); }).find("#1 is defined twice"), std::string::npos);
  for (const std::string& path :
       {empty, half, prose, shapeless, garbled, dangling, untyped, cycle, hidden, ring, hollow, twice}) {
    const std::string e = test::error_of([&] { load_step_mesh(path, "", 0.05); });
    EXPECT_EQ(e.rfind(path + ": ", 0), 0u) << e;
    EXPECT_EQ(e.find('\n'), std::string::npos) << e;
  }
  EXPECT_EQ(test::error_of([&] { load_step_mesh(dir.file("missing.step"), "", 0.05); }),
            dir.file("missing.step") + ": file not found");
  EXPECT_NE(test::error_of([&] { load_step_mesh(hood().path, "", 0); }).find("tessellation tolerance 0 mm"),
            std::string::npos);
}

TEST(StepHousing, AScenesPropNamesAStepFileAndItsTolerance) {
  const test::temp_dir dir;
  nlohmann::json j = scene_to_json(test::uniform_source_scene(20));
  j["props"] = nlohmann::json::array({{{"name", "hood"}, {"mesh", hood().path}, {"tessellation_mm", 1.0}}});
  const std::string path = dir.file("scene.json");
  write_file_atomic(path, j.dump());
  const scene s = load_scene(path);
  ASSERT_EQ(s.props.size(), 1u);
  EXPECT_EQ(s.props[0].tessellation_mm, 1.0);
  EXPECT_EQ(prop_mesh(s, s.props[0])->indices, load_step_mesh(hood().path, "", 1.0).indices);
  EXPECT_EQ(scene_to_json(s)["props"][0]["tessellation_mm"], 1.0);
  j["props"][0]["tessellation_mm"] = -1;
  write_file_atomic(path, j.dump());
  EXPECT_NE(test::error_of([&] { load_scene(path); }).find("props[0].tessellation_mm"), std::string::npos);
}

}  // namespace
}  // namespace airr
