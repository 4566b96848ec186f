// What a render session publishes: its snapshots' images, and how the model image and traced
// samples are mixed for the viewer.
#include <algorithm>
#include <cmath>
#include <string>

#include "airr/render/interleaved_image.hpp"
#include "airr/render/render_session.hpp"

namespace airr {

namespace {

image_rgb black_image(int width, int height) {
  image_rgb img;
  img.width = width;
  img.height = height;
  img.rgb.assign(std::size_t(width) * height * 3, 0.0f);
  return img;
}

}  // namespace

image_rgb render_snapshot::image() const {
  if (!rgb) return black_image(width, height);
  image_rgb img;
  img.width = width;
  img.height = height;
  img.rgb = *rgb;
  return img;
}

image_rgb render_snapshot::component_image(int component) const {
  if (!components || component < 0 || component >= component_count) return {};
  const int at = component_layout.slot[std::size_t(component)];
  if (at < 0) return black_image(width, height);
  return interleaved_image(components->data(), width, height, std::size_t(component_layout.count), std::size_t(at));
}

image_rgb render_snapshot::layer_image(std::size_t k) const {
  if (!layers || k >= layer_names.size()) return {};
  return interleaved_image(layers->data(), width, height, layer_names.size(), k);
}

std::vector<image_rgb> render_snapshot::component_images() const {
  std::vector<image_rgb> out;
  for (int k = 0; k < component_count && components; ++k) out.push_back(component_image(k));
  for (int k = 0; k < component_layout.luminaires && components; ++k) {
    out.push_back(interleaved_image(components->data(), width, height, std::size_t(component_layout.count),
                                    std::size_t(component_layout.first_luminaire + k)));
  }
  return out;
}

std::vector<std::string> render_snapshot::component_image_names() const {
  return components ? component_layer_names(component_layout.luminaires) : std::vector<std::string>{};
}

std::vector<float> render_snapshot::even_rgb() const {
  if (!rgb || !odd_rgb || spp < 2) return {};
  // Samples 0 .. spp-1: spp / 2 odd-numbered ones, the rest even-numbered.
  const double odd_n = double(spp / 2), even_n = double(spp - spp / 2);
  std::vector<float> even(rgb->size());
  for (std::size_t i = 0; i < even.size(); ++i) {
    even[i] = float((double(spp) * (*rgb)[i] - odd_n * (*odd_rgb)[i]) / even_n);
  }
  return even;
}

double model_image_weight(const std::vector<float>& model, const std::vector<float>& rgb, const std::vector<float>* odd,
                          std::uint64_t spp) {
  if (spp < 2 || !odd || model.size() != rgb.size() || odd->size() != rgb.size()) return 1;
  const double n = double(spp), n_odd = double(spp / 2), n_even = n - n_odd;
  double halves2 = 0, distance2 = 0;
  for (std::size_t i = 0; i < rgb.size(); ++i) {
    const double even = (n * rgb[i] - n_odd * (*odd)[i]) / n_even;
    halves2 += (double((*odd)[i]) - even) * (double((*odd)[i]) - even);
    distance2 += (double(rgb[i]) - model[i]) * (double(rgb[i]) - model[i]);
  }
  // var(odd - even) = sigma^2 (1 / n_odd + 1 / n_even); var(mean) = sigma^2 / n.
  const double noise2 = halves2 / (n * (1 / n_odd + 1 / n_even));
  const double error2 = std::max(0.0, distance2 - noise2);
  if (!(noise2 + error2 > 0)) return 1;  // the same images
  const double w = noise2 / (noise2 + error2);
  return w < 1e-3 ? 0.0 : w > 1 - 1e-3 ? 1.0 : w;
}

std::string estimate_name(const render_snapshot& snap) {
  const std::string model = snap.first_look ? "model image (first look)" : "model image";
  if (snap.model_image && snap.spp > 0 && snap.model_weight < 1) {
    return "tracer at " + std::to_string(snap.spp) + " spp with the " + model + " (" +
           std::to_string(int(std::lround(100 * snap.model_weight))) + "%)";
  }
  if (snap.model_image) return model;
  if (snap.preview) return "tracer (preview)";
  return "tracer at " + std::to_string(snap.spp) + " spp";
}

}  // namespace airr
