#include "airr/render/prop_hits.hpp"

#include <cstdint>
#include <limits>
#include <memory>
#include <mutex>

#include "airr/formats/prop_mesh.hpp"
#include "airr/layout/layout.hpp"
#include "airr/render/embree_scene.hpp"

namespace airr {

namespace {
struct prop_scene {
  std::shared_ptr<const embree_device> device;  // outlives the scene
  // Held so that no other mesh takes a key's address while this scene may share its prototype.
  std::vector<instance_mesh> meshes;
  std::vector<glm::dmat4> transforms;
  std::unique_ptr<embree_instanced_scene> embree;
};

// The last props' scene built: the next one shares its meshes' acceleration structures, so an
// edit that only moves props rebuilds the top level alone. Scenes are never changed once handed
// out, since another thread may still be tracing one.
struct last_prop_scene {
  std::mutex mutex;
  std::shared_ptr<const embree_device> device;
  std::shared_ptr<const prop_scene> scene;
  std::uint64_t builds = 0;
};
last_prop_scene& last_built() {
  static last_prop_scene last;
  return last;
}
// Whether a built scene holds exactly these meshes (by key: file, node and contents) at these
// places.
bool same_props(const prop_scene& built, const std::vector<instance_mesh>& meshes,
                const std::vector<glm::dmat4>& transforms) {
  if (built.meshes.size() != meshes.size() || built.transforms != transforms) return false;
  for (std::size_t i = 0; i < meshes.size(); ++i) {
    if (built.meshes[i].key != meshes[i].key || built.meshes[i].mesh != meshes[i].mesh) return false;
  }
  return true;
}
}  // namespace

std::uint64_t prop_scene_builds() {
  last_prop_scene& last = last_built();
  std::lock_guard<std::mutex> lock(last.mutex);
  return last.builds;
}

prop_hit_function scene_prop_hits(const scene& s) {
  std::vector<instance_mesh> meshes;
  std::vector<glm::dmat4> transforms;
  for (const auto& p : s.props) {
    if (!p.visible) continue;
    auto mesh = prop_mesh(s, p);
    const std::string key = prop_mesh_key(p, mesh.get());
    meshes.push_back({key, std::move(mesh)});
    transforms.push_back(prop_transform(p));
  }
  if (meshes.empty()) return {};

  std::shared_ptr<const prop_scene> props;
  {
    last_prop_scene& last = last_built();
    std::lock_guard<std::mutex> lock(last.mutex);
    if (last.scene && same_props(*last.scene, meshes, transforms)) {
      props = last.scene;  // an edit that left the props alone: nothing to build
    } else {
      if (!last.device) last.device = std::make_shared<const embree_device>();
      auto built = std::make_shared<prop_scene>();
      built->device = last.device;
      built->meshes = meshes;
      built->transforms = transforms;
      built->embree = std::make_unique<embree_instanced_scene>(*built->device, meshes,
                                                               last.scene ? last.scene->embree.get() : nullptr);
      built->embree->set_transforms(transforms);
      ++last.builds;
      last.scene = props = built;
    }
  }
  return [props](const glm::dvec3& o, const glm::dvec3& d, double t_max) {
    RTCRayHit rh = make_ray_hit(o, d, 1e-6f);
    rh.ray.tfar = float(std::min(t_max, double(std::numeric_limits<float>::max())));
    intersect(props->embree->get(), rh);
    return rh.hit.geomID == RTC_INVALID_GEOMETRY_ID ? std::numeric_limits<double>::infinity() : double(rh.ray.tfar);
  };
}

}  // namespace airr
