#pragma once
// airr bench: the latencies a designer sees after an edit, in a session set up as the designer's
// (first look, then the model image at view quality, the quick control variate computed beside the
// tracer, render threads at background priority): to each estimate of the edited layout.
#include <vector>

#include "airr/layout/scene.hpp"

struct designer_latencies {
  std::vector<double> first_look_ms, model_image_ms, traced_preview_ms, traced_ms;
  int edits = 0;
};

// `edits` edits of the sheet's tilt (alternately +5 deg and back), each after the last one's first
// full-resolution traced image.
designer_latencies measure_designer_latencies(const airr::scene& s, int edits);

void print_designer_latencies(const designer_latencies& d);
