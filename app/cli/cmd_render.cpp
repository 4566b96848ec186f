// airr render SCENE -o OUT.exr|OUT.png [--spp N] [--seed S] [--components | --component NAME]
//             [--layer NAME=EXPR ...] [--stokes] [--set key=value ...] [--shard i/N]
//             [--rays FILE [--rays-select EXPR] [--rays-limit N]]
#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <optional>
#include <tuple>

#include "airr/core/error.hpp"
#include "airr/formats/scene_json.hpp"
#include "airr/layout/layout.hpp"
#include "airr/measure/stokes_render.hpp"
#include "airr/render/memory_need.hpp"
#include "airr/render/ray_file.hpp"
#include "airr/render/render_metadata.hpp"
#include "airr/render/render_session.hpp"
#include "airr/render/render_shards.hpp"
#include "airr_version.hpp"
#include "cli/commands.hpp"
#include "cli/progress_bar.hpp"
#include "cluster/mpi_job.hpp"

// The ray file: the render's paths traced again, those selected kept.
static void write_rays(const std::string& path, const airr::scene& s, const airr::ray_file_params& p) {
  progress_bar bar("rays");
  const airr::ray_record r = airr::record_rays(s, p, [&](double done) {
    bar.update(done, "");
    return true;
  });
  bar.finish(std::to_string(r.paths.size()) + " paths");
  airr::write_ray_file(path, s, p, r);
  std::fprintf(stderr, "wrote %s (%zu paths, %zu segments; %llu paths selected%s)\n", path.c_str(), r.paths.size(),
               r.segments.size(), static_cast<unsigned long long>(r.selected),
               r.complete ? "" : ", the rest beyond the limit");
}

