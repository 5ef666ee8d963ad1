// This file is part of opencv_shading. License: Apache-2.0.
// Python bindings of lines and texturedTriangles (conversion and GIL release only).
#include <opencv2/imgproc.hpp>
#include <opencv2/shading.hpp>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <string>

#include "bindings.hpp"
#include "convert.hpp"

namespace py = pybind11;
namespace sh = cv::shading;
using namespace opencv_shading_py;

//! canvasSize (width, height) from any Python sequence of two integers.
static cv::Size toCanvasSize(const py::object& canvasSize)
{
    if (!PySequence_Check(canvasSize.ptr()) || PySequence_Size(canvasSize.ptr()) != 2)
        throw py::type_error("canvasSize: expected (width, height), got " +
                             py::repr(canvasSize).cast<std::string>());
    py::sequence wh = py::reinterpret_borrow<py::sequence>(canvasSize);
    return cv::Size(wh[0].cast<int>(), wh[1].cast<int>());
}

void bindLineAndTexture(py::module_& m)
{
    m.attr("LINE_BRESENHAM") = static_cast<int>(sh::LINE_BRESENHAM);
    m.attr("LINE_DDA") = static_cast<int>(sh::LINE_DDA);

    m.def(
        "lines",
        [](py::object canvas, const py::object& points, const py::object& colors,
           int algorithm) {
            cv::Mat c = wrapCanvas(canvas);
            Input p = toInput(points, "points"), col = toInput(colors, "colors");
            {
                py::gil_scoped_release nogil;
                sh::lines(c, p.mat, col.mat, algorithm);
            }
            return canvas;
        },
        py::arg("canvas"), py::arg("points"), py::arg("colors"),
        py::arg_v("algorithm", static_cast<int>(sh::LINE_BRESENHAM), "LINE_BRESENHAM"),
        "Draws line segments in place, colours interpolated along each.\n\n"
        "canvas: H x W x 3 float32 or uint8 array (or a view of one), drawn into.\n"
        "points: 2N x 2 points; segment i joins points[2i] and points[2i + 1].\n"
        "colors: 2N x 3 colours, one per point, in the canvas's units.\n"
        "algorithm: LINE_BRESENHAM (endpoints rounded; the pixels of cv2.line LINE_8) or "
        "LINE_DDA (1/256 px endpoints, exact fixed-point DDA).\nReturns canvas.");

    m.def(
        "texturedTriangles",
        [](py::object canvas, const py::object& verts2d, const py::object& faces,
           const py::object& texCoords, const py::object& texture, int interpolation,
           int borderMode) {
            cv::Mat c = wrapCanvas(canvas);
            Input v = toInput(verts2d, "verts2d"), f = toInput(faces, "faces", true),
                  uv = toInput(texCoords, "texCoords");
            const Input tex = toImage(texture, "texture");
            {
                py::gil_scoped_release nogil;
                sh::texturedTriangles(c, v.mat, f.mat, uv.mat, tex.mat, interpolation, borderMode);
            }
            return canvas;
        },
        py::arg("canvas"), py::arg("verts2d"), py::arg("faces"), py::arg("texCoords"),
        py::arg("texture"), py::arg_v("interpolation", static_cast<int>(cv::INTER_LINEAR),
                                      "cv2.INTER_LINEAR"),
        py::arg_v("borderMode", static_cast<int>(cv::BORDER_REPLICATE), "cv2.BORDER_REPLICATE"),
        "Draws triangles textured from an image, in place, in face order.\n\n"
        "canvas: H x W x 3 float32 or uint8 array (or a view of one).\n"
        "verts2d: L x 2 vertices. faces: K x 3 zero-based indices. texCoords: L x 2 texture "
        "coordinates in texture pixels (as cv2.remap's maps).\n"
        "texture: H x W x 3 uint8 or float32 image (converted to the canvas's units).\n"
        "interpolation: cv2.INTER_NEAREST or cv2.INTER_LINEAR. borderMode: cv2.BORDER_*.\n"
        "Each covered pixel equals cv2.remap of the texture with float32 maps of the "
        "interpolated coordinates.\nReturns canvas.");

    m.def(
        "forEachSpan",
        [](const py::object& canvasSize, const py::object& vertices, const py::function& fn,
           const py::object& depths) {
            const cv::Size size = toCanvasSize(canvasSize);
            Input v = toInput(vertices, "vertices"), z = toInput(depths, "depths");
            // The callback runs Python: the GIL stays held.
            auto call = [&fn](int y, int xBegin, int xEnd, const cv::Vec3d& w,
                              const cv::Vec3d& dwdx) {
                fn(y, xBegin, xEnd, py::make_tuple(w[0], w[1], w[2]),
                   py::make_tuple(dwdx[0], dwdx[1], dwdx[2]));
            };
            if (depths.is_none())
                sh::forEachSpan(size, v.mat, call);
            else
                sh::forEachSpan(size, v.mat, z.mat, call);
        },
        py::arg("canvasSize"), py::arg("vertices"), py::arg("fn"), py::arg("depths") = py::none(),
        "Calls fn(y, xBegin, xEnd, w, dwdx) for each span of samples the triangle covers on a "
        "canvas of canvasSize (width, height): row y, columns [xBegin, xEnd), the barycentric "
        "weights w at (xBegin, y) for the vertices in the order given and their change per "
        "pixel dwdx (tuples of 3 floats). The samples are exactly those flats covers; an "
        "exception raised by fn propagates.\n"
        "depths: the vertices' camera depths Zc (3 values > 0) for a triangle seen in 3D: "
        "then w and dwdx are h_i = w_i / z_i, affine along the span; h / sum(h) are the "
        "perspective-correct weights and 1 / sum(h) the depth.");

    m.def(
        "forEachSample",
        [](const py::object& canvasSize, const py::object& vertices, const py::function& fn,
           const py::object& depths) {
            const cv::Size size = toCanvasSize(canvasSize);
            Input v = toInput(vertices, "vertices"), z = toInput(depths, "depths");
            // The callback runs Python: the GIL stays held.
            auto call = [&fn](int x, int y, const cv::Vec3d& w) {
                fn(x, y, py::make_tuple(w[0], w[1], w[2]));
            };
            if (depths.is_none())
                sh::forEachSample(size, v.mat, call);
            else
                sh::forEachSample(size, v.mat, z.mat, call);
        },
        py::arg("canvasSize"), py::arg("vertices"), py::arg("fn"), py::arg("depths") = py::none(),
        "Calls fn(x, y, w) for each sample the triangle covers on a canvas of canvasSize "
        "(width, height): pixel (x, y) and its barycentric weights w (a tuple of 3 floats, "
        "summing to 1) for the vertices in the order given. The samples are exactly those "
        "flats covers (forEachSpan is faster); an exception raised by fn propagates.\n"
        "depths: the vertices' camera depths Zc (3 values > 0) for a triangle seen in 3D: the "
        "weights are then perspective-correct (those drawMesh3d interpolates with).");
}
