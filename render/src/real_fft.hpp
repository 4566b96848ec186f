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

}  // namespace airr::model_image_steps
