#pragma once
// Embree objects behind RAII: the device, a committed scene of one triangle mesh, a top-level
// scene of instances of such scenes whose transforms change without rebuilding anything else, and
// the ray queries every tracer of the project makes (the layout's tracer, a sheet's tile).
#include <algorithm>
#include <atomic>
#include <cstddef>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <embree3/rtcore.h>
#include <glm/glm.hpp>

#include "airr/core/mesh.hpp"

namespace airr {

class embree_device {
 public:
  embree_device();
  ~embree_device();
  embree_device(const embree_device&) = delete;
  embree_device& operator=(const embree_device&) = delete;
  RTCDevice get() const { return device_; }
  // What the device's scenes hold now (Embree's memory monitor).
  std::size_t bytes_in_use() const { return std::size_t(std::max<long long>(0, bytes_.load())); }

 private:
  RTCDevice device_ = nullptr;
  std::atomic<long long> bytes_{0};
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

// Instances of prototype meshes, the instance id of a hit being the index.
class embree_instanced_scene {
 public:
  // One instance per entry, in order (the instance id is the index); equal keys are built once,
  // and keys `shared` has already built (on the same device) are shared with it, not rebuilt.
  embree_instanced_scene(const embree_device& device, const std::vector<instance_mesh>& meshes,
                         const embree_instanced_scene* shared = nullptr);
  ~embree_instanced_scene();
  embree_instanced_scene(const embree_instanced_scene&) = delete;
  embree_instanced_scene& operator=(const embree_instanced_scene&) = delete;

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
