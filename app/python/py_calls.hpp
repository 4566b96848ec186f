#pragma once
// The Python module's functions over the libraries: render; psf, mtf, compare and the image files;
// fit; sweep, viewzone, optimise and tolerance.
#include <pybind11/pybind11.h>

namespace airr::python {

void add_render_functions(pybind11::module_& m);
void add_measure_functions(pybind11::module_& m);
void add_fit_functions(pybind11::module_& m);
void add_study_functions(pybind11::module_& m);

}  // namespace airr::python
