#pragma once
// The layout panel's polarization rows (private to the panels room; docs/polarization.md): the
// display's light, the half mirror's kind with its polarizer or plate, films on a part's faces,
// and the observer's polarizer.
#include <string>
#include <vector>

#include "airr/layout/scene.hpp"

namespace airr::ui {

void display_light_rows(source_polarization& light);
// The kind, then its rows: R and T of a plain half mirror, a reflective polarizer's axis and
// values, a plate's thickness, index and coatings; the derived R and T follow every edit.
void half_mirror_rows(half_mirror_params& hm);
// Each film with its rows and a button to take it off; buttons to lay a retarder or a polarizer
// on the part's front face. `part`: the part's --set key, e.g. "retroreflectors.0".
void film_rows(std::vector<film_params>& films, const std::string& part);
void analyzer_row(observer_params& o);

}  // namespace airr::ui
