#pragma once
// The layout panel's rows (private to the panels room): a number as a slider plus a typed value
// with its unit, whose label's context menu offers its --set key to the design windows.
#include <optional>
#include <string>

#include "airr/layout/scene.hpp"

namespace airr::ui {

// One row: slider over [lo, hi], a typed field (may go beyond the slider), label with unit. With
// its --set key, the label's context menu offers the row to the Optimise and Tolerance windows.
bool edit_number(const char* label, double& v, double lo, double hi, const char* unit, const char* fmt = "%.2f",
                 const char* help = nullptr, const std::string& key = {});
bool edit_int(const char* label, int& v, int lo, int hi, const char* unit);
// The pose rows of a part: centre and the three angles; `part` is its --set key, e.g. "half_mirror".
void edit_pose(pose& p, double reach_mm, const std::string& part);

// A row the designer picked, by its --set key, from the row's context menu: a variable of the
// Optimise window or a tolerance of the Tolerance window; taken once.
struct design_pick {
  std::string key;
  bool tolerance = false;
};
std::optional<design_pick> take_design_pick();

}  // namespace airr::ui
