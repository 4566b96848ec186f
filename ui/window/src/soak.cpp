#include "airr/ui/window/soak.hpp"

#include <cstdio>
#include <string>

#include "airr/core/assets.hpp"
#include "airr/core/files.hpp"
#include "airr/formats/design_spec.hpp"
#include "airr/formats/scene_json.hpp"
#include "airr/ui/panels/panels.hpp"
#include "airr/ui/views/views.hpp"

namespace airr::ui {

namespace {

// The cycle's actions, in order; each is made as its panel or menu item makes it.
enum class soak_action {
  drag_sheet_up,
  drag_mirror,
  drag_sheet_down,
  next_preset,
  start_fit,
  cancel_fit,
  next_model,
  start_zone,
  cancel_zone,
  start_optimise,
  cancel_optimise,
  undo,
  redo,
  save,
  reopen,  // then the sample: every job is cancelled and joined
  count
};

constexpr const char* presets[] = {"rf-an", "rf-ay"};
constexpr const char* models[] = {"ideal", "microfacet", "sinc_shift"};

// Edits the document as the layout panel does (the next frame applies it).
void set_value(studio& st, const std::string& key, const std::string& value) {
  st.doc = with_overrides(st.doc, {{key, value}}, "soak");
}

void act(studio& st, soak_script& soak, soak_action a) {
  const int c = soak.cycles;
  switch (a) {
    case soak_action::drag_sheet_up:
      for (int k = 1; k <= 5; ++k) st.doc.sheet().pose.pitch_deg += 0.2;  // a drag is many small edits
      break;
    case soak_action::drag_mirror:
      st.doc.half_mirror.pose.pitch_deg += c % 2 ? -0.5 : 0.5;
      break;
    case soak_action::drag_sheet_down:
      st.doc.sheet().pose.pitch_deg -= 1.0;
      break;
    case soak_action::next_preset:
      set_value(st, "retroreflectors.0.model.type", "sinc_shift");
      set_value(st, "retroreflectors.0.model.preset", presets[c % 2]);
      break;
    case soak_action::start_fit:
      st.fit_job_ = std::make_unique<fit_job>(asset_dir() + "/fit_example");
      break;
    case soak_action::cancel_fit:
      st.fit_job_.reset();
      break;
    case soak_action::next_model:
      set_value(st, "retroreflectors.0.model.type", models[c % 3]);
      break;
    case soak_action::start_zone:
      start_full_zone(st);
      break;
    case soak_action::cancel_zone:
      st.zone_job_.reset();
      break;
    case soak_action::start_optimise:
      st.design.spec = parse_design_spec(
          R"({"format": "airr-design", "version": 1,
              "variables": [{"key": "floating_distance_mm", "min": 120, "max": 200}],
              "objectives": [{"metric": "r50_mm", "goal": "minimise"}],
              "search": {"global_evaluations": 40, "local_evaluations": 10, "psf_samples": 4000}})",
          "soak", st.applied);
      st.design.spec_started = true;
      if (!start_design_job(st, design_job::kind::optimise)) throw input_error(st.design.error);
      break;
    case soak_action::cancel_optimise:
      st.design.job.reset();
      break;
    case soak_action::undo:
      studio_undo(st);
      break;
    case soak_action::redo:
      studio_redo(st);
      break;
    case soak_action::save:
      if (!studio_save(st, soak.scene_file)) throw input_error(st.status);
      break;
    case soak_action::reopen:
      studio_open(st, soak.scene_file);
      if (st.doc_path != soak.scene_file) throw input_error(st.status);
      break;
    case soak_action::count:
      break;
  }
}

void print_sample(const char* when, const soak_sample& s) {
  std::fprintf(stderr, "soak %-14s %7.1f s  cycle %4d  resident %7.1f MB  descriptors %3d  threads %3d\n", when,
               s.seconds, s.cycle, s.usage.resident_mb, s.usage.descriptors, s.usage.threads);
}

void finish(soak_script& soak) {
  std::string csv = "seconds,cycle,resident_mb,descriptors,threads\n";
  for (const soak_sample& s : soak.samples) {
    char row[128];
    std::snprintf(row, sizeof row, "%.1f,%d,%.1f,%d,%d\n", s.seconds, s.cycle, s.usage.resident_mb, s.usage.descriptors,
                  s.usage.threads);
    csv += row;
  }
  try {
    write_file_atomic(soak.log, csv);
  } catch (const std::exception& e) {
    soak.error = e.what();
  }
  if (soak.samples.empty()) return;
  print_sample("start", soak.samples.front());
  for (const soak_sample& s : soak.samples) {
    if (s.seconds >= 60) {
      print_sample("after 1 minute", s);
      break;
    }
  }
  print_sample("end", soak.samples.back());
}

}  // namespace

bool run_soak_script(studio& st, soak_script& soak, double now) {
  if (soak.started < 0) soak.started = soak.next_step = now;
  if (!soak.error.empty()) return false;
  if (now < soak.next_step) return true;
  soak.next_step = now + soak.step_seconds;
  const auto a = soak_action(soak.step);
  try {
    act(st, soak, a);
  } catch (const std::exception& e) {
    soak.error = std::string("soak: cycle ") + std::to_string(soak.cycles) + ", step " + std::to_string(soak.step) +
                 ": " + e.what();
    finish(soak);
    return false;
  }
  if (++soak.step < int(soak_action::count)) return true;
  soak.step = 0;
  soak.samples.push_back({now - soak.started, soak.cycles, read_process_usage()});
  ++soak.cycles;
  if (now - soak.started < soak.seconds) return true;
  finish(soak);
  return false;
}

}  // namespace airr::ui
