#pragma once
// The views: what the designer shows of the studio's state, one file each (view_render.cpp,
// view_layout.cpp, view_3d.cpp, view_plots.cpp, view_bokeh.cpp).
#include <imgui.h>

#include "airr/ui/studio/studio.hpp"

namespace airr::ui {

void draw_render_view(studio& st, double now_seconds);
// The colour the 3D and layout views draw the Ghosts window's class's paths in (magenta).
inline constexpr glm::vec4 ghost_path_colour{1.0f, 0.0f, 1.0f, 1.0f};
void draw_layout_view(studio& st);
// The 3D layout view in the screen rectangle at `at` of `size` (inside the layout view's window).
void draw_view_3d(studio& st, ImVec2 at, ImVec2 size);
// The Plots window: MTF, PSF, mean MTF against D, the viewing zone; its Bokeh tab.
void draw_plots_panel(studio& st);
void draw_bokeh_tab(studio& st);
// Starts the viewing zone's full pass for the applied layout, on the predicted map's sphere
// (false while the predicted plots are not yet those of the current layout).
bool start_full_zone(studio& st);
// The viewing zone's quantities, in the order of its menu (studio::zone_quantity), as
// airr-studio --zone names them; all but the first come from the full pass.
inline constexpr const char* zone_quantity_keys[] = {"visible",    "brightness", "mtf",         "stray",
                                                     "luminance",  "contrast",   "legible-1.5", "legible-3",
                                                     "legible-25", "char-height"};

}  // namespace airr::ui
