// This file is part of opencv_shading. License: Apache-2.0.
//
// demo_scene.hpp: what the opencv_shading samples share, header-only so each sample stays a
// single .cpp a user can copy next to this header.
//
//   makeDemoScene()  a built-in mesh (a perspective-projected torus knot, ~10,000 triangles)
//   makeDemoMesh3d() the same knot as a 3D mesh for cv::shading::drawMesh3d (unlit colours;
//                    defined in demo_mesh.hpp, which this header includes: copy both)
//   loadScene()      a mesh from an OpenCV FileStorage file (YAML or JSON)
//   loadMesh3d()     a 3D mesh from such a file
//   saveOrShow()     RGB float image -> BGR 8-bit PNG, plus a window when a display is there
//   runRenderDemo()  the command line, timing and output shared by demo_flat and demo_gouraud
//
// Mesh files hold four matrices, the arguments of cv::shading::render:
//   verts2d  L x 2 (x, y) pixel coordinates     faces  K x 3 zero-based vertex indices
//   vcolors  L x 3 RGB in [0, 1]                 depth  L x 1 (larger is farther)
// 3D mesh files (for drawMesh3d) hold verts3d (L x 3 world coordinates), faces, vcolors and
// optionally normals (L x 3); one file may hold both sets.
// e.g. written from Python with cv2.FileStorage("mesh.yml", cv2.FILE_STORAGE_WRITE).write(...).
#ifndef OPENCV_SHADING_SAMPLES_DEMO_SCENE_HPP
#define OPENCV_SHADING_SAMPLES_DEMO_SCENE_HPP

#include "demo_mesh.hpp"

#include <opencv2/core.hpp>
#include <opencv2/highgui.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <iomanip>
#include <iostream>
#include <stdexcept>
#include <string>
#include <vector>

