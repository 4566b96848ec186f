#pragma once
// Embree objects behind RAII: the device, one prototype scene per mesh file, and the top-level
// scene holding one instance per part, whose transforms change without rebuilding anything else.
#include <array>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <embree3/rtcore.h>
#include <glm/glm.hpp>

#include "airr/formats/mesh_gltf.hpp"

namespace airr {

class embree_device {
 public:
  embree_device();
  ~embree_device();
  embree_device(const embree_device&) = delete;
  embree_device& operator=(const embree_device&) = delete;
  RTCDevice get() const { return device_; }

 private:
  RTCDevice device_ = nullptr;
};

// A committed scene of one triangle mesh.
class embree_mesh_scene {
 public:
  embree_mesh_scene(const embree_device& device, const triangle_mesh& mesh);
  ~embree_mesh_scene();
  embree_mesh_scene(const embree_mesh_scene&) = delete;
  embree_mesh_scene& operator=(const embree_mesh_scene&) = delete;
  RTCScene get() const { return scene_; }

 private:
  RTCScene scene_ = nullptr;
};

// The parts of an AIRR layout; the instance id of a hit says which one: the display, the half
// mirror, then the retroreflective sheets in order from part_first_sheet, then the visible props.
enum part_id : unsigned { part_source = 0, part_half_mirror = 1, part_first_sheet = 2 };

// A ray to intersect from `tnear` on, with no hit yet.
RTCRayHit make_ray_hit(const glm::dvec3& origin, const glm::dvec3& dir, float tnear = 0.0f);
// Closest hits of a single ray, and of `count` coherent rays (camera rays of neighbouring
// pixels) as one stream, which Embree traces in packets.
void intersect(RTCScene scene, RTCRayHit& ray);
void intersect_coherent(RTCScene scene, RTCRayHit* rays, unsigned count);

// One instance's mesh: `key` names it (instances with equal keys share one prototype).
struct instance_mesh {
  std::string key;
  std::shared_ptr<const triangle_mesh> mesh;
};

// A prop's prototype key: its file and node, and the loaded mesh (a file changed on disk is a new
// mesh, so a new prototype).
std::string prop_mesh_key(const prop_params& p, const triangle_mesh* mesh);

class embree_layout_scene {
 public:
  // One instance per entry, in order (the instance id is the index); equal keys are built once,
  // and keys `shared` has already built (on the same device) are shared with it, not rebuilt.
  embree_layout_scene(const embree_device& device, const std::vector<instance_mesh>& meshes,
                      const embree_layout_scene* shared = nullptr);
  ~embree_layout_scene();
  embree_layout_scene(const embree_layout_scene&) = delete;
  embree_layout_scene& operator=(const embree_layout_scene&) = delete;

  // Moves the instances: updates their transforms and recommits the top level only.
  void set_transforms(const std::vector<glm::dmat4>& transforms);
  RTCScene get() const { return top_; }
  const std::vector<std::string>& keys() const { return keys_; }

 private:
  std::vector<std::string> keys_;
  std::map<std::string, std::shared_ptr<const embree_mesh_scene>> prototypes_;
  std::vector<RTCGeometry> instances_;
  RTCScene top_ = nullptr;
};

}  // namespace airr
