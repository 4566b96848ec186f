#include "airr/core/mesh.hpp"

#include <utility>

#include "airr/core/error.hpp"

namespace airr {

triangle_mesh make_unit_panel() {
  triangle_mesh m;
  m.name = "panel";
  m.positions = {{-0.5f, -0.5f, 0.f}, {0.5f, -0.5f, 0.f}, {0.5f, 0.5f, 0.f}, {-0.5f, 0.5f, 0.f}};
  m.indices = {0, 1, 2, 0, 2, 3};
  return m;
}

mesh_bounds bounds_of(const triangle_mesh& mesh) {
  if (mesh.positions.empty()) return {};
  mesh_bounds b{mesh.positions.front(), mesh.positions.front()};
  for (const auto& p : mesh.positions) {
    b.lo = glm::min(b.lo, p);
    b.hi = glm::max(b.hi, p);
  }
  return b;
}

static mesh_file_reader& installed_reader() {
  static mesh_file_reader reader;
  return reader;
}

void install_mesh_file_reader(mesh_file_reader reader) { installed_reader() = std::move(reader); }

std::shared_ptr<const triangle_mesh> read_mesh_file(const std::string& path) {
  if (!installed_reader()) throw input_error(path + ": this program cannot read mesh files");
  return installed_reader()(path);
}

}  // namespace airr
