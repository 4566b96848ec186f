#pragma once
// The model image of the whole layout: every sheet's model image (model_image.hpp), each sheet
// reached by its own path, and their sum. The tracer's control variate predicts a sample with every
// sheet's prediction for the same numbers, as its paths give each sheet's branch the first
// retroreflection's numbers.
#include <atomic>
#include <memory>
#include <string>
#include <vector>

#include "airr/layout/sheet_models.hpp"
#include "airr/render/model_image.hpp"

namespace airr {

struct layout_model_image {
  image_rgb image;  // the sum of the sheets' images
  // The sheets that have one; their own images are summed into `image` and let go (empty rgb,
  // their size kept).
  std::vector<std::shared_ptr<const model_image>> sheets;
  // The sheets without one and why ("retroreflectors[i]: ..."); their light is left to the tracer.
  std::vector<std::string> left_out;
  // With model_image_params::display_samples, `image` holds the display seen directly and in the
  // half mirror too; with keep_correlations, they and the display's texels they were made from
  // (display_parts_texels) are kept for remap_layout_model_image.
  std::vector<image_rgb> display_texels;
  image_rgb display_parts;
  scene layout;  // the scene it was computed for
  double seconds = 0;
};

// Null when no sheet has a model image, or when `cancel` is set while it runs. `models` are the
// scene's sheets' models, in order. Throws input_error for parameters out of range.
std::shared_ptr<const layout_model_image> compute_layout_model_image(const scene& s, const retro_model_list& models,
                                                                     const image_rgb* display,
                                                                     const model_image_params& p = {},
                                                                     const std::atomic<bool>* cancel = nullptr);

// The sum of the sheets' predictions for one tracer sample (see model_prediction).
glm::vec3 model_prediction(const layout_model_image& m, int px, int py, const glm::dvec2& jitter,
                           const retro_samples& u);
// The same for a pixel whose sheets' model_pixel_at are `pixels` (model_pixels_at): the pixel's paths
// found once for all its samples.
glm::vec3 model_prediction(const layout_model_image& m, const std::vector<model_pixel>& pixels,
                           const glm::dvec2& jitter, const retro_samples& u);
std::vector<model_pixel> model_pixels_at(const layout_model_image& m, int px, int py);

// The layout's model image `from` moved to `s`, a placement of the same layout
// (differ_in_placement_alone), sheet by sheet as remap_model_image does: the designer's first look
// while a part is dragged. Empty when the scenes differ in more, a sheet was left out of `from`, a
// sheet cannot be moved (see remap_model_image), or `cancel` was set. With p.display_samples, the
// display seen directly and in the half mirror are `from`'s when only sheets moved (one moved into
// the line of sight shows in the next view image), else made anew for `s` from `from`'s texels.
image_rgb remap_layout_model_image(const layout_model_image& from, const scene& s, const model_image_params& p,
                                   const std::atomic<bool>* cancel = nullptr, const remap_limits& limits = {});

// The designer's first look after an edit: the layout's model image at first_look() settings,
// computed on a camera with up to 4 times fewer pixels a side, but at least 128 (its display grid
// is coarser than that anyway), and scaled up to the scene's size. Empty when there is no model
// image or `cancel` was set.
image_rgb model_image_first_look(const scene& s, const retro_model_list& models, const image_rgb* display,
                                 const std::atomic<bool>* cancel = nullptr);

}  // namespace airr
