#pragma once
// Reading glTF files (private to the optics library): the file itself, its node hierarchy and
// checked access to its accessors. Every error names the file and the node or accessor at fault.
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include <tiny_gltf.h>
#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

#include "airr/formats/mesh_gltf.hpp"

namespace airr::gltf {

// Most triangles one file may hold (a generous housing is a few million).
inline constexpr std::size_t max_triangles = 20'000'000;
// Largest glTF or GLB file read (GLB's own length fields stop at 4 GiB; 20 million triangles
// take under 1 GiB).
inline constexpr std::uintmax_t max_gltf_bytes = std::uintmax_t(2) << 30;

// The file, read as GLB when it starts with GLB's magic, else as JSON glTF; external and
// data-URI buffers are read, images are not decoded (a data-URI image's bytes are kept in its
// `image`; gltf_images.hpp reads images).
struct file {
  std::string path;
  tinygltf::Model model;
  std::vector<glm::dmat4> world;  // every node's world transform, in the file's units
  std::vector<int> parent;        // -1 for roots
};
file read(const std::string& path);

// "node 'Hood' (#3)" for messages.
std::string node_label(const file& f, int node);
// The node a reference names: "#index" or a unique name. Throws input_error.
int find_node(const file& f, const std::string& ref);
// The nodes of the default scene's roots (or, without scenes, every node without a parent).
std::vector<int> scene_roots(const file& f);

// The "airr" object in an extras text (null without one): a JSON object, or a string holding one
// (Blender's custom-property panel makes only strings). Throws input_error "<what>: ..." for
// malformed JSON or anything but an object.
nlohmann::json airr_in_extras(const std::string& extras_json, const std::string& what);
// The "airr" object of the node's own extras, and of its mesh's (null when there is none).
nlohmann::json node_airr_extras(const file& f, int node);
nlohmann::json mesh_airr_extras(const file& f, int node);
// The node's "airr" object: its own, else its mesh's (Blender writes a property of the mesh data
// there). Throws input_error naming the file and the node.
nlohmann::json airr_extras(const file& f, int node);
// "extras airr", or "mesh 'Plane' (#2): extras airr" when the node's airr object is its mesh's.
std::string airr_extras_name(const file& f, int node);
// The node's role in a layout: from extras airr.role ("display", "half_mirror", "retroreflector",
// "observer", "prop"), else by name (lower-cased, beginning "airr_display", "airr_half_mirror",
// "airr_retroreflector" or "airr_observer"), else "" (a prop when it has geometry).
std::string node_role(const file& f, int node);
// Whether the role is one of the optical parts or the observer (never prop geometry).
bool is_part_role(const std::string& role);

// Calls `visit` for each triangle primitive of `node`'s own mesh with its positions mapped by `xf`
// (in double precision), its triangles (three vertex indices each, counter-clockwise from the
// front even when xf mirrors, degenerate ones left out) and its glTF material (-1: none).
using primitive_visitor = std::function<void(const std::vector<glm::dvec3>& positions,
                                             const std::vector<std::uint32_t>& triangles, int material)>;
void visit_node_primitives(const file& f, int node, const glm::dmat4& xf, const primitive_visitor& visit);

// Appends the triangles of `node`'s own mesh, their positions mapped by `xf` (the winding kept
// counter-clockwise from the front when xf mirrors), with their materials.
void append_node_triangles(const file& f, int node, const glm::dmat4& xf, triangle_mesh& out);
// The same for the node and all its descendants but those with a part role and theirs, each at xf
// times its world transform.
void append_subtree(const file& f, int node, const glm::dmat4& xf, triangle_mesh& out);

// A transform's rotation (its x axis, then its y axis made orthogonal to x) and translation.
struct rigid {
  glm::dmat3 rotation{1.0};
  glm::dvec3 translation{0.0};
};
// Throws input_error "<what>: degenerate transform" when x or y has no length or they are parallel.
rigid rigid_part(const glm::dmat4& m, const std::string& what);

// Millimetres per glTF unit (metres).
inline constexpr double mm_per_metre = 1000.0;
// The node's world transform in millimetres (translation included).
glm::dmat4 world_mm(const file& f, int node);
// The rigid part of world_mm as a pose.
pose node_rigid_pose(const file& f, int node);

}  // namespace airr::gltf
