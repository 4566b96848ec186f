#pragma once
// A whole layout in one glTF file: the optical parts are nodes with a role (in their extras,
// {"airr": {"role": "half_mirror", ...}}, or by name: "airr_display", "airr_half_mirror",
// "airr_retroreflector...", "airr_observer"), everything else with geometry is a prop. glTF's
// metres become millimetres. The exporter writes the same form, so a layout survives a round trip
// through Blender or any glTF tool.
#include <string>

#include <nlohmann/json.hpp>

#include "airr/layout/scene.hpp"

namespace airr {

// Whether a path names a glTF file (.gltf or .glb, any case).
bool is_gltf_path(const std::string& path);

// The layout in the glTF file as a scene document (the JSON form scene_from_json reads), with
// relative paths counting from the file's directory:
// - display, half mirror, retroreflectors (in node order): a flat mesh each (a non-planar one is
//   an error naming the node); the part's plane and front come from its triangles (counter-
//   clockwise seen from the front), its width axis from the node's x axis, its size from the
//   mesh's extent (the display's mesh is its whole panel, bezel included). The role's other fields
//   (a display's image, intensity, bezel_mm, emission_profile; a half mirror's reflectance and
//   transmittance; a sheet's model) come from its extras;
// - props: every topmost node outside the parts whose subtree has triangles, by node name (or
//   "#index"), with its rigid pose; surface, albedo, visible and name from extras, else the glTF
//   material;
// - seed, observer and render from the default scene's extras ({"airr": {...}}); without an
//   observer there, a node with the observer role places a look-at observer (looking along its -z).
// Throws input_error naming the file and the node.
nlohmann::json gltf_layout_document(const std::string& path);

// Whether any node of the file has a part's role (a layout, rather than a model to place as a prop).
bool gltf_has_layout_roles(const std::string& path);

// Writes the layout as glTF (.glb, or .gltf with the buffer embedded), atomically: one node per
// part with its rectangle, one per visible or hidden prop with its triangles and materials, a
// camera for the observer, and every role and field in extras. Throws input_error naming the path.
void export_gltf_layout(const scene& s, const std::string& path);

}  // namespace airr
