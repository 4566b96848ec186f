#include <filesystem>

#include "airr/core/files.hpp"
#include "airr/formats/image.hpp"
#include "gltf_images.hpp"
#include "gltf_layout_notes.hpp"
#include "gltf_materials.hpp"

namespace airr::gltf {

void choose_display_image(const file& f, int node, nlohmann::json& source, std::vector<std::string>& notes) {
  const int texture = base_color_texture(f, node);
  const nlohmann::json named = source.value("image", nlohmann::json(""));
  if (texture < 0 || !named.is_string()) return;  // a wrong type is the scene reader's to name
  const std::string name = named.get<std::string>();
  const std::string head = "note: " + f.path + ": display image: ";
  std::error_code ec;
  if (!name.empty() &&
      std::filesystem::exists(resolve_path(name, std::filesystem::path(f.path).parent_path().string()), ec)) {
    notes.push_back(head + name + ", which the display's extras name (its mesh's texture is not used)");
    return;
  }
  const std::string what = node_label(f, node) + ": base-colour texture " + std::to_string(texture);
  const int image = texture_image(f, texture, what);
  std::string path;
  read_image_file(f, image, what, [&](const std::string& p) {
    cached_image_pixels(p);  // read now, so that a damaged image is named here
    path = p;
  });
  source["image"] = path;
  const std::string used = is_embedded_image(f, image) ? "the file's embedded texture"
                                                       : "its mesh's texture " + f.model.images[std::size_t(image)].uri;
  const std::string why =
      name.empty() ? "the display's extras name no image"
                   : name + " not found" + (std::filesystem::path(name).is_relative() ? " next to the layout" : "");
  notes.push_back(head + used + " (" + why + ")");
}

}  // namespace airr::gltf
