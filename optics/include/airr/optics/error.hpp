#pragma once
#include <stdexcept>
#include <string>

namespace airr {

// An error in user input (a file, a field, a parameter); the message is one line naming where.
struct input_error : std::runtime_error {
  using std::runtime_error::runtime_error;
};

}  // namespace airr
