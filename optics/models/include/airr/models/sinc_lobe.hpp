#pragma once
// The angular spread of the sinc-shift model: the deviation delta from the exact retro direction
// has density p(delta) ~ sinc^2(k tan delta) / cos^2 delta on [0, pi/2), k = a R, so that the
// offset x = R tan delta at distance R is sinc^2(a x) distributed.
#include <vector>

namespace airr {

inline constexpr int sinc_lobe_table_size = 30000;

class sinc_lobe {
 public:
  // The 30000-point table over [0, 90 deg) for k = 1, normalised to sum 1.
  static const sinc_lobe& instance();

  // tan of the deviation angle for spread k = a R, from two uniform numbers. The table is
  // sampled as a discrete distribution with uniform jitter inside the cell, giving delta_1
  // for k = 1; tan(delta) = tan(delta_1) / k maps k tan(delta) onto the same sinc^2 law.
  // (The tangent, not the angle: the direction needs only its sine and cosine.)
  double sample_tan_delta(double k, double u_cell, double u_jitter) const {
    return sample_k_tan_delta(u_cell, u_jitter) / k;
  }
  // k tan(delta), the same for every k: samples at several spreads from the same numbers share it.
  double sample_k_tan_delta(double u_cell, double u_jitter) const;

  // The continuous density of delta (per radian) for spread k, normalised on [0, pi/2).
  static double pdf(double delta, double k);

 private:
  sinc_lobe();
  std::vector<double> cdf_;        // cdf_[j] = sum of weights of cells < j+1
  std::vector<double> tan_start_;  // tan of each cell's first angle
  // guide_[b]: the first cell whose cdf_ exceeds b / guide_size, so that a lookup searches only
  // between two neighbouring entries (the same cell as a search of the whole table).
  static constexpr int guide_size = 4096;
  std::vector<int> guide_;
};

double sinc(double x);

}  // namespace airr
