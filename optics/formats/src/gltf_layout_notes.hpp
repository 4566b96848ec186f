#pragma once
// What reading a glTF layout decides and notes beyond its parts (private to the formats library):
// where the observer comes from, and whether the file's scale looks wrong.
#include <string>

#include <nlohmann/json.hpp>

#include "airr/formats/gltf_layout.hpp"
#include "gltf_read.hpp"

namespace airr::gltf {

// Sets out.document["observer"] by the precedence gltf_layout.hpp describes, from the observer
// node (-1: none) and the scene extras' observer_source ("camera" or "extras"), with a note saying
// which was used. Needs the document's source and half mirror poses.
void place_observer(const file& f, int node, const std::string& observer_source, gltf_layout& out);

// The scale warning for the document's optical parts (gltf_layout::scale_warning), or "".
std::string scale_warning(const nlohmann::json& doc);

}  // namespace airr::gltf
