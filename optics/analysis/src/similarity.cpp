#include "airr/analysis/similarity.hpp"
#include "airr/core/error.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <string>

#include <opencv2/imgproc.hpp>

namespace airr::analysis {

namespace {

std::string size_text(const cv::Mat& m) { return std::to_string(m.cols) + "x" + std::to_string(m.rows); }

void check_pair(const cv::Mat& a, const cv::Mat& b, const ssim_params& params) {
  if (a.empty() || b.empty()) throw measurement_error("cannot compare an empty image");
  if (a.channels() != 1 || b.channels() != 1)
    throw measurement_error("SSIM compares single-channel (luminance) images");
  if (a.size() != b.size()) throw measurement_error("images differ in size: " + size_text(a) + " vs " + size_text(b));
  if (params.window < 3 || params.window % 2 == 0 || !(params.sigma > 0))
    throw measurement_error("SSIM window must be odd and at least 3 with a positive sigma");
  if (a.cols < params.window || a.rows < params.window)
    throw measurement_error("images of " + size_text(a) + " are smaller than the " + std::to_string(params.window) +
                            "-pixel SSIM window");
  if (!cv::checkRange(a) || !cv::checkRange(b)) throw measurement_error("images hold NaN or infinite values");
}

struct ssim_means {
  double ssim = 0;
  double cs = 0;  // contrast-structure term alone
};

ssim_means ssim_terms(const cv::Mat& a, const cv::Mat& b, const ssim_params& params, double range) {
  const double c1 = std::pow(params.k1 * range, 2), c2 = std::pow(params.k2 * range, 2);
  const cv::Size k(params.window, params.window);
  auto blur = [&](const cv::Mat& m) {
    cv::Mat out;
    cv::GaussianBlur(m, out, k, params.sigma, params.sigma, cv::BORDER_REFLECT);
    return out;
  };
  const cv::Mat mu_a = blur(a), mu_b = blur(b);
  const cv::Mat aa = blur(a.mul(a)), bb = blur(b.mul(b)), ab = blur(a.mul(b));
  // Only positions where the whole window lies inside the image.
  const int r = params.window / 2;
  ssim_means m;
  double n = 0;
  for (int y = r; y < a.rows - r; ++y)
    for (int x = r; x < a.cols - r; ++x) {
      const double ma = mu_a.at<double>(y, x), mb = mu_b.at<double>(y, x);
      const double va = aa.at<double>(y, x) - ma * ma, vb = bb.at<double>(y, x) - mb * mb;
      const double cov = ab.at<double>(y, x) - ma * mb;
      const double cs = (2 * cov + c2) / (va + vb + c2);
      m.cs += cs;
      m.ssim += (2 * ma * mb + c1) / (ma * ma + mb * mb + c1) * cs;
      n += 1;
    }
  m.cs /= n;
  m.ssim /= n;
  return m;
}

cv::Mat as_double(const cv::Mat& m) {
  cv::Mat out;
  m.convertTo(out, CV_64F);
  return out;
}

// 2x2 box average and subsample (odd last rows/columns are dropped).
cv::Mat halve(const cv::Mat& m) {
  const cv::Mat even = m(cv::Rect(0, 0, m.cols & ~1, m.rows & ~1));
  cv::Mat out;
  cv::resize(even, out, cv::Size(even.cols / 2, even.rows / 2), 0, 0, cv::INTER_AREA);
  return out;
}

}  // namespace

double auto_data_range(const cv::Mat& a, const cv::Mat& b) {
  double lo_a = 0, hi_a = 0, lo_b = 0, hi_b = 0;
  cv::minMaxLoc(a.reshape(1), &lo_a, &hi_a);
  cv::minMaxLoc(b.reshape(1), &lo_b, &hi_b);
  const double range = std::max(hi_a, hi_b) - std::min(lo_a, lo_b);
  return range > 0 ? range : 1.0;
}

double ssim(const cv::Mat& a, const cv::Mat& b, const ssim_params& params) {
  check_pair(a, b, params);
  const double range = params.data_range > 0 ? params.data_range : auto_data_range(a, b);
  return ssim_terms(as_double(a), as_double(b), params, range).ssim;
}

ms_ssim_result ms_ssim(const cv::Mat& a, const cv::Mat& b, const ssim_params& params) {
  check_pair(a, b, params);
  const double range = params.data_range > 0 ? params.data_range : auto_data_range(a, b);
  constexpr std::array<double, 5> weights = {0.0448, 0.2856, 0.3001, 0.2363, 0.1333};

  ms_ssim_result r;
  int smallest = std::min(a.cols, a.rows);
  while (r.scales < 5 && smallest >= params.window) {
    ++r.scales;
    smallest /= 2;
  }
  double weight_sum = 0;
  for (int i = 0; i < r.scales; ++i) weight_sum += weights[i];

  cv::Mat sa = as_double(a), sb = as_double(b);
  double log_value = 0;
  for (int i = 0; i < r.scales; ++i) {
    const ssim_means m = ssim_terms(sa, sb, params, range);
    // Negative terms (anti-correlated structure) count as no similarity at that scale.
    const double term = std::max(0.0, i + 1 == r.scales ? m.ssim : m.cs);
    if (term == 0) return {0.0, r.scales};
    log_value += weights[i] / weight_sum * std::log(term);
    if (i + 1 < r.scales) {
      sa = halve(sa);
      sb = halve(sb);
    }
  }
  r.value = std::exp(log_value);
  return r;
}

}  // namespace airr::analysis
