#pragma once
// Triangle meshes in glTF 2.0 files (.gltf with external or data-URI buffers, or .glb): the part
// geometry of a layout and the props placed around it.
#include <string>

#include "airr/core/mesh.hpp"
#include "airr/layout/scene.hpp"

namespace airr {

// Loads every triangle primitive of every mesh in the file's default scene, with node transforms
// applied, in the file's own units (a part's mesh, scaled to the part). Throws input_error naming
// the file and the node or accessor at fault.
triangle_mesh load_gltf_mesh(const std::string& path);

// A prop's mesh from a glTF file (prop_mesh.hpp reads any prop): the triangles of `node` (its
// name, or "#index") and its descendants, or of the whole default scene when `node` is empty,
// leaving out nodes with a part's role (gltf_layout.hpp) and their descendants, in millimetres
// (glTF's metres x 1000) in the node's own frame, that is its world transform less the rotation
// and translation that gltf_node_rigid_pose gives (a prop's pose), with every triangle's material.
triangle_mesh load_gltf_prop_mesh(const std::string& path, const std::string& node);

// The rigid part of a node's world transform, in millimetres: the pose whose rotation is the
// nearest rotation to the node's (scale and shear go into its mesh) and whose centre is the node's
// origin. Throws input_error when the node is missing or its transform is degenerate.
pose gltf_node_rigid_pose(const std::string& path, const std::string& node);

// How a prop's triangle scatters: its surface, or with prop_surface::material, the triangle's
// glTF material: metallic (>= 0.5) and smooth (roughness <= 0.3) is a mirror of its base colour,
// anything else diffuse with its base colour as albedo. The base colour is baseColorFactor times,
// when the material has a baseColorTexture, the mean linear colour of the texture's image (its
// codes sRGB-decoded, as glTF specifies; every texel alike, texture coordinates are not read; an
// embedded image is read through the cache gltf_layout.hpp describes).
struct surface_response {
  prop_surface kind = prop_surface::absorber;  // absorber, diffuse or mirror
  glm::vec3 reflectance{0.0f};
};
surface_response prop_surface_of(const prop_params& p, const triangle_mesh& mesh, std::uint32_t triangle);

// Writes one mesh as a self-contained .gltf (buffer embedded as a data URI) or, for a .glb path,
// as GLB, atomically.
void save_gltf_mesh(const triangle_mesh& mesh, const std::string& path);

}  // namespace airr
