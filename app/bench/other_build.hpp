#pragma once
// Another build's airr, measured side by side with this one (airr bench ... --compare).
#include <filesystem>
#include <string>
#include <vector>

struct build_under_test {
  std::string label;
  std::string airr;  // the executable
};

// The string as one single-quoted shell word.
std::string shell_quoted(const std::string& s);

// This build and, when `compare` is not empty, the other build's airr (input_error when it is not
// an executable).
std::vector<build_under_test> builds_under_test(const std::string& compare);

// Runs the build with `args` (shell words, already quoted) and returns what it printed on standard
// output; input_error naming `what` and the last line it printed when it fails.
std::string run_build(const build_under_test& b, const std::string& args, const std::string& what);

// The last line of `text` that is not empty (what a failed run said last).
std::string last_line(const std::string& text);

// A fresh directory under the system's temporary folder for a benchmark's renders (`what` names
// the benchmark in its name and errors), removed with everything in it when done.
struct scratch_dir {
  std::filesystem::path path;
  explicit scratch_dir(const std::string& what);
  ~scratch_dir();
  scratch_dir(const scratch_dir&) = delete;
  scratch_dir& operator=(const scratch_dir&) = delete;
};
