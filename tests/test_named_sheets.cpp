// Named sheets (docs/models.md): a scene's sheet takes the model of a shipped sheet that stands for
// a real one, by --set retroreflectors.N.sheet=NAME (or a sheet file's path), so a designer starts
// from a geometry like the ones on the bench, not the generic defaults.
#include <string>

#include <gtest/gtest.h>

#include "airr/core/assets.hpp"
#include "airr/formats/scene_json.hpp"
#include "airr/formats/sheet_json.hpp"
#include "airr/layout/psf.hpp"
#include "airr/layout/sheet_models.hpp"
#include "test_helpers.hpp"

using namespace airr;

TEST(NamedSheets, SetGivesASheetTheNamedModelAndLaterValuesGoOnTop) {
  const sheet_description rf_ay = load_sheet(asset_dir() + "/sheets/prism-rf-ay-like.json");
  const scene named = load_scene(default_scene_path(), {parse_override("retroreflectors.0.sheet=prism-rf-ay-like")});
  EXPECT_EQ(named.sheet().model, rf_ay.model);
  const scene tweaked = load_scene(default_scene_path(), {parse_override("retroreflectors.0.model.pitch_mm=0.5"),
                                                          parse_override("retroreflectors.0.sheet=prism-rf-ay-like")});
  EXPECT_EQ(tweaked.sheet().model.type, "prism_sheet");
  EXPECT_EQ(std::get<double>(tweaked.sheet().model.values.at("pitch_mm")), 0.5);

  // By path: a sheet saved elsewhere.
  test::temp_dir dir;
  save_sheet(rf_ay, dir.file("mine.json"));
  const scene by_path =
      load_scene(default_scene_path(), {parse_override("retroreflectors.0.sheet=" + dir.file("mine.json"))});
  EXPECT_EQ(by_path.sheet().model, rf_ay.model);
}

// The RF-Ay-like geometry blurs as a sheet on the bench does; the generic prism sheet, picked by
// its type alone, blurs several times more.
TEST(NamedSheets, TheNamedGeometryIsSharperThanTheGenericDefaults) {
  const scene generic = load_scene(default_scene_path(), {parse_override("retroreflectors.0.model.type=prism_sheet")});
  const scene named = load_scene(default_scene_path(), {parse_override("retroreflectors.0.sheet=prism-rf-ay-like")});
  const psf_params p{.samples = 100000};
  const double r50_generic = energy_radius(sample_psf(generic, make_sheet_models(generic), p), 0.5);
  const double r50_named = energy_radius(sample_psf(named, make_sheet_models(named), p), 0.5);
  std::printf("r50 on the default scene: generic prism sheet %.3f mm, RF-Ay-like %.3f mm\n", r50_generic, r50_named);
  EXPECT_LT(r50_named, 0.5 * r50_generic);
}

TEST(NamedSheets, AnUnknownNameOrSheetIsOneLineNamingTheKey) {
  const std::string unknown =
      test::error_of([] { load_scene(default_scene_path(), {parse_override("retroreflectors.0.sheet=rf-zz")}); });
  EXPECT_NE(unknown.find("--set retroreflectors.0.sheet: no shipped sheet 'rf-zz' (bead-sheet, prism-rf-an-like, "
                         "prism-rf-ay-like, tile-corner-cubes; or a sheet file's path, *.json)"),
            std::string::npos)
      << unknown;
  const std::string missing =
      test::error_of([] { load_scene(default_scene_path(), {parse_override("retroreflectors.2.sheet=bead-sheet")}); });
  EXPECT_NE(missing.find("--set retroreflectors.2.sheet: no sheet '2' (1 present, numbered from 0)"), std::string::npos)
      << missing;
  const std::string no_file = test::error_of(
      [] { load_scene(default_scene_path(), {parse_override("retroreflectors.0.sheet=/nowhere/sheet.json")}); });
  EXPECT_NE(no_file.find("--set retroreflectors.0.sheet: /nowhere/sheet.json"), std::string::npos) << no_file;
  for (const std::string& e : {unknown, missing, no_file}) EXPECT_EQ(e.find('\n'), std::string::npos) << e;
}
