#include "airr/render/prop_hits.hpp"

#include <limits>
#include <memory>

#include "airr/optics/layout.hpp"
#include "airr/optics/mesh_gltf.hpp"
#include "airr/render/embree_scene.hpp"

namespace airr {

namespace {
struct prop_scene {
  embree_device device;
  std::unique_ptr<embree_layout_scene> embree;
};
}  // namespace

prop_hit_function scene_prop_hits(const scene& s) {
  std::vector<instance_mesh> meshes;
  std::vector<glm::dmat4> transforms;
  for (const auto& p : s.props) {
    if (!p.visible) continue;
    meshes.push_back({p.mesh + "#" + p.node, cached_prop_mesh(resolve_scene_path(s, p.mesh), p.node)});
    transforms.push_back(prop_transform(p));
  }
  if (meshes.empty()) return {};
  auto props = std::make_shared<prop_scene>();
  props->embree = std::make_unique<embree_layout_scene>(props->device, meshes);
  props->embree->set_transforms(transforms);
  return [props](const glm::dvec3& o, const glm::dvec3& d, double t_max) {
    RTCRayHit rh = make_ray_hit(o, d, 1e-6f);
    rh.ray.tfar = float(std::min(t_max, double(std::numeric_limits<float>::max())));
    intersect(props->embree->get(), rh);
    return rh.hit.geomID == RTC_INVALID_GEOMETRY_ID ? std::numeric_limits<double>::infinity() : double(rh.ray.tfar);
  };
}

}  // namespace airr
