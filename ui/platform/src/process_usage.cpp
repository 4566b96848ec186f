#include "airr/ui/platform/process_usage.hpp"

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace airr::ui {

process_usage read_process_usage() {
  process_usage u;
  std::ifstream status("/proc/self/status");
  for (std::string line; std::getline(status, line);) {
    std::istringstream fields(line);
    std::string name;
    fields >> name;
    if (name == "VmRSS:") {
      double kb = 0;
      fields >> kb;
      u.resident_mb = kb / 1024;
    } else if (name == "Threads:") {
      fields >> u.threads;
    }
  }
  std::error_code ec;
  for (auto it = std::filesystem::directory_iterator("/proc/self/fd", ec); !ec && it != decltype(it)();
       it.increment(ec))
    ++u.descriptors;
  return u;
}

}  // namespace airr::ui
