#pragma once
// A layout's design metrics (spec section 9) as a design spec names them: at each of its eyes (the
// observer placed there, looking at the aerial image's centre) the visible fraction and the model
// PSF's mean MTF, MTF50, r50 and brightness, the stray light and a path expression's light (its
// ratio to the aerial image's, its angle from it) in a small render, over the eyes their mean or
// minimum; and the device's
// bounding box and how far its parts cut its props.
#include <cstddef>
#include <string>
#include <vector>

#include "airr/formats/design_spec.hpp"
#include "airr/layout/scene.hpp"

namespace airr {

// The scene with its observer at `eye`, looking at the aerial image's centre.
scene observer_at(scene s, const glm::dvec3& eye);

// The extent along x, y and z of the display panel, the half mirror and the sheets (mm).
glm::dvec3 device_size_mm(const scene& s);

// The length of the lines along which the display panel, the half mirror and the sheets cut
// through the visible props' surfaces (mm; 0 when no part cuts a prop). Throws input_error when a
// prop's mesh cannot be read.
double prop_cut_length_mm(const scene& s);

// What one layout scores on a spec: each objective's and constraint's metric value, the weighted
// objective (larger is better), and the constraints it breaks.
struct design_evaluation {
  std::vector<double> objective_values;
  std::vector<double> constraint_values;
  double score = 0;                 // sum of weight x value, minimised metrics counting negative
  std::vector<std::string> broken;  // "size_z_mm 260 > max 250", one per broken constraint
  bool feasible() const { return broken.empty(); }
};

// The weighted objective of the objectives' values (the spec's weights; minimised ones negative).
double design_score(const design_spec& spec, const std::vector<double>& objective_values);

// The constraints the values break, one line each ("size_z_mm 260 > max 250").
std::vector<std::string> broken_constraints(const design_spec& spec, const std::vector<double>& constraint_values);

// Evaluates s (a layout the spec's variables made) on the spec's metrics; the model PSFs are
// seeded by the spec, so equal layouts score equally whatever the threads.
design_evaluation evaluate_design(const design_spec& spec, const scene& s);

// Refuses, before anything is measured, a run of `what` (optimise, tolerance) that evaluates
// `layouts` layouts side by side and cannot hold its model PSFs: one a thread while eyes are
// measured, each of the spec's psf_samples (input_error "<what>: N PSFs at once of M samples needs
// about ..."). Nothing is refused when no metric takes a PSF.
void check_design_memory(const design_spec& spec, const std::string& what, std::size_t layouts);

// Throws input_error "<spec>: objectives[i].expression: path expression '...': at character N:
// ..." when a ghost metric's expression does not parse or names a prop the base scene lacks.
void check_design_expressions(const design_spec& spec);

// How far a constraint is broken (0 when it holds), in its metric's units.
double constraint_violation(const design_constraint& c, double value);

}  // namespace airr
