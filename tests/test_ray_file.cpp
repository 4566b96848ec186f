// The ray file (docs/ray-file.md): the paths it keeps add up, pixel by pixel, to the layers their
// expression selects; its segments join from the display to the eye; the limit keeps a prefix;
// one pass keeps several expressions' paths as their own passes would; bad input is refused before anything is traced
// or written.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>

#include "airr/core/error.hpp"
#include "airr/layout/layout.hpp"
#include "airr/render/ray_file.hpp"
#include "airr/render/tracer.hpp"
#include "error_of.hpp"
#include "test_helpers.hpp"

using namespace airr;

namespace {

// A small scene whose paths meet every kind of event: the half mirror both ways, the sheet, and a
// mirror prop that shows the display to the observer.
scene scene_with_mirror(const test::temp_dir& dir) {
  scene s = test::display_in_mirror_scene(dir, 24);
  s.observer.fov_deg = 20;
  return s;
}

glm::vec3 end_of(const ray_segment& g) { return g.start + g.length * g.direction; }

}  // namespace

TEST(RayFile, EnergiesSumToTheLayers) {
  test::temp_dir dir;
  const scene s = scene_with_mirror(dir);
  const std::uint64_t spp = 3;
  const std::vector<std::string> expressions = {".*", "D .* S0:retro .* E", "D [^S0:retro]* E", "D P:mirror .* E"};
  // The render's own sums, by layer, without the model image.
  auto layers = std::make_shared<path_layers>();
  for (const auto& e : expressions) layers->layers.push_back({e, path_expression::parse(e).bound(s, true)});
  embree_device device;
  tracer_scene ts;
  ts.use_model_image = false;
  ts.layers = layers;
  build_tracer_scene(ts, device, s);
  const int w = ts.camera.width, h = ts.camera.height;
  std::vector<float> sums(3 * std::size_t(w) * h), layer_sums(3 * layers->count() * std::size_t(w) * h);
  const std::atomic<bool> never{false};
  std::uint64_t rays = 0;
  trace_rows(ts, 0, h, 0, spp, sums, never, rays, nullptr, nullptr, nullptr, &layer_sums);

  for (std::size_t k = 0; k < expressions.size(); ++k) {
    const ray_record r = record_rays(s, {.select = expressions[k], .spp = spp, .threads = 2});
    EXPECT_TRUE(r.complete);
    EXPECT_EQ(r.selected, r.paths.size());
    std::vector<double> from_rays(3 * std::size_t(w) * h);
    for (const ray_path& p : r.paths)
      for (int c = 0; c < 3; ++c) from_rays[3 * (std::size_t(p.y) * w + p.x) + std::size_t(c)] += p.contribution[c];
    double worst = 0, total = 0;
    for (std::size_t i = 0; i < from_rays.size(); ++i) {
      const double layer = layer_sums[3 * layers->count() * (i / 3) + 3 * k + i % 3];
      worst = std::max(worst, std::abs(from_rays[i] - layer));
      total += layer;
    }
    std::printf("%-22s %6zu paths %7zu segments, light %.6g, worst pixel difference %.3g\n", expressions[k].c_str(),
                r.paths.size(), r.segments.size(), total / spp, worst);
    EXPECT_GT(r.paths.size(), 10u) << expressions[k];
    EXPECT_GT(total, 0) << expressions[k];
    EXPECT_LE(worst, 1e-5 * std::max(1.0, double(spp))) << expressions[k];
    if (k == 0) {  // every path: the whole image
      double image_worst = 0;
      for (std::size_t i = 0; i < sums.size(); ++i)
        image_worst = std::max(image_worst, std::abs(sums[i] - from_rays[i]));
      EXPECT_LE(image_worst, 1e-5 * double(spp));
    }
  }
}

