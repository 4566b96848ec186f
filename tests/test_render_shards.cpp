// A render split into shards (airr render --shard i/N) and merged (airr merge) is the render of one
// process, bit for bit, components and metadata included; merge refuses a missing shard, a shard
// of another render and a shard given twice, each with one line naming the file, and writes
// nothing then.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "airr/core/assets.hpp"
#include "airr/formats/image.hpp"
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
  ASSERT_EQ(layers.size(), 4u);
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
