#include "airr/analysis/slanted_edge_mtf.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>
#include <stdexcept>
#include <utility>

#include <opencv2/core.hpp>

#include "airr/core/error.hpp"
#include "airr/core/geometry.hpp"

namespace airr::analysis {

namespace {

constexpr int min_region_size = 20;

[[noreturn]] void fail(const std::string& problem) { throw measurement_error(problem); }

std::string fmt(double v, int precision = 3) {
  std::ostringstream s;
  s.precision(precision);
  s << v;
  return s.str();
}

double hamming(double t) { return 0.54 + 0.46 * std::cos(std::numbers::pi * t); }

double sinc(double x) {
  if (std::abs(x) < 1e-12) return 1.0;
  const double px = std::numbers::pi * x;
  return std::sin(px) / px;
}

// Edge position x = offset + slope * y in region pixel coordinates (pixel centres at integers).
struct edge_line {
  double offset = 0;
  double slope = 0;
  double rms_residual = 0;
  int rows_used = 0;
};

cv::Mat checked_region(const cv::Mat& image, const slanted_edge_params& params, cv::Rect& roi) {
  if (image.empty()) fail("image is empty");
  if (image.channels() != 1)
    fail("slanted-edge MTF needs a single-channel image, got " + std::to_string(image.channels()) + " channels");
  const cv::Rect full(0, 0, image.cols, image.rows);
  roi = params.roi.value_or(full);
  if (roi.width <= 0 || roi.height <= 0 || (roi & full) != roi)
    fail("ROI " + std::to_string(roi.x) + "," + std::to_string(roi.y) + "," + std::to_string(roi.width) + "," +
         std::to_string(roi.height) + " lies outside the " + std::to_string(image.cols) + "x" +
         std::to_string(image.rows) + " image");
  if (roi.width < min_region_size || roi.height < min_region_size)
    fail(std::string(params.roi ? "ROI " : "image ") + std::to_string(roi.width) + "x" + std::to_string(roi.height) +
         " is too small (need at least " + std::to_string(min_region_size) + "x" + std::to_string(min_region_size) +
         " pixels)");
  cv::Mat region;
  image(roi).convertTo(region, CV_64F);

  double lo = 0, hi = 0;
  for (int y = 0; y < region.rows; ++y) {
    const double* row = region.ptr<double>(y);
    for (int x = 0; x < region.cols; ++x) {
      if (!std::isfinite(row[x]))
        fail(std::string("pixel (") + std::to_string(roi.x + x) + ", " + std::to_string(roi.y + y) + ") is " +
             (std::isnan(row[x]) ? "NaN" : "infinite") + "; the image must hold finite values");
      if (x == 0 && y == 0) lo = hi = row[x];
      lo = std::min(lo, row[x]);
      hi = std::max(hi, row[x]);
    }
  }
  if (hi - lo <= 1e-12 * std::max(1.0, std::abs(hi)))
    fail("image region is flat (every pixel is " + fmt(hi) + "); there is no edge to measure");
  return region;
}

// The edge runs along the axis with the weaker gradient.
bool is_near_vertical(const cv::Mat& region) {
  double gx = 0, gy = 0;
  for (int y = 1; y + 1 < region.rows; ++y)
    for (int x = 1; x + 1 < region.cols; ++x) {
      gx += std::abs(region.at<double>(y, x + 1) - region.at<double>(y, x - 1));
      gy += std::abs(region.at<double>(y + 1, x) - region.at<double>(y - 1, x));
    }
  return gx >= gy;
}

double median(std::vector<double> v) {
  if (v.empty()) return 0;
  const auto mid = v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2);
  std::nth_element(v.begin(), mid, v.end());
  return *mid;
}

// Robust pixel noise from horizontal differences (the edge touches few of them).
double noise_sigma(const cv::Mat& region) {
  std::vector<double> diffs;
  diffs.reserve(static_cast<size_t>(region.rows) * region.cols);
  for (int y = 0; y < region.rows; ++y) {
    const double* row = region.ptr<double>(y);
    for (int x = 0; x + 1 < region.cols; ++x) diffs.push_back(std::abs(row[x + 1] - row[x]));
  }
  return 1.4826 * median(std::move(diffs)) / std::sqrt(2.0);
}

// Mean of the right-hand columns minus the left-hand columns: sign gives the polarity.
double column_contrast(const cv::Mat& region) {
  const int k = std::max(2, region.cols / 8);
  double left = 0, right = 0;
  for (int y = 0; y < region.rows; ++y) {
    const double* row = region.ptr<double>(y);
    for (int x = 0; x < k; ++x) {
      left += row[x];
      right += row[region.cols - 1 - x];
    }
  }
  return (right - left) / (static_cast<double>(k) * region.rows);
}

// Centroid of the polarity-corrected row derivative under a Hamming window; empty when the
// windowed derivative does not hold at least min_sum of edge signal.
std::optional<double> row_centroid(const double* row, int n, double polarity, double centre, double half_width,
                                   double min_sum) {
  double sum = 0, sum_x = 0;
  for (int x = 1; x + 1 < n; ++x) {
    const double t = (x - centre) / half_width;
    if (std::abs(t) >= 1) continue;
    const double w = hamming(t) * polarity * 0.5 * (row[x + 1] - row[x - 1]);
    sum += w;
    sum_x += w * x;
  }
  if (!(sum > min_sum)) return std::nullopt;
  return sum_x / sum;
}

// Least-squares line through (y, x) points, refitted once without outliers.
edge_line fit_line(const std::vector<double>& ys, const std::vector<double>& xs) {
  auto fit = [](const std::vector<double>& y, const std::vector<double>& x, const std::vector<char>& keep) {
    double n = 0, sy = 0, sx = 0, syy = 0, sxy = 0;
    for (size_t i = 0; i < y.size(); ++i) {
      if (!keep[i]) continue;
      n += 1;
      sy += y[i];
      sx += x[i];
      syy += y[i] * y[i];
      sxy += y[i] * x[i];
    }
    edge_line line;
    const double det = n * syy - sy * sy;
    line.slope = det > 0 ? (n * sxy - sy * sx) / det : 0.0;
    line.offset = n > 0 ? (sx - line.slope * sy) / n : 0.0;
    line.rows_used = static_cast<int>(n);
    return line;
  };
  std::vector<char> keep(ys.size(), 1);
  edge_line line = fit(ys, xs, keep);
  std::vector<double> residuals(ys.size());
  for (size_t i = 0; i < ys.size(); ++i) residuals[i] = std::abs(xs[i] - (line.offset + line.slope * ys[i]));
  const double limit = std::max(0.5, 3.0 * 1.4826 * median(residuals));
  for (size_t i = 0; i < ys.size(); ++i) keep[i] = residuals[i] <= limit;
  line = fit(ys, xs, keep);
  double ss = 0;
  for (size_t i = 0; i < ys.size(); ++i) {
    const double r = xs[i] - (line.offset + line.slope * ys[i]);
    ss += r * r;
  }
  line.rms_residual = ys.empty() ? 0.0 : std::sqrt(ss / static_cast<double>(ys.size()));
  return line;
}

edge_line locate_edge(const cv::Mat& region, double polarity, double contrast, const std::optional<edge_line>& previous,
                      double half_width) {
  std::vector<double> ys, xs;
  const int n = region.cols;
  for (int y = 0; y < region.rows; ++y) {
    const double centre = previous ? previous->offset + previous->slope * y : 0.5 * (n - 1);
    if (auto c = row_centroid(region.ptr<double>(y), n, polarity, centre, half_width, 0.25 * contrast)) {
      ys.push_back(y);
      xs.push_back(*c);
    }
  }
  const int min_rows = std::max(10, region.rows / 2);
  if (static_cast<int>(ys.size()) < min_rows)
    fail("no edge found: only " + std::to_string(ys.size()) + " of " + std::to_string(region.rows) +
         " rows show a step");
  return fit_line(ys, xs);
}

struct esf_profile {
  std::vector<double> values;  // mean pixel value per bin
  double start = 0;            // distance of the first bin's lower end from the edge, pixels
  double bin = 0.25;           // bin width, pixels
};

esf_profile bin_esf(const cv::Mat& region, const edge_line& line, double polarity, int oversampling) {
  const double cos_t = 1.0 / std::sqrt(1.0 + line.slope * line.slope);
  const int rows = region.rows, cols = region.cols;
  // Signed distance along the normal, growing towards the bright side.
  auto distance = [&](double x, double y) { return polarity * (x - line.offset - line.slope * y) * cos_t; };
  // Keep the distance range every row covers, so each bin sees all phases of the slant.
  double lo = -1e300, hi = 1e300;
  for (int y = 0; y < rows; ++y) {
    const double a = distance(0, y), b = distance(cols - 1, y);
    lo = std::max(lo, std::min(a, b));
    hi = std::min(hi, std::max(a, b));
  }
  esf_profile esf;
  esf.bin = 1.0 / oversampling;
  const int nbins = static_cast<int>(std::floor((hi - lo) / esf.bin));
  if (nbins < 8 * oversampling) fail("the edge leaves the region; centre the region on the edge");
  esf.start = lo;
  std::vector<double> sum(nbins, 0.0);
  std::vector<int> count(nbins, 0);
  for (int y = 0; y < rows; ++y) {
    const double* row = region.ptr<double>(y);
    for (int x = 0; x < cols; ++x) {
      const int k = static_cast<int>(std::floor((distance(x, y) - lo) / esf.bin));
      if (k < 0 || k >= nbins) continue;
      sum[k] += row[x];
      ++count[k];
    }
  }
  esf.values.assign(nbins, 0.0);
  int last = -1;
  for (int k = 0; k < nbins; ++k) {
    if (count[k] == 0) continue;
    esf.values[k] = sum[k] / count[k];
    if (last >= 0 && k - last > oversampling)
      fail("edge projection leaves gaps; tilt the edge 2 to 10 degrees from the pixel axis");
    // Fill empty bins between filled ones linearly.
    for (int j = last + 1; j < k; ++j)
      esf.values[j] = last < 0 ? esf.values[k]
                               : esf.values[last] + (esf.values[k] - esf.values[last]) * (j - last) / double(k - last);
    last = k;
  }
  for (int j = last + 1; j < nbins; ++j) esf.values[j] = esf.values[last];
  return esf;
}

// Mean ESF over the outer tenth at each end: the dark and bright levels.
std::pair<double, double> plateaus(const esf_profile& esf) {
  const size_t n = esf.values.size();
  const size_t tail = std::max<size_t>(1, n / 10);
  double low = 0, high = 0;
  for (size_t k = 0; k < tail; ++k) {
    low += esf.values[k];
    high += esf.values[n - 1 - k];
  }
  return {low / tail, high / tail};
}

// Distance between the 10% and 90% points of the (1-pixel smoothed) ESF, in pixels.
double rise_distance(const esf_profile& esf, int oversampling, double low, double high) {
  const int n = static_cast<int>(esf.values.size());
  std::vector<double> smooth(n);
  for (int k = 0; k < n; ++k) {
    const int a = std::max(0, k - oversampling / 2), b = std::min(n - 1, k + oversampling / 2);
    double s = 0;
    for (int j = a; j <= b; ++j) s += esf.values[j];
    smooth[k] = s / (b - a + 1);
  }
  auto crossing = [&](double level, bool from_left) {
    if (from_left) {
      for (int k = 0; k + 1 < n; ++k)
        if (smooth[k] < level && smooth[k + 1] >= level) return k + (level - smooth[k]) / (smooth[k + 1] - smooth[k]);
      return 0.0;
    }
    for (int k = n - 1; k > 0; --k)
      if (smooth[k] > level && smooth[k - 1] <= level) return k - (smooth[k] - level) / (smooth[k] - smooth[k - 1]);
    return double(n - 1);
  };
  // Outermost crossings, so noise near the plateaus cannot make the rise look sharper.
  const double k10 = crossing(low + 0.1 * (high - low), true);
  const double k90 = crossing(low + 0.9 * (high - low), false);
  return std::max(k90 - k10, 1.0) * esf.bin;
}

}  // namespace

