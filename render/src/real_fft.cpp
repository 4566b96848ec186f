#include "real_fft.hpp"

#include <fftw3.h>

#include <map>
#include <mutex>
#include <new>
#include <utility>

namespace airr::model_image_steps {

namespace {

// Kept for the process's life and destroyed with it (a clean exit leaves nothing allocated).
struct plans {
  fftwf_plan forward = nullptr, inverse = nullptr;
  plans() = default;
  plans(const plans&) = delete;
  plans& operator=(const plans&) = delete;
  ~plans() {
    if (forward) fftwf_destroy_plan(forward);
    if (inverse) fftwf_destroy_plan(inverse);
  }
};

std::mutex planner;

// FFTW_ESTIMATE: a plan in milliseconds (FFTW_MEASURE's second-long search would cost more than
// one model image saves).
const plans& plans_for(int width, int height) {
  static std::map<std::pair<int, int>, plans> kept;
  const std::lock_guard lock(planner);
  plans& p = kept[{width, height}];
  if (!p.forward || !p.inverse) {  // new, or a failed plan before
    const std::size_t reals = std::size_t(width) * height, complexes = std::size_t(height) * (width / 2 + 1);
    fft_buffer<float> r = real_buffer(reals);
    fft_buffer<std::complex<float>> c = complex_buffer(complexes);
    auto* cc = reinterpret_cast<fftwf_complex*>(c.data.get());
    if (!p.forward) p.forward = fftwf_plan_dft_r2c_2d(height, width, r.data.get(), cc, FFTW_ESTIMATE);
    if (!p.inverse) p.inverse = fftwf_plan_dft_c2r_2d(height, width, cc, r.data.get(), FFTW_ESTIMATE);
    if (!p.forward || !p.inverse) throw std::bad_alloc();
  }
  return p;
}

}  // namespace

fft_buffer<float> real_buffer(std::size_t n) {
  float* p = fftwf_alloc_real(n);
  if (!p) throw std::bad_alloc();
  return {{p, [](float* q) { fftwf_free(q); }}, n};
}

fft_buffer<std::complex<float>> complex_buffer(std::size_t n) {
  auto* p = reinterpret_cast<std::complex<float>*>(fftwf_alloc_complex(n));
  if (!p) throw std::bad_alloc();
  return {{p, [](std::complex<float>* q) { fftwf_free(reinterpret_cast<fftwf_complex*>(q)); }}, n};
}

void fft_forward(int width, int height, float* in, std::complex<float>* out) {
  fftwf_execute_dft_r2c(plans_for(width, height).forward, in, reinterpret_cast<fftwf_complex*>(out));
}

void fft_inverse(int width, int height, std::complex<float>* in, float* out) {
  fftwf_execute_dft_c2r(plans_for(width, height).inverse, reinterpret_cast<fftwf_complex*>(in), out);
}

}  // namespace airr::model_image_steps
