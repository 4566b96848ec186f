#pragma once
// The 3D layout view's drawing: shaded triangles and lines rendered by OpenGL 3.3 into a texture
// that the view shows. Large meshes (props) are uploaded once and kept while they live.
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "airr/formats/mesh_gltf.hpp"

namespace airr::ui {

// Something to draw: triangles (shaded by their normals, both faces alike) or lines (unlit).
struct gl_draw_item {
  std::shared_ptr<const triangle_mesh> mesh;  // triangles, kept on the GPU while the mesh lives
  std::vector<glm::vec3> lines;               // or line segments, two points each (world mm)
  std::vector<glm::vec3> triangles;           // or small triangle lists, three points each (world mm)
  glm::mat4 model{1.0f};                      // the mesh's placement
  glm::vec4 colour{1.0f};                     // alpha < 1: drawn blended after the opaque items
};

class gl_layout_renderer {
 public:
  gl_layout_renderer() = default;
  ~gl_layout_renderer();
  gl_layout_renderer(const gl_layout_renderer&) = delete;
  gl_layout_renderer& operator=(const gl_layout_renderer&) = delete;

  // Renders the items with the view-projection matrix into the texture (resized to width x
  // height); false with error() set when OpenGL cannot (the shaders failed to build).
  bool render(int width, int height, const glm::mat4& view_projection, const std::vector<gl_draw_item>& items);
  unsigned texture() const { return colour_; }
  const std::string& error() const { return error_; }

 private:
  struct gpu_mesh {
    unsigned vao = 0, vbo = 0;
    int vertices = 0;
    std::weak_ptr<const triangle_mesh> source;
  };
  bool ensure_program();
  void ensure_target(int width, int height);
  const gpu_mesh& upload(const std::shared_ptr<const triangle_mesh>& mesh);
  void draw_vertices(const std::vector<float>& interleaved, unsigned mode);

  unsigned program_ = 0, fbo_ = 0, colour_ = 0, depth_ = 0, scratch_vao_ = 0, scratch_vbo_ = 0;
  int width_ = 0, height_ = 0;
  int loc_mvp_ = -1, loc_model_ = -1, loc_colour_ = -1, loc_lit_ = -1;
  std::string error_;
  std::map<const triangle_mesh*, gpu_mesh> meshes_;
};

}  // namespace airr::ui
