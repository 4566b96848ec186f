#pragma once
// A one-line progress bar with elapsed time and ETA on stderr (redrawn in place on a terminal).
#include <unistd.h>
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <string>

class progress_bar {
 public:
  // A bar that is not `shown` draws nothing (the other ranks of an MPI job).
  explicit progress_bar(std::string label, bool shown = true)
      : label_(std::move(label)), tty_(::isatty(2)), shown_(shown) {}

  void update(double fraction, const std::string& detail = "") {
    if (!shown_) return;
    const double elapsed = seconds();
    if (!tty_ && fraction < 1.0 && elapsed - last_print_ < 2.0) return;  // logs: one line each 2 s
    last_print_ = elapsed;
    const int width = 30, filled = int(std::clamp(fraction, 0.0, 1.0) * width);
    const double eta = fraction > 0 ? elapsed * (1.0 - fraction) / fraction : 0.0;
    std::fprintf(stderr, "%s%s [%.*s%*s] %5.1f%% %6.1fs elapsed, ETA %5.1fs %s%s", tty_ ? "\r" : "", label_.c_str(),
                 filled, "##############################", width - filled, "", 100.0 * fraction, elapsed, eta,
                 detail.c_str(), tty_ ? "\033[K" : "\n");
    std::fflush(stderr);
  }
  void finish(const std::string& detail = "") {
    last_print_ = -1e9;
    update(1.0, detail);
    if (tty_ && shown_) std::fputc('\n', stderr);
  }
  double seconds() const { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count(); }

 private:
  std::string label_;
  bool tty_;
  bool shown_;
  double last_print_ = -1e9;
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
};
