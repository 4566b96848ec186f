#pragma once
// A long call from Python: it runs with the GIL released, and between its steps takes the GIL
// back to check for Ctrl+C and to tell the caller's progress callback how far it is. Either one
// raising stops the work; the exception is raised again in the caller once the work has stopped
// (no thread of it left running).
#include <exception>
#include <optional>

#include <pybind11/pybind11.h>

namespace airr::python {

class python_job {
 public:
  // `progress`: None, or a callable taking the fraction done (0 to 1).
  explicit python_job(pybind11::object progress) : progress_(std::move(progress)) {}

  // From the work, without the GIL: whether to go on. Calls the callback when the fraction has grown.
  bool keep_going(double fraction) {
    pybind11::gil_scoped_acquire gil;
    if (error_) return false;
    if (PyErr_CheckSignals() != 0) {
      error_.emplace();
      return false;
    }
    if (!progress_.is_none() && fraction > told_) {
      told_ = fraction;
      try {
        progress_(fraction);
      } catch (pybind11::error_already_set& e) {
        error_.emplace(std::move(e));
        return false;
      }
    }
    return true;
  }

  // With the GIL, after the work stopped: raises what stopped it, if anything did.
  void finish() {
    if (error_) {
      pybind11::error_already_set e = std::move(*error_);
      error_.reset();
      throw e;
    }
    if (!progress_.is_none() && told_ < 1.0) {
      told_ = 1.0;
      progress_(1.0);
    }
  }

  bool stopped() const { return error_.has_value(); }

  // Thrown by check() through work that cannot be told to stop otherwise.
  struct stop : std::exception {};
  // From the work, without the GIL: throws stop when it should stop.
  void check(double fraction) {
    if (!keep_going(fraction)) throw stop();
  }

 private:
  pybind11::object progress_;
  double told_ = -1.0;
  std::optional<pybind11::error_already_set> error_;
};

}  // namespace airr::python
