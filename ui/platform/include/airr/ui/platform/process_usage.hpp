#pragma once
// What this process holds of the machine now: resident memory, open file descriptors and threads
// (from /proc/self), for the designer's soak run.
namespace airr::ui {

struct process_usage {
  double resident_mb = 0;
  int descriptors = 0;
  int threads = 0;
};

process_usage read_process_usage();

}  // namespace airr::ui
