#pragma once
// What every exported render carries: spp, seed, the layout JSON, the pixel size in mm and the units.
#include <cstdio>
#include <string>

#include "airr/formats/image.hpp"
#include "airr/formats/scene_json.hpp"
#include "airr/render/render_session.hpp"

namespace airr {

// Maps a white source seen through a lossless retroreflector to display white.
inline double default_exposure(const scene& s) {
  const double white = white_radiance(s.source) * s.half_mirror.reflectance * s.half_mirror.transmittance;
  return white > 0 ? 1.0 / white : 1.0;
}

inline image_metadata render_metadata(const scene& s, const render_snapshot& snap, double exposure) {
  char mm[64], ex[64];
  std::snprintf(mm, sizeof mm, "%.17g", snap.mm_per_pixel);
  std::snprintf(ex, sizeof ex, "%.9g", exposure);
  return {{"airr:spp", std::to_string(snap.spp)},
          {"airr:seed", std::to_string(s.seed)},
          {"airr:layout", scene_to_json(s).dump()},
          {"airr:mm_per_pixel", mm},
          {"airr:exposure", ex},
          {"airr:units", image_units(s.source)},
          {"airr:generator", "airr render"}};
}

}  // namespace airr
