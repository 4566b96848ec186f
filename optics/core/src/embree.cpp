#include "airr/core/embree.hpp"

#include <cstdio>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <string>

#include <glm/gtc/type_ptr.hpp>

namespace airr {

static void embree_error(void*, RTCError code, const char* message) {
  std::fprintf(stderr, "embree error %d: %s\n", int(code), message ? message : "");
}

embree_device::embree_device() {
  device_ = rtcNewDevice(nullptr);
  if (!device_)
    throw std::runtime_error("cannot create the Embree device (error " +
                             std::to_string(int(rtcGetDeviceError(nullptr))) + ")");
  rtcSetDeviceErrorFunction(device_, embree_error, nullptr);
  rtcSetDeviceMemoryMonitorFunction(
      device_,
      [](void* bytes, ssize_t change, bool) {
        *static_cast<std::atomic<long long>*>(bytes) += change;
        return true;
      },
      &bytes_);
}

embree_device::~embree_device() { rtcReleaseDevice(device_); }

RTCRayHit make_ray_hit(const glm::dvec3& origin, const glm::dvec3& dir, float tnear) {
  RTCRayHit rh{};
  rh.ray.org_x = float(origin.x);
  rh.ray.org_y = float(origin.y);
  rh.ray.org_z = float(origin.z);
  rh.ray.dir_x = float(dir.x);
  rh.ray.dir_y = float(dir.y);
  rh.ray.dir_z = float(dir.z);
  rh.ray.tnear = tnear;
  rh.ray.tfar = std::numeric_limits<float>::infinity();
  rh.ray.mask = 0xffffffffu;
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  return rh;
}

void intersect(RTCScene scene, RTCRayHit& ray) {
  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  rtcIntersect1(scene, &ctx, &ray);
}

void intersect_coherent(RTCScene scene, RTCRayHit* rays, unsigned count) {
  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  ctx.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
  rtcIntersect1M(scene, &ctx, rays, count, sizeof(RTCRayHit));
}

embree_mesh_scene::embree_mesh_scene(const embree_device& device, const triangle_mesh& mesh) {
  scene_ = rtcNewScene(device.get());
  RTCGeometry geom = rtcNewGeometry(device.get(), RTC_GEOMETRY_TYPE_TRIANGLE);
  auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                        3 * sizeof(float), mesh.positions.size()));
  std::memcpy(v, mesh.positions.data(), mesh.positions.size() * sizeof(glm::vec3));
  auto* idx = static_cast<unsigned*>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                                             3 * sizeof(unsigned), mesh.indices.size() / 3));
  std::memcpy(idx, mesh.indices.data(), mesh.indices.size() * sizeof(unsigned));
  rtcCommitGeometry(geom);
  rtcAttachGeometry(scene_, geom);
  rtcReleaseGeometry(geom);
  rtcCommitScene(scene_);
}

embree_mesh_scene::~embree_mesh_scene() { rtcReleaseScene(scene_); }

embree_instanced_scene::embree_instanced_scene(const embree_device& device, const std::vector<instance_mesh>& meshes,
                                               const embree_instanced_scene* shared) {
  for (const auto& m : meshes) {
    keys_.push_back(m.key);
    if (prototypes_.count(m.key)) continue;
    if (shared) {
      const auto built = shared->prototypes_.find(m.key);
      if (built != shared->prototypes_.end()) {
        prototypes_[m.key] = built->second;
        continue;
      }
    }
    prototypes_[m.key] = std::make_shared<const embree_mesh_scene>(device, *m.mesh);
  }
  top_ = rtcNewScene(device.get());
  instances_.resize(keys_.size());
  for (unsigned i = 0; i < keys_.size(); ++i) {
    instances_[i] = rtcNewGeometry(device.get(), RTC_GEOMETRY_TYPE_INSTANCE);
    rtcSetGeometryInstancedScene(instances_[i], prototypes_.at(keys_[i])->get());
    rtcSetGeometryTimeStepCount(instances_[i], 1);
    const glm::mat4 identity(1.0f);
    rtcSetGeometryTransform(instances_[i], 0, RTC_FORMAT_FLOAT4X4_COLUMN_MAJOR, glm::value_ptr(identity));
    rtcCommitGeometry(instances_[i]);
    rtcAttachGeometryByID(top_, instances_[i], i);
  }
  rtcCommitScene(top_);
}

embree_instanced_scene::~embree_instanced_scene() {
  for (auto g : instances_) rtcReleaseGeometry(g);
  rtcReleaseScene(top_);
  prototypes_.clear();
}

void embree_instanced_scene::set_transforms(const std::vector<glm::dmat4>& transforms) {
  for (unsigned i = 0; i < instances_.size() && i < transforms.size(); ++i) {
    const glm::mat4 m(transforms[i]);
    rtcSetGeometryTransform(instances_[i], 0, RTC_FORMAT_FLOAT4X4_COLUMN_MAJOR, glm::value_ptr(m));
    rtcCommitGeometry(instances_[i]);
  }
  rtcCommitScene(top_);
}

}  // namespace airr
