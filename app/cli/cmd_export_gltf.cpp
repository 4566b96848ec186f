// airr export-gltf SCENE -o layout.glb [--set key=value ...]
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "airr/formats/gltf_layout.hpp"
#include "airr/formats/scene_json.hpp"
#include "cli/commands.hpp"

void add_export_gltf_command(CLI::App& app) {
  struct options {
    std::string scene_path, out;
    std::vector<std::string> sets;
  };
  auto opt = std::make_shared<options>();
  auto* cmd = app.add_subcommand("export-gltf",
                                 "Write the layout as glTF (.glb or .gltf): every part, prop and the observer, with "
                                 "their roles in extras, and the display's image embedded as its texture, so "
                                 "that a glTF tool opens it and airr reads it back");
  cmd->add_option("scene", opt->scene_path, "Scene file (JSON, or a glTF layout)")->required();
  cmd->add_option("-o,--output", opt->out, "Output .glb or .gltf file")->required();
  cmd->add_option("--set", opt->sets, "Override a scene field, e.g. retroreflectors.0.pose.pitch_deg=20");
  cmd->callback([opt] {
    std::vector<airr::scene_override> overrides;
    for (const auto& s : opt->sets) overrides.push_back(airr::parse_override(s));
    const airr::scene s = load_scene_noting(opt->scene_path, overrides);
    airr::export_gltf_layout(s, opt->out);
    std::printf("wrote %s: display, half mirror, %zu retroreflector%s, %zu prop%s, observer\n", opt->out.c_str(),
                s.retroreflectors.size(), s.retroreflectors.size() == 1 ? "" : "s", s.props.size(),
                s.props.size() == 1 ? "" : "s");
  });
}
