#pragma once
// A progressive 6-D low-discrepancy sequence (the Kronecker sequence R6: x_i = frac(i * alpha),
// alpha_k = phi^-k, phi the positive root of x^7 = x + 1). Any prefix of it covers the cube
// evenly; a random per-pixel rotation (Cranley-Patterson) keeps each point uniform, so estimates
// stay unbiased while samples of one pixel stratify each other.
#include <array>
#include <cmath>
#include <cstdint>

namespace airr {

inline constexpr std::array<double, 6> r6_alpha = {0.8986537126286992, 0.8075784952213447, 0.7257334129697596,
                                                   0.6521830259439715, 0.5860866975779692, 0.5266889867007356};

inline std::array<double, 6> r6_point(std::uint64_t i, const std::array<double, 6>& rotation) {
  const std::array<double, 6>& alpha = r6_alpha;
  std::array<double, 6> u{};
  for (int k = 0; k < 6; ++k) {
    // i * alpha mod 1 without losing precision for large i: split i into high and low parts.
    // (x - floor(x) is fmod(x, 1) exactly for x >= 0, and much cheaper.)
    const double h = double(i >> 26) * 67108864.0 * alpha[k], l = double(i & 67108863u) * alpha[k];
    const double hi = h - std::floor(h), lo = l - std::floor(l);
    double v = hi + lo + rotation[k];
    v -= std::floor(v);
    u[k] = v;
  }
  return u;
}

// The sequence's first four coordinates point after point (from point 0, rotated by 0.5 each way):
// a step adds alpha, so a short run costs no more than a grid.
struct r4_walk {
  std::array<double, 4> u{0.5, 0.5, 0.5, 0.5};
  void next() {
    for (int k = 0; k < 4; ++k) {
      u[k] += r6_alpha[k];
      if (u[k] >= 1) u[k] -= 1;
    }
  }
};

}  // namespace airr
