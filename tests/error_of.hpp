#pragma once
// The message of the error a piece of code throws, for tests of error wording.
#include <stdexcept>
#include <string>

namespace airr::test {

// The message of the std::runtime_error (every project error is one) thrown by f, or "" when none is thrown.
template <class F>
std::string error_of(F&& f) {
  try {
    f();
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "";
}

}  // namespace airr::test
