#pragma once
// The light reaching the observer as Stokes images (docs/polarization.md): `airr render --stokes`.
#include <array>
#include <cstdint>
#include <functional>

#include "airr/formats/image.hpp"
#include "airr/layout/scene.hpp"

namespace airr {

// S0 to S3 of the light reaching the observer, before its polarizer, per channel, in the image's
// frame (x its right, y its up; S1 = I_right - I_up, S3 > 0 when the field turns from right
// towards up), and the degree of polarization sqrt(S1^2 + S2^2 + S3^2) / S0 (0 where S0 is not
// positive). The four are traced with the same samples, so their noise is shared.
struct stokes_images {
  std::array<image_rgb, 4> s;  // layers S0 to S3 of an EXR file
  image_rgb degree;
  std::uint64_t spp = 0;
};

// The EXR layers a Stokes render writes: S0 to S3, then the degree of polarization.
inline constexpr const char* stokes_layer_names[] = {"S0", "S1", "S2", "S3", "dop"};

// Renders the four at `spp` (threads as render_session's); `progress` hears the parameter being
// traced (0 to 3) and its samples per pixel so far.
stokes_images render_stokes(const scene& s, std::uint64_t spp, int threads = 0,
                            const std::function<void(int, std::uint64_t)>& progress = {});

}  // namespace airr
