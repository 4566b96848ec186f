#pragma once
// The scene file's polarization fields (docs/scene-format.md): the display's light, films on a
// part's faces, the reflective polarizer and the plate (private to the formats library).
#include <array>
#include <vector>

#include <nlohmann/json.hpp>

#include "airr/core/json_reader.hpp"
#include "airr/layout/scene.hpp"

namespace airr {

nlohmann::json polarization_to_json(const source_polarization& p);
void read_polarization(json_reader r, source_polarization& p);

nlohmann::json films_to_json(const std::vector<film_params>& films);
// Reads the part's "films" when present.
void read_films(json_reader& part, std::vector<film_params>& films);

nlohmann::json reflective_polarizer_to_json(const reflective_polarizer_params& p);
void read_reflective_polarizer(json_reader r, reflective_polarizer_params& p);

inline constexpr std::array half_mirror_kind_names{"half_mirror", "reflective_polarizer", "plate"};
nlohmann::json plate_to_json(const plate_params& p);
void read_plate(json_reader r, plate_params& p);

}  // namespace airr