mtf_curve slanted_edge_mtf(const cv::Mat& image, const slanted_edge_params& params) {
  if (params.oversampling < 2 || params.oversampling > 16)
    fail("oversampling must be between 2 and 16, got " + std::to_string(params.oversampling));
  if (!(params.max_cycles_per_pixel > 0)) fail("the highest reported frequency must be positive");
  mtf_curve curve;
  cv::Mat region = checked_region(image, params, curve.roi);

  curve.orientation = is_near_vertical(region) ? edge_orientation::near_vertical : edge_orientation::near_horizontal;
  // Measure a near-horizontal edge as a near-vertical one in the transposed region.
  if (curve.orientation == edge_orientation::near_horizontal) region = region.t();

  const double noise = noise_sigma(region);
  const double step = column_contrast(region);
  if (std::abs(step) < 3.0 * noise || std::abs(step) < 1e-9)
    fail("no edge found: the difference between the two sides (" + fmt(std::abs(step)) +
         ") is not above the pixel noise (" + fmt(noise) + ")");
  const double polarity = step > 0 ? 1.0 : -1.0;
  curve.rising = polarity > 0;

  // Pass one over whole rows, then passes with a window that follows the fitted edge.
  const int cols = region.cols;
  edge_line line = locate_edge(region, polarity, std::abs(step), std::nullopt, 0.5 * cols);
  for (int pass = 0; pass < 3; ++pass) {
    const double cos_t = 1.0 / std::sqrt(1.0 + line.slope * line.slope);
    const esf_profile esf = bin_esf(region, line, polarity, params.oversampling);
    const auto [low, high] = plateaus(esf);
    const double rise = rise_distance(esf, params.oversampling, low, high);
    const double half_width = std::min(0.5 * cols, std::max(8.0, 4.0 * rise / cos_t));
    line = locate_edge(region, polarity, std::abs(step), line, half_width);
  }

  if (line.rms_residual > 0.1 * cols)
    fail("no straight edge found: row edge positions scatter by " + fmt(line.rms_residual) +
         " px around the best line");
  for (int y : {0, region.rows - 1}) {
    const double x = line.offset + line.slope * y;
    if (x < 2 || x > cols - 3) fail("the edge leaves the region; centre the region on the edge");
  }
  if (std::abs(line.slope) * (region.rows - 1) < 1.0)
    fail("the edge is only " + fmt(std::atan(std::abs(line.slope)) * 180 / std::numbers::pi) +
         " deg from the pixel axis; tilt it 2 to 10 degrees so the rows sample every phase");
  curve.edge_angle_deg = degrees(std::atan(line.slope));

  const esf_profile esf = bin_esf(region, line, polarity, params.oversampling);
  const int n = static_cast<int>(esf.values.size());
  const auto [low, high] = plateaus(esf);
  curve.esf_contrast = high - low;
  if (!(curve.esf_contrast > 0)) fail("no edge found: the edge spread function does not rise across the edge");
  const double rise = rise_distance(esf, params.oversampling, low, high);
  const double span = n * esf.bin;
  if (rise > 0.5 * span)
    fail("the edge is too blurred for the region (10-90% rise " + fmt(rise) + " px over " + fmt(span) +
         " px); use a wider region");

  // A window much wider than the rise keeps its bias on the MTF small while cutting noise far
  // from the edge.
  const double reach = std::max(-esf.start, esf.start + span);
  const double half_width = std::min(reach, std::max(16.0, 12.0 * rise));
  curve.window_half_width_px = half_width;

  const int fft_size = cv::getOptimalDFTSize(std::max(n, 1024 * params.oversampling));
  cv::Mat lsf = cv::Mat::zeros(1, fft_size, CV_64F);
  for (int k = 1; k + 1 < n; ++k) {
    const double d = esf.start + (k + 0.5) * esf.bin;
    if (std::abs(d) >= half_width) continue;
    lsf.at<double>(0, k) = 0.5 * (esf.values[k + 1] - esf.values[k - 1]) * hamming(d / half_width);
  }
  cv::Mat spectrum;
  cv::dft(lsf, spectrum, cv::DFT_COMPLEX_OUTPUT);
  const auto* bins = spectrum.ptr<cv::Vec2d>(0);
  const double dc = std::hypot(bins[0][0], bins[0][1]);
  if (!(dc > 0)) fail("no edge found: the line spread function has no area");

  const double df = 1.0 / (fft_size * esf.bin);
  for (int k = 0; k <= fft_size / 2; ++k) {
    const double f = k * df;
    if (f > params.max_cycles_per_pixel + 1e-12) break;
    // The central difference over two bins and the averaging into bins of one bin width are
    // filters on the ESF; divide their responses out.
    const double response = sinc(2.0 * f * esf.bin) * sinc(f * esf.bin);
    curve.cycles_per_pixel.push_back(f);
    curve.mtf.push_back(std::hypot(bins[k][0], bins[k][1]) / dc / response);
  }
  return curve;
}

std::vector<double> to_lp_per_mm(const std::vector<double>& cycles_per_pixel, double mm_per_pixel) {
  if (!(mm_per_pixel > 0) || !std::isfinite(mm_per_pixel))
    throw measurement_error("pixel size must be a positive number of mm, got " + fmt(mm_per_pixel));
  std::vector<double> out;
  out.reserve(cycles_per_pixel.size());
  for (double f : cycles_per_pixel) out.push_back(f / mm_per_pixel);
  return out;
}

}  // namespace airr::analysis