void add_render_command(CLI::App& app) {
  struct options {
    std::string scene_path, out;
    std::uint64_t spp = 64;
    std::optional<std::uint64_t> seed;
    std::vector<std::string> sets;
    double exposure = 0;
    int threads = 0;
    bool components = false;
    bool stokes = false;
    std::string component;
    std::string shard;
    std::vector<std::string> layers;
    std::string rays;
    airr::ray_file_params ray_params;
  };
  auto opt = std::make_shared<options>();
  auto* cmd = app.add_subcommand("render", "Render a scene to EXR (linear) or PNG (sRGB)");
  cmd->add_option("scene", opt->scene_path, "Scene JSON file")->required();
  cmd->add_option("-o,--output", opt->out, "Output image (.exr or .png)")->required();
  cmd->add_option("--spp", opt->spp, "Samples per pixel")->check(CLI::Range(1, 1 << 24));
  cmd->add_option("--seed", opt->seed, "Random seed (overrides the scene's)");
  cmd->add_option("--set", opt->sets,
                  "Override a scene value, e.g. retroreflectors.0.pose.pitch_deg=20 or floating_distance_mm=200");
  cmd->add_option("--exposure", opt->exposure,
                  "PNG scale factor; default maps a white source through a lossless retroreflector to 1");
  cmd->add_option("--threads", opt->threads, "Worker threads (0: all cores)")->check(CLI::Range(0, 1024));
  auto* layers =
      cmd->add_flag("--components", opt->components,
                    "EXR: also write the image's components as layers aerial, direct, reflection, rest, room, sun, "
                    "luminaires, and each luminaire's own: luminaire0, luminaire1, ...");
  cmd->add_option("--component", opt->component,
                  "Write one component instead of the whole image: aerial, direct, reflection, rest, room, sun, "
                  "luminaires or one luminaire's (luminaire0, ...)")
      ->check(CLI::Validator(
          [](const std::string& name) {
            return airr::is_component_name(name) ? std::string() : "not a component: " + name;
          },
          "COMPONENT"))
      ->excludes(layers);
  cmd->add_option("--layer", opt->layers,
                  "EXR: also write the light of the paths a path expression selects as a layer NAME, e.g. "
                  "--layer 'aerial0=D H:r S0:retro H:t E' (repeatable; the paths none selects go to a layer "
                  "'unmatched'; docs/path-expressions.md)");
  cmd->add_flag("--stokes", opt->stokes,
                "EXR: also write the Stokes parameters of the light reaching the observer (before its polarizer) as "
                "layers S0, S1, S2, S3 and their degree of polarization, dop")
      ->excludes(layers);
  cmd->add_option("--shard", opt->shard,
                  "Render rows of shard i of N (0 <= i < N) alone into an EXR for airr merge (e.g. a Slurm array "
                  "task's share)");
  cmd->add_option("--rays", opt->rays,
                  "Also write the paths --rays-select selects, segment by segment, to a ray file (docs/ray-file.md; "
                  "airr.read_rays reads it)");
  cmd->add_option("--rays-select", opt->ray_params.select,
                  "The path expression selecting the paths of the ray file (default: every path)");
  cmd->add_option("--rays-limit", opt->ray_params.segment_limit,
                  "The most segments the ray file holds (default 1000000); the paths kept are the first selected");
  cmd->callback([opt] {
    std::vector<airr::scene_override> overrides;
    for (const auto& s : opt->sets) overrides.push_back(airr::parse_override(s));
    airr::scene s = load_scene_noting(opt->scene_path, overrides);
    if (opt->seed) s.seed = *opt->seed;
    const bool split = opt->components || !opt->component.empty();
    const int luminaires = int(s.environment.luminaires.size());
    const std::vector<std::string> component_names = airr::component_layer_names(luminaires);
    if (!opt->component.empty() &&
        std::find(component_names.begin(), component_names.end(), opt->component) == component_names.end()) {
      throw airr::input_error("--component " + opt->component + ": the scene has " + std::to_string(luminaires) +
                              " luminaire" + (luminaires == 1 ? "" : "s"));
    }
    if (opt->components && !opt->out.ends_with(".exr")) {
      throw airr::input_error(opt->out + ": --components needs an EXR output (layers); use --component for a PNG");
    }
    const mpi_job& job = this_job();
    if (opt->stokes) {
      if (!opt->out.ends_with(".exr")) throw airr::input_error(opt->out + ": --stokes needs an EXR output (layers)");
      if (!opt->component.empty() || !opt->shard.empty() || job.size > 1)
        throw airr::input_error("--stokes: renders the whole image in one process, without --component or --shard");
    }
    std::shared_ptr<const airr::path_layers> path_layers;
    if (!opt->layers.empty()) {
      if (!opt->out.ends_with(".exr")) throw airr::input_error(opt->out + ": --layer needs an EXR output (layers)");
      std::vector<std::string> taken;
      if (opt->components) taken = component_names;
      if (opt->stokes)
        taken.insert(taken.end(), std::begin(airr::stokes_layer_names), std::end(airr::stokes_layer_names));
      path_layers = std::make_shared<const airr::path_layers>(airr::parse_layer_arguments(opt->layers, s, taken));
    }
    std::optional<airr::shard_index> shard;  // this process's rows go to a shard file
    airr::session_params params{.threads = opt->threads,
                                .target_spp = opt->spp,
                                .components = split,
                                .layers = path_layers,
                                .final_images_only = true};
    if (!opt->shard.empty()) {
      if (job.size > 1) throw airr::input_error("--shard: not under mpirun or srun, whose ranks split the render");
      shard = airr::parse_shard(opt->shard, "--shard");
      if (!opt->out.ends_with(".exr")) throw airr::input_error(opt->out + ": a shard is written to an EXR file");
    }
    // Under mpirun or srun each rank traces the rows of its shard, and rank 0 gathers them.
    const std::optional<airr::shard_index> rows = shard ? shard
                                                  : job.size > 1
                                                      ? std::optional<airr::shard_index>({job.rank, job.size})
                                                      : std::nullopt;
    if (rows) {
      if (rows->count > s.observer.height)
        throw airr::input_error(std::string(shard ? "--shard: " : "mpirun/srun: ") + std::to_string(rows->count) +
                                (shard ? " shards" : " ranks") + " for an image " + std::to_string(s.observer.height) +
                                " rows high (at most one per row)");
      std::tie(params.first_row, params.end_row) = airr::shard_rows(*rows, s.observer.height);
    }
    if (!opt->rays.empty()) {
      if (rows || opt->stokes)
        throw airr::input_error("--rays: renders the whole image in one process, without --shard or --stokes");
      opt->ray_params.spp = opt->spp;
      opt->ray_params.threads = opt->threads;
      airr::check_ray_file(opt->rays, s, opt->ray_params);
    }
    airr::check_render_memory(s, params);  // refused before anything is allocated
    // Ended before the images are written: its sums are not needed then (render/memory_need).
    std::optional<airr::render_session> session(std::in_place, s, params);
    std::optional<progress_bar> bar;
    if (job.root()) bar.emplace(job.size > 1 ? "render (" + std::to_string(job.size) + " ranks)" : "render");
    // The job's progress is its slowest rank's: every rank counts, each time, until all are done.
    std::function<std::uint64_t(std::uint64_t)> job_spp;
    if (job.size > 1) job_spp = job_min;
    const airr::render_snapshot snap = airr::render_to_spp(
        *session, opt->spp,
        [&](std::uint64_t job_spp) {
          if (bar) bar->update(double(job_spp) / double(opt->spp), std::to_string(job_spp) + " spp");
          return true;
        },
        std::chrono::milliseconds(0), job_spp);
    session.reset();
    if (bar)
      bar->finish(std::to_string(snap.spp) + " spp, " +
                  std::to_string(std::uint64_t(snap.rays / std::max(snap.seconds, 1e-9))) + " rays/s");
    const float exposure = opt->exposure > 0 ? float(opt->exposure) : float(airr::default_exposure(s));
    // The components and path layers are written from the snapshot in place, unless gathered from
    // the ranks, written to a shard or one of them chosen: copied out then.
    const bool copied = job.size > 1 || shard || !opt->component.empty();
    std::vector<airr::image_rgb> parts, path_images;
    if (copied) {
      parts = snap.component_images();
      for (std::size_t k = 0; k < snap.layer_names.size(); ++k) path_images.push_back(snap.layer_image(k));
    }
    std::vector<airr::image_layer> layers;
    // The seven components, then each luminaire's own, from slot first_luminaire on.
    const airr::component_slots& slots = snap.component_layout;
    for (int k = 0; k < airr::component_count + slots.luminaires && opt->components; ++k) {
      const std::string& name = component_names[std::size_t(k)];
      const int at =
          k < airr::component_count ? slots.slot[std::size_t(k)] : slots.first_luminaire + k - airr::component_count;
      if (copied)
        layers.push_back({name, &parts[std::size_t(k)]});
      else if (at < 0)
        layers.push_back({.name = name, .zeros = true});
      else
        layers.push_back({name, nullptr, snap.components->data(), std::size_t(slots.count), std::size_t(at)});
    }
    for (std::size_t k = 0; k < snap.layer_names.size(); ++k) {
      if (copied)
        layers.push_back({snap.layer_names[k], &path_images[k]});
      else
        layers.push_back({snap.layer_names[k], nullptr, snap.layers->data(), snap.layer_names.size(), k});
    }
    airr::image_rgb image = snap.image();
    if (job.size > 1) {
      image = gather_rows(image, params.first_row, params.end_row);
      for (auto& p : parts) p = gather_rows(p, params.first_row, params.end_row);
      for (auto& p : path_images) p = gather_rows(p, params.first_row, params.end_row);
      if (!job.root()) return;
    }
    if (!opt->component.empty()) {
      for (std::size_t k = 0; k < parts.size(); ++k) {
        if (opt->component == component_names[k]) image = parts[k];
      }
    }
    airr::image_metadata meta = airr::render_metadata(s, snap, exposure);
    if (!opt->component.empty()) meta["airr:component"] = opt->component;
    if (path_layers) {
      for (const auto& l : path_layers->layers) meta["airr:layer:" + l.name] = l.expression.text();
    }
    if (shard) {
      airr::render_image whole{image, {}, meta};
      for (const auto& l : layers) whole.layers.emplace_back(l.name, *l.image);
      airr::write_render_shard(opt->out, whole, *shard, AIRR_VERSION);
      const auto [first, end] = airr::shard_rows(*shard, snap.height);
      std::fprintf(stderr, "wrote %s (shard %s: rows %d to %d of %dx%d, %llu spp)\n", opt->out.c_str(),
                   opt->shard.c_str(), first, end - 1, snap.width, snap.height,
                   static_cast<unsigned long long>(snap.spp));
      return;
    }
    airr::stokes_images stokes;
    if (opt->stokes) {
      progress_bar stokes_bar("stokes");
      stokes = airr::render_stokes(s, opt->spp, opt->threads, [&](int i, std::uint64_t spp) {
        stokes_bar.update((i + double(spp) / double(opt->spp)) / 4, "S" + std::to_string(i));
      });
      stokes_bar.finish();
      for (int i = 0; i < 4; ++i) layers.push_back({airr::stokes_layer_names[i], &stokes.s[std::size_t(i)]});
      layers.push_back({airr::stokes_layer_names[4], &stokes.degree});
    }
    airr::write_image(opt->out, image, meta, exposure, layers);
    std::fprintf(stderr, "wrote %s (%dx%d, %llu spp, %.6g mm/pixel)\n", opt->out.c_str(), snap.width, snap.height,
                 static_cast<unsigned long long>(snap.spp), snap.mm_per_pixel);
    if (!opt->rays.empty()) write_rays(opt->rays, s, opt->ray_params);
    // Rounding noise of the mirror image (1e-14 mm) printed as 0.
    const auto tidy = [](double v) { return std::abs(v) < 1e-9 ? 0.0 : v; };
    const glm::dvec3 aerial = airr::aerial_image_center(s);
    const airr::pinhole_camera cam = airr::make_camera(s);
    std::fprintf(stderr,
                 "floating distance D %.6g mm; aerial image centred at (%.6g, %.6g, %.6g) mm; observer (%s) at (%.6g, "
                 "%.6g, %.6g) mm, %s\n",
                 airr::floating_distance(s), tidy(aerial.x), tidy(aerial.y), tidy(aerial.z),
                 s.observer.placement == airr::observer_placement::orbit ? "orbit" : "look_at", tidy(cam.position.x),
                 tidy(cam.position.y), tidy(cam.position.z), cam.aperture_mm > 0 ? "thin lens" : "pinhole");
  });
}
