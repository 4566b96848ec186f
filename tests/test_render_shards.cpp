// A render split into shards (airr render --shard i/N) and merged (airr merge) is the render of one
// process, bit for bit, components and metadata included; merge refuses a missing shard, a shard
// of another render and a shard given twice, each with one line naming the file, and writes
// nothing then.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <string>
#include <vector>

#include "airr/core/assets.hpp"
#include "airr/formats/image.hpp"
#include "airr/render/tracer.hpp"
#include "test_helpers.hpp"

using namespace airr;

namespace {

// The default scene, small, at 8 spp.
std::string render_args(const std::string& out, const std::string& more = "") {
  return "render " + default_scene_path() + " -o " + out +
         " --spp 8 --set observer.width=80 --set observer.height=61 " + more;
}

std::string bytes_of(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), {}};
}

void expect_same_pixels(const image_rgb& a, const image_rgb& b, const std::string& what) {
  EXPECT_EQ(a.width, b.width) << what;
  EXPECT_EQ(a.height, b.height) << what;
  EXPECT_TRUE(a.rgb == b.rgb) << what;
}

}  // namespace

TEST(RenderShards, MergedShardsAreTheRenderOfOneProcess) {
  test::temp_dir dir;
  ASSERT_EQ(test::run_cli(render_args(dir.file("whole.exr"), "--components")).exit_code, 0);
  // An odd split of an odd height: shards of 20, 20 and 21 rows.
  std::string shards;
  for (const char* i : {"2", "0", "1"}) {
    const std::string shard = dir.file(std::string("shard") + i + ".exr");
    const test::command_result r = test::run_cli(render_args(shard, "--components --shard " + std::string(i) + "/3"));
    ASSERT_EQ(r.exit_code, 0) << r.out;
    shards += " " + shard;
  }
  const test::command_result merged = test::run_cli("merge" + shards + " -o " + dir.file("merged.exr"));
  ASSERT_EQ(merged.exit_code, 0) << merged.out;
  expect_same_pixels(load_image(dir.file("whole.exr")).pixels, load_image(dir.file("merged.exr")).pixels, "image");
  const auto layers = read_image_layer_names(dir.file("whole.exr"));
  ASSERT_EQ(layers.size(), std::size_t(component_count));
  EXPECT_EQ(read_image_layer_names(dir.file("merged.exr")), layers);
  for (const std::string& name : layers)
    expect_same_pixels(load_image_layer(dir.file("whole.exr"), name), load_image_layer(dir.file("merged.exr"), name),
                       name);
  EXPECT_EQ(read_image_metadata(dir.file("whole.exr")), read_image_metadata(dir.file("merged.exr")));
  // A shard alone is not the whole: its rows are those of the whole, the others absent.
  EXPECT_EQ(load_image(dir.file("shard1.exr")).pixels.height, 20);

  // PNG: the same file, byte for byte.
  ASSERT_EQ(test::run_cli(render_args(dir.file("whole.png"))).exit_code, 0);
  for (const char* i : {"0", "1"})
    ASSERT_EQ(test::run_cli(render_args(dir.file(std::string("p") + i + ".exr"), "--shard " + std::string(i) + "/2"))
                  .exit_code,
              0);
  ASSERT_EQ(test::run_cli("merge " + dir.file("p1.exr") + " " + dir.file("p0.exr") + " -o " + dir.file("merged.png"))
                .exit_code,
            0);
  EXPECT_EQ(bytes_of(dir.file("whole.png")), bytes_of(dir.file("merged.png")));
}

TEST(RenderShards, MergeRefusesMissingForeignAndRepeatedShards) {
  test::temp_dir dir;
  const std::string a0 = dir.file("a0.exr"), a1 = dir.file("a1.exr"), a2 = dir.file("a2.exr");
  const std::string seeded = dir.file("seed5.exr"), other = dir.file("tilted.exr"), out = dir.file("out.exr");
  ASSERT_EQ(test::run_cli(render_args(a0, "--shard 0/3")).exit_code, 0);
  ASSERT_EQ(test::run_cli(render_args(a1, "--shard 1/3")).exit_code, 0);
  ASSERT_EQ(test::run_cli(render_args(a2, "--shard 2/3")).exit_code, 0);
  ASSERT_EQ(test::run_cli(render_args(seeded, "--shard 1/3 --seed 5")).exit_code, 0);
  ASSERT_EQ(test::run_cli(render_args(other, "--shard 1/3 --set retroreflectors.0.pose.pitch_deg=10")).exit_code, 0);
  ASSERT_EQ(test::run_cli(render_args(dir.file("whole.exr"))).exit_code, 0);

  test::expect_one_line_error(test::run_cli("merge " + a0 + " " + a2 + " -o " + out),
                              {"shard 1/3 is missing", "a0.exr", "a2.exr"});
  test::expect_one_line_error(test::run_cli("merge " + a0 + " " + other + " " + a2 + " -o " + out),
                              {"tilted.exr", "another scene"});
  test::expect_one_line_error(test::run_cli("merge " + a0 + " " + seeded + " " + a2 + " -o " + out),
                              {"seed5.exr", "another seed"});
  test::expect_one_line_error(test::run_cli("merge " + a0 + " " + a1 + " " + a1 + " " + a2 + " -o " + out),
                              {"a1.exr", "shard 1/3 again"});
  test::expect_one_line_error(test::run_cli("merge " + a0 + " " + dir.file("whole.exr") + " -o " + out),
                              {"whole.exr", "not a render shard"});
  test::expect_one_line_error(test::run_cli(render_args(dir.file("x.exr"), "--shard 3/3")), {"--shard", "3/3"});
  test::expect_one_line_error(test::run_cli(render_args(dir.file("x.exr"), "--shard 0/62")),
                              {"--shard", "62 shards", "61 rows"});
  EXPECT_FALSE(std::filesystem::exists(out));
}

