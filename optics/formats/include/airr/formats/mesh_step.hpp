#pragma once
// Triangle meshes from STEP files (AP203, AP214, AP242), the format mechanical CAD exchanges
// housings in, read with Open CASCADE.
#include <string>

#include "airr/core/mesh.hpp"

namespace airr {

// Whether the path names a STEP file (.step or .stp, any case).
bool is_step_path(const std::string& path);

// The file's shapes (those of the product named `node` and its components, or all of them when
// `node` is empty) tessellated so that no point of a triangle lies farther than `tolerance_mm`
// from the surface it stands for, in millimetres whatever unit the file uses, in the file's own
// frame. A face with a colour in the file gets it as its triangles' material (diffuse, that base
// colour). Throws input_error naming the file: unreadable, no surfaces, an unknown node, too large.
triangle_mesh load_step_mesh(const std::string& path, const std::string& node, double tolerance_mm);

}  // namespace airr
