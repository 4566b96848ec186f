#include "bench/other_build.hpp"

#include <unistd.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <memory>

#include "airr/core/error.hpp"

namespace fs = std::filesystem;

std::string shell_quoted(const std::string& s) {
  std::string out = "'";
  for (char c : s) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

std::vector<build_under_test> builds_under_test(const std::string& compare) {
  std::vector<build_under_test> builds{{"this build", fs::read_symlink("/proc/self/exe").string()}};
  if (!compare.empty()) {
    if (::access(compare.c_str(), X_OK) != 0) throw airr::input_error(compare + ": not an executable airr");
    builds.push_back({"other build", fs::absolute(compare).string()});
  }
  return builds;
}

std::string run_build(const build_under_test& b, const std::string& args, const std::string& what) {
  const std::string cmd = shell_quoted(b.airr) + " " + args + " 2>&1";
  std::unique_ptr<FILE, int (*)(FILE*)> pipe(::popen(cmd.c_str(), "r"), ::pclose);
  if (!pipe) throw airr::input_error(what + ": cannot run " + b.airr);
  std::string out;
  std::array<char, 4096> buf;
  std::size_t n;
  while ((n = std::fread(buf.data(), 1, buf.size(), pipe.get())) > 0) out.append(buf.data(), n);
  const int status = ::pclose(pipe.release());
  if (status != 0) throw airr::input_error(what + ": " + b.airr + " failed: " + last_line(out));
  return out;
}

std::string last_line(const std::string& text) {
  const std::size_t end = text.find_last_not_of('\n');
  if (end == std::string::npos) return {};
  const std::size_t begin = text.rfind('\n', end);
  const std::size_t from = begin == std::string::npos ? 0 : begin + 1;
  return text.substr(from, end + 1 - from);
}

scratch_dir::scratch_dir(const std::string& what) {
  std::string tmpl = (fs::temp_directory_path() / ("airr-" + what + "-XXXXXX")).string();
  if (!::mkdtemp(tmpl.data()))
    throw airr::input_error(what + ": cannot create a temporary directory in " + fs::temp_directory_path().string());
  path = tmpl;
}

scratch_dir::~scratch_dir() {
  std::error_code ec;
  fs::remove_all(path, ec);
}
