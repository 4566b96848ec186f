// airr ghosts SCENE -o DIR [--spp N] [--census-spp N] [--top K] [--class EXPR ...] [--baseline MM]
//             [--set key=value ...]:
// the light paths that reach the observer, ranked by their light inside the aerial image's
// outline and by their peak, each placed by parallax; DIR/ghosts.csv and an EXR of each class.
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "airr/core/error.hpp"
#include "airr/measure/ghost_table.hpp"
#include "cli/commands.hpp"
#include "cli/progress_bar.hpp"

void add_ghosts_command(CLI::App& app) {
  struct options {
    std::string scene_path, out;
    airr::ghost_params p;
    std::vector<std::string> sets;
  };
  auto opt = std::make_shared<options>();
  auto* cmd = app.add_subcommand(
      "ghosts",
      "Rank the light paths that reach the observer (ghosts and stray light) by their light inside the "
      "aerial image's outline and by their peak, and place each by parallax (docs/path-expressions.md)");
  cmd->add_option("scene", opt->scene_path, "Scene JSON or glTF file")->required();
  cmd->add_option("-o,--output", opt->out, "Folder for ghosts.csv and an EXR of each path class")->required();
  cmd->add_option("--spp", opt->p.spp, "Samples per pixel of each eye's render")->check(CLI::Range(1, 1 << 16));
  cmd->add_option("--census-spp", opt->p.census_spp, "Samples per pixel of the census that finds the path classes")
      ->check(CLI::Range(1, 1 << 12));
  cmd->add_option("--top", opt->p.top, "Path classes measured, those with the most light")->check(CLI::Range(1, 62));
  cmd->add_option("--baseline", opt->p.baseline_mm, "Between the two eyes whose parallax places each class (mm)")
      ->check(CLI::Range(0.001, 1000.0));
  cmd->add_option("--class", opt->p.expressions,
                  "A path expression measured as a class of its own besides the census's, e.g. 'D .* H:r1 .* E' "
                  "(repeatable)");
  cmd->add_option("--threads", opt->p.threads, "Worker threads (0: all cores)")->check(CLI::Range(0, 1024));
  cmd->add_option("--set", opt->sets, "Override a scene value, e.g. half_mirror.kind=plate");
  cmd->callback([opt] {
    std::vector<airr::scene_override> overrides;
    for (const auto& s : opt->sets) overrides.push_back(airr::parse_override(s));
    const airr::scene s = load_scene_noting(opt->scene_path, overrides);
    std::error_code ec;
    std::filesystem::create_directories(opt->out, ec);
    if (ec) throw airr::input_error(opt->out + ": cannot make the folder: " + ec.message());
    progress_bar bar("ghosts");
    const airr::ghost_table t =
        airr::compute_ghost_table(s, opt->p, [&](const std::string& stage, double f) { bar.update(f, stage); });
    bar.finish(std::to_string(t.labels_seen) + " path classes seen");
    const std::string csv = opt->out + "/ghosts.csv";
    airr::write_ghost_csv(t, csv);
    std::printf("aerial image: centroid (%.2f, %.2f) px, %.1f mm from the observer by parallax\n", t.aerial_centroid.x,
                t.aerial_centroid.y, t.aerial_distance_mm);
    std::printf("%4s %4s %10s %10s %10s %9s %10s  %s\n", "rank", "peak", "share", "luminance", "peak_lum", "arcmin",
                "depth_mm", "path");
    for (std::size_t i = 0; i < t.classes.size(); ++i) {
      const airr::ghost_class& g = t.classes[i];
      std::size_t peak_rank = 0;
      while (t.by_peak[peak_rank] != i) ++peak_rank;
      std::printf("%4zu %4zu %10.4g %10.4g %10.4g %9.2f %10.1f  %s\n", i + 1, peak_rank + 1, g.share,
                  g.outline_luminance, g.peak, g.separation_arcmin, g.distance_mm - t.aerial_distance_mm,
                  g.expression.c_str());
      const std::string image = opt->out + "/class_" + std::to_string(i + 1) + ".exr";
      airr::write_image(image, g.image, {{"airr:path_expression", g.expression}});
    }
    std::fprintf(stderr, "wrote %s and %zu images (class_N.exr) in %.1f s\n", csv.c_str(), t.classes.size(), t.seconds);
  });
}
