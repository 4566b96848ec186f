#pragma once
// How much brighter a layout's parts make its aerial image than a plain half mirror would
// (docs/polarization.md): `airr gain`, the designer's p-AIRR readout.
#include <cstdint>
#include <functional>

#include "airr/layout/scene.hpp"

namespace airr {

// The layout compared with: the same parts and poses, the half mirror a plain one of
// R = T = 0.5 and no films anywhere (the display's light and the observer kept).
scene with_plain_half_mirror(const scene& s);

// The aerial component's luminance summed over the image (all its light the observer sees, in
// luminance times pixels), with the scene's parts and with the plain half mirror.
struct polarization_gain {
  double aerial = 0;
  double half_mirror = 0;
  std::uint64_t spp = 0;
  double gain() const { return half_mirror > 0 ? aerial / half_mirror : 0; }
};

// Renders both layouts' aerial components at `spp` (threads as render_session's); `progress`
// hears 0, 1 and 2 renders done. Throws measurement_error when the compared layout forms no
// aerial image in view.
polarization_gain measure_polarization_gain(const scene& s, std::uint64_t spp, int threads = 0,
                                            const std::function<void(int)>& progress = {});

}  // namespace airr
