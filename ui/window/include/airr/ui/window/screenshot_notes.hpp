#pragma once
// What a scripted screenshot showed, beside it as JSON for the checks of the picture: the panels'
// rectangles, the layout views' labels, outlines and marks, and the Bokeh tab's numbers (when open),
// all in framebuffer pixels.
#include <string>

#include "airr/ui/studio/studio.hpp"

namespace airr::ui {

// `sx`, `sy`: framebuffer pixels per window unit. Throws input_error when the file cannot be written.
void write_screenshot_notes(const studio& st, const std::string& path, int fw, int fh, float sx, float sy);

}  // namespace airr::ui