// Hand-made bad shards (a good shard's header or pixels changed and written again): each is one line
// naming the file and the key, and nothing is written.
TEST(RenderShards, BadShardsNameTheFileAndTheKey) {
  test::temp_dir dir;
  const std::string s0 = dir.file("s0.exr"), s1 = dir.file("s1.exr"), s2 = dir.file("s2.exr");
  const std::string bad = dir.file("bad.exr"), out = dir.file("out.exr");
  for (const std::string i : {"0", "1", "2"})
    ASSERT_EQ(test::run_cli(render_args(dir.file("s" + i + ".exr"), "--components --shard " + i + "/3")).exit_code, 0);
  const image_rgb pixels = load_image(s0, image_encoding::linear).pixels;
  const image_metadata meta = read_image_metadata(s0);
  const auto layers = load_image_layers(s0);
  ASSERT_EQ(pixels.height, 20);
  const auto write_bad = [&](const image_metadata& m, const image_rgb& img, const image_rgb* layer) {
    std::vector<image_layer> written;
    for (const auto& [name, l] : layers) written.push_back({name, layer ? layer : &l});
    write_image(bad, img, m, 1.0f, written);
  };
  const auto merge_bad = [&] { return test::run_cli("merge " + bad + " " + s1 + " " + s2 + " -o " + out); };
  write_bad(meta, pixels, nullptr);
  ASSERT_EQ(merge_bad().exit_code, 0);  // written again unchanged, it merges
  std::filesystem::remove(out);

  const std::vector<std::pair<std::function<void(image_metadata&)>, std::string>> cases = {
      {[](image_metadata& m) { m.erase("airr:rows"); }, "not a render shard (no airr:rows"},
      {[](image_metadata& m) { m.erase("airr:height"); }, "not a render shard (no airr:height"},
      {[](image_metadata& m) { m["airr:shard"] = "3/2"; }, "airr:shard: '3/2' is not a shard i/N"},
      {[](image_metadata& m) { m["airr:shard"] = "-1/3"; }, "airr:shard: '-1/3' is not a shard i/N"},
      {[](image_metadata& m) { m["airr:shard"] = "0/99999999999"; }, "airr:shard: '0/99999999999' is not a shard"},
      {[](image_metadata& m) { m["airr:shard"] = "0/100"; }, "airr:shard: 100 shards of an image 61 rows high"},
      {[](image_metadata& m) { m["airr:height"] = "sixty"; }, "airr:height: 'sixty' is not an image height"},
      {[](image_metadata& m) { m["airr:height"] = "-61"; }, "airr:height: '-61' is not an image height"},
      {[](image_metadata& m) { m["airr:height"] = "4294967357"; }, "airr:height: '4294967357' is not an image"},
      {[](image_metadata& m) { m["airr:height"] = "100000"; }, "airr:height: '100000' is not an image height of 1"},
      {[](image_metadata& m) { m["airr:height"] = "70"; }, "airr:rows: '0 20' are not shard 0/3's rows of 70"},
      {[](image_metadata& m) { m["airr:rows"] = "0 2000000000"; }, "airr:rows: '0 2000000000' are not shard 0/3"},
  };
  for (const auto& [mutate, message] : cases) {
    image_metadata m = meta;
    mutate(m);
    write_bad(m, pixels, nullptr);
    test::expect_one_line_error(merge_bad(), {"bad.exr: " + message});
    EXPECT_FALSE(std::filesystem::exists(out)) << message;
  }
  // Of another render (named by the shard merged against it).
  for (const auto& [key, message] : {std::pair{"airr:version", "written by another build (airr:version differs)"},
                                     std::pair{"airr:spp", "another number of samples (airr:spp differs)"}}) {
    image_metadata m = meta;
    m[key] = "9";
    write_bad(m, pixels, nullptr);
    test::expect_one_line_error(merge_bad(), {"bad.exr is a shard of: " + std::string(message)});
  }
  // Pixels that are not the header's: fewer rows, a width beyond the render's limit.
  write_image(bad, image_rows(pixels, 0, 19), meta);
  test::expect_one_line_error(merge_bad(), {"bad.exr: holds 19 rows, not its shard's 20"});
  image_rgb wide;
  wide.width = 8193, wide.height = 20;
  wide.rgb.assign(std::size_t(3) * wide.width * wide.height, 0.5f);
  write_image(bad, wide, meta);
  test::expect_one_line_error(merge_bad(), {"bad.exr: the render, 8193 x 61, is beyond the render's limits"});
  // Truncated, and not an image at all.
  const std::string good = bytes_of(s0);
  std::ofstream(bad, std::ios::binary | std::ios::trunc) << good.substr(0, good.size() / 2);
  test::expect_one_line_error(merge_bad(), {"bad.exr"});
  std::ofstream(bad, std::ios::binary | std::ios::trunc) << "not an image";
  test::expect_one_line_error(merge_bad(), {"bad.exr"});
  EXPECT_FALSE(std::filesystem::exists(out));
}
