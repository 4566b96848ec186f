// airr merge SHARD... -o OUT.exr|OUT.png: the render its shards (airr render --shard i/N) make up;
// airr merge PART...: the outputs of the command whose partials (--shard i/N --part F) they are.
#include <cstdlib>

#include "airr/core/error.hpp"
#include "airr/render/render_shards.hpp"
#include "cli/commands.hpp"
#include "cluster/item_shards.hpp"

void add_merge_command(CLI::App& app) {
  struct options {
    std::vector<std::string> shards;
    std::string out;
  };
  auto opt = std::make_shared<options>();
  auto* cmd = app.add_subcommand("merge",
                                 "Put the shards of a render (airr render --shard i/N) together, or finish the work "
                                 "of a sweep, full viewing zone or tolerance study from its partials (--part)");
  cmd->add_option("shards", opt->shards, "The shards' EXR files or partials, all N of them, in any order")->required();
  cmd->add_option("-o,--output", opt->out,
                  "Render shards: the whole render (.exr or .png), as one process writes it (partials write their "
                  "command's own outputs)");
  cmd->callback([opt] {
    if (are_partials(opt->shards)) {
      if (!opt->out.empty())
        throw airr::input_error("merge: -o is for render shards; partials write the outputs their command names");
      // The command runs again over the shards' items and writes its own outputs.
      std::vector<std::string> args = {"airr"};
      for (const std::string& a : merged_command_line(opt->shards)) args.push_back(a);
      CLI::App again{"airr"};
      add_commands(again);
      std::vector<char*> argv;
      for (std::string& a : args) argv.push_back(a.data());
      again.parse(int(argv.size()), argv.data());
      return;
    }
    if (opt->out.empty()) throw airr::input_error("merge: render shards need -o OUT.exr or OUT.png");
    const airr::render_image whole = airr::merge_render_shards(opt->shards);
    std::vector<airr::image_layer> layers;
    for (const auto& [name, img] : whole.layers) layers.push_back({name, &img});
    if (!layers.empty() && !opt->out.ends_with(".exr"))
      throw airr::input_error(opt->out + ": the shards hold the image's components; write them to an EXR");
    const auto exposure = whole.meta.find("airr:exposure");
    const float scale = exposure == whole.meta.end() ? 1.0f : std::strtof(exposure->second.c_str(), nullptr);
    airr::write_image(opt->out, whole.rgb, whole.meta, scale, layers);
    std::fprintf(stderr, "wrote %s (%dx%d from %zu shards)\n", opt->out.c_str(), whole.rgb.width, whole.rgb.height,
                 opt->shards.size());
  });
}
