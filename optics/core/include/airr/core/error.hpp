#pragma once
// The project's error types: every error a user can cause or a measurement can meet is one of
// these, with a one-line message naming where (file, field, region) and what is wrong.
#include <stdexcept>
#include <string>

namespace airr {

struct airr_error : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// An error in user input (a file, a field, a parameter).
struct input_error : airr_error {
  using airr_error::airr_error;
};

// A measurement that cannot be made on the data given (no edge, a flat region, ...).
struct measurement_error : airr_error {
  using airr_error::airr_error;
};

// A number as error messages show it: `digits` significant digits, no trailing zeros ("0.1",
// "1e+30", "7").
std::string number_text(double v, int digits = 6);

// A library's message made one line of an error: its lines joined by "; ", blank ones dropped.
std::string one_line(const std::string& message);

}  // namespace airr
