// This file is part of opencv_shading. License: Apache-2.0.
// Argument conversion shared by the binding files: array-likes to cv::Mat inputs, and numpy
// canvases wrapped in place (never copied).
#ifndef OPENCV_SHADING_PY_CONVERT_HPP
#define OPENCV_SHADING_PY_CONVERT_HPP

#include <opencv2/core.hpp>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <cstdint>
#include <limits>
#include <string>
#include <utility>

namespace opencv_shading_py {

namespace py = pybind11;

// ---- inputs -------------------------------------------------------------------------------

// An input array as the C++ API takes it: `mat` views `keep`'s buffer (or is empty for None).
struct Input {
    py::object keep;
    cv::Mat mat;
};

inline bool isDtype(const py::array& a, const py::dtype& dt) {
    return a.dtype().equal(dt) && a.dtype().attr("isnative").cast<bool>();
}

// Any array-like (ndarray, list, tuple, None) -> cv::Mat of CV_32S, CV_32F or CV_64F.
// No copy when the array already has one of those dtypes and is C-contiguous. `index`: integer
// data are indices (faces) and must fit in int32; other integers wider than 16 bits go to
// float64, which holds every coordinate the library accepts exactly.
inline Input toInput(const py::handle& obj, const char* name, bool index = false) {
    Input in;
    if (obj.is_none())
        return in;
    py::module_ np = py::module_::import("numpy");
    py::array a = np.attr("asarray")(obj);
    const char kind = a.dtype().kind();
    const py::ssize_t itemsize = a.dtype().itemsize();
    int depth = -1;
    if (isDtype(a, py::dtype::of<double>())) {
        depth = CV_64F;
    } else if (isDtype(a, py::dtype::of<float>())) {
        depth = CV_32F;
    } else if (isDtype(a, py::dtype::of<int32_t>())) {
        depth = CV_32S;
    } else if (kind == 'b' || kind == 'i' || kind == 'u') {
        if (index && a.size() > 0 && itemsize >= 4) {
            py::object lo = a.attr("min")(), hi = a.attr("max")();
            const py::int_ minv(std::numeric_limits<int32_t>::min());
            const py::int_ maxv(std::numeric_limits<int32_t>::max());
            if (lo < minv || hi > maxv)
                throw py::value_error(std::string(name) + ": index " +
                                      py::str(lo < minv ? lo : hi).cast<std::string>() +
                                      " does not fit in int32");
        }
        depth = (index || kind == 'b' || itemsize <= 2) ? CV_32S : CV_64F;
    } else if (kind == 'f') {
        depth = itemsize <= 4 ? CV_32F : CV_64F;  // float16 / non-native / long double
    } else {
        throw py::type_error(std::string(name) + ": expected numbers, got an array of dtype " +
                             py::str(a.dtype()).cast<std::string>());
    }
    const char* dt = depth == CV_64F ? "float64" : depth == CV_32F ? "float32" : "int32";
    a = np.attr("ascontiguousarray")(a, py::arg("dtype") = dt);
    const int nd = static_cast<int>(a.ndim());
    int rows = 1, cols = 1, cn = 1;
    if (nd >= 1)
        rows = static_cast<int>(a.shape(0));
    if (nd >= 2)
        cols = static_cast<int>(a.shape(1));
    if (nd == 3)
        cn = static_cast<int>(a.shape(2));  // N x 1 x C or 1 x N x C: a multi-channel Mat
    if (nd > 3 || cn > CV_CN_MAX)
        throw py::value_error(std::string(name) + ": expected at most 3 dimensions (N x C, or "
                              "N x 1 x C with C <= 512), got shape " +
                              py::str(a.attr("shape")).cast<std::string>());
    in.mat = cv::Mat(rows, cols, CV_MAKETYPE(depth, cn), const_cast<void*>(a.data()));
    in.keep = std::move(a);
    return in;
}

// ---- canvases and in/out buffers: wrapped in place, never copied ----------------------------

inline std::string describe(const py::array& a) {
    return "dtype " + py::str(a.dtype()).cast<std::string>() + ", shape " +
           py::str(a.attr("shape")).cast<std::string>() + ", strides " +
           py::str(a.attr("strides")).cast<std::string>();
}

// A writable numpy H x W x cn (cn == 0: H x W) array of dtype T as a cv::Mat header on its
// memory. Views (img[10:200, 30:300]) keep their row step; elements within a row must be
// contiguous since cv::Mat has one step per row only.
template <typename T>
inline cv::Mat wrapInPlace(const py::handle& obj, const char* name, int cn, const char* dtypes) {
    const std::string what = cn ? "an H x W x 3 numpy array of dtype " + std::string(dtypes)
                                : "an H x W numpy array of dtype " + std::string(dtypes);
    if (!py::isinstance<py::array>(obj))
        throw py::type_error(std::string(name) + ": expected " + what + ", got " +
                             py::str(py::type::of(obj)).cast<std::string>());
    py::array a = py::reinterpret_borrow<py::array>(obj);
    if (!isDtype(a, py::dtype::of<T>()))
        throw py::type_error(std::string(name) + ": expected " + what + ", got " + describe(a));
    const py::ssize_t es = static_cast<py::ssize_t>(sizeof(T));
    const int nd = cn ? 3 : 2;
    if (a.ndim() != nd || (cn && a.shape(2) != cn))
        throw py::value_error(std::string(name) + ": expected " + what + ", got " + describe(a));
    if (!a.writeable())
        throw py::value_error(std::string(name) + ": the array is read-only; pass a writable "
                              "array (it is drawn into in place)");
    const py::ssize_t rows = a.shape(0), cols = a.shape(1), pix = es * (cn ? cn : 1);
    const bool rowOk = cols <= 1 || a.strides(1) == pix;
    const bool chOk = !cn || a.strides(2) == es;
    const bool stepOk = rows <= 1 || (a.strides(0) >= pix * cols && a.strides(0) % es == 0);
    if (!rowOk || !chOk || !stepOk)
        throw py::value_error(std::string(name) + ": each row's pixels must be contiguous "
                              "(pixel stride = channels * itemsize, channel stride = itemsize, "
                              "positive row stride) to draw in place; got " + describe(a) +
                              "; use numpy.ascontiguousarray and copy back");
    const int type = CV_MAKETYPE(cv::DataType<T>::depth, cn ? cn : 1);
    const size_t step = rows <= 1 ? static_cast<size_t>(cv::Mat::AUTO_STEP)
                                  : static_cast<size_t>(a.strides(0));
    return cv::Mat(static_cast<int>(rows), static_cast<int>(cols), type, a.mutable_data(), step);
}

// A read-only colour image (a texture): uint8 or float32 H x W x 3, any other dtype converted
// to float32; `mat` views `keep`.
inline Input toImage(const py::handle& obj, const char* name) {
    py::module_ np = py::module_::import("numpy");
    py::array t = np.attr("asarray")(obj);
    const bool is8u = isDtype(t, py::dtype::of<uint8_t>());
    t = np.attr("ascontiguousarray")(t, py::arg("dtype") = is8u ? "uint8" : "float32");
    if (t.ndim() != 3 || t.shape(2) != 3)
        throw py::value_error(std::string(name) + ": expected an H x W x 3 array, got " +
                              describe(t));
    Input in;
    in.mat = cv::Mat(static_cast<int>(t.shape(0)), static_cast<int>(t.shape(1)),
                     is8u ? CV_8UC3 : CV_32FC3, const_cast<void*>(t.data()));
    in.keep = t;
    return in;
}

inline cv::Mat wrapCanvas(const py::handle& obj) {
    if (py::isinstance<py::array>(obj) &&
        isDtype(py::reinterpret_borrow<py::array>(obj), py::dtype::of<uint8_t>()))
        return wrapInPlace<uint8_t>(obj, "canvas", 3, "float32 or uint8");
    return wrapInPlace<float>(obj, "canvas", 3, "float32 or uint8");
}

}  // namespace opencv_shading_py

#endif  // OPENCV_SHADING_PY_CONVERT_HPP
