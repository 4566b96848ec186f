// airr-studio: the interactive designer. A window with the layout panel, the progressive render,
// the side view and live plots; scripted runs write a screenshot and exit.
#include <algorithm>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <numeric>

#include <GLFW/glfw3.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>
#include <imgui.h>
#include <CLI/CLI.hpp>

#include "airr/core/assets.hpp"
#include "airr/formats/design_spec.hpp"
#include "airr/formats/scene_json.hpp"
#include "airr/measure/contrast.hpp"
#include "airr/render/memory_need.hpp"
#include "airr/ui/panels/panels.hpp"
#include "airr/ui/platform/screenshot.hpp"
#include "airr/ui/studio/studio.hpp"
#include "airr/ui/views/views.hpp"
#include "airr/ui/window/screenshot_notes.hpp"
#include "airr/ui/window/soak.hpp"
#include "airr/ui/window/window.hpp"
#include "airr_version.hpp"

namespace {

struct options {
  std::string scene_path;
  std::vector<std::string> sets;
  int frames = 0;
  std::string screenshot;
  int bench_edits = 0;
  int threads = 0;
  std::string fit_dir;
  bool predict_preset = false;
  std::uint64_t predict_samples = 1000000;
  std::string save_as;
  std::string export_bokeh;        // after a scripted run, the Bokeh tab's pictures (and the plot data beside them)
  std::vector<std::string> edits;  // applied as one designer edit after the scripted frames
  double screenshot_after = -1;    // with edits: seconds after the edit (0: its first image)
  std::string component;           // the render view shows this component (empty: the whole image)
  bool luminance_view = false;     // the render view shows luminance in false colour
  bool contrast_view = false;      // ... or the contrast
  std::string plots = "mtf";       // the Plots window's tab
  std::string zone;                // the viewing zone's quantity; the full pass is computed before the screenshot
  double legible_at = 3;           // the contrast threshold of the legibility map beside the zone
  std::string design;              // a design spec for the Optimise and Tolerance windows
  airr::ui::design_script design_run;
  airr::ui::ghost_script ghost_run;
  airr::ui::soak_script soak;  // --soak: a long scripted run
};

struct app_state {
  airr::ui::studio* st = nullptr;
  float content_scale = 1.0f;
  bool rebuild_fonts = true;
};

// Fonts and sizes follow the monitor's content scale.
void load_fonts(float scale) {
  ImGuiIO& io = ImGui::GetIO();
  io.Fonts->Clear();
  const char* dejavu = "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf";
  const float size = std::round(15.0f * scale);
  if (std::filesystem::exists(dejavu)) {
    io.Fonts->AddFontFromFileTTF(dejavu, size);
  } else {
    ImFontConfig cfg;
    cfg.SizePixels = std::round(13.0f * scale);
    io.Fonts->AddFontDefault(&cfg);
  }
  ImGuiStyle style;
  ImGui::StyleColorsDark(&style);
  style.WindowRounding = 3.0f;
  style.FrameRounding = 2.0f;
  style.ScaleAllSizes(scale);
  ImGui::GetStyle() = style;
}

double percentile(std::vector<double> v, double q) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  return v[std::min(v.size() - 1, std::size_t(q * (v.size() - 1) + 0.5))];
}

}  // namespace

