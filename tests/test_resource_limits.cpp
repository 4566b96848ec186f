// Files that declare absurd sizes, and absurd physical sizes and distances, as a new user would
// meet them with mutated files: the command line refuses each with one line naming the file and
// the limit, before allocating for it (the command runs with its address space capped at 4 GB),
// and no library's own message leaks around that line.
#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <functional>

#include "airr/core/assets.hpp"
#include "airr/core/files.hpp"
#include "airr/core/json_reader.hpp"
#include "airr/formats/scene_json.hpp"
#include "airr/measure/viewing_zone_full.hpp"
#include "airr/models/shift_table.hpp"
#include "gltf_builder.hpp"
#include "test_helpers.hpp"

using namespace airr;

namespace {

constexpr const char* memory_cap = test::address_space_reserved ? "" : "ulimit -v 4000000; ";

test::command_result run_capped(const std::string& args) {
  return test::run_command(std::string(memory_cap) + AIRR_CLI + " " + args);
}

void expect_refused(const test::command_result& r, const std::vector<std::string>& must_contain) {
  test::expect_one_line_error(r, must_contain);
  EXPECT_EQ(r.out.find("bad_alloc"), std::string::npos) << r.out;
}

using test::scene_file;

std::uint32_t crc32(const std::string& bytes) {
  std::uint32_t c = 0xffffffffu;
  for (unsigned char b : bytes) {
    c ^= b;
    for (int k = 0; k < 8; ++k) c = (c >> 1) ^ (0xedb88320u & (0u - (c & 1u)));
  }
  return ~c;
}

std::string big_endian(std::uint32_t v) { return {char(v >> 24), char(v >> 16), char(v >> 8), char(v)}; }

std::string png_chunk(const std::string& type, const std::string& data) {
  return big_endian(std::uint32_t(data.size())) + type + data + big_endian(crc32(type + data));
}

// A PNG whose header claims `w` x `h` RGB pixels, with a few bytes of (compressed) data.
void write_png_claiming(const std::string& path, std::uint32_t w, std::uint32_t h) {
  const std::string ihdr = big_endian(w) + big_endian(h) + std::string("\x08\x02\x00\x00\x00", 5);
  const std::string idat("\x78\x9c\x63\x60\x00\x00\x00\x02\x00\x01", 10);
  std::ofstream(path, std::ios::binary) << std::string("\x89PNG\r\n\x1a\n", 8) << png_chunk("IHDR", ihdr)
                                        << png_chunk("IDAT", idat) << png_chunk("IEND", "");
}

// A little-endian TIFF whose directory claims `w` x `h` 8-bit grey pixels in one strip.
void write_tiff_claiming(const std::string& path, std::uint32_t w, std::uint32_t h) {
  std::string t("II\x2a\x00\x08\x00\x00\x00", 8);
  const auto u16 = [&](std::uint16_t v) { t += char(v & 0xff), t += char(v >> 8); };
  const auto u32 = [&](std::uint32_t v) { u16(std::uint16_t(v & 0xffff)), u16(std::uint16_t(v >> 16)); };
  const auto entry = [&](std::uint16_t tag, std::uint16_t type, std::uint32_t value) {
    u16(tag), u16(type), u32(1), u32(value);
  };
  u16(8);
  entry(256, 4, w);    // ImageWidth
  entry(257, 4, h);    // ImageLength
  entry(258, 3, 8);    // BitsPerSample
  entry(259, 3, 1);    // Compression: none
  entry(262, 3, 1);    // Photometric: black is zero
  entry(273, 4, 200);  // StripOffsets
  entry(278, 4, h);    // RowsPerStrip
  entry(279, 4, 16);   // StripByteCounts
  u32(0);
  t.resize(216, '\0');
  std::ofstream(path, std::ios::binary) << t;
}

}  // namespace

