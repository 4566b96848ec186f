#pragma once
// The layout's props as blockers of straight lines, for the geometric viewing-zone pass (which
// lives in the optics library and cannot trace meshes itself).
#include "airr/layout/scene.hpp"
#include "airr/layout/viewing_zone.hpp"

namespace airr {

// Where a line first meets one of the scene's visible props (an Embree scene of their meshes,
// built here and kept alive by the returned function); an empty function when there are none.
// Throws input_error when a prop's mesh cannot be read.
prop_hit_function scene_prop_hits(const scene& s);

}  // namespace airr