TEST(RayFile, SegmentsRunFromTheDisplayToTheEye) {
  test::temp_dir dir;
  const scene s = scene_with_mirror(dir);
  const ray_record r = record_rays(s, {.select = ".*", .spp = 2, .threads = 2});
  const pinhole_camera cam = make_camera(s);
  const part_frame display = source_frame(s);
  int mirror_paths = 0, retro_paths = 0;
  for (const ray_path& p : r.paths) {
    ASSERT_GE(p.segment_count, 1u);
    const ray_segment* g = r.segments.data() + p.first_segment;
    const ray_segment& first = g[0];
    const ray_segment& last = g[p.segment_count - 1];
    EXPECT_EQ(first.event.kind, path_event_kind::display);
    // Leaves the emitting area, towards its front.
    const glm::dvec3 at = glm::dvec3(first.start) - display.center;
    EXPECT_NEAR(glm::dot(at, display.n), 0.0, 1e-3);
    EXPECT_LE(std::abs(glm::dot(at, display.u)), 0.5 * display.width + 1e-3);
    EXPECT_GT(glm::dot(glm::dvec3(first.direction), display.n), 0.0);
    EXPECT_LT(glm::distance(glm::dvec3(end_of(last)), cam.position), 1e-2);
    for (int c = 0; c < 3; ++c) EXPECT_FLOAT_EQ(last.radiance[c], p.contribution[c]);
    for (std::uint32_t j = 1; j < p.segment_count; ++j) {
      EXPECT_NE(g[j].event.kind, path_event_kind::display);
      EXPECT_NEAR(glm::length(g[j].direction), 1.0f, 1e-5f);
      // A sheet shifts the light sideways; anything else joins the segments.
      if (g[j].event.kind != path_event_kind::sheet) {
        EXPECT_LT(glm::distance(end_of(g[j - 1]), g[j].start), 1e-2f) << "path of pixel " << p.x << ", " << p.y;
      }
      if (g[j].event.kind == path_event_kind::prop) ++mirror_paths;
      if (g[j].event.kind == path_event_kind::sheet && g[j].event.taken) ++retro_paths;
    }
  }
  EXPECT_GT(mirror_paths, 0);
  EXPECT_GT(retro_paths, 0);
}

TEST(RayFile, TheLimitKeepsTheFirstPaths) {
  test::temp_dir dir;
  const scene s = scene_with_mirror(dir);
  const ray_record all = record_rays(s, {.select = ".*", .spp = 2, .threads = 2});
  const ray_record some = record_rays(s, {.select = ".*", .segment_limit = 50, .spp = 2, .threads = 2});
  EXPECT_FALSE(some.complete);
  EXPECT_LE(some.segments.size(), 50u);
  EXPECT_GT(some.segments.size(), 40u);  // no path has ten segments here
  EXPECT_GT(some.selected, some.paths.size());
  ASSERT_LE(some.paths.size(), all.paths.size());
  for (std::size_t i = 0; i < some.paths.size(); ++i) {
    EXPECT_EQ(some.paths[i].x, all.paths[i].x);
    EXPECT_EQ(some.paths[i].y, all.paths[i].y);
    EXPECT_EQ(some.paths[i].sample, all.paths[i].sample);
    EXPECT_EQ(some.paths[i].contribution, all.paths[i].contribution);
  }
}

// One pass for several expressions keeps in each record what a pass of its own keeps, with room
// to spare and with a limit that cuts each short at a different row.
TEST(RayFile, OnePassKeepsEachExpressionsPathsAsItsOwnPassWould) {
  test::temp_dir dir;
  const scene s = scene_with_mirror(dir);
  const std::vector<std::string> expressions = {"D .* S0:retro .* E", "D [^S0:retro]* E", "D P:mirror .* E"};
  int cut = 0;
  for (const std::uint64_t limit : {std::uint64_t(1'000'000), std::uint64_t(30)}) {
    const ray_file_params p{.segment_limit = limit, .spp = 2, .threads = 2};
    const std::vector<ray_record> together = record_rays(s, expressions, p);
    ASSERT_EQ(together.size(), expressions.size());
    for (std::size_t k = 0; k < expressions.size(); ++k) {
      ray_file_params own = p;
      own.select = expressions[k];
      const ray_record alone = record_rays(s, own);
      const ray_record& r = together[k];
      EXPECT_EQ(r.complete, alone.complete) << expressions[k];
      EXPECT_GT(r.paths.size(), 3u) << expressions[k];
      ASSERT_EQ(r.paths.size(), alone.paths.size()) << expressions[k] << ", limit " << limit;
      ASSERT_EQ(r.segments.size(), alone.segments.size()) << expressions[k];
      for (std::size_t i = 0; i < r.paths.size(); ++i) {
        EXPECT_EQ(r.paths[i].x, alone.paths[i].x);
        EXPECT_EQ(r.paths[i].y, alone.paths[i].y);
        EXPECT_EQ(r.paths[i].sample, alone.paths[i].sample);
        EXPECT_EQ(r.paths[i].segment_count, alone.paths[i].segment_count);
        EXPECT_EQ(r.paths[i].contribution, alone.paths[i].contribution);
      }
      for (std::size_t i = 0; i < r.segments.size(); ++i) {
        EXPECT_EQ(r.segments[i].start, alone.segments[i].start);
        EXPECT_EQ(r.segments[i].event, alone.segments[i].event);
      }
      if (limit == 1'000'000) {
        EXPECT_EQ(r.selected, alone.selected) << expressions[k];
      }
      std::printf("limit %llu, %-20s %3zu paths, %4zu segments, %s\n", static_cast<unsigned long long>(limit),
                  expressions[k].c_str(), r.paths.size(), r.segments.size(), r.complete ? "complete" : "cut short");
      cut += !r.complete;
    }
  }
  EXPECT_EQ(cut, int(expressions.size()));  // each cut short by the small limit
}