int main(int argc, char** argv) {
  // Past a file-size limit (ulimit -f) a write then fails with an error naming the file, instead
  // of the signal killing the program half-way.
  std::signal(SIGXFSZ, SIG_IGN);
  options opt;
  CLI::App cli{"airr-studio: design AIRR optical systems interactively"};
  cli.set_version_flag("--version", std::string("airr-studio ") + AIRR_VERSION);
  cli.add_option("scene", opt.scene_path, "Scene JSON file (default: the shipped default scene)");
  cli.add_option("--set", opt.sets,
                 "Override a scene value, e.g. retroreflectors.0.pose.pitch_deg=20 or floating_distance_mm=200");
  cli.add_option("--frames", opt.frames, "Run this many frames, then exit (scripted run)")
      ->check(CLI::Range(1, 1000000));
  cli.add_option("--screenshot", opt.screenshot, "After the scripted frames, save the window as PNG");
  cli.add_option("--bench-edits", opt.bench_edits, "Measure edit-to-image latency over this many edits, then exit")
      ->check(CLI::Range(1, 100000));
  cli.add_option("--threads", opt.threads, "Tracer threads (0: all cores)")->check(CLI::Range(0, 1024));
  auto* fit_option = cli.add_option("--fit", opt.fit_dir,
                                    "Open the fit window and fit this data directory (scripted runs apply the result)");
  cli.add_flag("--predict-preset", opt.predict_preset,
               "Open the fit window and predict a preset from the first sheet's model (scripted runs apply the "
               "result)")
      ->excludes(fit_option);
  cli.add_option("--predict-samples", opt.predict_samples,
                 "Samples per measurement of --predict-preset (default 1000000; fewer: quicker and rougher)")
      ->check(CLI::Range(std::uint64_t(10000), std::uint64_t(100000000)));
  cli.add_option("--save-as", opt.save_as, "After a scripted run, save the scene to this file");
  cli.add_option("--export-bokeh", opt.export_bokeh,
                 "After a scripted run, export the bokeh views as PNG to this file and siblings, and the plot data "
                 "as CSV beside them");
  cli.add_option("--edit", opt.edits,
                 "After the scripted frames, change key=value as one edit in the designer would (repeatable), then "
                 "take the screenshot --screenshot-after seconds later");
  cli.add_option("--screenshot-after", opt.screenshot_after,
                 "With --edit: seconds from the edit to the screenshot (0: the first frame showing the edit; "
                 "default: once the edit's plots are done)")
      ->check(CLI::Range(0.0, 3600.0));
  cli.add_option("--zone", opt.zone,
                 "The viewing zone shows this quantity; a scripted run computes the full pass before its screenshot, "
                 "and the legibility map beside the zone")
      ->check(CLI::IsMember(
          std::vector<std::string>(std::begin(airr::ui::zone_quantity_keys), std::end(airr::ui::zone_quantity_keys))));
  cli.add_option("--legible-at", opt.legible_at,
                 "The legibility map beside the viewing zone counts from this contrast threshold (1.5, 3 or 25)")
      ->check(CLI::IsMember({1.5, 3.0, 25.0}));
  cli.add_option("--plots", opt.plots, "The Plots window opens on this tab (mtf or bokeh)")
      ->check(CLI::IsMember({"mtf", "bokeh"}));
  cli.add_option("--component", opt.component,
                 "The render view shows one component of the image: aerial, direct, reflection, rest, room, sun, "
                 "luminaires or one luminaire's (luminaire0, ...)")
      ->check(CLI::Validator(
          [](const std::string& name) {
            return airr::is_component_name(name) ? std::string() : "not a component: " + name;
          },
          "COMPONENT"));
  cli.add_flag("--luminance-view", opt.luminance_view,
               "The render view shows luminance in false colour with its scale");
  cli.add_flag("--contrast-view", opt.contrast_view,
               "The render view shows each pixel's contrast (the aerial image against the rest) in false colour")
      ->excludes("--luminance-view");
  cli.add_option("--soak", opt.soak.seconds, "Run the designer's soak cycle this many seconds, then exit")
      ->check(CLI::Range(1.0, 1e6));
  cli.add_option("--soak-log", opt.soak.log, "With --soak: the samples as CSV (default soak.csv)");
  cli.add_option("--design", opt.design, "A design spec (airr-design) for the Optimise and Tolerance windows");
  cli.add_flag("--optimise", opt.design_run.optimise, "After the scripted frames, run the Optimise window's search");
  cli.add_flag("--tolerance", opt.design_run.tolerance,
               "After the scripted frames, run the Tolerance window's analysis");
  cli.add_flag("--apply-optimised", opt.design_run.apply, "Then apply the optimised layout (one undoable step)");
  cli.add_option("--undo", opt.design_run.undo, "Then undo this many steps")->check(CLI::Range(0, 100));
  cli.add_flag("--ghosts", opt.ghost_run.run, "After the scripted frames, find the Ghosts window's table");
  cli.add_option("--ghost-class", opt.ghost_run.show, "Then show its class K (from 1)")->check(CLI::Range(0, 63));
  CLI11_PARSE(cli, argc, argv);
  if (!opt.screenshot.empty() && opt.frames == 0) opt.frames = 60;

  // Load the scene before opening a window, so bad input fails fast with one line.
  airr::scene s, as_saved;
  std::string path = opt.scene_path.empty() ? airr::default_scene_path() : opt.scene_path;
  try {
    std::vector<airr::scene_override> overrides;
    for (const auto& v : opt.sets) overrides.push_back(airr::parse_override(v));
    std::vector<std::string> notes;
    s = airr::load_scene(path, overrides, notes);
    for (const auto& line : notes) std::fprintf(stderr, "%s\n", line.c_str());
    as_saved = overrides.empty() ? s : airr::load_scene(path);
    airr::check_render_memory(as_saved, airr::session_params{.components = true});  // as the designer renders
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 1;
  }

  glfwSetErrorCallback([](int code, const char* msg) { std::fprintf(stderr, "glfw error %d: %s\n", code, msg); });
  if (!glfwInit()) {
    std::fprintf(stderr, "error: cannot initialise GLFW (no display?); use `airr render` without a display\n");
    return 1;
  }
  airr::ui::studio st;
  st.settings = airr::ui::load_settings();
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
  glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
  glfwWindowHint(GLFW_SCALE_TO_MONITOR, GLFW_TRUE);
  // The window's class matches the menu entry's StartupWMClass, so docks group it under its icon.
  glfwWindowHintString(GLFW_X11_CLASS_NAME, "airr-studio");
  glfwWindowHintString(GLFW_X11_INSTANCE_NAME, "airr-studio");
  GLFWwindow* window =
      glfwCreateWindow(st.settings.window_width, st.settings.window_height, "AIRR Studio", nullptr, nullptr);
  if (!window) {
    std::fprintf(stderr, "error: cannot open an OpenGL 3.3 window\n");
    glfwTerminate();
    return 1;
  }
  glfwMakeContextCurrent(window);
  glfwSwapInterval(opt.frames > 0 || opt.bench_edits > 0 ? 0 : 1);

  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  static const std::string ini_path = airr::ui::config_dir() + "/imgui.ini";
  ImGui::GetIO().IniFilename = ini_path.c_str();
  ImGui_ImplGlfw_InitForOpenGL(window, true);
  ImGui_ImplOpenGL3_Init("#version 330");

  app_state app;
  app.st = &st;
  float xs = 1, ys = 1;
  glfwGetWindowContentScale(window, &xs, &ys);
  app.content_scale = std::max(xs, 1.0f);
  glfwSetWindowUserPointer(window, &app);
  glfwSetWindowContentScaleCallback(window, [](GLFWwindow* w, float x, float) {
    auto* a = static_cast<app_state*>(glfwGetWindowUserPointer(w));
    a->content_scale = std::max(x, 1.0f);
    a->rebuild_fonts = true;
  });
  glfwSetDropCallback(window, [](GLFWwindow* w, int count, const char** paths) {
    auto* a = static_cast<app_state*>(glfwGetWindowUserPointer(w));
    if (count > 0) airr::ui::studio_drop_file(*a->st, paths[0]);
  });

  st.session_options.threads = opt.threads;
  st.session_options.background_priority = true;
  st.session_options.first_look = true;
  st.session_options.quick_model_image = true;
  st.session_options.components = true;  // the render view can show each
  const std::vector<std::string> components = airr::component_layer_names(airr::max_luminaires);
  for (std::size_t k = 0; k < components.size(); ++k) {
    if (opt.component == components[k]) st.view.component = int(k);
  }
  st.view.luminance = opt.luminance_view;
  st.view.contrast = opt.contrast_view;
  st.plots_tab = opt.plots == "bokeh" ? 1 : 0;
  st.select_plots_tab = true;
  for (int k = 0; k < int(std::size(airr::ui::zone_quantity_keys)); ++k) {
    if (opt.zone == airr::ui::zone_quantity_keys[k]) st.zone_quantity = k;
  }
  for (std::size_t k = 0; k < airr::default_contrast_thresholds.size(); ++k) {
    if (opt.legible_at == airr::default_contrast_thresholds[k]) st.legibility_threshold = int(k);
  }
  st.keep_recovery = opt.frames == 0 && opt.bench_edits == 0;
  if (opt.soak.seconds > 0) {
    if (opt.soak.log.empty()) opt.soak.log = "soak.csv";
    opt.soak.scene_file = std::filesystem::path(opt.soak.log).replace_extension(".scene.json").string();
  }
  if (st.keep_recovery) airr::ui::studio_check_recovery(st);
  airr::ui::studio_start(st, as_saved, path);
  st.doc = s;  // --set overrides show as unsaved changes
  st.status = "opened " + path;
  if (!opt.fit_dir.empty()) {
    st.show_fit = true;
    st.fit_dir = opt.fit_dir;
    try {
      st.fit_job_ = std::make_unique<airr::ui::fit_job>(opt.fit_dir);
    } catch (const std::exception& e) {
      std::fprintf(stderr, "error: %s\n", e.what());
      return 1;
    }
  }
  if (!opt.design.empty()) {
    try {
      st.design.spec = airr::load_design_spec(opt.design);
    } catch (const std::exception& e) {
      std::fprintf(stderr, "error: %s\n", e.what());
      return 1;
    }
    st.design.spec_started = true;
    st.design.show_optimise = opt.design_run.optimise || !opt.design_run.tolerance;
    st.design.show_tolerance = opt.design_run.tolerance;
  }
  if (opt.predict_preset) {
    st.show_fit = true;
    st.predict_samples = opt.predict_samples;
    airr::ui::start_preset_prediction(st);
    if (!st.fit_job_) {
      std::fprintf(stderr, "error: %s\n", st.fit_error.c_str());
      return 1;
    }
  }

  using clock = std::chrono::steady_clock;
  const auto t0 = clock::now();
  auto now = [&] { return std::chrono::duration<double>(clock::now() - t0).count(); };
  std::vector<double> frame_ms;
  int frame = 0, edits_done = 0;
  bool screenshot_pending = !opt.screenshot.empty();
  int settle_frames = 0;
  int exit_code = 0;
  double edit_at = -1;  // when the scripted --edit was made
  // A second after the last input the window redraws four times a second, or at the next event:
  // redrawing continuously would take the cores from the tracer (on software OpenGL, all of them).
  const bool interactive = opt.frames == 0 && opt.bench_edits == 0;
  double last_input = 0;

  while (true) {
    if (interactive && now() - last_input > 1.0) {
      glfwWaitEventsTimeout(0.25);
    } else {
      glfwPollEvents();
    }
    if (glfwWindowShouldClose(window)) {
      glfwSetWindowShouldClose(window, GLFW_FALSE);
      if (opt.frames > 0 || !airr::ui::studio_dirty(st)) break;
      st.after_save_prompt = airr::ui::studio::pending_action::quit;
      st.show_save_prompt = true;
    }
    if (st.quit_requested) break;
    if (opt.soak.seconds > 0 && !airr::ui::run_soak_script(st, opt.soak, now())) {
      if (!opt.soak.error.empty()) std::fprintf(stderr, "error: %s\n", opt.soak.error.c_str());
      exit_code = opt.soak.error.empty() ? 0 : 1;
      break;
    }
    if (app.rebuild_fonts) {
      load_fonts(app.content_scale);
      ImGui_ImplOpenGL3_DestroyFontsTexture();
      ImGui_ImplOpenGL3_CreateFontsTexture();
      app.rebuild_fonts = false;
    }
    const auto f0 = clock::now();
    ImGui_ImplOpenGL3_NewFrame();
    ImGui_ImplGlfw_NewFrame();
    ImGui::NewFrame();
    airr::ui::studio_frame(st, now());
    const ImGuiIO& io = ImGui::GetIO();
    if (io.MouseDelta.x != 0 || io.MouseDelta.y != 0 || io.MouseWheel != 0 || io.MouseWheelH != 0 ||
        ImGui::IsAnyMouseDown() || ImGui::IsAnyItemActive() || !io.InputQueueCharacters.empty()) {
      last_input = now();
    }
    ImGui::Render();
    int fw = 0, fh = 0;
    glfwGetFramebufferSize(window, &fw, &fh);
    glViewport(0, 0, fw, fh);
    glClearColor(0.08f, 0.08f, 0.09f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT);
    ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
    ++frame;

    if (opt.frames > 0 && frame >= opt.frames) {
      // A scripted full viewing zone runs to its end before the screenshot.
      const bool zone_current = st.zone_job_ && st.zone_job_->generation() == st.generation;
      if (!opt.zone.empty() && opt.edits.empty() && (!zone_current || st.zone_job_->running())) {
        if (!zone_current) airr::ui::start_full_zone(st);
        glfwSwapBuffers(window);
        continue;
      }
      if (st.fit_job_ && st.fit_job_->running()) {
        glfwSwapBuffers(window);  // a scripted fit runs to its end before the run finishes
        continue;
      }
      if (st.fit_job_ && !st.fit_applied) {
        st.fit_applied = true;
        if (const auto r = st.fit_job_->result()) {
          airr::ui::apply_fitted_preset(st, r->preset);
        } else {
          std::fprintf(stderr, "error: fit failed: %s\n", st.fit_job_->error().c_str());
          exit_code = 1;
        }
        glfwSwapBuffers(window);
        continue;
      }
      if (airr::ui::run_ghost_script(st, opt.ghost_run)) {
        glfwSwapBuffers(window);
        continue;
      }
      if (airr::ui::run_design_script(st, opt.design_run)) {
        glfwSwapBuffers(window);
        continue;
      }
      if (!opt.edits.empty() && edit_at < 0) {
        // The scripted edit, made as a panel would: the next frame applies it.
        try {
          std::vector<airr::scene_override> overrides;
          for (const auto& e : opt.edits) overrides.push_back(airr::parse_override(e));
          st.doc = airr::with_overrides(st.doc, overrides, "--edit");
        } catch (const std::exception& e) {
          std::fprintf(stderr, "error: %s\n", e.what());
          exit_code = 1;
          break;
        }
        edit_at = now();
        glfwSwapBuffers(window);
        continue;
      }
      if (screenshot_pending && edit_at >= 0 && opt.screenshot_after >= 0) {
        // A timed look after the edit: its first image, or what shows so many seconds later.
        const bool due = opt.screenshot_after <= 0 ? st.first_image_uploaded : now() - edit_at >= opt.screenshot_after;
        if (!due) {
          glfwSwapBuffers(window);
          // Meanwhile the window idles as it would a second after the user's edit.
          if (now() - edit_at > 1.0) glfwWaitEventsTimeout(0.25);
          continue;
        }
      } else if (screenshot_pending) {
        // A few frames after the last edit was applied, showing the finished plots and at least
        // a few samples of the final layout.
        const airr::render_snapshot settled = st.session->wait_for(st.generation, 4);
        if (settle_frames == 0 && settled.spp > 0) {
          // Measured on these samples, not on the first wave's (traced before the control variate
          // came, and noisier).
          st.analysis.submit_render(settled, st.doc);
          st.last_measured_spp = settled.spp;
        }
        st.analysis.wait_idle();
        if (++settle_frames < 3) {
          glfwSwapBuffers(window);
          continue;
        }
      }
      if (screenshot_pending) {
        try {
          airr::ui::write_framebuffer_png(opt.screenshot, fw, fh);
          int ww = 0, wh = 0;
          glfwGetWindowSize(window, &ww, &wh);
          airr::ui::write_screenshot_notes(st, opt.screenshot + ".json", fw, fh, ww ? float(fw) / ww : 1.0f,
                                           wh ? float(fh) / wh : 1.0f);
          const int shown = st.view.uploaded_component;
          std::fprintf(stderr, "wrote %s (%dx%d); the render view shows %s%s%s\n", opt.screenshot.c_str(), fw, fh,
                       ("the " + st.view.uploaded_estimate).c_str(), shown >= 0 ? ", component " : "",
                       shown >= 0 ? airr::component_layer_names(airr::max_luminaires)[std::size_t(shown)].c_str() : "");
        } catch (const std::exception& e) {
          std::fprintf(stderr, "error: %s\n", e.what());
          exit_code = 1;
        }
      }
      if (!opt.export_bokeh.empty()) {
        // As File > Export bokeh pictures and Export plot data (the CSV beside the pictures).
        const std::string csv = (std::filesystem::path(opt.export_bokeh).replace_extension(".csv")).string();
        const bool pictures = airr::ui::studio_export_bokeh(st, opt.export_bokeh);
        const std::string said = st.status;
        if (!pictures || !airr::ui::studio_export_plots(st, csv)) {
          std::fprintf(stderr, "error: %s\n", pictures ? st.status.c_str() : said.c_str());
          exit_code = 1;
        } else {
          std::fprintf(stderr, "%s; plot data in %s\n", said.c_str(), csv.c_str());
        }
      }
      for (const std::string* e : {&opt.design_run.error, &opt.ghost_run.error}) {
        if (e->empty()) continue;
        std::fprintf(stderr, "error: %s\n", e->c_str());
        exit_code = 1;
      }
      if (!opt.save_as.empty() && !airr::ui::studio_save(st, opt.save_as)) {
        std::fprintf(stderr, "error: %s\n", st.status.c_str());
        exit_code = 1;
      }
      if (opt.bench_edits == 0) break;
    }
    glfwSwapBuffers(window);
    frame_ms.push_back(std::chrono::duration<double, std::milli>(clock::now() - f0).count());
    if (st.first_image_uploaded) {
      // The edit's first image is on screen now.
      st.edit_latencies_ms.push_back(1e3 * (now() - st.edit_time));
      st.first_image_uploaded = false;
      st.edit_time = -1;
    }

    // Latency benchmark: a new edit once the previous one's first image is on screen.
    if (opt.bench_edits > 0 && st.edit_time < 0 && frame > 5) {
      if (edits_done == opt.bench_edits) break;
      st.doc.sheet().pose.pitch_deg = (edits_done % 2) ? s.sheet().pose.pitch_deg : s.sheet().pose.pitch_deg + 2.0;
      ++edits_done;
    }
  }

  if (opt.bench_edits > 0) {
    const auto& l = st.edit_latencies_ms;
    const auto& r = st.first_image_ready_ms;
    std::printf(
        "edit to its first image (the model image's first look in %d of %zu edits), ready in the session: "
        "median %.1f ms, p95 %.1f ms\n",
        st.first_images_from_model, r.size(), percentile(r, 0.5), percentile(r, 0.95));
    std::printf(
        "edit-to-image latency in the window (until the frame showing it is swapped): median %.1f ms, "
        "p95 %.1f ms, max %.1f ms over %zu edits\n",
        percentile(l, 0.5), percentile(l, 0.95), l.empty() ? 0.0 : *std::max_element(l.begin(), l.end()), l.size());
    std::printf("frame time while the tracer runs: median %.1f ms, p95 %.1f ms over %zu frames\n",
                percentile(frame_ms, 0.5), percentile(frame_ms, 0.95), frame_ms.size());
  }
  if (opt.frames == 0 && opt.bench_edits == 0) {
    glfwGetWindowSize(window, &st.settings.window_width, &st.settings.window_height);
    airr::ui::save_settings(st.settings);
    airr::ui::studio_clear_recovery();  // a clean exit: the user saved or chose to discard
  }
  st.session->stop();
  st.view_3d.renderer.reset();  // its OpenGL objects go while the context lives
  ImGui_ImplOpenGL3_Shutdown();
  ImGui_ImplGlfw_Shutdown();
  ImGui::DestroyContext();
  glfwDestroyWindow(window);
  glfwTerminate();
  return exit_code;
}
