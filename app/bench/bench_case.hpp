#pragma once
// One case of the model-image benchmarks: the scene at a size, with sheet 0 a sinc-shift preset
// at a tilt, its models built and its display's texture loaded.
#include <string>

#include "airr/formats/image.hpp"
#include "airr/formats/scene_json.hpp"
#include "airr/layout/sheet_models.hpp"

struct bench_case {
  airr::scene s;
  airr::retro_model_list models;
  airr::image_rgb texture;
  bool textured = false;
  const airr::image_rgb* display() const { return textured ? &texture : nullptr; }
};

inline bench_case load_bench_case(const std::string& scene_path, int size, const std::string& preset, double tilt) {
  bench_case c;
  const std::string side = std::to_string(size);
  c.s = airr::load_scene(scene_path, {{"observer.width", side},
                                      {"observer.height", side},
                                      {"retroreflectors.0.model.type", "\"sinc_shift\""},
                                      {"retroreflectors.0.model.preset", "\"" + preset + "\""},
                                      {"retroreflectors.0.pose.pitch_deg", std::to_string(tilt)}});
  c.models = airr::make_sheet_models(c.s);
  const std::string texture_path = airr::resolve_scene_path(c.s, c.s.source.image);
  c.textured = !texture_path.empty();
  if (c.textured) c.texture = airr::load_image(texture_path).pixels;
  return c;
}
