#pragma once
// What reading a glTF layout decides and notes beyond its parts (private to the formats library):
// where the observer comes from, which image the display shows, and whether the file's scale
// looks wrong.
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "airr/formats/gltf_layout.hpp"
#include "gltf_read.hpp"

namespace airr::gltf {

// Sets out.document["observer"] by the precedence gltf_layout.hpp describes, from the observer
// node (-1: none) and the scene extras' observer_source ("camera" or "extras"), with a note saying
// which was used. Needs the document's source and half mirror poses.
void place_observer(const file& f, int node, const std::string& observer_source, gltf_layout& out);

// The display's image: the file its extras name (`source`'s "image", relative to the glTF's
// folder) when it exists, else the base-colour texture of the display node's mesh, if it has one,
// extracted (gltf_images.hpp) and read once (a damaged one is an error naming the file and the
// node); source["image"] then names that file. With a texture, a note says which was used.
void choose_display_image(const file& f, int node, nlohmann::json& source, std::vector<std::string>& notes);

// The scale warning for the document's optical parts (gltf_layout::scale_warning), or "".
std::string scale_warning(const nlohmann::json& doc);

}  // namespace airr::gltf
