// A layout in one glTF file carries its display's image (issue 30): the exporter embeds it as the
// display mesh's base-colour texture, the reader falls back to it when the named file is missing,
// and a prop's base-colour texture counts for its albedo by its mean.
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "airr/core/assets.hpp"
#include "airr/core/files.hpp"
#include "airr/formats/gltf_layout.hpp"
#include "airr/formats/image.hpp"
#include "airr/formats/mesh_gltf.hpp"
#include "airr/formats/prop_mesh.hpp"
#include "airr/formats/scene_json.hpp"
#include "glb_file.hpp"
#include "gltf_builder.hpp"
#include "test_helpers.hpp"

namespace airr {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

// Points the cache of extracted images at a folder of the test's own, for the test's lifetime.
struct cache_in {
  std::string saved;
  bool had = false;
  explicit cache_in(const std::string& dir) {
    if (const char* v = std::getenv("XDG_CACHE_HOME")) had = true, saved = v;
    setenv("XDG_CACHE_HOME", dir.c_str(), 1);
  }
  ~cache_in() { had ? (void)setenv("XDG_CACHE_HOME", saved.c_str(), 1) : (void)unsetenv("XDG_CACHE_HOME"); }
  std::string embedded() const { return std::string(std::getenv("XDG_CACHE_HOME")) + "/airr-studio/embedded"; }
};

std::string bytes_of(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// The shipped kiosk at 64 x 64; its emission profile (not embedded) by absolute path, so that a
// copy of its GLB elsewhere lacks only the image.
scene kiosk() {
  scene s = load_scene(asset_dir() + "/scenes/two_sheet_kiosk.json");
  s.source.emission_profile = resolve_scene_path(s, s.source.emission_profile);
  s.observer.width = s.observer.height = 64;
  return s;
}

// Exports the kiosk and copies the GLB alone into an empty folder two levels deeper (so that the
// image's relative path in extras points nowhere); the copy's path.
std::string kiosk_copied_alone(const test::temp_dir& dir) {
  fs::create_directories(dir.path / "alone" / "here");
  export_gltf_layout(kiosk(), dir.file("kiosk.glb"));
  fs::copy_file(dir.file("kiosk.glb"), dir.file("alone/here/kiosk.glb"));
  return dir.file("alone/here/kiosk.glb");
}

bool has_note(const std::vector<std::string>& notes, const std::string& text) {
  for (const auto& n : notes) {
    if (n.find(text) != std::string::npos) return true;
  }
  return false;
}

double max_difference(const render_snapshot& a, const render_snapshot& b) {
  double d = 0;
  for (std::size_t i = 0; i < a.rgb->size(); ++i) d = std::max(d, double(std::abs((*a.rgb)[i] - (*b.rgb)[i])));
  return d;
}

double mean_of(const render_snapshot& a) {
  double sum = 0;
  for (const float v : *a.rgb) sum += v;
  return sum / double(a.rgb->size());
}

TEST(SelfContained, KioskGlbEmbedsTheChartsOwnBytesAsTheDisplaysTexture) {
  test::temp_dir dir;
  export_gltf_layout(kiosk(), dir.file("kiosk.glb"));
  const test::glb_file glb(dir.file("kiosk.glb"));
  ASSERT_EQ(glb.doc["images"].size(), 1u);
  EXPECT_EQ(glb.doc["images"][0]["mimeType"], "image/png");
  EXPECT_TRUE(glb.image(0) == bytes_of(asset_dir() + "/charts/test_chart.png"));
  // The display's mesh: the textured emitting area and the bezel's frame, a primitive each.
  const json& display = glb.doc["nodes"][0];
  EXPECT_EQ(display["extras"]["airr"]["role"], "display");
  const json& prims = glb.doc["meshes"][display["mesh"].get<std::size_t>()]["primitives"];
  ASSERT_EQ(prims.size(), 2u);
  const json& mat = glb.doc["materials"][prims[0]["material"].get<std::size_t>()];
  EXPECT_EQ(mat["pbrMetallicRoughness"]["baseColorTexture"]["index"], 0);
  EXPECT_TRUE(prims[0]["attributes"].contains("TEXCOORD_0"));
  EXPECT_FALSE(prims[1]["attributes"].contains("TEXCOORD_0"));
  // The extras still name the file, relative to the GLB.
  EXPECT_EQ(fs::path(glb.doc["nodes"][0]["extras"]["airr"]["image"].get<std::string>()).filename(), "test_chart.png");

  // A .gltf holds it as a data URI; a uniform display has no texture.
  export_gltf_layout(kiosk(), dir.file("kiosk.gltf"));
  const json text = json::parse(bytes_of(dir.file("kiosk.gltf")));
  EXPECT_EQ(text["images"][0]["uri"].get<std::string>().rfind("data:image/png;base64,", 0), 0u);
  scene uniform = kiosk();
  uniform.source.image.clear();
  export_gltf_layout(uniform, dir.file("uniform.glb"));
  EXPECT_FALSE(test::glb_file(dir.file("uniform.glb")).doc.contains("images"));
}

TEST(SelfContained, KioskGlbCopiedAloneRendersLikeTheSceneAndNotWithoutItsTexture) {
  test::temp_dir dir;
  const cache_in cache(dir.file("cache"));
  const std::string alone = kiosk_copied_alone(dir);
  std::vector<std::string> notes;
  const scene back = load_scene(alone, {}, notes);
  EXPECT_TRUE(has_note(notes, "display image: the file's embedded texture ("));
  EXPECT_TRUE(has_note(notes, "test_chart.png not found next to the layout)"));
  EXPECT_EQ(fs::path(back.source.image).parent_path(), fs::path(cache.embedded()));
  EXPECT_TRUE(bytes_of(back.source.image) == bytes_of(asset_dir() + "/charts/test_chart.png"));
  EXPECT_NEAR(back.source.width_mm, 60, 1e-5);  // the emitting area, the bezel outside it
  EXPECT_EQ(back.source.bezel_mm, 6);

  const scene original = kiosk();
  const render_snapshot want = test::render_to(original, 4);
  const render_snapshot got = test::render_to(back, 4);
  ASSERT_EQ(got.rgb->size(), want.rgb->size());
  EXPECT_GT(mean_of(want), 1e-3);
  EXPECT_LE(max_difference(got, want), 1e-4 * std::max(1.0, mean_of(want)));

  // Without the texture (and with the missing file's name) it is an error naming the file...
  test::glb_file bare(alone);
  for (const char* key : {"images", "textures", "samplers"}) bare.doc.erase(key);
  for (auto& m : bare.doc["materials"]) {
    m.erase("emissiveTexture");
    m["pbrMetallicRoughness"].erase("baseColorTexture");
  }
  for (auto& mesh : bare.doc["meshes"]) {
    for (auto& p : mesh["primitives"]) p["attributes"].erase("TEXCOORD_0");
  }
  bare.write(dir.file("alone/here/bare.glb"));
  EXPECT_NE(test::error_of([&] { load_scene(dir.file("alone/here/bare.glb")); }).find("test_chart.png"),
            std::string::npos);
  // ... and without the name too, a uniform display: another image.
  bare.doc["nodes"][0]["extras"]["airr"]["image"] = "";
  bare.write(dir.file("alone/here/bare.glb"));
  const render_snapshot plain = test::render_to(load_scene(dir.file("alone/here/bare.glb")), 4);
  EXPECT_GT(max_difference(plain, want), 0.1 * mean_of(want));
}

TEST(SelfContained, NamedImageBesideTheLayoutWinsOverTheTexture) {
  test::temp_dir dir;
  const cache_in cache(dir.file("cache"));
  export_gltf_layout(kiosk(), dir.file("kiosk.glb"));
  std::vector<std::string> notes;
  const scene back = load_scene(dir.file("kiosk.glb"), {}, notes);
  EXPECT_EQ(fs::path(back.source.image).filename(), "test_chart.png");
  EXPECT_EQ(fs::canonical(resolve_scene_path(back, back.source.image)),
            fs::canonical(asset_dir() + "/charts/test_chart.png"));
  EXPECT_TRUE(has_note(notes, "which the display's extras name (its mesh's texture is not used)"));
}

TEST(SelfContained, WideImagesAreEmbeddedAsSixteenBitPng) {
  test::temp_dir dir;
  const cache_in cache(dir.file("cache"));
  image_rgb img{3, 2, {}};
  for (int i = 0; i < 18; ++i) img.rgb.push_back(float(i) / 17.0f * 0.9f + 0.01f);
  write_image(dir.file("chart.exr"), img, {});
  scene s = kiosk();
  s.source.image = dir.file("chart.exr");
  fs::create_directories(dir.path / "a" / "b");
  export_gltf_layout(s, dir.file("a/b/layout.glb"));
  const std::string png = test::glb_file(dir.file("a/b/layout.glb")).image(0);
  ASSERT_GT(png.size(), 25u);
  EXPECT_EQ(png.substr(1, 3), "PNG");
  EXPECT_EQ(int(static_cast<unsigned char>(png[24])), 16);  // IHDR bit depth
  fs::remove(dir.file("chart.exr"));
  const scene back = load_scene(dir.file("a/b/layout.glb"));
  const image_rgb got = load_image(back.source.image).pixels;
  ASSERT_EQ(got.rgb.size(), img.rgb.size());
  for (std::size_t i = 0; i < img.rgb.size(); ++i) EXPECT_NEAR(got.rgb[i], img.rgb[i], 1.0 / 65535) << i;
}

// The sRGB curve as IEC 61966-2-1 defines it.
double srgb_to_linear(int code) {
  const double c = code / 255.0;
  return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}

// A prop of two triangles whose material has `factor` and the base-colour texture `png` (bytes).
void write_textured_prop(const std::string& path, const std::string& png, test::gltf_builder::storage how) {
  test::gltf_builder b;
  const int pos = b.add_positions({0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0});
  const int idx = b.add_indices({0, 1, 2, 0, 2, 3}, 5125);
  const int mat = b.add_material("painted", {0.5, 1.0, 0.8, 1}, 0, 1);
  b.doc["materials"][mat]["pbrMetallicRoughness"]["baseColorTexture"] = {{"index", 0}};
  const int plain = b.add_material("plain", {0.3, 0.2, 0.1, 1}, 0, 1);
  if (how == test::gltf_builder::storage::glb) {
    b.doc["images"] = {{{"bufferView", b.add_view(png.data(), png.size())}, {"mimeType", "image/png"}}};
  } else {
    b.doc["images"] = {
        {{"uri", "data:image/png;base64," + b.base64(std::vector<unsigned char>(png.begin(), png.end()))}}};
  }
  b.doc["textures"] = {{{"source", 0}}};
  const int mesh = b.add_mesh({{pos, idx, mat}, {pos, idx, plain}});
  b.add_node({{"name", "box"}, {"mesh", mesh}});
  b.write(path, how);
}

TEST(SelfContained, PropAlbedoIsTheBaseColourFactorTimesTheTexturesMean) {
  test::temp_dir dir;
  const cache_in cache(dir.file("cache"));
  // Two texels of known 8-bit sRGB codes: (255, 0, 128) and (0, 64, 128).
  image_rgb tex{2, 1, {}};
  for (int code : {255, 0, 128, 0, 64, 128}) tex.rgb.push_back(float(srgb_to_linear(code)));
  write_image(dir.file("tex.png"), tex, {});
  const std::string png = bytes_of(dir.file("tex.png"));
  const glm::dvec3 mean((srgb_to_linear(255) + srgb_to_linear(0)) / 2, (srgb_to_linear(0) + srgb_to_linear(64)) / 2,
                        srgb_to_linear(128));
  const glm::dvec3 want = glm::dvec3(0.5, 1.0, 0.8) * mean;
  for (const auto how : {test::gltf_builder::storage::glb, test::gltf_builder::storage::data_uri}) {
    const std::string path = dir.file(how == test::gltf_builder::storage::glb ? "prop.glb" : "prop.gltf");
    write_textured_prop(path, png, how);
    const triangle_mesh mesh = load_prop_mesh(path, "");
    prop_params p;
    p.surface = prop_surface::material;
    const surface_response painted = prop_surface_of(p, mesh, 0), plain = prop_surface_of(p, mesh, 2);
    EXPECT_EQ(painted.kind, prop_surface::diffuse);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(painted.reflectance[c], want[c], 1e-5) << path << " channel " << c;
    EXPECT_NEAR(plain.reflectance.x, 0.3, 1e-6);  // no texture: the factor alone
  }
}

TEST(SelfContained, CorruptEmbeddedImageIsAnErrorNamingTheFileAndTheNode) {
  test::temp_dir dir;
  const cache_in cache(dir.file("cache"));
  const std::string alone = kiosk_copied_alone(dir);
  test::glb_file glb(alone);
  const json& view = glb.doc["bufferViews"][glb.doc["images"][0]["bufferView"].get<std::size_t>()];
  const std::size_t start = view["byteOffset"].get<std::size_t>() + 40, length = view["byteLength"].get<std::size_t>();
  for (std::size_t i = start; i < start + length - 60; ++i) glb.bin[i] = char(i * 7);  // the PNG's signature kept
  glb.write(alone);
  const std::string error = test::error_of([&] { load_scene(alone); });
  EXPECT_NE(error.find(alone + ": node 'Display' (#0): base-colour texture 0: image 0: "), std::string::npos) << error;
  EXPECT_EQ(error.find(cache.embedded()), std::string::npos) << error;  // the cache's copy is not named...
  EXPECT_TRUE(fs::is_empty(cache.embedded()));                          // ... and not kept

  // Not an image at all.
  std::fill(glb.bin.begin() + std::ptrdiff_t(start - 40), glb.bin.begin() + std::ptrdiff_t(start), 'x');
  glb.write(alone);
  EXPECT_NE(test::error_of([&] { load_scene(alone); }).find("image 0: the embedded image is neither PNG nor JPEG"),
            std::string::npos);
  // A prop's texture likewise.
  write_textured_prop(dir.file("prop.glb"), "not an image", test::gltf_builder::storage::glb);
  const std::string prop_error = test::error_of([&] { load_prop_mesh(dir.file("prop.glb"), ""); });
  EXPECT_NE(prop_error.find(dir.file("prop.glb") + ": node 'box' (#0): material 0: texture 0: image 0: "),
            std::string::npos)
      << prop_error;
}

}  // namespace
}  // namespace airr
