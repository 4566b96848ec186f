#pragma once
// How the model PSF's samples are drawn, for the observer's PSF and the through-focus bundle
// alike: sample i's six numbers (a rotated R6 point, so that its dimensions stratify each other
// across the samples, or independent ones) and its retroreflection samples, over blocks that run in
// parallel and join in order, so that the result does not depend on the number of threads.
#include <algorithm>
#include <array>
#include <cstdint>
#include <vector>

#include <tbb/parallel_for.h>

#include "airr/core/low_discrepancy.hpp"
#include "airr/core/random.hpp"
#include "airr/models/retro_model.hpp"

namespace airr {

// body(point, retro, part) for every sample, `part` the sample's block's; the parts in order.
// `stream` and `salt` keep different users' sequences apart.
template <class Part, class Body>
std::vector<Part> sample_in_blocks(std::uint64_t samples, std::uint64_t seed, std::uint64_t stream, std::uint64_t salt,
                                   bool stratified, const Body& body) {
  std::array<double, 6> rotation;
  pcg32 rotation_rng = sample_rng(0, stream, seed ^ salt);
  for (double& r : rotation) r = rotation_rng.next_double();
  constexpr std::uint64_t block = 8192;
  const std::size_t blocks = std::size_t((samples + block - 1) / block);
  std::vector<Part> parts(blocks);
  tbb::parallel_for(std::size_t(0), blocks, [&](std::size_t k) {
    const std::uint64_t end = std::min<std::uint64_t>(samples, (k + 1) * block);
    for (std::uint64_t i = k * block; i < end; ++i) {
      pcg32 rng = sample_rng(i, stream, seed);
      std::array<double, 6> point;
      if (stratified) {
        point = r6_point(i, rotation);
      } else {
        for (double& x : point) x = rng.next_double();
      }
      retro_samples u;
      u.lobe = {point[2], point[3]};
      u.shift = {point[4], point[5]};
      u.more = rng.split();
      body(point, u, parts[k]);
    }
  });
  return parts;
}

}  // namespace airr
