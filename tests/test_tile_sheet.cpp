// The tile sheet: a designer's mesh repeated behind a plate. Its shipped tile, the prism sheet's
// cube corners, must trace as the prism sheet does and as the corner-cube shift table says.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <memory>
#include <string>

#include "airr/core/error.hpp"
#include "airr/formats/mesh_gltf.hpp"
#include "airr/models/corner_cube.hpp"
#include "airr/models/prism_sheet.hpp"
#include "airr/models/shift_table.hpp"
#include "airr/models/tile_sheet.hpp"
#include "chi_square.hpp"
#include "prism_test_support.hpp"
#include "test_helpers.hpp"

using namespace airr;

namespace {

// The shipped tile at 0.1 mm pitch in millimetres, its faces a metal coat of `reflectance` when
// given.
std::shared_ptr<const triangle_mesh> cube_tile_mm(std::optional<float> reflectance = std::nullopt) {
  triangle_mesh m = make_corner_cube_tile(0.1);
  for (glm::vec3& p : m.positions) p *= 1000.0f;
  if (reflectance) {
    m.materials = {mesh_material{"coat", glm::vec3(*reflectance), 1.0f, 0.0f}};
    m.triangle_materials.assign(m.indices.size() / 3, 0);
  }
  return std::make_shared<const triangle_mesh>(m);
}

struct tile_sheet {
  tile_sheet_geometry g;
  std::unique_ptr<tile_structure> t;
  explicit tile_sheet(const tile_sheet_geometry& geometry) : g(geometry), t(std::make_unique<tile_structure>(g)) {}
  test::path_source paths() const {
    return [this](const glm::dvec3& wi, pcg32& rng) {
      const glm::dvec2 u(rng.next_double(), rng.next_double());
      const double a = radians(g.azimuth_deg);
      const glm::dvec2 local = u * g.period_mm;
      const glm::dvec2 entry(std::cos(a) * local.x - std::sin(a) * local.y,
                             std::sin(a) * local.x + std::cos(a) * local.y);
      return trace_tile_sheet(g, *t, wi, entry, rng.next_double(), rng);
    };
  }
};

tile_sheet_geometry cube_tile_geometry() {
  tile_sheet_geometry g;
  g.tile = cube_tile_mm();
  g.tile_file = "cube tile";
  return g;
}

}  // namespace

// In air with mirror faces, the shipped tile's retroreflected shifts follow the corner-cube shift
// table (chi-square) and its retroreflected share the table's effective area, over uniform
// azimuths.
TEST(TileSheet, ShiftsFollowTheCornerCubeShiftTable) {
  const shift_table table = load_shift_table(default_shift_table_path());
  tile_sheet_geometry g = cube_tile_geometry();
  g.tile = cube_tile_mm(1.0f);
  g.index = 1;
  g.plate_mm = 0;
  g.wavelength_nm = 0;
  const tile_sheet sheet(g);
  const double edge = 2 * 0.1 / std::sqrt(3.0) / std::sqrt(2.0);
  pcg32 rng(11, 5);
  for (const std::size_t row : {std::size_t(0), std::size_t(3), std::size_t(6)}) {
    const int bins = table.bins();
    std::vector<double> counts(std::size_t(bins), 0.0);
    double kept = 0, tried = 0;
    while (kept < 20000) {
      const prism_path p = sheet.paths()(test::unit_direction(table.theta_deg[row], 360 * rng.next_double()), rng);
      tried += 1;
      if (p.fate != prism_fate::retroreflected) continue;
      EXPECT_EQ(p.face_reflections, 3);
      const double s = glm::length(p.shift_mm) / edge;
      counts[std::size_t(std::min(bins - 1, int(s / table.s_max * bins)))] += 1;
      kept += 1;
    }
    std::vector<double> expected;
    for (double pr : table.probability[row]) expected.push_back(pr * kept);
    const test::chi_square_result r = test::chi_square(counts, expected);
    const double share = kept / tried, f = table.retro_fraction[row];
    std::printf("theta %g: chi-square %.1f on %d dof, p = %.3f; retroreflected %.4f, table %.4f\n",
                table.theta_deg[row], r.statistic, r.dof, r.p_value, share, f);
    EXPECT_GT(r.p_value, 1e-3) << "theta " << table.theta_deg[row];
    EXPECT_NEAR(share, f, 4 * std::sqrt(f * (1 - f) / tried) + 2e-3) << "theta " << table.theta_deg[row];
  }
}

// Total internal reflection in a plate of index 1.5, the grooves turned by 17 deg: the tile sheet
// sends light where the prism sheet does (front reflection, retroreflected, stray, transmitted),
// within 4.5 standard errors of the difference.
TEST(TileSheet, TracesAsThePrismSheet) {
  tile_sheet_geometry g = cube_tile_geometry();
  g.azimuth_deg = 17;
  g.wavelength_nm = 0;
  const tile_sheet sheet(g);
  prism_sheet_geometry prism;
  prism.azimuth_deg = 17;
  prism.wavelength_nm = 0;
  for (const double theta : {0.0, 20.0, 35.0}) {
    const glm::dvec3 wi = test::unit_direction(theta, 13);
    const int n = 40000;
    const test::fates a = test::trace_many(sheet.paths(), wi, n, 3), b = test::trace_many(prism, wi, n, 4);
    const auto expect_same = [&](double x, double y, const char* what) {
      const double p = 0.5 * (x + y) / n, sigma = std::sqrt(2 * p * (1 - p) / n);
      std::printf("theta %g %s: tile %.4f prism %.4f\n", theta, what, x / n, y / n);
      EXPECT_NEAR(x / n, y / n, 4.5 * sigma + 1e-4) << what << " at " << theta;
    };
    expect_same(a.front, b.front, "front");
    expect_same(a.retro, b.retro, "retroreflected");
    expect_same(a.cube_retro, b.cube_retro, "by one cube corner");
    expect_same(a.stray, b.stray, "stray");
    expect_same(a.transmitted, b.transmitted, "transmitted");
    EXPECT_LE(a.lost / n, 0.001);
  }
}

