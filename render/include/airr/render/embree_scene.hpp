#pragma once
// The layout's Embree scene (an embree_instanced_scene, core/embree.hpp): its parts' instance
// ids and the prototype keys of its props.
#include <string>

#include "airr/core/embree.hpp"
#include "airr/formats/mesh_gltf.hpp"

namespace airr {

// The parts of an AIRR layout; the instance id of a hit says which one: the display, the half
// mirror, then the retroreflective sheets in order from part_first_sheet, then the visible props.
enum part_id : unsigned { part_source = 0, part_half_mirror = 1, part_first_sheet = 2 };

// A prop's prototype key: its file and node, and the loaded mesh (a file changed on disk is a new
// mesh, so a new prototype).
std::string prop_mesh_key(const prop_params& p, const triangle_mesh* mesh);

}  // namespace airr
