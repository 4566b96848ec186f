// airr gain SCENE [--spp N] [--threads N] [--set key=value ...]: the aerial image's brightness with
// the scene's parts (a reflective polarizer, films, a polarized display) against the same layout
// with a plain half mirror.
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "airr/measure/polarization_gain.hpp"
#include "cli/commands.hpp"

void add_gain_command(CLI::App& app) {
  struct options {
    std::string scene_path;
    std::uint64_t spp = 16;
    int threads = 0;
    std::vector<std::string> sets;
  };
  auto opt = std::make_shared<options>();
  auto* cmd = app.add_subcommand("gain",
                                 "Compare the aerial image's brightness with the scene's parts against the same "
                                 "layout with a plain half mirror (R = T = 0.5, no films): the gain of p-AIRR");
  cmd->add_option("scene", opt->scene_path, "Scene JSON or glTF file")->required();
  cmd->add_option("--spp", opt->spp, "Samples per pixel of each render")->check(CLI::Range(1, 1 << 16));
  cmd->add_option("--threads", opt->threads, "Worker threads (0: all cores)")->check(CLI::Range(0, 1024));
  cmd->add_option("--set", opt->sets, "Override a scene value, e.g. source.polarization.state=linear");
  cmd->callback([opt] {
    std::vector<airr::scene_override> overrides;
    for (const auto& s : opt->sets) overrides.push_back(airr::parse_override(s));
    const airr::scene s = load_scene_noting(opt->scene_path, overrides);
    const auto g = airr::measure_polarization_gain(
        s, opt->spp, opt->threads, [](int done) { std::fprintf(stderr, "gain: %d of 2 renders done\n", done); });
    std::printf("aerial image, its luminance summed over the image at %llu spp:\n",
                static_cast<unsigned long long>(g.spp));
    std::printf("  with the scene's parts: %.6g\n", g.aerial);
    std::printf("  with a plain half mirror (R = T = 0.5, no films): %.6g\n", g.half_mirror);
    std::printf("gain: %.4fx\n", g.gain());
  });
}
