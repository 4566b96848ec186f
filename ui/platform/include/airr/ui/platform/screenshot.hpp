#pragma once
// Reads the current OpenGL framebuffer and writes it as an 8-bit PNG, atomically.
#include <string>

namespace airr::ui {

void write_framebuffer_png(const std::string& path, int width, int height);

}  // namespace airr::ui