TEST(ResourceLimits, ImageHeadersClaimingBillionsOfPixelsAreRefusedNamingTheLimit) {
  test::temp_dir dir;
  write_png_claiming(dir.file("huge.png"), 65535, 65535);
  expect_refused(run_capped("mtf " + dir.file("huge.png") + " -o " + dir.file("mtf.csv")),
                 {dir.file("huge.png"), "65535x65535", "limit is 67108864 pixels"});
  write_tiff_claiming(dir.file("huge.tif"), 1000000000, 1000000000);
  expect_refused(run_capped("mtf " + dir.file("huge.tif") + " -o " + dir.file("mtf.csv")),
                 {dir.file("huge.tif"), "image too large", "limit is 67108864 pixels"});
}

TEST(ResourceLimits, RenderOfHundredThousandPixelsSquareIsRefused) {
  test::temp_dir dir;
  const auto path = scene_file(dir, [](nlohmann::json& j) {
    j["observer"]["width"] = 100000;
    j["observer"]["height"] = 100000;
  });
  expect_refused(run_capped("render " + path + " -o " + dir.file("o.exr")), {path, "observer.width", "[1, 8192]"});
}

TEST(ResourceLimits, GltfAccessorOfTwoToTheFortyElementsIsRefused) {
  test::temp_dir dir;
  test::gltf_builder b;
  const int positions = b.add_positions({0, 0, 0, 0.1f, 0, 0, 0, 0.1f, 0});
  b.doc["accessors"][std::size_t(positions)]["count"] = std::uint64_t(1) << 40;
  const int mesh = b.add_mesh({{positions, -1, -1}});
  b.add_node({{"name", "huge"}, {"mesh", mesh}});
  b.write(dir.file("huge.gltf"), test::gltf_builder::storage::data_uri);
  const auto path = scene_file(dir, [&](nlohmann::json& j) {
    j["props"] = {{{"name", "huge"}, {"mesh", dir.file("huge.gltf")}}};
  });
  expect_refused(run_capped("render " + path + " -o " + dir.file("o.exr")),
                 {path, "huge.gltf", "accessor", "1099511627776"});
}

TEST(ResourceLimits, ShiftTableOfTenToTheTwelveBinsIsRefused) {
  test::temp_dir dir;
  nlohmann::json table = read_json_file(default_shift_table_path());
  table["bins"] = std::int64_t(1000000) * 1000000;
  std::ofstream(dir.file("table.json")) << table.dump();
  const auto path = scene_file(dir, [&](nlohmann::json& j) {
    j["retroreflectors"][0]["model"] = {
        {"type", "sinc_shift"}, {"preset", "rf-ay"}, {"shift_table", dir.file("table.json")}};
  });
  expect_refused(run_capped("render " + path + " -o " + dir.file("o.exr")),
                 {dir.file("table.json"), "bins", "1000000"});
}

TEST(ResourceLimits, JsonNestedAHundredThousandDeepIsRefusedNamingTheLimit) {
  test::temp_dir dir;
  const std::string deep = std::string(100000, '[') + std::string(100000, ']');
  std::ofstream(dir.file("scene.json")) << "{\"format\": \"airr-scene\", \"version\": 2, \"props\": " << deep << "}";
  expect_refused(run_capped("render " + dir.file("scene.json") + " -o " + dir.file("o.exr")),
                 {dir.file("scene.json"), "nested deeper than 64 levels"});
  // The same in a glTF file (its JSON is parsed by tinygltf, after the depth is checked).
  std::ofstream(dir.file("deep.gltf")) << "{\"asset\": {\"version\": \"2.0\"}, \"extras\": " << deep << "}";
  const auto path = scene_file(dir, [&](nlohmann::json& j) {
    j["props"] = {{{"name", "deep"}, {"mesh", dir.file("deep.gltf")}}};
  });
  expect_refused(run_capped("render " + path + " -o " + dir.file("o.exr")),
                 {dir.file("deep.gltf"), "nested deeper than 64 levels"});
}

