// This file is part of opencv_shading. License: Apache-2.0.
// Python bindings of the polygon functions: fillPolygons, triangulatePolygons, FILL_*.
#include <opencv2/shading.hpp>

#include "bindings.hpp"
#include "convert.hpp"

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <cstring>
#include <string>
#include <vector>

namespace py = pybind11;
namespace sh = cv::shading;
using namespace opencv_shading_py;

namespace {

// The contours and the Python objects their Mats view.
struct ContourList {
    std::vector<Input> inputs;
    std::vector<cv::Mat> mats;
};

// As cv2.fillPoly: a sequence of contours (each N x 2 array-like), or a K x N x 2 array
// (K contours of N points); a 2D N x 2 array is one contour.
ContourList toContours(const py::handle& obj) {
    ContourList out;
    if (obj.is_none())
        return out;
    std::vector<py::object> items;
    if (py::isinstance<py::array>(obj)) {
        py::array a = py::reinterpret_borrow<py::array>(obj);
        if (a.ndim() == 2) {
            items.push_back(a);
        } else if (a.ndim() == 3) {
            for (py::ssize_t k = 0; k < a.shape(0); ++k)
                items.push_back(a[py::int_(k)]);
        } else {
            throw py::value_error("polygons: expected a list of N x 2 arrays, an N x 2 array or "
                                  "a K x N x 2 array, got shape " +
                                  py::str(a.attr("shape")).cast<std::string>());
        }
    } else {
        if (!PySequence_Check(obj.ptr()) || PyUnicode_Check(obj.ptr()))
            throw py::type_error("polygons: expected a sequence of contours (N x 2 points each), "
                                 "got " + py::str(py::type::of(obj)).cast<std::string>());
        for (py::handle h : py::reinterpret_borrow<py::sequence>(obj))
            items.push_back(py::reinterpret_borrow<py::object>(h));
    }
    for (size_t i = 0; i < items.size(); ++i) {
        const std::string name = "polygons[" + std::to_string(i) + "]";
        out.inputs.push_back(toInput(items[i], name.c_str()));
        out.mats.push_back(out.inputs.back().mat);
    }
    return out;
}

// cv2's Scalar: one number or up to 4.
cv::Scalar toColor(const py::handle& obj) {
    py::module_ np = py::module_::import("numpy");
    py::array a = np.attr("asarray")(obj, py::arg("dtype") = "float64").attr("ravel")();
    if (a.size() < 1 || a.size() > 4)
        throw py::value_error("color: expected 1 to 4 numbers, got " +
                              py::repr(obj).cast<std::string>());
    const double* p = static_cast<const double*>(a.data());
    if (a.size() == 1)
        return cv::Scalar::all(p[0]);
    cv::Scalar s;
    for (py::ssize_t i = 0; i < a.size(); ++i)
        s[static_cast<int>(i)] = p[i];
    return s;
}

}  // namespace

void bindPolygon(py::module_& m) {
    m.attr("FILL_EVEN_ODD") = static_cast<int>(sh::FILL_EVEN_ODD);
    m.attr("FILL_NONZERO") = static_cast<int>(sh::FILL_NONZERO);

    m.def(
        "fillPolygons",
        [](py::object canvas, const py::object& polygons, const py::object& color,
           int fillRule) {
            cv::Mat c = wrapCanvas(canvas);
            ContourList contours = toContours(polygons);
            const cv::Scalar col = toColor(color);
            {
                py::gil_scoped_release nogil;
                sh::fillPolygons(c, contours.mats, col, fillRule);
            }
            return canvas;
        },
        py::arg("canvas"), py::arg("polygons"), py::arg("color"),
        py::arg_v("fillRule", static_cast<int>(sh::FILL_EVEN_ODD), "FILL_EVEN_ODD"),
        "Fills polygons (holes, self-intersections) by scan conversion, in place.\n\n"
        "canvas: H x W x 3 float32 or uint8 array (or a view of one).\n"
        "polygons: a list of contours, each N x 2 points (x, y), as cv2.fillPoly takes them; "
        "or one N x 2 array, or a K x N x 2 array. Contours of fewer than 3 points draw nothing.\n"
        "color: up to 3 numbers in the canvas's units.\n"
        "fillRule: FILL_EVEN_ODD or FILL_NONZERO: which winding numbers around (x + e, y + e^2) "
        "are inside.\nReturns canvas.");

    m.def(
        "triangulatePolygons",
        [](const py::object& polygons, int fillRule, bool returnVertices) -> py::object {
            ContourList contours = toContours(polygons);
            cv::Mat faces, vertices;
            {
                py::gil_scoped_release nogil;
                sh::triangulatePolygons(contours.mats, faces, fillRule, vertices);
            }
            py::array_t<int32_t> f({static_cast<py::ssize_t>(faces.rows),
                                    static_cast<py::ssize_t>(3)});
            if (faces.rows > 0)
                std::memcpy(f.mutable_data(), faces.ptr<int32_t>(),
                            sizeof(int32_t) * 3 * static_cast<size_t>(faces.rows));
            if (!returnVertices)
                return std::move(f);
            py::array_t<double> v({static_cast<py::ssize_t>(vertices.rows),
                                   static_cast<py::ssize_t>(2)});
            if (vertices.rows > 0)
                std::memcpy(v.mutable_data(), vertices.ptr<double>(),
                            sizeof(double) * 2 * static_cast<size_t>(vertices.rows));
            return py::make_tuple(f, v);
        },
        py::arg("polygons"),
        py::arg_v("fillRule", static_cast<int>(sh::FILL_EVEN_ODD), "FILL_EVEN_ODD"),
        py::arg("returnVertices") = false,
        "Triangles covering what fillPolygons covers with the same rule, each sample at most "
        "once, exactly (crossings off the 1/256 px grid move to nearby grid points, checked "
        "to change no sample; edges thousands of pixels long, and rarely dense crossings no "
        "grid point suits, fall back to snap rounding, where samples within 1/512 px of an "
        "edge may differ).\n\n"
        "polygons: as for fillPolygons; contours may cross and touch.\n"
        "Returns faces, K x 3 int32 indices into the contours' points concatenated in order, "
        "then the added crossing points; with returnVertices=True, (faces, vertices), vertices "
        "N x 2 float64 in pixels: the snapped points, then the crossings' grid points (1/256 px).");
}
