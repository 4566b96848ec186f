#pragma once
// An OpenGL texture holding an 8-bit RGBA image, owned (deleted with the object).
#include <cstdint>
#include <vector>

namespace airr::ui {

class gl_texture {
 public:
  gl_texture() = default;
  ~gl_texture();
  gl_texture(const gl_texture&) = delete;
  gl_texture& operator=(const gl_texture&) = delete;

  void upload(int width, int height, const std::vector<std::uint8_t>& rgba);
  unsigned id() const { return id_; }
  int width() const { return width_; }
  int height() const { return height_; }

 private:
  unsigned id_ = 0;
  int width_ = 0, height_ = 0;
};

}  // namespace airr::ui