TEST(ResourceLimits, AbsurdDistancesAndSizesAreRefusedWithTheirRange) {
  test::temp_dir dir;
  const std::vector<std::pair<std::function<void(nlohmann::json&)>, std::vector<std::string>>> cases = {
      {[](nlohmann::json& j) { j["observer"]["distance_mm"] = 9.2e18; },
       {"observer.distance_mm", "[1, 100000]", "9.2e+18"}},
      {[](nlohmann::json& j) {
         j["observer"]["placement"] = "look_at";
         j["observer"]["position_mm"] = {0, 0, 9.2e18};
       },
       {"observer.position_mm", "[-100000, 100000]"}},
      {[](nlohmann::json& j) { j["half_mirror"]["width_mm"] = 1e-30; }, {"half_mirror.width_mm", "[0.1, 100000]"}},
      {[](nlohmann::json& j) {
         j["retroreflectors"][0]["pose"]["center_mm"] = {0, 0, -1e30};
       },
       {"retroreflectors[0].pose.center_mm", "[-100000, 100000]", "-1e+30"}},
  };
  for (const auto& [edit, expected] : cases) {
    const auto path = scene_file(dir, edit);
    auto must = expected;
    must.push_back(path);
    expect_refused(run_capped("render " + path + " -o " + dir.file("o.exr")), must);
  }
}

// libpng prints "libpng error: ..." itself; only the project's line may reach the user.
TEST(ResourceLimits, LibraryMessagesDoNotLeakAroundTheErrorLine) {
  test::temp_dir dir;
  const std::string chart = read_text_file(asset_dir() + "/charts/test_chart.png");
  std::ofstream(dir.file("truncated.png"), std::ios::binary) << chart.substr(0, 200);
  std::ofstream(dir.file("garbage.png"), std::ios::binary) << std::string("\x89PNG\r\n\x1a\n", 8) << "garbage!";
  std::string flipped = chart;
  const std::size_t idat = chart.find("IDAT");
  ASSERT_NE(idat, std::string::npos);
  flipped[idat + 20] = char(flipped[idat + 20] ^ 0x5a);  // the image data's checksum fails
  std::ofstream(dir.file("flipped.png"), std::ios::binary) << flipped;
  for (const char* name : {"truncated.png", "garbage.png", "flipped.png"}) {
    const auto r = run_capped("mtf " + dir.file(name) + " -o " + dir.file("mtf.csv"));
    expect_refused(r, {dir.file(name)});
    EXPECT_EQ(r.out.find("libpng"), std::string::npos) << r.out;
  }
}

// The largest render accepted, 8192 x 8192 with components (about 7 GB), under a 4 GB
// address-space limit: refused before it starts with one line naming the need and the limit
// (it used to abort with std::bad_alloc); a small render under the same limit runs.
TEST(ResourceLimits, ARenderBeyondTheProcesssMemoryIsRefusedBeforeItStarts) {
  AIRR_SKIP_WHEN_ADDRESS_SPACE_RESERVED();
  test::temp_dir dir;
  const std::string airr = std::string(AIRR_CLI) + " render " + default_scene_path() + " --spp 1 --components";
  const auto big = test::run_command("ulimit -v 4000000; " + airr +
                                     " --set observer.width=8192 --set observer.height=8192 -o " + dir.file("big.exr"));
  test::expect_one_line_error(big, {"render: 8192 x 8192 with components needs about", "ulimit -v"});
  EXPECT_EQ(big.exit_code, 1) << big.out;
  EXPECT_FALSE(std::filesystem::exists(dir.file("big.exr")));
  const auto small = test::run_command("ulimit -v 4000000; " + airr +
                                       " --set observer.width=64 --set observer.height=64 -o " + dir.file("small.exr"));
  EXPECT_EQ(small.exit_code, 0) << small.out;
  EXPECT_TRUE(std::filesystem::exists(dir.file("small.exr")));
}

