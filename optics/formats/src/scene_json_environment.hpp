#pragma once
// The scene file's environment (docs/scene-format.md): the room, the sun and the luminaires; and
// the pose every placed thing has (private to the formats library).
#include <nlohmann/json.hpp>

#include "airr/core/json_reader.hpp"
#include "airr/formats/scene_json.hpp"
#include "airr/layout/scene.hpp"

namespace airr {

nlohmann::json pose_to_json(const pose& p);
void read_pose(json_reader r, pose& p);

// Written only when set (or in the complete form), so layouts in a dark room keep their form.
bool environment_written(const environment_params& e, json_form form);
nlohmann::json environment_to_json(const environment_params& e);
void read_environment(json_reader r, environment_params& e);

}  // namespace airr
