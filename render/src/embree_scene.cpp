#include "airr/render/embree_scene.hpp"

#include <cstdint>
#include <string>

namespace airr {

std::string prop_mesh_key(const prop_params& p, const triangle_mesh* mesh) {
  return "prop:" + p.mesh + "#" + p.node + "@" + std::to_string(reinterpret_cast<std::uintptr_t>(mesh));
}

}  // namespace airr
