// The census of light paths (tracer.hpp's census_rows): every label's light.
#include "airr/render/tracer.hpp"
#include "tracer_path.hpp"

namespace airr {

void census_rows(const tracer_scene& ts, int y0, int y1, std::uint64_t first, std::uint64_t count,
                 std::map<std::string, census_class>& classes, const std::atomic<bool>& cancel, std::uint64_t& rays) {
  static const path_layers none;
  glm::vec3 unmatched(0.0f);  // what the census's sink adds up besides, unused
  layer_sink sink{none, &unmatched};
  sink.census = &classes;
  tracer_path::label_rows(ts, y0, y1, first, count, sink, cancel, rays);
}

}  // namespace airr
