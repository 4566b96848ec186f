#pragma once
// A whole layout in one glTF file: the optical parts are nodes with a role (in their extras,
// {"airr": {"role": "half_mirror", ...}}, or by name: "airr_display", "airr_half_mirror",
// "airr_retroreflector...", "airr_observer"), everything else with geometry is a prop. glTF's
// metres become millimetres. The exporter writes the same form, so a layout survives a round trip
// through Blender or any glTF tool.
//
// As Blender 3.4 writes it:
// - the "airr" extras may be a JSON object or a string holding one (Blender's custom-property
//   panel makes only strings, numbers and booleans): {"airr": "{\"role\": \"half_mirror\"}"};
// - they may sit on the node (the object's properties) or on its mesh (the mesh data's,
//   meshes[i].extras); when both have them the node's are used and a note says so;
// - a file drawn in millimetres (Blender 3.4 exports no unit scale) reads a thousand times too
//   large: a warning names the factor to scale it by (gltf_layout::scale_warning);
// - the observer: a node with the observer role (the camera the exporter writes) wins over the
//   scene extras' observer, unless the scene extras say "observer_source": "extras". An unmoved
//   camera (within 0.01 mm and 1e-5 rad of the extras' observer) keeps the extras' observer as it
//   is (an orbit stays an orbit); a moved one places a look-at observer with the extras' other
//   fields (lens, field of view, size), aiming as far ahead as the extras' observer aimed
//   (300 mm without one). A note says which was used.
//
// Self-contained: the display's image travels in the file as the base-colour texture of the
// display's mesh (see export_gltf_layout), while its extras keep naming the image file. Reading,
// the named file (relative to the glTF's folder) wins when it exists; when the extras name none,
// or it is missing, the mesh's texture is used: an embedded one is extracted once into the cache,
// <XDG_CACHE_HOME or ~/.cache>/airr-studio/embedded/<content hash>-<size>.png (or .jpg), written
// atomically and reused while its bytes match, and source.image names that file (so the renderer
// and every other reader of source.image read it like any image; a scene saved from such a layout
// names the cache's copy). A note says which image was used; a damaged embedded image is an error
// naming the file and the display's node.
#include <string>
#include <utility>
#include <vector>

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
//   transmittance; a sheet's model) come from its extras; the display's image, when its file is
//   missing, from its mesh's base-colour texture (as the top of this header says);
// - props: every topmost node outside the parts whose subtree has triangles, by node name (or
//   "#index"), with its rigid pose; surface, albedo, visible and name from extras, else the glTF
//   material;
// - seed, render, observer and observer_source ("camera", the default, or "extras") from the default
//   scene's extras ({"airr": {...}}); the observer as the top of this header says (a look-at
//   observer from the observer node alone looks along the node's -z).
// Throws input_error naming the file and the node.
nlohmann::json gltf_layout_document(const std::string& path);

// A glTF layout read: its scene document (as gltf_layout_document), what reading it noted for the
// user (each line "note: <file>: ..." or "warning: <file>: ...", for the caller to print), and the
// node each part came from (for naming it in errors).
struct gltf_layout {
  std::string path;
  nlohmann::json document;
  std::vector<std::string> notes;
  // The scale warning (without "warning: <file>: "), empty when the size is plausible: the largest
  // side of the optical parts between 2 mm and 2 m. Outside, it names the power of ten that brings
  // that side nearest 300 mm (the default half mirror's width), e.g. 0.001 for a file drawn in
  // millimetres.
  std::string scale_warning;
  // Scene field -> the node it came from: {"half_mirror", "node 'Beam splitter' (#1)"}; also
  // "source", "retroreflectors[i]", "props[i]" and, when the camera node placed the observer,
  // "observer.position_mm", "observer.look_at_mm" and "observer:" (the layout check's errors).
  std::vector<std::pair<std::string, std::string>> part_nodes;
};
gltf_layout read_gltf_layout(const std::string& path);

// An error from checking a layout's document ("<path>: <field>: <problem>", as scene_from_json and
// check_scene write them) naming the node the field came from: "<path>: node 'Beam splitter' (#1):
// half_mirror.reflectance: <problem>". Messages about no part's field (e.g. "<path> (with --set):
// ...", a value the command line set) keep their text. The scale warning, when there is one, is
// appended to every message: a file drawn in millimetres usually fails the checks.
std::string gltf_layout_error(const gltf_layout& layout, const std::string& message);

// Whether any node of the file has a part's role (a layout, rather than a model to place as a prop).
bool gltf_has_layout_roles(const std::string& path);

// Writes the layout as glTF (.glb, or .gltf with the buffer embedded), atomically: one node per
// part with its rectangle, one per visible or hidden prop with its triangles and materials, a
// camera for the observer, and every role and field in extras. The display's mesh is its whole
// panel in two primitives: the emitting area, whose material has the display's image (if any) as
// baseColorTexture and emissiveTexture, its texture coordinates spanning [0, 1] over that area
// (texel row 0 at its top), and around it the bezel's black frame (without a bezel, none); so the
// mesh's extent stays the panel the reader takes the size from, and the image covers only the
// emitting area. The image is the file's own bytes when it is PNG or JPEG (identical pixels),
// else PNG (16-bit, linear, when the file has more than 8 bits per channel, since 16-bit files read
// as linear; 8-bit sRGB otherwise); in a .glb it sits in the binary buffer, in a .gltf in a data
// URI. Throws input_error naming the path (or the image file).
void export_gltf_layout(const scene& s, const std::string& path);

}  // namespace airr
