#include "airr/ui/views/label_placement.hpp"

#include <algorithm>
#include <array>

namespace airr::ui {

bool rects_overlap(const screen_rect& a, const screen_rect& b) {
  return a.x0 < b.x1 && b.x0 < a.x1 && a.y0 < b.y1 && b.y0 < a.y1;
}

bool segment_crosses(const screen_segment& s, const screen_rect& r) {
  // Liang-Barsky: clip the segment's parameter range against the four sides.
  const glm::vec2 d = s.b - s.a;
  float t0 = 0, t1 = 1;
  const std::array<float, 4> p = {-d.x, d.x, -d.y, d.y};
  const std::array<float, 4> q = {s.a.x - r.x0, r.x1 - s.a.x, s.a.y - r.y0, r.y1 - s.a.y};
  for (std::size_t i = 0; i < 4; ++i) {
    if (p[i] == 0) {
      if (q[i] <= 0) return false;  // parallel to this side and outside it
      continue;
    }
    const float t = q[i] / p[i];
    if (p[i] < 0)
      t0 = std::max(t0, t);
    else
      t1 = std::min(t1, t);
    if (t0 > t1) return false;
  }
  return true;
}

static screen_rect grown(const screen_rect& r, float by) { return {r.x0 - by, r.y0 - by, r.x1 + by, r.y1 + by}; }

std::vector<placed_label> place_labels(const std::vector<label_request>& requests,
                                       const std::vector<screen_segment>& lines,
                                       const std::vector<screen_rect>& reserved, const screen_rect& canvas, float gap) {
  // Directions in order of preference: right-below (the reading position), then the other
  // corners, then straight below, above, right and left.
  constexpr std::array<glm::vec2, 8> directions = {glm::vec2{1, 1}, {1, -1}, {-1, 1}, {-1, -1},
                                                   glm::vec2{0, 1}, {0, -1}, {1, 0},  {-1, 0}};
  constexpr int rings = 8;
  std::vector<placed_label> out;
  std::vector<screen_rect> taken = reserved;
  for (const label_request& q : requests) {
    auto box_at = [&](const glm::vec2& dir, int ring) {
      const float reach = gap + 2 + ring * 0.6f * q.size.y;
      // The box's corner (or edge centre) nearest the anchor sits `reach` away along `dir`.
      const float x = dir.x > 0   ? q.anchor.x + reach
                      : dir.x < 0 ? q.anchor.x - reach - q.size.x
                                  : q.anchor.x - 0.5f * q.size.x;
      const float y = dir.y > 0   ? q.anchor.y + reach
                      : dir.y < 0 ? q.anchor.y - reach - q.size.y
                                  : q.anchor.y - 0.5f * q.size.y;
      return screen_rect{x, y, x + q.size.x, y + q.size.y};
    };
    // Penalty of a spot: outside the canvas, on another label or reserved text, across a line.
    auto penalty = [&](const screen_rect& b) {
      int p = 0;
      if (b.x0 < canvas.x0 || b.y0 < canvas.y0 || b.x1 > canvas.x1 || b.y1 > canvas.y1) p += 100;
      const screen_rect padded = grown(b, gap);
      for (const screen_rect& t : taken) p += rects_overlap(padded, t) ? 10 : 0;
      for (const screen_segment& s : lines) p += segment_crosses(s, padded) ? 1 : 0;
      return p;
    };
    placed_label best;
    int best_penalty = -1;
    auto consider = [&](const screen_rect& b, bool near) {
      const int p = penalty(b);
      if (best_penalty < 0 || p < best_penalty) {
        best = {b, p == 0, near};
        best_penalty = p;
      }
      return p == 0;
    };
    // The usual spots first: around the anchor, a little farther each ring.
    bool found = false;
    for (int ring = 0; ring < rings && !found; ++ring) {
      for (const glm::vec2& dir : directions) {
        if ((found = consider(box_at(dir, ring), ring < 2))) break;
      }
    }
    // Crowded: every spot of the canvas on a grid, nearest to the anchor first (a leader line
    // then joins a label placed away from its point).
    if (!found) {
      struct spot {
        float distance;
        screen_rect box;
      };
      std::vector<spot> spots;
      const float step = 3;
      for (float y = canvas.y0; y + q.size.y <= canvas.y1; y += step) {
        for (float x = canvas.x0; x + q.size.x <= canvas.x1; x += step) {
          const screen_rect b{x, y, x + q.size.x, y + q.size.y};
          const glm::vec2 nearest(std::clamp(q.anchor.x, b.x0, b.x1), std::clamp(q.anchor.y, b.y0, b.y1));
          spots.push_back({glm::length(nearest - q.anchor), b});
        }
      }
      std::sort(spots.begin(), spots.end(), [](const spot& a, const spot& b) { return a.distance < b.distance; });
      for (const spot& sp : spots) {
        if (consider(sp.box, sp.distance < gap + 2 + 1.2f * q.size.y)) break;
      }
    }
    taken.push_back(best.box);
    out.push_back(best);
  }
  return out;
}

}  // namespace airr::ui
