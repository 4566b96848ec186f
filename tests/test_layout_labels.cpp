// The layout view's labels: in the shipped scenes and in random general layouts, at the sizes the
// designer gives its side and top views, no label overprints another, a part's outline, a drag
// handle or the scale bar, and every label stays inside its view (measured by label_overlap.hpp).
#include <gtest/gtest.h>

#include "airr/core/assets.hpp"
#include "airr/core/error.hpp"
#include "airr/formats/prop_mesh.hpp"
#include "airr/formats/scene_json.hpp"
#include "airr/ui/views/layout_projection.hpp"
#include "label_overlap.hpp"
#include "test_helpers.hpp"

using namespace airr;
using namespace airr::ui;

namespace {

// DejaVu Sans at 15 px, the designer's font, is at most 9 px a character and 17 px a line.
glm::vec2 text_size(const std::string& t) { return {9.0f * float(t.size()), 17.0f}; }

// The view sizes the designer's layout window gives each projection: at 1600 x 1000 (stacked
// beside the 3D view), in a larger window, and in a tall one (side by side above the 3D view).
const ImVec2 canvases[] = {{358, 184}, {700, 350}, {300, 420}};

test::label_overlaps measure(const scene& s, projection proj, ImVec2 canvas) {
  std::vector<mesh_bounds> bounds;
  for (const prop_params& p : s.props) bounds.push_back(bounds_of(*prop_mesh(s, p)));
  const ImVec2 at(40, 30);
  const projection_view v = compute_projection(s, bounds, proj, at, canvas, 15.0f, text_size);
  std::vector<std::pair<std::string, test::rect4>> labels;
  for (const view_text& t : v.labels) {
    labels.push_back({t.text, {t.place.box.x0, t.place.box.y0, t.place.box.x1, t.place.box.y1}});
  }
  std::vector<test::segment4> lines;
  for (const screen_segment& g : v.outlines) lines.push_back({g.a.x, g.a.y, g.b.x, g.b.y});
  std::vector<test::rect4> marks = {{v.scale_box.x0, v.scale_box.y0, v.scale_box.x1, v.scale_box.y1}};
  for (const screen_rect& h : v.handles) marks.push_back({h.x0, h.y0, h.x1, h.y1});
  return test::measure_label_overlaps(labels, lines, marks, {at.x, at.y, at.x + canvas.x, at.y + canvas.y});
}

void expect_clear(const scene& s, const std::string& name) {
  for (projection proj : {projection::side, projection::top}) {
    for (const ImVec2& canvas : canvases) {
      const test::label_overlaps o = measure(s, proj, canvas);
      std::string what;
      for (const auto& w : o.what) what += "\n  " + w;
      EXPECT_EQ(o.label_pairs + o.label_lines + o.label_marks + o.outside, 0)
          << name << (proj == projection::side ? ", side" : ", top") << " view " << canvas.x << " x " << canvas.y << ":"
          << what;
    }
  }
}

}  // namespace

TEST(LayoutLabels, ShippedScenesHaveNoOverprintedLabel) {
  for (const char* name : {"default.json", "ideal_bench.json", "two_sheet_kiosk.json"}) {
    expect_clear(load_scene(asset_dir() + "/scenes/" + name), name);
  }
}

TEST(LayoutLabels, RandomGeneralLayoutsHaveNoOverprintedLabel) {
  pcg32 rng(2024, 11);
  int tested = 0;
  for (int attempt = 0; attempt < 200 && tested < 40; ++attempt) {
    scene s = test::random_general_layout(rng);
    try {
      check_scene(s, "random layout");
    } catch (const input_error&) {
      continue;
    }
    expect_clear(s, "random layout " + std::to_string(attempt));
    ++tested;
  }
  EXPECT_EQ(tested, 40);
}

// The measure can fail: two labels forced onto one spot, and a line through a label, are counted.
TEST(LayoutLabels, TheMeasureSeesOverprints) {
  const test::label_overlaps o = test::measure_label_overlaps({{"a", {0, 0, 50, 15}}, {"b", {40, 5, 90, 20}}},
                                                              {{-10, 10, 100, 10}}, {}, {0, 0, 200, 200});
  EXPECT_EQ(o.label_pairs, 1);
  EXPECT_EQ(o.label_lines, 2);
}

// The placement moves a label off a line it would sit on and off a label placed before it.
TEST(LayoutLabels, PlacementAvoidsLinesAndLabels) {
  const screen_rect canvas{0, 0, 400, 400};
  const std::vector<label_request> two_on_one = {{{200, 200}, {60, 16}}, {{200, 200}, {60, 16}}};
  const std::vector<screen_segment> lines = {{{100, 215}, {300, 215}}};  // right through the first choice
  const auto placed = place_labels(two_on_one, lines, {}, canvas, 3.0f);
  ASSERT_EQ(placed.size(), 2u);
  for (const auto& p : placed) {
    EXPECT_TRUE(p.clear);
    EXPECT_FALSE(segment_crosses(lines[0], p.box));
  }
  EXPECT_FALSE(rects_overlap(placed[0].box, placed[1].box));
}
