#pragma once
// Where text labels go on a drawing: each next to its point, clear of the labels placed before
// it, of reserved areas (other text) and of the drawing's lines, and inside the canvas.
#include <vector>

#include <glm/glm.hpp>

namespace airr::ui {

// Screen rectangle, y down; empty when x1 <= x0 or y1 <= y0.
struct screen_rect {
  float x0 = 0, y0 = 0, x1 = 0, y1 = 0;
};
struct screen_segment {
  glm::vec2 a{0.0f}, b{0.0f};
};

bool rects_overlap(const screen_rect& a, const screen_rect& b);
// Whether any point of the segment lies inside the rectangle.
bool segment_crosses(const screen_segment& s, const screen_rect& r);

struct label_request {
  glm::vec2 anchor{0.0f};  // the point the label names
  glm::vec2 size{0.0f};    // the text's extent
};
struct placed_label {
  screen_rect box;
  bool clear = true;  // false: no spot was free, and this one overlaps or crosses the least
  bool near = true;   // false: placed away from its point (draw a leader line to it)
};

// Places the labels in the requests' order: first the spots around each anchor (eight directions
// at growing distances), then, where all of those are taken, every spot of the canvas nearest
// first. `gap` keeps text that far from lines and from other labels.
std::vector<placed_label> place_labels(const std::vector<label_request>& requests,
                                       const std::vector<screen_segment>& lines,
                                       const std::vector<screen_rect>& reserved, const screen_rect& canvas, float gap);

}  // namespace airr::ui