namespace shading_samples {

//! A 2D-projected triangle mesh in the form cv::shading::render takes.
struct MeshScene {
    cv::Mat verts2d;  //!< L x 2 CV_32F: (x, y) pixel coordinates
    cv::Mat faces;    //!< K x 3 CV_32S: zero-based indices into verts2d
    cv::Mat vcolors;  //!< L x 3 CV_32F: RGB in [0, 1]
    cv::Mat depth;    //!< L x 1 CV_32F: camera-space distance, larger is farther
};

namespace detail {

inline bool envFlag(const char* name)
{
    const char* v = std::getenv(name);
    return v != nullptr && *v != '\0' && std::string(v) != "0";
}

// An open mesh file and what its loader says in errors.
struct MeshFile {
    cv::FileStorage fs;
    std::string path;
    std::string loader;  // "loadScene", "loadMesh3d"
    std::string keys;    // the matrices a file needs, for the message when one is missing
};

inline MeshFile openMeshFile(const std::string& path, const std::string& loader,
                             const std::string& keys)
{
    if (!std::ifstream(path))  // checked first for a clear message (FileStorage logs its own)
        CV_Error(cv::Error::StsError,
                 cv::format("%s: cannot read '%s'", loader.c_str(), path.c_str()));
    MeshFile f{cv::FileStorage(path, cv::FileStorage::READ), path, loader, keys};
    if (!f.fs.isOpened())
        CV_Error(cv::Error::StsError, cv::format("%s: cannot open '%s' as an OpenCV YAML/JSON file",
                                                 loader.c_str(), path.c_str()));
    return f;
}

// Reads one matrix as `rows x cols` of `type`, accepting the layouts users write (multi-channel
// N x 1, a 1 x N depth row) and converting the element type once. A missing optional matrix
// comes back empty.
inline cv::Mat readMatrix(const MeshFile& f, const char* key, int cols, int type,
                          bool required = true)
{
    const char* who = f.loader.c_str();
    const char* path = f.path.c_str();
    const cv::FileNode node = f.fs[key];
    if (node.empty()) {
        if (!required)
            return cv::Mat();
        CV_Error(cv::Error::StsParseError,
                 cv::format("%s: '%s' has no matrix '%s' (a mesh file needs %s)", who, path, key,
                            f.keys.c_str()));
    }
    cv::Mat m;
    node >> m;
    if (m.empty())
        CV_Error(cv::Error::StsParseError,
                 cv::format("%s: '%s': '%s' is empty or not an OpenCV matrix", who, path, key));
    m = m.reshape(1);
    if (cols == 1 && m.rows == 1)
        m = m.t();  // a depth row vector
    if (m.cols != cols)
        CV_Error(cv::Error::StsBadSize,
                 cv::format("%s: '%s': '%s' is %d x %d, expected N x %d", who, path, key, m.rows,
                            m.cols, cols));
    cv::Mat out;
    m.convertTo(out, type);
    return out;
}

}  // namespace detail

/** A deterministic demo mesh: a trefoil-knot tube seen in perspective, lit per vertex.

About `approxTriangles` triangles (exactly 10,000 for the default), projected so the knot fills
most of `size`. Colours are a hue that runs along the knot, lit by a Lambert + Blinn-Phong light
at each vertex, so flat shading shows the facets and Gouraud smooths them. The tube is closed and
its back faces are kept: the painter's order (depth = distance to the eye) hides them. */
inline MeshScene makeDemoScene(cv::Size size = {512, 512}, int approxTriangles = 10000)
{
    CV_Assert(size.width > 0 && size.height > 0 && approxTriangles > 0);
    const detail::KnotTube tube = detail::makeKnotTube(approxTriangles);
    const int nverts = tube.along * tube.around;

    // Camera: object tilted for a 3/4 view, then pushed 9 units down +z in front of the eye.
    const cv::Matx33d rx(1, 0, 0, 0, std::cos(-0.75), -std::sin(-0.75), 0, std::sin(-0.75),
                         std::cos(-0.75));
    const cv::Matx33d ry(std::cos(0.35), 0, std::sin(0.35), 0, 1, 0, -std::sin(0.35), 0,
                         std::cos(0.35));
    const cv::Matx33d rot = ry * rx;
    const cv::Vec3d eyeOffset(0, 0, 9.0);
    const cv::Vec3d light = detail::normalized({-0.45, 0.65, -0.6});  // upper left, eye side

    MeshScene s;
    s.verts2d.create(nverts, 2, CV_32F);
    s.vcolors.create(nverts, 3, CV_32F);
    s.depth.create(nverts, 1, CV_32F);
    s.faces = tube.faces;
    std::vector<cv::Point2d> proj(static_cast<size_t>(nverts));

    for (int v = 0; v < nverts; ++v) {
        const cv::Vec3d& radial = tube.radial[static_cast<size_t>(v)];
        const cv::Vec3d n = rot * radial;  // the tube's surface normal, in camera space
        const cv::Vec3d p = rot * (tube.centre[static_cast<size_t>(v)] +
                                   detail::kTubeRadius * radial) + eyeOffset;
        const cv::Vec3d base = detail::palette(static_cast<double>(v / tube.around) / tube.along);

        // Camera looks down +z with y up; the image's y grows downwards.
        proj[static_cast<size_t>(v)] = {p[0] / p[2], -p[1] / p[2]};
        s.depth.at<float>(v) = static_cast<float>(cv::norm(p));

        const cv::Vec3d toEye = detail::normalized(-p);
        const double diffuse = std::max(0.0, n.dot(light));
        const double specular =
            std::pow(std::max(0.0, n.dot(detail::normalized(light + toEye))), 16.0);
        for (int k = 0; k < 3; ++k)
            s.vcolors.at<float>(v, k) = static_cast<float>(
                std::min(1.0, base[k] * (0.22 + 0.78 * diffuse) + 0.3 * specular));
    }

    // Scale and centre the projection to fill 86% of the canvas (still a perspective camera:
    // this only sets its focal length and principal point).
    cv::Point2d lo(proj[0]), hi(proj[0]);
    for (const cv::Point2d& p : proj) {
        lo = {std::min(lo.x, p.x), std::min(lo.y, p.y)};
        hi = {std::max(hi.x, p.x), std::max(hi.y, p.y)};
    }
    const double scale = 0.86 * std::min(size.width / (hi.x - lo.x), size.height / (hi.y - lo.y));
    const cv::Point2d mid = (lo + hi) * 0.5;
    for (int v = 0; v < nverts; ++v) {
        const cv::Point2d& q = proj[static_cast<size_t>(v)];
        s.verts2d.at<float>(v, 0) = static_cast<float>(size.width * 0.5 + scale * (q.x - mid.x));
        s.verts2d.at<float>(v, 1) = static_cast<float>(size.height * 0.5 + scale * (q.y - mid.y));
    }
    // The faces turn counter-clockwise about the outward normal, so with the image's y axis
    // pointing down, front faces have a negative signed area (clockwise on screen).
    return s;
}

/** Loads a mesh from an OpenCV FileStorage file (.yml/.yaml/.json, optionally .gz) holding the
matrices `verts2d`, `faces`, `vcolors` and `depth`. Throws cv::Exception naming the file and the
missing or malformed key. */
inline MeshScene loadScene(const std::string& path)
{
    const detail::MeshFile f =
        detail::openMeshFile(path, "loadScene", "verts2d, faces, vcolors and depth");
    MeshScene s;
    s.verts2d = detail::readMatrix(f, "verts2d", 2, CV_32F);
    s.faces = detail::readMatrix(f, "faces", 3, CV_32S);
    s.vcolors = detail::readMatrix(f, "vcolors", 3, CV_32F);
    s.depth = detail::readMatrix(f, "depth", 1, CV_32F);
    if (s.vcolors.rows != s.verts2d.rows || s.depth.rows != s.verts2d.rows)
        CV_Error(cv::Error::StsUnmatchedSizes,
                 cv::format("loadScene: '%s': verts2d has %d rows but vcolors %d and depth %d",
                            path.c_str(), s.verts2d.rows, s.vcolors.rows, s.depth.rows));
    return s;
}

/** Loads a 3D mesh from an OpenCV FileStorage file holding `verts3d` (L x 3), `faces` (K x 3),
`vcolors` (L x 3, RGB in [0, 1]) and optionally `normals` (L x 3; absent: drawMesh3d computes
them). Throws cv::Exception naming the file and the missing or malformed key. */
inline Mesh3d loadMesh3d(const std::string& path)
{
    const detail::MeshFile f = detail::openMeshFile(
        path, "loadMesh3d", "verts3d, faces and vcolors, optionally normals");
    Mesh3d m;
    m.verts3d = detail::readMatrix(f, "verts3d", 3, CV_32F);
    m.faces = detail::readMatrix(f, "faces", 3, CV_32S);
    m.vcolors = detail::readMatrix(f, "vcolors", 3, CV_32F);
    m.normals = detail::readMatrix(f, "normals", 3, CV_32F, /*required=*/false);
    const int normalRows = m.normals.empty() ? m.verts3d.rows : m.normals.rows;
    if (m.vcolors.rows != m.verts3d.rows || normalRows != m.verts3d.rows)
        CV_Error(cv::Error::StsUnmatchedSizes,
                 cv::format("loadMesh3d: '%s': verts3d has %d rows but vcolors %d and normals %d",
                            path.c_str(), m.verts3d.rows, m.vcolors.rows, normalRows));
    return m;
}

/** True when a window can be shown: a display is there (X11 or Wayland; always on Windows and
macOS) and neither OPENCV_SHADING_NO_GUI nor CI (set by most CI services) is set. */
inline bool guiAvailable()
{
    if (detail::envFlag("OPENCV_SHADING_NO_GUI") || detail::envFlag("CI"))
        return false;
#if defined(_WIN32) || defined(__APPLE__)
    return true;
#else
    return detail::envFlag("DISPLAY") || detail::envFlag("WAYLAND_DISPLAY");
#endif
}

/** Writes an RGB image (float in [0, 1], or 8-bit) as a BGR PNG and says so, then shows it until
a key is pressed when guiAvailable() and `allowGui`. Returns whether the PNG was written; a
missing GUI backend is not an error (the PNG is the result). */
inline bool saveOrShow(const std::string& window, const cv::Mat& rgbFloatImage,
                       const std::string& pngPath, bool allowGui = true)
{
    CV_CheckEQ(rgbFloatImage.channels(), 3, "saveOrShow expects a 3-channel RGB image");
    cv::Mat rgb = rgbFloatImage;
    if (rgb.depth() != CV_8U && rgb.depth() != CV_32F)
        rgb.convertTo(rgb, CV_32F);  // cvtColor takes 8U, 16U or 32F
    cv::Mat bgr, bgr8;
    cv::cvtColor(rgb, bgr, cv::COLOR_RGB2BGR);  // the library keeps RGB; imwrite wants BGR
    bgr.convertTo(bgr8, CV_8U, rgb.depth() == CV_8U ? 1.0 : 255.0);  // rounds and saturates

    bool written = false;
    try {
        written = cv::imwrite(pngPath, bgr8);
    } catch (const cv::Exception& e) {
        std::cerr << e.what() << '\n';
    }
    if (written)
        std::cout << "wrote " << pngPath << std::endl;  // flushed: see below
    else
        std::cerr << "error: could not write '" << pngPath << "'\n";

    if (allowGui && guiAvailable()) {
        // A DISPLAY naming no live server makes some backends (Qt) abort the process instead of
        // throwing; the PNG and the report above are out by then. --no-gui avoids it.
        try {
            cv::imshow(window, bgr8);
            std::cout << "(press any key in the '" << window << "' window to close it)\n";
            cv::waitKey(0);
            cv::destroyWindow(window);
        } catch (const cv::Exception&) {
            // OpenCV built without a GUI backend: the PNG is all there is to show.
        }
    }
    return written;
}

//! Command line shared by the samples: [MESH_FILE] [--out FILE.png] [--no-gui] [extra flags].
struct DemoOptions {
    std::string input;               //!< mesh file; empty = built-in scene
    std::string out;                 //!< PNG to write
    bool gui = true;                 //!< false with --no-gui
    bool help = false;               //!< -h / --help
    std::vector<std::string> flags;  //!< extra flags given (those the caller allowed)
};

inline std::string usage(const std::string& program, const std::string& extra = "")
{
    return "usage: " + program + " [MESH.yml|MESH.json] [--out FILE.png] [--no-gui]" + extra +
           "\n  MESH: OpenCV FileStorage file with verts2d, faces, vcolors, depth"
           " (default: built-in scene)\n  --no-gui: only write the PNG (also"
           " OPENCV_SHADING_NO_GUI=1)\n";
}

//! Parses the shared command line; throws std::invalid_argument on anything unexpected.
inline DemoOptions parseDemoOptions(int argc, char** argv, const std::string& defaultOut,
                                    const std::vector<std::string>& extraFlags = {})
{
    DemoOptions opt;
    opt.out = defaultOut;
    for (int i = 1; i < argc; ++i) {
        const std::string arg = argv[i];
        if (arg == "--out") {
            if (i + 1 >= argc)
                throw std::invalid_argument("--out needs a file name");
            opt.out = argv[++i];
        } else if (arg == "--no-gui") {
            opt.gui = false;
        } else if (arg == "-h" || arg == "--help") {
            opt.help = true;
        } else if (std::find(extraFlags.begin(), extraFlags.end(), arg) != extraFlags.end()) {
            opt.flags.push_back(arg);
        } else if (arg.rfind("-", 0) != 0 && opt.input.empty()) {
            opt.input = arg;
        } else {
            throw std::invalid_argument("unexpected argument '" + arg + "'");
        }
    }
    return opt;
}

/** The image at `path` as the samples keep colours (RGB, 8-bit), for textures; throws
std::invalid_argument naming the file when it cannot be read. */
inline cv::Mat readRgbImage(const std::string& path)
{
    const cv::Mat bgr = cv::imread(path, cv::IMREAD_COLOR);
    if (bgr.empty())
        throw std::invalid_argument("cannot read image '" + path + "'");
    cv::Mat rgb;
    cv::cvtColor(bgr, rgb, cv::COLOR_BGR2RGB);
    return rgb;
}

/** The texture samples' command line, `program [IMAGE] [--out FILE.png] [--no-gui]`: fills `opt`
and `texture` (IMAGE read as RGB, or `makeDefault()` without one). Returns -1 to go on, else the
exit status: 0 after --help, 2 for a bad argument, 1 for an unreadable image. */
inline int parseTextureSampleOptions(int argc, char** argv, const std::string& program,
                                     const std::function<cv::Mat()>& makeDefault,
                                     DemoOptions& opt, cv::Mat& texture)
{
    const std::string usage = "usage: " + program + " [image] [--out file.png] [--no-gui]\n";
    try {
        opt = parseDemoOptions(argc, argv, program + ".png");
    } catch (const std::invalid_argument& e) {
        std::cerr << "error: " << e.what() << "\n" << usage;
        return 2;
    }
    if (opt.help) {
        std::cout << usage;
        return 0;
    }
    try {
        texture = opt.input.empty() ? makeDefault() : readRgbImage(opt.input);
    } catch (const std::invalid_argument& e) {
        std::cerr << "error: " << e.what() << "\n";
        return 1;
    }
    return -1;
}

inline bool hasFlag(const DemoOptions& opt, const std::string& flag)
{
    return std::find(opt.flags.begin(), opt.flags.end(), flag) != opt.flags.end();
}

//! Median wall time of `fn` in milliseconds over `runs` calls, after one untimed warm-up call
//! (first-touch allocation and thread-pool start-up are not what we want to measure).
inline double medianMs(const std::function<void()>& fn, int runs = 20)
{
    CV_Assert(runs > 0);
    fn();
    std::vector<double> ms;
    for (int r = 0; r < runs; ++r) {
        const int64 t0 = cv::getTickCount();
        fn();
        ms.push_back(static_cast<double>(cv::getTickCount() - t0) * 1000.0 / cv::getTickFrequency());
    }
    std::sort(ms.begin(), ms.end());
    return 0.5 * (ms[(ms.size() - 1) / 2] + ms[ms.size() / 2]);
}

using RenderFn = std::function<void(const MeshScene&, cv::Mat&)>;

/** The body of demo_flat and demo_gouraud: parse the command line, load or build the scene,
time `render` (which fills `img` from the scene), then write and show the image. Returns the
process exit code. */
inline int runRenderDemo(int argc, char** argv, const std::string& name, const RenderFn& render)
{
    try {
        const DemoOptions opt = parseDemoOptions(argc, argv, name + ".png");
        if (opt.help) {
            std::cout << usage(name);
            return 0;
        }
        const MeshScene scene = opt.input.empty() ? makeDemoScene() : loadScene(opt.input);
        std::cout << "scene: " << (opt.input.empty() ? "built-in torus knot" : opt.input) << ", "
                  << scene.verts2d.rows << " vertices, " << scene.faces.rows << " triangles\n";

        cv::Mat img;
        const int runs = 20;
        const double ms = medianMs([&] { render(scene, img); }, runs);
        std::cout << "render: " << std::fixed << std::setprecision(3) << ms << " ms (median of "
                  << runs << " runs, " << cv::getNumThreads() << " threads)\n";

        return saveOrShow(name, img, opt.out, opt.gui) ? 0 : 1;
    } catch (const std::invalid_argument& e) {
        std::cerr << name << ": " << e.what() << '\n' << usage(name);
        return 2;
    } catch (const std::exception& e) {  // cv::Exception included: its text says what was wrong
        std::cerr << name << ": " << e.what() << '\n';
        return 1;
    }
}

}  // namespace shading_samples

#endif  // OPENCV_SHADING_SAMPLES_DEMO_SCENE_HPP
