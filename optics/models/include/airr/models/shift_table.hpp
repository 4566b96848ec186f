#pragma once
// Corner-cube exit-point shift distributions P(theta) (spec section 3): for each tabulated
// incidence angle, a normalised histogram of the shift between entry and exit points on the
// aperture plane, in cube edge lengths, plus the retroreflected fraction of the aperture.
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace airr {

struct shift_table {
  std::vector<double> theta_deg;                 // ascending, e.g. 0, 5, ..., 45
  double s_max = 1.5;                            // histogram range [0, s_max]
  std::vector<std::vector<double>> probability;  // [theta][bin]; each row sums to 1
  std::vector<double> retro_fraction;            // [theta]: retroreflected / entering the aperture
  nlohmann::json provenance;                     // grid, angles, date, command, run time
  std::vector<std::vector<double>> cdf;          // [theta][bin]: cumulative probability (finalize_shift_table)

  int bins() const { return probability.empty() ? 0 : int(probability[0].size()); }
};

// Fills `cdf` from `probability` (sample_shift needs it); load_shift_table and the generator
// call it. Throws std::invalid_argument for rows of different lengths or a row with no probability.
void finalize_shift_table(shift_table& table);

// Throws input_error naming the file and the problem (malformed, rows not normalised, ...).
shift_table load_shift_table(const std::string& path);
// The same, loaded once per path and shared.
std::shared_ptr<const shift_table> cached_shift_table(const std::string& path);
// Atomic write (temporary file, then rename).
void save_shift_table(const shift_table& table, const std::string& path);

// The table shipped in assets/shift_tables/corner_cube.json.
std::string default_shift_table_path();

// The two tables around an incidence angle: the upper one is chosen when u_pick < t. Angles
// outside the table (and NaN) clamp to an end row (lower = upper). Throws std::logic_error for an
// empty table or one without its CDF.
struct shift_rows {
  std::size_t lower = 0, upper = 0;
  double t = 0;
  std::size_t picked(double u_pick) const { return u_pick < t ? upper : lower; }
};
shift_rows shift_rows_at(const shift_table& table, double theta_deg);

// Draws a shift (edge lengths) for incidence angle theta_deg: one of the two neighbouring
// tables is chosen with the linear interpolation weight (u_pick), a bin from its distribution
// (u_bin) and a uniform position inside the bin (u_jitter). Angles outside the table clamp.
double sample_shift(const shift_table& table, double theta_deg, double u_pick, double u_bin, double u_jitter);
// The same from the rows of shift_rows_at, for many draws at one angle.
double sample_shift(const shift_table& table, const shift_rows& rows, double u_pick, double u_bin, double u_jitter);
// The shift drawn from one row (the bin and the position inside it): sample_shift is
// shift_in_row(table, rows.picked(u_pick), u_bin, u_jitter).
double shift_in_row(const shift_table& table, std::size_t row, double u_bin, double u_jitter);

}  // namespace airr
