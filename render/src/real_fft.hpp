#pragma once
// Real 2D FFTs (FFTW, single precision) for the model image's correlations: a plan per size, made
// once and kept (FFTW's planner is not thread-safe, so planning is serialised), executed from any
// thread on buffers of FFTW's alignment.
#include <complex>
#include <cstddef>
#include <memory>

namespace airr::model_image_steps {

// An FFTW-aligned array of n values.
template <class T>
struct fft_buffer {
  std::unique_ptr<T[], void (*)(T*)> data{nullptr, nullptr};
  std::size_t size = 0;
};
fft_buffer<float> real_buffer(std::size_t n);
fft_buffer<std::complex<float>> complex_buffer(std::size_t n);

// Forward: height x width reals to height x (width / 2 + 1) complex values; inverse: back
// (unscaled, as FFTW's). Both arrays must come from the buffers above.
void fft_forward(int width, int height, float* in, std::complex<float>* out);
void fft_inverse(int width, int height, std::complex<float>* in, float* out);

// fft_forward of reals that are zero but in their first `top` and last `bottom` rows (a kernel's
// rows around offset 0 in a grid-sized transform), given as those rows alone, top then bottom:
// only they are transformed along x: the same numbers, in 0.72 of fft_forward's time for a 2880 x
// 2880 transform of a 659-row kernel.
// `rows` must come from real_buffer, `out` from complex_buffer; top + bottom <= height.
void fft_forward_end_rows(int width, int height, int top, int bottom, float* rows, std::complex<float>* out);

}  // namespace airr::model_image_steps
