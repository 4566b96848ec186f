#pragma once
// A display's angular luminance profile: L(theta) / L(0), theta from the display's normal in
// degrees, from a CSV file with the columns angle_deg,relative_luminance.
#include <memory>
#include <string>
#include <vector>

namespace airr {

struct emission_profile {
  std::vector<double> angle_deg;  // ascending, from 0, at most 90
  std::vector<double> relative;   // at angle 0 exactly 1

  // Linear between rows; beyond the last row, the last value.
  double at(double theta_deg) const;
};

// Throws input_error naming the file, the line and the problem: angles not ascending from 0 to at
// most 90, a negative value, a zero value at 0 (the others are divided by it), fewer than 2 rows.
emission_profile read_emission_profile(const std::string& path);
// The same, read once per path and modification time, shared.
std::shared_ptr<const emission_profile> load_emission_profile(const std::string& path);

}  // namespace airr
