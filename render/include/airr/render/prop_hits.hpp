#pragma once
// The layout's props as blockers of straight lines, for the geometric viewing-zone pass (which
// lives in the optics library and cannot trace meshes itself).
#include <cstdint>

#include "airr/layout/scene.hpp"
#include "airr/layout/viewing_zone.hpp"

namespace airr {

// Where a line first meets one of the scene's visible props (an Embree scene of their meshes,
// built here and kept alive by the returned function); an empty function when there are none.
// When the props are those of the last call (same meshes at the same places: an edit of the
// observer or a part), the last call's scene is answered again, not rebuilt. Throws input_error
// when a prop's mesh cannot be read.
prop_hit_function scene_prop_hits(const scene& s);

// How many props' scenes scene_prop_hits has built in this process (for tests and benchmarks).
std::uint64_t prop_scene_builds();

}  // namespace airr
