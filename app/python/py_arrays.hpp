#pragma once
// Images and curves as numpy arrays (copies the array owns), and JSON as Python's dicts and lists.
#include <vector>

#include <pybind11/numpy.h>
#include <opencv2/core.hpp>

#include "airr/formats/image.hpp"

namespace airr::python {

// H x W x 3 float32, linear.
inline pybind11::array_t<float> to_array(const image_rgb& img) {
  pybind11::array_t<float> a({img.height, img.width, 3});
  std::copy(img.rgb.begin(), img.rgb.end(), a.mutable_data());
  return a;
}

inline pybind11::array_t<double> to_array(const std::vector<double>& v) {
  pybind11::array_t<double> a(pybind11::ssize_t(v.size()));
  std::copy(v.begin(), v.end(), a.mutable_data());
  return a;
}

// A CV_64FC1 matrix as H x W float64.
inline pybind11::array_t<double> to_array(const cv::Mat& m) {
  pybind11::array_t<double> a({m.rows, m.cols});
  for (int y = 0; y < m.rows; ++y) std::copy(m.ptr<double>(y), m.ptr<double>(y) + m.cols, a.mutable_data(y, 0));
  return a;
}

// Through Python's json module: dicts, lists, numbers, text, True/False and None.
inline pybind11::object to_python(const nlohmann::json& j) {
  return pybind11::module_::import("json").attr("loads")(j.dump());
}

}  // namespace airr::python
