// This file is part of opencv_shading. License: Apache-2.0.
// The binding files' entry points, each called once from the module init (opencv_shading.cpp).
#ifndef OPENCV_SHADING_PY_BINDINGS_HPP
#define OPENCV_SHADING_PY_BINDINGS_HPP

#include <pybind11/pybind11.h>

//! lines, LINE_*, texturedTriangles (bind_line.cpp).
void bindLineAndTexture(pybind11::module_& m);

//! fillPolygons, triangulatePolygons, FILL_* (bind_polygon.cpp).
void bindPolygon(pybind11::module_& m);

#endif  // OPENCV_SHADING_PY_BINDINGS_HPP
