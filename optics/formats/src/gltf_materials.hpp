#pragma once
// glTF materials as the tracer sees them (private to the formats library): a material's base
// colour, metallic and roughness, its base-colour texture counted by its mean.
#include <cstdint>
#include <string>

#include <glm/glm.hpp>

#include "gltf_read.hpp"

namespace airr::gltf {

// The index in out.materials of glTF material `material` (-1: glTF's default material), added
// when no equal one is there yet. Its base colour is baseColorFactor times, when the material has
// a baseColorTexture, the texture's mean linear colour (texture_mean_linear). `what` names the
// node in errors.
std::uint32_t material_slot(const file& f, int material, const std::string& what, triangle_mesh& out);

// The mean linear colour of the texture's image, every texel alike (texture coordinates are not
// read), its code values sRGB-decoded whatever their depth, as glTF specifies for base colour.
// Throws input_error "<file>: <what>: image N: ..." for a missing or unreadable image.
glm::vec3 texture_mean_linear(const file& f, int texture, const std::string& what);

// The base-colour texture of the node's own mesh: that of its first primitive whose material has
// one (-1: none).
int base_color_texture(const file& f, int node);

}  // namespace airr::gltf