// A sweep whose points at once would not fit is refused before it measures; a small one runs.
TEST(ResourceLimits, ASweepBeyondTheProcesssMemoryIsRefusedBeforeItStarts) {
  AIRR_SKIP_WHEN_ADDRESS_SPACE_RESERVED();
  test::temp_dir dir;
  const std::string sweep = std::string(AIRR_CLI) + " sweep " + default_scene_path() +
                            " --psf --vary tilt=0:10:10 --threads 2 -o " + dir.file("s.csv");
  const auto big = test::run_command("ulimit -v 4000000; " + sweep + " --samples 100000000");
  test::expect_one_line_error(big, {"sweep: 2 points at once of 100000000 PSF samples needs about 13", "ulimit -v"});
  EXPECT_EQ(big.exit_code, 1) << big.out;
  EXPECT_FALSE(std::filesystem::exists(dir.file("s.csv")));
  const auto small = test::run_command("ulimit -v 4000000; " + sweep + " --samples 10000");
  EXPECT_EQ(small.exit_code, 0) << small.out;
  EXPECT_TRUE(std::filesystem::exists(dir.file("s.csv")));
}

// An optimisation or tolerance run whose PSFs at once (one a thread, the spec's psf_samples each)
// would not fit is refused before its first layout, with nothing written; a small one runs.
TEST(ResourceLimits, DesignRunsBeyondTheProcesssMemoryAreRefusedBeforeTheyStart) {
  AIRR_SKIP_WHEN_ADDRESS_SPACE_RESERVED();
  test::temp_dir dir;
  auto spec = [&](std::uint64_t psf_samples) {
    nlohmann::json j = {
        {"format", "airr-design"},
        {"version", 1},
        {"scene", default_scene_path()},
        {"eyes_mm", {{0, 0, 450}, {20, 0, 450}}},
        {"variables", {{{"key", "floating_distance_mm"}, {"min", 100}, {"max", 140}}}},
        {"objectives", {{{"metric", "mean_mtf"}, {"goal", "maximise"}}}},
        {"tolerances", {{{"key", "half_mirror.pose.pitch_deg"}, {"sd", 0.3}}}},
        {"tolerance", {{"samples", 10}, {"seed", 1}}},
        {"search", {{"seed", 1}, {"global_evaluations", 2}, {"local_evaluations", 0}, {"psf_samples", psf_samples}}}};
    const std::string path = dir.file("spec_" + std::to_string(psf_samples) + ".json");
    write_file_atomic(path, j.dump());
    return path;
  };
  const std::string big = spec(100'000'000), small = spec(2000);
  const std::string cap = "ulimit -v 4000000; " + std::string(AIRR_CLI);
  const auto optimise = test::run_command(cap + " optimise " + big + " --threads 2 -o " + dir.file("best.json"));
  test::expect_one_line_error(optimise, {"optimise: 2 PSFs at once of 100000000 samples needs about 13", "ulimit -v"});
  EXPECT_EQ(optimise.exit_code, 1) << optimise.out;
  EXPECT_FALSE(std::filesystem::exists(dir.file("best.json")));
  const auto tolerance = test::run_command(cap + " tolerance " + big + " --threads 2 -o " + dir.file("tol.csv"));
  test::expect_one_line_error(tolerance,
                              {"tolerance: 2 PSFs at once of 100000000 samples needs about 13", "ulimit -v"});
  EXPECT_EQ(tolerance.exit_code, 1) << tolerance.out;
  EXPECT_FALSE(std::filesystem::exists(dir.file("tol.csv")));
  // One thread holds one PSF: half the need.
  const auto one = test::run_command(cap + " tolerance " + big + " --threads 1 -o " + dir.file("tol.csv"));
  test::expect_one_line_error(one, {"tolerance: 1 PSF at once of 100000000 samples needs about 6", "ulimit -v"});
  const auto small_run = test::run_command(cap + " tolerance " + small + " --threads 2 -o " + dir.file("tol.csv"));
  EXPECT_EQ(small_run.exit_code, 0) << small_run.out;
  EXPECT_TRUE(std::filesystem::exists(dir.file("tol.csv")));
  const auto small_search = test::run_command(cap + " optimise " + small + " --threads 2 -o " + dir.file("best.json"));
  EXPECT_EQ(small_search.exit_code, 0) << small_search.out;
  EXPECT_TRUE(std::filesystem::exists(dir.file("best.json")));
}

