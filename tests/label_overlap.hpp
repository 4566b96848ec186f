#pragma once
// The test's own measure of labels overprinting: pairs of label rectangles that share area, label
// rectangles that a drawn line passes through (sampled every quarter pixel), labels on other marks
// (the scale bar's text, the drag handles), labels outside their canvas. It shares no code with the placement it
// judges.
#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <vector>

namespace airr::test {

using rect4 = std::array<double, 4>;     // x0, y0, x1, y1
using segment4 = std::array<double, 4>;  // ax, ay, bx, by

struct label_overlaps {
  int label_pairs = 0;  // labels that overprint each other
  int label_lines = 0;  // labels a part's outline runs through
  int label_marks = 0;  // labels on other marks: the scale bar's text, the drag handles
  int outside = 0;      // labels not wholly inside the canvas
  std::vector<std::string> what;
};

inline double shared_area(const rect4& a, const rect4& b) {
  const double w = std::min(a[2], b[2]) - std::max(a[0], b[0]), h = std::min(a[3], b[3]) - std::max(a[1], b[1]);
  return w > 0 && h > 0 ? w * h : 0;
}

inline bool line_enters(const segment4& s, const rect4& r) {
  const double length = std::hypot(s[2] - s[0], s[3] - s[1]);
  const int steps = std::max(1, int(std::ceil(length * 4)));
  for (int i = 0; i <= steps; ++i) {
    const double t = double(i) / steps, x = s[0] + t * (s[2] - s[0]), y = s[1] + t * (s[3] - s[1]);
    if (x > r[0] && x < r[2] && y > r[1] && y < r[3]) return true;
  }
  return false;
}

inline label_overlaps measure_label_overlaps(const std::vector<std::pair<std::string, rect4>>& labels,
                                             const std::vector<segment4>& lines, const std::vector<rect4>& marks,
                                             const rect4& canvas) {
  label_overlaps o;
  for (std::size_t i = 0; i < labels.size(); ++i) {
    const auto& [name, r] = labels[i];
    for (std::size_t j = i + 1; j < labels.size(); ++j) {
      if (shared_area(r, labels[j].second) > 0) {
        ++o.label_pairs;
        o.what.push_back("'" + name + "' on '" + labels[j].first + "'");
      }
    }
    for (const segment4& s : lines) {
      if (line_enters(s, r)) {
        ++o.label_lines;
        o.what.push_back("a line through '" + name + "'");
        break;
      }
    }
    for (const rect4& t : marks) {
      if (shared_area(r, t) > 0) {
        ++o.label_marks;
        o.what.push_back("'" + name + "' on the scale bar or a handle");
      }
    }
    if (r[0] < canvas[0] || r[1] < canvas[1] || r[2] > canvas[2] || r[3] > canvas[3]) {
      ++o.outside;
      o.what.push_back("'" + name + "' outside its view");
    }
  }
  return o;
}

}  // namespace airr::test
