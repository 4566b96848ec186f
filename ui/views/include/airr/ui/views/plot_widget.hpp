#pragma once
// A small line-plot widget drawn with ImGui draw lists: axes, ticks, tick labels, axis titles,
// legend. One call draws one plot into the current window.
#include <string>
#include <vector>

namespace airr::ui {

struct plot_curve {
  std::string label;
  std::vector<double> x;
  std::vector<double> y;
  unsigned colour = 0;  // ImU32; 0 picks from the palette by index
  bool dashed = false;
  std::vector<double> band{};  // optional half-width at each x: a translucent band y +- band
  bool points = false;         // a dot at each point, no line
};

// Values on a grid drawn as coloured cells under the curves (viridis from value_min to
// value_max; non-finite values grey): row j at y = y_first + j (y_last - y_first) / (ny - 1), x likewise.
struct plot_heatmap {
  std::vector<double> values;  // ny rows of nx
  int nx = 0, ny = 0;
  double x_first = 0, x_last = 1, y_first = 0, y_last = 1;
  double value_min = 0, value_max = 1;
};

struct plot_params {
  std::string title;
  std::string x_title;
  std::string y_title;
  double x_min = 0, x_max = 1, y_min = 0, y_max = 1;
  bool auto_x = true, auto_y = false;
  float height = 200;  // pixels before content scale; width fills the window
  const plot_heatmap* heatmap = nullptr;
  bool equal_aspect = false;  // widen one axis's range so that a unit is as long on both (pictures in mm)
  bool compact = false;       // a small picture: its title above, no ticks or axis titles
};

// What the cursor points at, when it is over the plot area.
struct plot_hover {
  bool active = false;
  bool clicked = false;  // the left button went down over the plot area this frame
  double x = 0, y = 0;
  float area[4] = {0, 0, 0, 0};    // the plot area on screen: x0, y0, x1, y1
  double range[4] = {0, 0, 0, 0};  // the ranges drawn there: x_min, x_max, y_min, y_max
  // Where the title and the y title were drawn (x0, y0, x1, y1; all zero when not drawn).
  float title_box[4] = {0, 0, 0, 0};
  float y_title_box[4] = {0, 0, 0, 0};
};

plot_hover draw_plot(const char* id, const std::vector<plot_curve>& curves, const plot_params& params);

// "Nice" tick positions covering [lo, hi], about `target` of them.
std::vector<double> nice_ticks(double lo, double hi, int target);

unsigned plot_palette(int index);
// The viridis colour map at t in [0, 1] (clamped), as ImU32.
unsigned viridis(double t);

}  // namespace airr::ui
