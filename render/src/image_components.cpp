// The image's components as a render keeps and names them: which the scene's light can make,
// where a pixel's sums hold each, and each luminaire's own (tracer.hpp).
#include <algorithm>
#include <string>
#include <vector>

#include "airr/render/tracer.hpp"

namespace airr {

component_slots possible_component_slots(const ambient_lights& a) {
  component_slots s;
  s.count = 0;
  for (int k = 0; k < component_count; ++k) {
    // The tracer adds to these only with such light (trace_path_as, sample_lights).
    const bool possible = k == component_room         ? a.room > 0
                          : k == component_sun        ? a.sun > 0
                          : k == component_luminaires ? !a.luminaires.empty()
                                                      : true;
    s.slot[std::size_t(k)] = possible ? s.count++ : -1;
  }
  if (!a.luminaires.empty()) {
    s.first_luminaire = s.count;
    s.luminaires = int(a.luminaires.size());
    s.count += s.luminaires;
  }
  return s;
}

component_slots all_component_slots(const ambient_lights& a) {
  component_slots s;
  s.first_luminaire = component_count;
  s.luminaires = int(a.luminaires.size());
  s.count = component_count + s.luminaires;
  return s;
}

std::string luminaire_component_name(int k) { return "luminaire" + std::to_string(k); }

std::vector<std::string> component_layer_names(int luminaires) {
  std::vector<std::string> out(std::begin(component_names), std::end(component_names));
  for (int k = 0; k < luminaires; ++k) out.push_back(luminaire_component_name(k));
  return out;
}

bool is_component_name(const std::string& name) {
  const std::vector<std::string> all = component_layer_names(max_luminaires);
  return std::find(all.begin(), all.end(), name) != all.end();
}

}  // namespace airr