TEST(RayFile, BadInputIsRefusedBeforeAnythingIsWritten) {
  test::temp_dir dir;
  const scene s = scene_with_mirror(dir);
  const std::string file = dir.file("out.rays");
  const auto refused = [&](const std::string& path, const ray_file_params& p) {
    const std::string e = test::error_of([&] { check_ray_file(path, s, p); });
    EXPECT_FALSE(std::filesystem::exists(path)) << path;
    return e;
  };
  EXPECT_NE(refused(file, {.select = "D H:q E"}).find("at character 5"), std::string::npos);
  EXPECT_NE(refused(file, {.select = "D P:hood E"}).find("hood"), std::string::npos);
  EXPECT_NE(refused(file, {.segment_limit = 0}).find("the ray limit must be in [1, "), std::string::npos);
  EXPECT_NE(refused("/dev/full/out.rays", {}).find("Not a directory"), std::string::npos);
  // 2^32 segments need 378 GB: more than a memory-backed disk (at most the machine's memory) has.
  const std::string shm = "/dev/shm/airr-ray-file-test.rays";
  if (std::filesystem::is_directory("/dev/shm")) {
    const std::string e = refused(shm, {.segment_limit = max_ray_segments});
    EXPECT_NE(e.find("free; give a smaller limit"), std::string::npos) << e;
    EXPECT_NE(e.find(shm), std::string::npos) << e;
  }
  check_ray_file(file, s, {});  // a sensible file passes
}

TEST(RayFile, TheCommandWritesTheFileItsHeaderAnnounces) {
  test::temp_dir dir;
  const std::string scene_path = test::scene_file(dir, [](nlohmann::json& j) {
    j["observer"]["width"] = 16;
    j["observer"]["height"] = 12;
  });
  const std::string rays = dir.file("out.rays");
  const test::command_result bad = test::run_cli("render " + scene_path + " -o " + dir.file("a.exr") +
                                                 " --spp 2 --rays " + rays + " --rays-select 'D H:q E'");
  test::expect_one_line_error(bad, {"path expression 'D H:q E'", "at character 5"});
  EXPECT_FALSE(std::filesystem::exists(dir.file("a.exr")));
  EXPECT_FALSE(std::filesystem::exists(rays));
  const test::command_result ok = test::run_cli("render " + scene_path + " -o " + dir.file("a.exr") +
                                                " --spp 2 --rays " + rays + " --rays-select 'D H:r .* E'");
  ASSERT_EQ(ok.exit_code, 0) << ok.out;
  const std::uintmax_t bytes = std::filesystem::file_size(rays);
  std::FILE* f = std::fopen(rays.c_str(), "rb");
  ASSERT_NE(f, nullptr);
  char head[68];
  ASSERT_EQ(std::fread(head, 1, sizeof head, f), sizeof head);
  std::fclose(f);
  EXPECT_EQ(std::string(head, 8), "AIRRRAYS");
  std::uint64_t paths = 0, segments = 0;
  std::uint32_t n = 0;
  std::memcpy(&paths, head + 48, 8);
  std::memcpy(&segments, head + 56, 8);
  std::memcpy(&n, head + 64, 4);
  EXPECT_EQ(n, std::string("D H:r .* E").size());
  EXPECT_GT(paths, 0u);
  EXPECT_EQ(bytes, 68 + n + 40 * paths + 48 * segments);
}