// The aperture each retroreflected path diffracts by (the entry points that meet the same faces in
// the same order) is the prism sheet's face-order part: the spreads' medians agree within 3%.
TEST(TileSheet, DiffractsAsThePrismSheet) {
  const tile_sheet sheet(cube_tile_geometry());
  const prism_sheet_geometry prism;
  for (const double theta : {0.0, 15.0}) {
    const glm::dvec3 wi = test::unit_direction(theta, 13);
    const double tile = test::median_retro_spread(sheet.paths(), wi, 9, 1);
    const double reference = test::median_retro_spread(prism, wi, 9, 2);
    std::printf("theta %g: median spread tile %.3f mrad, prism %.3f mrad\n", theta, tile * 1e3, reference * 1e3);
    EXPECT_NEAR(tile / reference, 1.0, 0.03) << theta;
  }
}

TEST(TileSheet, NoLightIsLostByALosslessSheet) {
  const tile_sheet sheet(cube_tile_geometry());
  for (const test::fates& f : test::expect_no_light_lost(sheet.paths(), 5)) EXPECT_GT(f.transmitted, 0);
}

// A metallic material is a metal coat of its base colour: three faces return 0.9^3 of the light,
// and nothing goes out of the back.
TEST(TileSheet, MetallicFacesReflectTheirBaseColour) {
  tile_sheet_geometry g = cube_tile_geometry();
  g.tile = cube_tile_mm(0.9f);
  g.wavelength_nm = 0;  // no evanescent draws
  const tile_sheet sheet(g);
  pcg32 rng(2, 2);
  int three = 0;
  for (int i = 0; i < 5000; ++i) {
    const prism_path p = sheet.paths()(test::unit_direction(10, 40), rng);
    EXPECT_NE(p.fate, prism_fate::transmitted);
    if (p.fate == prism_fate::retroreflected && p.face_reflections == 3 && p.front_reflections == 0) {
      EXPECT_NEAR(p.weight, 0.729, 1e-6);
      ++three;
    }
  }
  EXPECT_GT(three, 2000);
}

// The model reads its tile from a glTF file beside the scene (metres), or the shipped one.
TEST(TileSheet, ReadsItsTileFromGltf) {
  const test::temp_dir dir;
  triangle_mesh m = make_corner_cube_tile(0.2);
  save_gltf_mesh(m, dir.file("tile.gltf"));
  retro_model_params p{.type = "tile_sheet", .values = {}};
  set_model_value(p, "tile", std::string("tile.gltf"));
  set_model_value(p, "period_x_mm", 2 * 0.2 / std::sqrt(3.0));
  set_model_value(p, "period_y_mm", 0.4);
  const auto model = make_retro_model(p, {.base_dir = dir.path.string()});
  const auto& tile = dynamic_cast<const tile_sheet_retro&>(*model);
  EXPECT_EQ(tile.structure().faces().size(), 12u);
  EXPECT_NEAR(tile.structure().top_mm() - tile.structure().bottom_mm(), std::sqrt(2.0) * 0.2 / 3, 1e-6);
  const auto shipped = make_retro_model({.type = "tile_sheet", .values = {}});
  EXPECT_EQ(dynamic_cast<const tile_sheet_retro&>(*shipped).structure().faces().size(), 12u);
  std::printf("tile's Embree memory: %zu bytes\n", tile.structure().memory_bytes());
}

// Tiles that cannot be traced are refused, naming the model's field and the file.
TEST(TileSheet, BadTilesAreRefusedNamingTheFile) {
  const test::temp_dir dir;
  auto error_of = [&](const std::function<void(retro_model_params&)>& edit) {
    retro_model_params p{.type = "tile_sheet", .values = {}};
    edit(p);
    try {
      make_retro_model(p, {.base_dir = dir.path.string()});
    } catch (const input_error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  const std::string missing =
      error_of([](retro_model_params& p) { set_model_value(p, "tile", std::string("none.gltf")); });
  EXPECT_NE(missing.find("retroreflectors[0].model.tile"), std::string::npos) << missing;
  EXPECT_NE(missing.find("none.gltf"), std::string::npos) << missing;
  // The shipped tile with a period too small for it: it reaches past the next cells.
  const std::string small = error_of([](retro_model_params& p) { set_model_value(p, "period_x_mm", 0.03); });
  EXPECT_NE(small.find("corner_cube_tile.gltf"), std::string::npos) << small;
  EXPECT_NE(small.find("more than a period"), std::string::npos) << small;
  triangle_mesh flat = make_unit_panel();
  for (glm::vec3& v : flat.positions) v = (v + glm::vec3(0.5f, 0.5f, 0)) * 1e-4f;
  save_gltf_mesh(flat, dir.file("flat.gltf"));
  const std::string flat_error =
      error_of([](retro_model_params& p) { set_model_value(p, "tile", std::string("flat.gltf")); });
  EXPECT_NE(flat_error.find("flat.gltf: the tile is flat"), std::string::npos) << flat_error;
  tile_sheet_geometry g = cube_tile_geometry();
  triangle_mesh bad = *g.tile;
  bad.positions[2].y = std::nanf("");
  g.tile = std::make_shared<const triangle_mesh>(bad);
  EXPECT_THROW(tile_structure{g}, input_error);
}
