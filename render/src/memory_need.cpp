#include "airr/render/memory_need.hpp"

#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <new>
#include <sstream>

#include "airr/core/error.hpp"
#include "airr/render/ambient_lights.hpp"
#include "airr/render/tracer.hpp"

namespace airr {

namespace {

// Peak resident bytes of `airr render` (its session publishing images only at its target) per
// pixel and beyond the pixels, measured by `airr bench --memory` on the default scene from 2048^2 to
// 4096^2 (1 spp): 30 bytes a pixel, 93 with components (the four its dark room can have), 688 MB
// besides. Counted: while tracing, the sums 12 and their odd half 12 (single precision, turned
// into the images in place) and the model image 12, which while it is made holds its pixels'
// angles alone (5: and whether each lands on the fine grid; their paths are traced anew where
// needed); 12 a component held, and the
// encoded file's share (about 2 a component).
constexpr double final_bytes_per_pixel = 36, final_bytes_per_component = 14;
// A session publishing every wave (the designer) keeps the predictions beside the sums (24 bytes a
// pixel), makes its images beside them (24, and 12 a component) and holds a wave's new images
// beside the last (48: the estimate, its odd half and the shown mix; 12 more a component).
constexpr double wave_images_bytes = 24 + 24 + 48, wave_images_bytes_per_component = 24;
constexpr double fixed_bytes = 700e6;
// Peak resident bytes of `airr sweep --psf` (one point, one thread) beyond its 150 MB at the start:
// 48 bytes a sample at 10 million samples, 58 at 30 million (the samples' arrays doubling as
// they grow); two points on two threads took twice one point's.
constexpr double psf_bytes_per_sample = 64, psf_fixed_bytes = 16e6;

// A field of /proc/meminfo in bytes (0 when it cannot be read).
std::uint64_t meminfo_bytes(const std::string& name) {
  std::ifstream in("/proc/meminfo");
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind(name + ":", 0) != 0) continue;
    std::istringstream fields(line.substr(name.size() + 1));
    std::uint64_t kb = 0;
    fields >> kb;
    return kb * 1024;
  }
  return 0;
}

// This process's virtual size in bytes (0 when it cannot be read).
std::uint64_t virtual_bytes() {
  std::ifstream in("/proc/self/statm");
  std::uint64_t pages = 0;
  in >> pages;
  return pages * std::uint64_t(::sysconf(_SC_PAGESIZE));
}

std::string gigabytes(double bytes) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.1f GB", bytes / 1e9);
  return buf;
}

}  // namespace

memory_allowance process_memory_allowance() {
  memory_allowance a;
  const std::uint64_t available = meminfo_bytes("MemAvailable") + meminfo_bytes("SwapFree");
  if (available > 0) a = {available, "the machine's available memory and swap"};
  rlimit limit{};
  if (::getrlimit(RLIMIT_AS, &limit) == 0 && limit.rlim_cur != RLIM_INFINITY) {
    const std::uint64_t used = virtual_bytes(), cap = std::uint64_t(limit.rlim_cur);
    const std::uint64_t left = cap > used ? cap - used : 0;
    if (a.source.empty() || left < a.bytes) a = {left, "the process's address-space limit, ulimit -v"};
  }
  return a;
}

std::uint64_t render_memory_need(const scene& s, const session_params& p) {
  const std::uint64_t pixels = std::uint64_t(s.observer.width) * std::uint64_t(s.observer.height);
  // A path-expression layer: its double sums, the snapshot's floats and the image written of them.
  const std::uint64_t layers = p.layers ? pixels * 60 * p.layers->count() : 0;
  const ambient_lights ambient = make_ambient_lights(s.environment);
  const int held = !p.components         ? 0
                   : p.final_images_only ? possible_component_slots(ambient).count
                                         : all_component_slots(ambient).count;
  return std::uint64_t(fixed_bytes) + traced_pixels_memory_need(pixels, held, p.final_images_only) + layers;
}

std::uint64_t traced_pixels_memory_need(std::uint64_t pixels, int components, bool final_images_only) {
  double bytes = final_bytes_per_pixel + final_bytes_per_component * components;
  if (!final_images_only) bytes += wave_images_bytes + wave_images_bytes_per_component * components;
  return std::uint64_t(double(pixels) * bytes);
}

void check_render_memory(const scene& s, const session_params& p) {
  check_memory_need("render: " + std::to_string(s.observer.width) + " x " + std::to_string(s.observer.height) +
                        (p.components ? " with components" : ""),
                    render_memory_need(s, p));
}

std::uint64_t psf_memory_need(std::uint64_t samples) {
  return std::uint64_t(psf_fixed_bytes + psf_bytes_per_sample * double(samples));
}

void check_memory_need(const std::string& what, std::uint64_t need) {
  const memory_allowance a = process_memory_allowance();
  if (a.source.empty()) return;  // nothing known of the machine: nothing to refuse on
  if (need <= a.bytes) return;
  throw input_error(what + " needs about " + gigabytes(double(need)) + " of memory; this process may take " +
                    gigabytes(double(a.bytes)) + " more (" + a.source + ")");
}

std::string out_of_memory_message(const std::string& what) {
  const memory_allowance a = process_memory_allowance();
  return what + ": out of memory (an allocation failed" +
         (a.source.empty() ? std::string(")")
                           : "; this process may take " + gigabytes(double(a.bytes)) + " more, " + a.source + ")");
}

std::string failure_message(const std::exception& e, const std::string& what) {
  return dynamic_cast<const std::bad_alloc*>(&e) ? out_of_memory_message(what) : e.what();
}

}  // namespace airr
