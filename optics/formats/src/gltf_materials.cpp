#include "gltf_materials.hpp"

#include <algorithm>
#include <cmath>

#include "airr/core/error.hpp"
#include "airr/core/files.hpp"
#include "airr/formats/image.hpp"
#include "gltf_images.hpp"

namespace airr::gltf {

std::uint32_t material_slot(const file& f, int material, const std::string& what, triangle_mesh& out) {
  mesh_material mm;
  if (material >= 0) {
    if (std::size_t(material) >= f.model.materials.size()) {
      throw input_error(f.path + ": material " + std::to_string(material) + " does not exist");
    }
    const tinygltf::Material& gm = f.model.materials[std::size_t(material)];
    const auto& pbr = gm.pbrMetallicRoughness;
    mm.name = gm.name;
    auto unit = [](double v) { return std::isfinite(v) ? float(std::clamp(v, 0.0, 1.0)) : 0.0f; };
    if (pbr.baseColorFactor.size() >= 3) {
      mm.base_color = {unit(pbr.baseColorFactor[0]), unit(pbr.baseColorFactor[1]), unit(pbr.baseColorFactor[2])};
    }
    if (pbr.baseColorTexture.index >= 0) {
      const glm::vec3 mean =
          texture_mean_linear(f, pbr.baseColorTexture.index, what + ": material " + std::to_string(material));
      mm.base_color = glm::clamp(mm.base_color * mean, 0.0f, 1.0f);
    }
    mm.metallic = unit(pbr.metallicFactor);
    mm.roughness = unit(pbr.roughnessFactor);
  }
  for (std::size_t k = 0; k < out.materials.size(); ++k) {
    if (out.materials[k] == mm) return std::uint32_t(k);
  }
  out.materials.push_back(mm);
  return std::uint32_t(out.materials.size() - 1);
}

glm::vec3 texture_mean_linear(const file& f, int texture, const std::string& what) {
  // Kept while the glTF is unchanged: every primitive of a large model may use the texture.
  static file_cache<glm::vec3> means;
  return *means.get(f.path + "#texture" + std::to_string(texture), f.path, [&] {
    const int image = texture_image(f, texture, what);
    glm::dvec3 sum(0.0);
    std::size_t texels = 1;
    read_image_file(f, image, what + ": texture " + std::to_string(texture), [&](const std::string& path) {
      const image_rgb px = load_image(path, image_encoding::srgb).pixels;
      for (std::size_t i = 0; i < px.rgb.size(); i += 3) sum += glm::dvec3(px.rgb[i], px.rgb[i + 1], px.rgb[i + 2]);
      texels = px.rgb.size() / 3;
    });
    return std::make_shared<const glm::vec3>(sum / double(texels));
  });
}

int base_color_texture(const file& f, int node) {
  const int mesh = f.model.nodes[std::size_t(node)].mesh;
  if (mesh < 0 || std::size_t(mesh) >= f.model.meshes.size()) return -1;
  for (const tinygltf::Primitive& p : f.model.meshes[std::size_t(mesh)].primitives) {
    if (p.material < 0 || std::size_t(p.material) >= f.model.materials.size()) continue;
    const int texture = f.model.materials[std::size_t(p.material)].pbrMetallicRoughness.baseColorTexture.index;
    if (texture >= 0) return texture;
  }
  return -1;
}

}  // namespace airr::gltf
