#pragma once
// Counter-based random numbers: every sample is seeded from (pixel, sample index, seed), so the
// result does not depend on which thread draws it or in which order.
#include <cstdint>

namespace airr {

inline std::uint64_t mix64(std::uint64_t z) {
  z += 0x9e3779b97f4a7c15ull;
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
  return z ^ (z >> 31);
}

// PCG32 (XSH-RR): small state, good statistics.
class pcg32 {
 public:
  pcg32(std::uint64_t seed, std::uint64_t stream) : inc_((stream << 1u) | 1u) {
    next_u32();
    state_ += seed;
    next_u32();
  }
  std::uint32_t next_u32() {
    const std::uint64_t old = state_;
    state_ = old * 6364136223846793005ull + inc_;
    const auto xorshifted = static_cast<std::uint32_t>(((old >> 18u) ^ old) >> 27u);
    const auto rot = static_cast<std::uint32_t>(old >> 59u);
    return (xorshifted >> rot) | (xorshifted << ((32u - rot) & 31u));
  }
  // Uniform in [0, 1).
  double next_double() {
    const std::uint64_t hi = next_u32(), lo = next_u32();
    return double(((hi << 32) | lo) >> 11) * 0x1.0p-53;
  }
  float next_float() { return float(next_u32() >> 8) * 0x1.0p-24f; }
  // An independent generator seeded from this one's next two numbers.
  pcg32 split() {
    const std::uint64_t hi = next_u32(), lo = next_u32();
    return pcg32(mix64((hi << 32) | lo), lo);
  }

 private:
  std::uint64_t state_ = 0;
  std::uint64_t inc_;
};

inline pcg32 sample_rng(std::uint64_t pixel, std::uint64_t sample, std::uint64_t seed) {
  return pcg32(mix64(pixel ^ mix64(seed)), mix64(sample + 0x51ed270b2ull * (seed + 1)));
}

}  // namespace airr
