// airr mtf IMAGE [--pixel-mm X] [--roi x,y,w,h] [--linear-input] -o mtf.csv [--plot mtf.png]
#include <algorithm>
#include <cstdio>
#include <memory>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "airr/analysis/edge_file.hpp"
#include "airr/analysis/mtf_csv.hpp"
#include "airr/analysis/mtf_metrics.hpp"
#include "airr/analysis/plot_png.hpp"
#include "cli/commands.hpp"

namespace {

cv::Rect parse_roi(const std::string& text) {
  std::vector<int> v;
  std::stringstream in(text);
  std::string part;
  while (std::getline(in, part, ',')) {
    try {
      size_t used = 0;
      v.push_back(std::stoi(part, &used));
      if (used != part.size()) throw std::invalid_argument(part);
    } catch (const std::logic_error&) {
      throw std::runtime_error("--roi expects x,y,w,h in pixels, got '" + text + "'");
    }
  }
  if (v.size() != 4) throw std::runtime_error("--roi expects x,y,w,h in pixels, got '" + text + "'");
  if (v[2] <= 0 || v[3] <= 0) throw std::runtime_error("--roi width and height must be positive, got '" + text + "'");
  return {v[0], v[1], v[2], v[3]};
}

}  // namespace

void add_mtf_command(CLI::App& app) {
  struct options {
    std::string image, csv, plot, roi;
    std::optional<double> pixel_mm;
    airr::image_encoding encoding = airr::image_encoding::automatic;
  };
  auto opt = std::make_shared<options>();
  auto* cmd = app.add_subcommand("mtf",
                                 "Measure the slanted-edge MTF of an image (edge about 5 deg "
                                 "from vertical or horizontal)");
  cmd->add_option("image", opt->image, "Image with one slanted edge (EXR, PNG, TIFF, JPEG)")->required();
  cmd->add_option("-o,--output", opt->csv, "CSV file to write (cycles_per_pixel,lp_per_mm,mtf)")->required();
  cmd->add_option("--pixel-mm", opt->pixel_mm,
                  "Pixel size in mm on the measured plane; default: the image's airr:mm_per_pixel");
  cmd->add_option("--roi", opt->roi, "Region x,y,w,h in pixels around the edge; default: whole image");
  add_image_encoding_flags(cmd, opt->encoding);
  cmd->add_option("--plot", opt->plot, "Also write a PNG plot of the MTF");
  cmd->callback([opt] {
    airr::analysis::slanted_edge_params params;
    if (!opt->roi.empty()) params.roi = parse_roi(opt->roi);
    if (opt->pixel_mm && !(*opt->pixel_mm > 0)) throw std::runtime_error("--pixel-mm must be positive");
    const auto result = airr::analysis::measure_edge_file(opt->image, params, {.encoding = opt->encoding});

    std::string pixel_source = "--pixel-mm";
    double mm = 0;
    if (opt->pixel_mm) {
      mm = *opt->pixel_mm;
    } else if (result.image.mm_per_pixel) {
      mm = *result.image.mm_per_pixel;
      pixel_source = "airr:mm_per_pixel";
    } else {
      throw std::runtime_error(opt->image +
                               ": no pixel size: the image has no airr:mm_per_pixel attribute; pass --pixel-mm");
    }

    const auto& c = result.curve;
    std::printf("image: %s (%dx%d, %s), pixel %.6g mm (%s)\n", opt->image.c_str(), result.image.luminance.cols,
                result.image.luminance.rows, result.image.srgb_decoded ? "sRGB decoded" : "linear", mm,
                pixel_source.c_str());
    std::printf("region: %d,%d,%d,%d\n", c.roi.x, c.roi.y, c.roi.width, c.roi.height);
    std::printf("edge: %s, %s, %.3f deg from the pixel axis\n",
                airr::analysis::edge_orientation_names[static_cast<int>(c.orientation)],
                c.rising ? "dark to bright" : "bright to dark", c.edge_angle_deg);
    if (const auto m50 = airr::analysis::mtf50(c, mm))
      std::printf("MTF50: %.5f cycles/pixel = %.5g lp/mm\n", m50->cycles_per_pixel, m50->lp_per_mm);
    else
      std::printf("MTF50: not reached (MTF stays above 0.5 up to %.3g cycles/pixel)\n", c.cycles_per_pixel.back());
    const auto mean = airr::analysis::mean_mtf(c, mm);
    if (mean.clamped)
      std::printf(
          "mean MTF over (0, %.4g] lp/mm: %.5f (the Nyquist frequency %.4g lp/mm is below 1 lp/mm; "
          "averaged over the available range)\n",
          mean.upper_lp_per_mm, mean.value, mean.upper_lp_per_mm);
    else
      std::printf("mean MTF over (0, 1] lp/mm: %.5f\n", mean.value);

    airr::analysis::write_mtf_csv(opt->csv, c, mm);
    std::printf("wrote %s\n", opt->csv.c_str());
    if (!opt->plot.empty()) {
      // Plot up to the Nyquist frequency; above it the values are less trustworthy.
      airr::analysis::plot_series s;
      s.label = "slanted edge, " + std::filesystem::path(opt->image).filename().string();
      const auto lp = airr::analysis::to_lp_per_mm(c.cycles_per_pixel, mm);
      for (size_t i = 0; i < lp.size() && c.cycles_per_pixel[i] <= c.nyquist_cycles_per_pixel + 1e-12; ++i) {
        s.x.push_back(lp[i]);
        s.y.push_back(c.mtf[i]);
      }
      airr::analysis::plot_params pp;
      char title[96];
      std::snprintf(title, sizeof title, "slanted-edge MTF (edge %.2f deg, %.4g mm/pixel)", c.edge_angle_deg, mm);
      pp.title = title;
      pp.x_min = 0.0;
      pp.y_min = 0.0;
      pp.y_max = std::max(1.05, *std::max_element(s.y.begin(), s.y.end()));
      airr::analysis::write_plot_png(opt->plot, {s}, pp);
      std::printf("wrote %s\n", opt->plot.c_str());
    }
  });
}
