#include "real_fft.hpp"

#include <fftw3.h>
#include <sys/mman.h>

#include <algorithm>
#include <cstring>
#include <map>
#include <mutex>
#include <new>
#include <tuple>
#include <utility>

namespace airr::model_image_steps {

namespace {

// A plan kept for the process's life and destroyed with it (a clean exit leaves nothing allocated).
struct kept_plan {
  fftwf_plan plan = nullptr;
  kept_plan() = default;
  kept_plan(const kept_plan&) = delete;
  kept_plan& operator=(const kept_plan&) = delete;
  ~kept_plan() {
    if (plan) fftwf_destroy_plan(plan);
  }
};

struct plans {
  kept_plan forward, inverse;
};

// Transforms along x of a number of rows, out of place; and along y of every column, in place.
struct end_row_plans {
  kept_plan rows, columns;
};

std::mutex planner;

// FFTW_ESTIMATE: a plan in milliseconds (FFTW_MEASURE's second-long search would cost more than
// one model image saves).
const plans& plans_for(int width, int height) {
  static std::map<std::pair<int, int>, plans> kept;
  const std::lock_guard lock(planner);
  plans& p = kept[{width, height}];
  if (!p.forward.plan || !p.inverse.plan) {  // new, or a failed plan before
    const std::size_t reals = std::size_t(width) * height, complexes = std::size_t(height) * (width / 2 + 1);
    fft_buffer<float> r = real_buffer(reals);
    fft_buffer<std::complex<float>> c = complex_buffer(complexes);
    auto* cc = reinterpret_cast<fftwf_complex*>(c.data.get());
    if (!p.forward.plan) p.forward.plan = fftwf_plan_dft_r2c_2d(height, width, r.data.get(), cc, FFTW_ESTIMATE);
    if (!p.inverse.plan) p.inverse.plan = fftwf_plan_dft_c2r_2d(height, width, cc, r.data.get(), FFTW_ESTIMATE);
    if (!p.forward.plan || !p.inverse.plan) throw std::bad_alloc();
  }
  return p;
}

const end_row_plans& end_row_plans_for(int width, int height, int count) {
  static std::map<std::tuple<int, int, int>, end_row_plans> kept;
  const std::lock_guard lock(planner);
  end_row_plans& p = kept[{width, height, count}];
  if (!p.rows.plan || !p.columns.plan) {
    const int spectrum_width = width / 2 + 1;
    fft_buffer<float> r = real_buffer(std::size_t(width) * count);
    fft_buffer<std::complex<float>> c = complex_buffer(std::size_t(height) * spectrum_width);
    auto* cc = reinterpret_cast<fftwf_complex*>(c.data.get());
    if (!p.rows.plan)
      p.rows.plan = fftwf_plan_many_dft_r2c(1, &width, count, r.data.get(), nullptr, 1, width, cc, nullptr, 1,
                                            spectrum_width, FFTW_ESTIMATE);
    if (!p.columns.plan)
      p.columns.plan = fftwf_plan_many_dft(1, &height, spectrum_width, cc, nullptr, spectrum_width, 1, cc, nullptr,
                                           spectrum_width, 1, FFTW_FORWARD, FFTW_ESTIMATE);
    if (!p.rows.plan || !p.columns.plan) throw std::bad_alloc();
  }
  return p;
}

// Buffers are mapped straight from the system, not taken from the heap: a grid's (tens of MB) go
// back when freed, where from a thread's malloc arena they stayed resident and raised a render's
// later peak. The mapping's length is kept in a header before the data, as long as FFTW's
// alignment needs.
constexpr std::size_t header = 64;

void* map_bytes(std::size_t bytes) {
  const std::size_t total = bytes + header;
  void* base = mmap(nullptr, total, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS | MAP_POPULATE, -1, 0);
  if (base == MAP_FAILED) throw std::bad_alloc();
  *static_cast<std::size_t*>(base) = total;
  return static_cast<char*>(base) + header;
}

void unmap_bytes(void* p) {
  if (!p) return;
  char* base = static_cast<char*>(p) - header;
  munmap(base, *reinterpret_cast<std::size_t*>(base));
}

}  // namespace

fft_buffer<float> real_buffer(std::size_t n) {
  return {{static_cast<float*>(map_bytes(n * sizeof(float))), [](float* q) { unmap_bytes(q); }}, n};
}

fft_buffer<std::complex<float>> complex_buffer(std::size_t n) {
  return {{static_cast<std::complex<float>*>(map_bytes(n * sizeof(std::complex<float>))),
           [](std::complex<float>* q) { unmap_bytes(q); }},
          n};
}

void fft_forward(int width, int height, float* in, std::complex<float>* out) {
  fftwf_execute_dft_r2c(plans_for(width, height).forward.plan, in, reinterpret_cast<fftwf_complex*>(out));
}

void fft_inverse(int width, int height, std::complex<float>* in, float* out) {
  fftwf_execute_dft_c2r(plans_for(width, height).inverse.plan, reinterpret_cast<fftwf_complex*>(in), out);
}

void fft_forward_end_rows(int width, int height, int top, int bottom, float* rows, std::complex<float>* out) {
  const int count = top + bottom;
  const std::size_t spectrum_width = std::size_t(width) / 2 + 1;
  const end_row_plans& p = end_row_plans_for(width, height, count);
  // The rows' spectra side by side at the array's start, then each moved to its row (the bottom
  // ones first: they move down, past where the top ones stay).
  auto* cc = reinterpret_cast<fftwf_complex*>(out);
  fftwf_execute_dft_r2c(p.rows.plan, rows, cc);
  std::complex<float>* bottom_at = out + (std::size_t(height) - std::size_t(bottom)) * spectrum_width;
  std::memmove(bottom_at, out + std::size_t(top) * spectrum_width, std::size_t(bottom) * spectrum_width * sizeof(*out));
  std::fill(out + std::size_t(top) * spectrum_width, bottom_at, std::complex<float>(0));
  fftwf_execute_dft(p.columns.plan, cc, cc);
}

}  // namespace airr::model_image_steps
