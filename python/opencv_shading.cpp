// This file is part of opencv_shading. License: Apache-2.0.
// Python bindings (pybind11): argument conversion and GIL release only. Every pixel is drawn by
// the C++ library; see <opencv2/shading.hpp> for the rules.
#include <opencv2/shading.hpp>
#if __has_include(<opencv2/shading/meshio.hpp>)
#include <opencv2/shading/meshio.hpp>
#define OPENCV_SHADING_PY_MESHIO 1
#endif

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include "bindings.hpp"
#include "convert.hpp"

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <initializer_list>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

namespace py = pybind11;
namespace sh = cv::shading;
using namespace opencv_shading_py;

namespace {

// A shadeType argument: an int (SHADE_*) or one of the course's names "flat", "gouraud", "phong".
struct ShadeArg {
    int value;
};

}  // namespace

namespace pybind11 {
namespace detail {

template <>
struct type_caster<ShadeArg> {
    PYBIND11_TYPE_CASTER(ShadeArg, const_name("int | str"));

    bool load(handle src, bool) {
        if (PyUnicode_Check(src.ptr())) {
            std::string s = src.cast<std::string>(), low = s;
            std::transform(low.begin(), low.end(), low.begin(),
                           [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
            static const char* const names[] = {"flat", "gouraud", "phong"};
            for (int i = 0; i < 3; ++i) {
                if (low == names[i]) {
                    value.value = i;  // SHADE_FLAT, SHADE_GOURAUD, SHADE_PHONG
                    return true;
                }
            }
            throw value_error("shadeType: '" + s +
                              "' is not one of 'flat', 'gouraud', 'phong' (any case) "
                              "or SHADE_FLAT, SHADE_GOURAUD, SHADE_PHONG");
        }
        // Reject floats and bools as cv2 does; accept anything with __index__ (numpy ints too).
        if (PyFloat_Check(src.ptr()) || PyBool_Check(src.ptr()) || !PyIndex_Check(src.ptr()))
            return false;
        make_caster<int> ic;
        if (!ic.load(src, true))
            return false;
        value.value = cast_op<int>(ic);
        return true;
    }

    static handle cast(ShadeArg s, return_value_policy, handle) {
        return PyLong_FromLong(s.value);
    }
};

}  // namespace detail
}  // namespace pybind11

namespace {

PyObject* g_error = nullptr;  // opencv_shading.error, alive as long as the interpreter


template <typename T>
T toNumber(const py::handle& h, const char* name) {
    try {
        return h.cast<T>();
    } catch (const py::cast_error&) {
        throw py::type_error(std::string(name) + ": expected a number, got " +
                             py::repr(h).cast<std::string>());
    }
}

// A sequence of exactly n numbers.
std::vector<double> toDoubles(const py::handle& obj, size_t n, const char* name) {
    py::module_ np = py::module_::import("numpy");
    py::array a = np.attr("asarray")(obj, py::arg("dtype") = "float64").attr("ravel")();
    if (static_cast<size_t>(a.size()) != n)
        throw py::value_error(std::string(name) + ": expected " + std::to_string(n) +
                              " numbers, got " + py::repr(obj).cast<std::string>());
    const double* p = static_cast<const double*>(a.data());
    return std::vector<double>(p, p + n);
}

cv::Point3d toPoint3d(const py::handle& obj, const char* name) {
    std::vector<double> v = toDoubles(obj, 3, name);
    return cv::Point3d(v[0], v[1], v[2]);
}

cv::Vec3d toVec3d(const py::handle& obj, const char* name) {
    std::vector<double> v = toDoubles(obj, 3, name);
    return cv::Vec3d(v[0], v[1], v[2]);
}

// cv2's Scalar: one number or up to 4.
cv::Scalar toScalar(const py::handle& obj, const char* name) {
    if (PyFloat_Check(obj.ptr()) || PyLong_Check(obj.ptr()))
        return cv::Scalar::all(obj.cast<double>());
    py::module_ np = py::module_::import("numpy");
    py::array a = np.attr("asarray")(obj, py::arg("dtype") = "float64").attr("ravel")();
    if (a.size() < 1 || a.size() > 4)
        throw py::value_error(std::string(name) + ": expected 1 to 4 numbers, got " +
                              py::repr(obj).cast<std::string>());
    cv::Scalar s;
    for (py::ssize_t i = 0; i < a.size(); ++i)
        s[static_cast<int>(i)] = static_cast<const double*>(a.data())[i];
    return s;
}

// cv2's Size: (width, height), integers.
cv::Size toSize(const py::handle& obj) {
    if (!PySequence_Check(obj.ptr()) || PySequence_Size(obj.ptr()) != 2)
        throw py::type_error("size: expected (width, height), got " +
                             py::repr(obj).cast<std::string>());
    py::sequence seq = py::reinterpret_borrow<py::sequence>(obj);
    return cv::Size(toNumber<int>(seq[0], "size"), toNumber<int>(seq[1], "size"));
}

// A str or os.PathLike file name.
std::string toPath(const py::handle& obj) {
    py::object p = py::module_::import("os").attr("fspath")(obj);
    if (!PyUnicode_Check(p.ptr()))
        throw py::type_error("filename: expected str or os.PathLike, got " +
                             py::str(py::type::of(p)).cast<std::string>());
    return p.cast<std::string>();
}


// ---- outputs --------------------------------------------------------------------------------

py::dtype dtypeOf(int depth) {
    switch (depth) {
    case CV_8U: return py::dtype::of<uint8_t>();
    case CV_8S: return py::dtype::of<int8_t>();
    case CV_16U: return py::dtype::of<uint16_t>();
    case CV_16S: return py::dtype::of<int16_t>();
    case CV_32S: return py::dtype::of<int32_t>();
    case CV_32F: return py::dtype::of<float>();
    case CV_64F: return py::dtype::of<double>();
    default: throw std::runtime_error("opencv_shading: unsupported output depth");
    }
}

// A numpy array sharing the Mat's buffer (the array owns a reference to it): no copy.
py::array toNumpy(const cv::Mat& m0) {
    cv::Mat m = m0.isContinuous() ? m0 : m0.clone();
    const int cn = m.channels();
    std::vector<py::ssize_t> shape = {m.rows, m.cols}, strides;
    if (cn > 1)
        shape.push_back(cn);
    if (m.empty())
        return py::array(dtypeOf(m.depth()), shape);
    strides = {static_cast<py::ssize_t>(m.step[0]), static_cast<py::ssize_t>(m.elemSize())};
    if (cn > 1)
        strides.push_back(static_cast<py::ssize_t>(m.elemSize1()));
    auto* owner = new cv::Mat(m);
    py::capsule base(owner, [](void* p) { delete static_cast<cv::Mat*>(p); });
    return py::array(dtypeOf(m.depth()), shape, strides, owner->data, base);
}

// `arr` is the numpy array `wrap` views and `used` the Mat the C++ call wrote: normally the
// same buffer. Should the call have reallocated it, its content is copied back (same shape and
// type) or returned as a new array.
py::object finish(const py::object& arr, const cv::Mat& wrap, const cv::Mat& used) {
    if (used.data == wrap.data)
        return arr;
    if (used.size == wrap.size && used.type() == wrap.type()) {
        cv::Mat w = wrap;
        used.copyTo(w);
        return arr;
    }
    return toNumpy(used);
}

py::array_t<float> newFloat(int rows, int cols, int cn) {
    std::vector<py::ssize_t> shape = {rows, cols};
    if (cn > 1)
        shape.push_back(cn);
    return py::array_t<float>(shape);
}

/** Runs a 3D draw (drawFn(canvas, depthBuffer, faceIds) without the GIL) into numpy outputs
the C++ writes into: an absent depthBuffer starts as the C++ would create it (canvas-sized,
+inf). Returns (canvas, depthBuffer, faceIds). */
template <class DrawFn>
py::tuple draw3d(py::object canvas, py::object depthBuffer, DrawFn&& drawFn) {
    cv::Mat c = wrapCanvas(canvas);
    cv::Mat dbWrap;
    if (depthBuffer.is_none()) {
        py::array_t<float> db = newFloat(c.rows, c.cols, 1);
        dbWrap = cv::Mat(c.size(), CV_32FC1, db.mutable_data());
        dbWrap.setTo(std::numeric_limits<float>::infinity());
        depthBuffer = db;
    } else {
        dbWrap = wrapInPlace<float>(depthBuffer, "depthBuffer", 0, "float32");
    }
    py::array_t<int32_t> ids({static_cast<py::ssize_t>(c.rows), static_cast<py::ssize_t>(c.cols)});
    const cv::Mat idWrap(c.size(), CV_32SC1, ids.mutable_data());
    cv::Mat db = dbWrap, id = idWrap;
    {
        py::gil_scoped_release nogil;
        drawFn(c, db, id);
    }
    py::object dbOut = finish(depthBuffer, dbWrap, db);
    return py::make_tuple(canvas, dbOut, finish(ids, idWrap, id));
}

// ---- settings -------------------------------------------------------------------------------

py::tuple tuple3(double a, double b, double c) { return py::make_tuple(a, b, c); }

std::string reprNumber(double v) { return py::repr(py::float_(v)).cast<std::string>(); }

std::string reprTuple(double a, double b, double c) {
    return "(" + reprNumber(a) + ", " + reprNumber(b) + ", " + reprNumber(c) + ")";
}

std::string reprLight(const sh::PointLight& l) {
    return "PointLight(position=" + reprTuple(l.position.x, l.position.y, l.position.z) +
           ", intensity=" + reprTuple(l.intensity[0], l.intensity[1], l.intensity[2]) + ")";
}

std::string enumName(int v, std::initializer_list<const char*> names) {
    if (v >= 0 && v < static_cast<int>(names.size()))
        return names.begin()[v];
    return std::to_string(v);
}

std::vector<sh::PointLight> toLights(const py::handle& obj) {
    std::vector<sh::PointLight> lights;
    if (obj.is_none())
        return lights;
    for (py::handle h : py::iter(obj)) {
        if (!py::isinstance<sh::PointLight>(h))
            throw py::type_error("lights: expected PointLight objects, got " +
                                 py::str(py::type::of(h)).cast<std::string>());
        lights.push_back(h.cast<sh::PointLight>());
    }
    return lights;
}

py::list fromLights(const std::vector<sh::PointLight>& lights) {
    py::list out;
    for (const sh::PointLight& l : lights)
        out.append(py::cast(l));
    return out;
}

bool sameLight(const sh::PointLight& a, const sh::PointLight& b) {
    return a.position == b.position && a.intensity == b.intensity;
}

}  // namespace

PYBIND11_MODULE(opencv_shading, m) {
    m.doc() = "Triangle scan conversion and shading into NumPy images (OpenCV's cv::shading).\n\n"
              "Canvases are H x W x 3 float32 (colours usually in [0, 1]) or uint8 arrays, drawn "
              "into in place (views and slices too); sizes are (width, height) as in cv2.";
    m.attr("__version__") = OPENCV_SHADING_VERSION;

    m.attr("SHADE_FLAT") = static_cast<int>(sh::SHADE_FLAT);
    m.attr("SHADE_GOURAUD") = static_cast<int>(sh::SHADE_GOURAUD);
    m.attr("SHADE_PHONG") = static_cast<int>(sh::SHADE_PHONG);
    m.attr("VISIBILITY_ZBUFFER") = static_cast<int>(sh::VISIBILITY_ZBUFFER);
    m.attr("VISIBILITY_PAINTER") = static_cast<int>(sh::VISIBILITY_PAINTER);
    m.attr("CULL_NONE") = static_cast<int>(sh::CULL_NONE);
    m.attr("CULL_BACK") = static_cast<int>(sh::CULL_BACK);
    m.attr("CULL_FRONT") = static_cast<int>(sh::CULL_FRONT);

    // opencv_shading.error(RuntimeError), like cv2.error: the C++ message plus code, err, func,
    // file, line attributes.
    g_error = PyErr_NewExceptionWithDoc(
        "opencv_shading.error",
        "A cv::Exception raised by the C++ library; str() is its message (what()).",
        PyExc_RuntimeError, nullptr);
    m.attr("error") = py::handle(g_error);  // the module holds a reference, g_error another
    py::register_exception_translator([](std::exception_ptr p) {
        try {
            if (p)
                std::rethrow_exception(p);
        } catch (const cv::Exception& e) {
            py::object inst = py::handle(g_error)(e.what());
            inst.attr("code") = e.code;
            inst.attr("err") = e.err;
            inst.attr("func") = e.func;
            inst.attr("file") = e.file;
            inst.attr("line") = e.line;
            PyErr_SetObject(g_error, inst.ptr());
        }
    });

    const sh::RenderSettings defaults;

    py::class_<sh::PointLight>(m, "PointLight", "A point light: world position, RGB intensity.")
        .def(py::init([](const py::object& position, const py::object& intensity) {
                 return sh::PointLight(toPoint3d(position, "position"),
                                       toVec3d(intensity, "intensity"));
             }),
             py::arg("position") = py::make_tuple(0.0, 0.0, 0.0),
             py::arg("intensity") = py::make_tuple(1.0, 1.0, 1.0),
             "PointLight(position=(0, 0, 0), intensity=(1, 1, 1)): position in world "
             "coordinates, intensity RGB (usually in [0, 1]).")
        .def_property(
            "position",
            [](const sh::PointLight& l) {
                return tuple3(l.position.x, l.position.y, l.position.z);
            },
            [](sh::PointLight& l, const py::object& v) { l.position = toPoint3d(v, "position"); },
            "World coordinates (x, y, z).")
        .def_property(
            "intensity",
            [](const sh::PointLight& l) {
                return tuple3(l.intensity[0], l.intensity[1], l.intensity[2]);
            },
            [](sh::PointLight& l, const py::object& v) { l.intensity = toVec3d(v, "intensity"); },
            "RGB intensity.")
        .def("__repr__", &reprLight)
        .def("__eq__", [](const sh::PointLight& a, const py::object& b) {
            return py::isinstance<sh::PointLight>(b) && sameLight(a, b.cast<sh::PointLight>());
        });

    py::class_<sh::RenderSettings>(
        m, "RenderSettings",
        "How drawMesh3d shades and which faces it keeps: shading, visibility, culling, near "
        "plane, point lights and the Phong material. Keyword construction; attributes read and "
        "write ('lights' returns a copy: assign a new list to change it).")
        .def(py::init([](ShadeArg shadeType, int visibility, int cullMode, double zNear,
                         const py::object& lights, const py::object& ambient, double ka,
                         double kd, double ks, double shininess, int textureInterpolation,
                         int textureBorder, bool clear, const py::object& background) {
                 sh::RenderSettings s;
                 s.shadeType = shadeType.value;
                 s.visibility = visibility;
                 s.cullMode = cullMode;
                 s.zNear = zNear;
                 s.lights = toLights(lights);
                 s.ambient = toVec3d(ambient, "ambient");
                 s.ka = ka;
                 s.kd = kd;
                 s.ks = ks;
                 s.shininess = shininess;
                 s.textureInterpolation = textureInterpolation;
                 s.textureBorder = textureBorder;
                 s.clear = clear;
                 s.background = toScalar(background, "background");
                 return s;
             }),
             py::kw_only(), py::arg_v("shadeType", ShadeArg{defaults.shadeType}, "SHADE_GOURAUD"),
             py::arg_v("visibility", defaults.visibility, "VISIBILITY_ZBUFFER"),
             py::arg_v("cullMode", defaults.cullMode, "CULL_NONE"),
             py::arg("zNear") = defaults.zNear, py::arg("lights") = py::tuple(),
             py::arg("ambient") =
                 tuple3(defaults.ambient[0], defaults.ambient[1], defaults.ambient[2]),
             py::arg("ka") = defaults.ka, py::arg("kd") = defaults.kd,
             py::arg("ks") = defaults.ks, py::arg("shininess") = defaults.shininess,
             py::arg_v("textureInterpolation", defaults.textureInterpolation,
                       "cv2.INTER_LINEAR"),
             py::arg_v("textureBorder", defaults.textureBorder, "cv2.BORDER_REPLICATE"),
             py::arg("clear") = defaults.clear, py::arg("background") = py::make_tuple(0, 0, 0),
             "Defaults: Gouraud, z-buffer, no culling, zNear 1e-3, no lights (unlit: vertex "
             "colours as given), ambient (1, 1, 1), ka 0.2, kd 0.7, ks 0.5, shininess 16, "
             "textures sampled bilinearly with the border replicated, no clear (background "
             "black).")
        .def_property(
            "shadeType", [](const sh::RenderSettings& s) { return s.shadeType; },
            [](sh::RenderSettings& s, ShadeArg v) { s.shadeType = v.value; },
            "SHADE_FLAT, SHADE_GOURAUD or SHADE_PHONG (or 'flat', 'gouraud', 'phong').")
        .def_readwrite("visibility", &sh::RenderSettings::visibility,
                       "VISIBILITY_ZBUFFER or VISIBILITY_PAINTER.")
        .def_readwrite("cullMode", &sh::RenderSettings::cullMode,
                       "CULL_NONE, CULL_BACK or CULL_FRONT.")
        .def_readwrite("zNear", &sh::RenderSettings::zNear, "Near clipping plane, camera z > 0.")
        .def_property(
            "lights", [](const sh::RenderSettings& s) { return fromLights(s.lights); },
            [](sh::RenderSettings& s, const py::object& v) { s.lights = toLights(v); },
            "List of PointLight (a copy); empty: unlit.")
        .def_property(
            "ambient",
            [](const sh::RenderSettings& s) {
                return tuple3(s.ambient[0], s.ambient[1], s.ambient[2]);
            },
            [](sh::RenderSettings& s, const py::object& v) { s.ambient = toVec3d(v, "ambient"); },
            "Ambient intensity Ia, RGB.")
        .def_readwrite("ka", &sh::RenderSettings::ka, "Ambient reflectance.")
        .def_readwrite("kd", &sh::RenderSettings::kd, "Diffuse reflectance.")
        .def_readwrite("ks", &sh::RenderSettings::ks, "Specular reflectance.")
        .def_readwrite("shininess", &sh::RenderSettings::shininess, "Phong exponent.")
        .def_readwrite("textureInterpolation", &sh::RenderSettings::textureInterpolation,
                       "drawTexturedMesh3d: cv2.INTER_LINEAR or cv2.INTER_NEAREST.")
        .def_readwrite("textureBorder", &sh::RenderSettings::textureBorder,
                       "drawTexturedMesh3d: cv2.BORDER_* (as cv2.remap's borderMode).")
        .def_readwrite("clear", &sh::RenderSettings::clear,
                       "Start a new frame: the canvas cleared to background and a given "
                       "depthBuffer to +inf, band by band as they are drawn (no separate pass).")
        .def_property(
            "background",
            [](const sh::RenderSettings& s) {
                return tuple3(s.background[0], s.background[1], s.background[2]);
            },
            [](sh::RenderSettings& s, const py::object& v) {
                s.background = toScalar(v, "background");
            },
            "The colour clear sets, in the canvas's units (RGB).")
        .def("__repr__", [](const sh::RenderSettings& s) {
            std::string lights;
            for (const sh::PointLight& l : s.lights)
                lights += (lights.empty() ? "" : ", ") + reprLight(l);
            return "RenderSettings(shadeType=" +
                   enumName(s.shadeType, {"SHADE_FLAT", "SHADE_GOURAUD", "SHADE_PHONG"}) +
                   ", visibility=" +
                   enumName(s.visibility, {"VISIBILITY_ZBUFFER", "VISIBILITY_PAINTER"}) +
                   ", cullMode=" + enumName(s.cullMode, {"CULL_NONE", "CULL_BACK", "CULL_FRONT"}) +
                   ", zNear=" + reprNumber(s.zNear) + ", lights=[" + lights + "], ambient=" +
                   reprTuple(s.ambient[0], s.ambient[1], s.ambient[2]) + ", ka=" +
                   reprNumber(s.ka) + ", kd=" + reprNumber(s.kd) + ", ks=" + reprNumber(s.ks) +
                   ", shininess=" + reprNumber(s.shininess) +
                   ", textureInterpolation=" + std::to_string(s.textureInterpolation) +
                   ", textureBorder=" + std::to_string(s.textureBorder) +
                   ", clear=" + (s.clear ? "True" : "False") + ", background=" +
                   reprTuple(s.background[0], s.background[1], s.background[2]) + ")";
        });

    m.def(
        "flats",
        [](py::object canvas, const py::object& vertices, const py::object& vcolors) {
            cv::Mat c = wrapCanvas(canvas);
            Input v = toInput(vertices, "vertices"), col = toInput(vcolors, "vcolors");
            {
                py::gil_scoped_release nogil;
                sh::flats(c, v.mat, col.mat);
            }
            return canvas;
        },
        py::arg("canvas"), py::arg("vertices"), py::arg("vcolors"),
        "Fills one triangle with the mean of its 3 vertex colours (flat shading), in place.\n\n"
        "canvas: H x W x 3 float32 or uint8 array (or a view of one), drawn into.\n"
        "vertices: 3 x 2 points (x, y) in pixels. vcolors: 3 x 3 colours in the canvas's units.\n"
        "Returns canvas.");

    m.def(
        "gouraud",
        [](py::object canvas, const py::object& vertices, const py::object& vcolors) {
            cv::Mat c = wrapCanvas(canvas);
            Input v = toInput(vertices, "vertices"), col = toInput(vcolors, "vcolors");
            {
                py::gil_scoped_release nogil;
                sh::gouraud(c, v.mat, col.mat);
            }
            return canvas;
        },
        py::arg("canvas"), py::arg("vertices"), py::arg("vcolors"),
        "Fills one triangle interpolating its 3 vertex colours (Gouraud shading), in place.\n\n"
        "canvas: H x W x 3 float32 or uint8 array (or a view of one), drawn into.\n"
        "vertices: 3 x 2 points (x, y) in pixels. vcolors: 3 x 3 colours in the canvas's units.\n"
        "Returns canvas.");

    m.def(
        "drawMesh",
        [](py::object canvas, const py::object& verts2d, const py::object& faces,
           const py::object& vcolors, const py::object& depth, ShadeArg shadeType) {
            cv::Mat c = wrapCanvas(canvas);
            Input v = toInput(verts2d, "verts2d"), f = toInput(faces, "faces", true),
                  col = toInput(vcolors, "vcolors"), d = toInput(depth, "depth");
            {
                py::gil_scoped_release nogil;
                sh::drawMesh(c, v.mat, f.mat, col.mat, d.mat, shadeType.value);
            }
            return canvas;
        },
        py::arg("canvas"), py::arg("verts2d"), py::arg("faces"), py::arg("vcolors"),
        py::arg("depth") = py::none(), py::arg_v("shadeType", ShadeArg{sh::SHADE_GOURAUD},
                                                 "SHADE_GOURAUD"),
        "Draws a triangle mesh onto canvas in place, in painter's order (largest mean vertex "
        "depth first).\n\n"
        "canvas: H x W x 3 float32 or uint8 array (or a view of one).\n"
        "verts2d: L x 2 vertices (x, y). faces: K x 3 zero-based vertex indices.\n"
        "vcolors: L x 3 colours in the canvas's units. depth: L depths (larger is farther), or "
        "None to draw faces in the order given.\n"
        "shadeType: SHADE_FLAT or SHADE_GOURAUD, or 'flat' / 'gouraud'.\nReturns canvas.");

    m.def(
        "render",
        [](const py::object& verts2d, const py::object& faces, const py::object& vcolors,
           const py::object& depth, ShadeArg shadeType, const py::object& size,
           const py::object& background) {
            Input v = toInput(verts2d, "verts2d"), f = toInput(faces, "faces", true),
                  col = toInput(vcolors, "vcolors"), d = toInput(depth, "depth");
            const cv::Size sz = toSize(size);
            const cv::Scalar bg = toScalar(background, "background");
            // The C++ writes straight into a numpy array; a bad size is left to it to report.
            py::array_t<float> out;
            cv::Mat wrap;
            if (sz.width > 0 && sz.height > 0) {
                out = newFloat(sz.height, sz.width, 3);
                wrap = cv::Mat(sz, CV_32FC3, out.mutable_data());
            }
            cv::Mat img = wrap;
            {
                py::gil_scoped_release nogil;
                sh::render(v.mat, f.mat, col.mat, d.mat, img, shadeType.value, sz, bg);
            }
            return finish(out, wrap, img);
        },
        py::arg("verts2d"), py::arg("faces"), py::arg("vcolors"), py::arg("depth"),
        py::arg_v("shadeType", ShadeArg{sh::SHADE_GOURAUD}, "SHADE_GOURAUD"),
        py::arg("size") = py::make_tuple(512, 512), py::arg("background") = py::make_tuple(1, 1, 1),
        "Renders a triangle mesh into a new image: size filled with background, then drawMesh.\n\n"
        "verts2d: L x 2 vertices (x, y). faces: K x 3 zero-based vertex indices.\n"
        "vcolors: L x 3 colours in [0, 1]. depth: L depths (larger is farther), or None.\n"
        "shadeType: SHADE_FLAT or SHADE_GOURAUD, or 'flat' / 'gouraud'.\n"
        "size: (width, height). background: colour of uncovered pixels.\n"
        "Returns the image, height x width x 3 float32.");

    m.def(
        "computeNormals",
        [](const py::object& verts3d, const py::object& faces) {
            Input v = toInput(verts3d, "verts3d"), f = toInput(faces, "faces", true);
            cv::Mat vn, fn;
            {
                py::gil_scoped_release nogil;
                sh::computeNormals(v.mat, f.mat, vn, fn);
            }
            return py::make_tuple(toNumpy(vn), toNumpy(fn));
        },
        py::arg("verts3d"), py::arg("faces"),
        "Face and vertex normals of a triangle mesh.\n\n"
        "Face normal: normalize((v1 - v0) x (v2 - v0)), zero if degenerate. Vertex normal: the "
        "normalized sum of the unit normals of its faces (zero if none).\n"
        "verts3d: L x 3 vertices. faces: K x 3 zero-based vertex indices.\n"
        "Returns (vertexNormals L x 3 float32, faceNormals K x 3 float32).");

    m.def(
        "lookAt",
        [](const py::object& eye, const py::object& target, const py::object& up) {
            const cv::Point3d e = toPoint3d(eye, "eye"), t = toPoint3d(target, "target");
            const cv::Vec3d u = toVec3d(up, "up");
            cv::Mat rvec, tvec;
            sh::lookAt(e, t, u, rvec, tvec);  // a few flops: not worth releasing the GIL
            return py::make_tuple(toNumpy(rvec), toNumpy(tvec));
        },
        py::arg("eye"), py::arg("target"), py::arg("up"),
        "The OpenCV camera pose of a camera at eye looking at target, up appearing up.\n\n"
        "eye, target: 3D points (must differ). up: 3D direction, not parallel to the view.\n"
        "Returns (rvec, tvec), each 3 x 1 float64 (Rodrigues rotation, translation; world to "
        "camera), as cv2.solvePnP gives them.");

    m.def(
        "drawMesh3d",
        [](py::object canvas, const py::object& verts3d, const py::object& faces,
           const py::object& vcolors, const py::object& cameraMatrix, const py::object& rvec,
           const py::object& tvec, const sh::RenderSettings& settings,
           const py::object& normals, py::object depthBuffer) {
            Input v = toInput(verts3d, "verts3d"), f = toInput(faces, "faces", true),
                  col = toInput(vcolors, "vcolors"), k = toInput(cameraMatrix, "cameraMatrix"),
                  r = toInput(rvec, "rvec"), t = toInput(tvec, "tvec"),
                  n = toInput(normals, "normals");
            return draw3d(canvas, depthBuffer, [&](cv::Mat& c, cv::Mat& db, cv::Mat& id) {
                sh::drawMesh3d(c, v.mat, f.mat, col.mat, k.mat, r.mat, t.mat, settings, n.mat,
                               db, id);
            });
        },
        py::arg("canvas"), py::arg("verts3d"), py::arg("faces"), py::arg("vcolors"),
        py::arg("cameraMatrix"), py::arg("rvec"), py::arg("tvec"),
        py::arg_v("settings", sh::RenderSettings(), "RenderSettings()"),
        py::arg("normals") = py::none(), py::arg("depthBuffer") = py::none(),
        "Draws a 3D mesh seen by an OpenCV camera (as cv2.projectPoints), in place: culled, "
        "clipped at settings.zNear, z-buffered (or painter's), lit by settings.lights with flat, "
        "Gouraud or Phong shading.\n\n"
        "canvas: H x W x 3 float32 (colours in [0, 1]) or uint8 array (or a view of one).\n"
        "verts3d: L x 3 world points. faces: K x 3 zero-based indices. vcolors: L x 3 colours.\n"
        "cameraMatrix: 3 x 3 intrinsics. rvec: Rodrigues 3-vector or 3 x 3 rotation. tvec: "
        "3-vector.\nsettings: RenderSettings. normals: L x 3 vertex normals, or None to compute "
        "them.\ndepthBuffer: H x W float32 array tested against and updated in place (meshes "
        "drawn in several calls composite), or None for a new one filled with +inf.\n"
        "Returns (canvas, depthBuffer, faceIds): depthBuffer holds camera Zc of drawn samples, "
        "faceIds (H x W int32) the index of the face that coloured each pixel, -1 elsewhere.");

    m.def(
        "drawTexturedMesh3d",
        [](py::object canvas, const py::object& verts3d, const py::object& faces,
           const py::object& texCoords, const py::object& texture,
           const py::object& cameraMatrix, const py::object& rvec, const py::object& tvec,
           const sh::RenderSettings& settings, const py::object& normals,
           py::object depthBuffer) {
            Input v = toInput(verts3d, "verts3d"), f = toInput(faces, "faces", true),
                  uv = toInput(texCoords, "texCoords"), k = toInput(cameraMatrix, "cameraMatrix"),
                  r = toInput(rvec, "rvec"), t = toInput(tvec, "tvec"),
                  n = toInput(normals, "normals");
            const Input tex = toImage(texture, "texture");
            return draw3d(canvas, depthBuffer, [&](cv::Mat& c, cv::Mat& db, cv::Mat& id) {
                sh::drawTexturedMesh3d(c, v.mat, f.mat, uv.mat, tex.mat, k.mat, r.mat, t.mat,
                                       settings, n.mat, db, id);
            });
        },
        py::arg("canvas"), py::arg("verts3d"), py::arg("faces"), py::arg("texCoords"),
        py::arg("texture"), py::arg("cameraMatrix"), py::arg("rvec"), py::arg("tvec"),
        py::arg_v("settings", sh::RenderSettings(), "RenderSettings()"),
        py::arg("normals") = py::none(), py::arg("depthBuffer") = py::none(),
        "drawMesh3d with a texture in place of the vertex colours, sampled perspective-"
        "correctly as cv2.remap samples (settings.textureInterpolation, "
        "settings.textureBorder); lit, the texel takes the vertex colour's place in the Phong "
        "model.\n\n"
        "texCoords: L x 2 texture coordinates in texture pixels (a file's normalized (u, v) "
        "are (u * cols - 0.5, (1 - v) * rows - 0.5)). texture: H x W x 3 uint8 or float32 "
        "image. The other arguments and the result are drawMesh3d's.");

#ifdef OPENCV_SHADING_PY_MESHIO
    m.def(
        "loadMesh",
        [](const py::object& path) {
            const std::string filename = toPath(path);
            cv::Mat v, f, n, col, tc;
            {
                py::gil_scoped_release nogil;
                sh::loadMesh(filename, v, f, n, col, tc);
            }
            // As cv2 does for empty Mats: the parts the file lacks are None.
            auto opt = [](const cv::Mat& a) -> py::object {
                return a.empty() ? py::object(py::none()) : py::object(toNumpy(a));
            };
            return py::make_tuple(toNumpy(v), toNumpy(f), opt(n), opt(col), opt(tc));
        },
        py::arg("filename"),
        "Loads a triangle mesh (OBJ, PLY, STL, glTF/GLB, OFF, ... through assimp) as one mesh.\n\n"
        "Returns (vertices L x 3 float32, faces K x 3 int32, normals L x 3 float32 or None, "
        "colors L x 3 float32 RGB in [0, 1] or None, texCoords L x 2 (or L x 3) float32 or "
        "None); None where the file has none.");

    m.def(
        "saveMesh",
        [](const py::object& path, const py::object& vertices, const py::object& faces,
           const py::object& normals, const py::object& colors, const py::object& texCoords) {
            const std::string filename = toPath(path);
            Input v = toInput(vertices, "vertices"), f = toInput(faces, "faces", true),
                  n = toInput(normals, "normals"), col = toInput(colors, "colors"),
                  tc = toInput(texCoords, "texCoords");
            py::gil_scoped_release nogil;
            sh::saveMesh(filename, v.mat, f.mat, n.mat, col.mat, tc.mat);
        },
        py::arg("filename"), py::arg("vertices"), py::arg("faces"),
        py::arg("normals") = py::none(), py::arg("colors") = py::none(),
        py::arg("texCoords") = py::none(),
        "Saves a triangle mesh in the format its extension names (.obj, .ply, .stl, .gltf, "
        ".glb, .off, ...).\n\n"
        "vertices: L x 3. faces: K x 3 zero-based indices. normals: L x 3 or None. colors: "
        "L x 3 RGB in [0, 1] or None. texCoords: L x 2 (or L x 3) or None.\n"
        "Arguments are checked before the file is opened: a rejected call writes nothing.");
#endif

    bindLineAndTexture(m);  // bind_line.cpp
    bindPolygon(m);         // bind_polygon.cpp
}
