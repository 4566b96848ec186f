#pragma once
// A long scripted run of the designer (airr-studio --soak SECONDS): a cycle of what a designer does
// for hours (drags the sheet and the half mirror, changes presets and models, opens and cancels
// fits, zone passes and optimisations, undoes and redoes, saves and reopens the scene), with the
// process's resident memory, descriptors and threads sampled once a cycle, when no job runs.
#include <string>
#include <vector>

#include "airr/ui/platform/process_usage.hpp"
#include "airr/ui/studio/studio.hpp"

namespace airr::ui {

struct soak_sample {
  double seconds = 0;
  int cycle = 0;
  process_usage usage;
};

struct soak_script {
  double seconds = 0;         // how long it runs
  std::string log;            // the samples as CSV (seconds, cycle, resident MB, descriptors, threads)
  std::string scene_file;     // where it saves and reopens the scene
  double step_seconds = 0.4;  // between actions
  // Progress.
  double started = -1, next_step = 0;
  int step = 0, cycles = 0;
  std::vector<soak_sample> samples;
  std::string error;  // an action that failed, or the log that could not be written
};

// Advances the script by a frame: true while it runs. At its end the log is written and a summary
// printed (the samples at the start, after a minute and at the end).
bool run_soak_script(studio& st, soak_script& soak, double now);

}  // namespace airr::ui