// A zone pass whose workers' PSFs would not fit in any machine is refused before its first eye.
TEST(ResourceLimits, AZonePassBeyondTheMachinesMemoryIsRefused) {
  const scene s = load_scene(default_scene_path());
  eye_grid g;
  g.nx = g.ny = 2;
  full_zone_params p;
  p.psf_samples = 10'000'000'000ULL;  // 640 GB a worker
  const std::string error = test::error_of([&] { full_viewing_zone(s, g, p); });
  EXPECT_NE(error.find("viewing zone: 4 eyes of 10000000000 PSF samples and a 48 x 48 render each needs about"),
            std::string::npos)
      << error;
  EXPECT_NE(error.find("more ("), std::string::npos) << error;
}

// An image that cannot be created says the system's reason.
TEST(ResourceLimits, AnImageThatCannotBeCreatedSaysWhy) {
  test::temp_dir dir;
  const auto path = scene_file(dir, [](nlohmann::json& j) {
    j["observer"]["width"] = 16;
    j["observer"]["height"] = 16;
  });
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"/dev/full/x.png", "Not a directory"},
      {dir.file("no/such/folder/x.exr"), "No such file or directory"},
  };
  for (const auto& [out, reason] : cases) {
    const auto r = test::run_cli("render " + path + " -o " + out + " --spp 1");
    EXPECT_NE(r.exit_code, 0) << r.out;
    EXPECT_NE(r.out.find("error: " + out + ": cannot write image: " + reason + "\n"), std::string::npos) << r.out;
  }
}

TEST(ResourceLimits, FullDiskWhileWritingARenderLeavesTheOldOne) {
  test::temp_dir dir;
  const auto path = scene_file(dir, [](nlohmann::json& j) {
    j["source"]["image"] = asset_dir() + "/charts/test_chart.png";
    j["observer"]["width"] = 128;
    j["observer"]["height"] = 128;
  });
  const std::string out = dir.file("render.exr");
  ASSERT_EQ(test::run_cli("render " + path + " -o " + out + " --spp 1").exit_code, 0);
  const std::string before = read_text_file(out);
  ASSERT_GT(before.size(), 8192u);
  const auto r = test::run_command("ulimit -f 4; " + std::string(AIRR_CLI) + " render " + path + " -o " + out +
                                   " --spp 2 --seed 9");
  EXPECT_NE(r.exit_code, 0) << r.out;
  EXPECT_EQ(r.out.find("File size limit"), std::string::npos) << "killed by the signal: " << r.out;
  EXPECT_NE(r.out.find("error: " + out + ": write failed: File too large"), std::string::npos) << r.out;
  EXPECT_EQ(read_text_file(out), before);
  // A PNG too: its writer alone would leave the file cut at the limit and report it written.
  const std::string png = dir.file("render.png");
  ASSERT_EQ(test::run_cli("render " + path + " -o " + png + " --spp 1").exit_code, 0);
  const std::string png_before = read_text_file(png);
  const auto r2 = test::run_command("ulimit -f 4; " + std::string(AIRR_CLI) + " render " + path + " -o " + png +
                                    " --spp 2 --seed 9 --set observer.width=512 --set observer.height=512");
  EXPECT_NE(r2.exit_code, 0) << r2.out;
  EXPECT_NE(r2.out.find("error: " + png + ": write failed: File too large"), std::string::npos) << r2.out;
  EXPECT_EQ(read_text_file(png), png_before);
  std::size_t files = 0;
  for ([[maybe_unused]] const auto& e : std::filesystem::directory_iterator(dir.path)) ++files;
  EXPECT_EQ(files, 3u) << "a temporary file was left beside the renders";
}
