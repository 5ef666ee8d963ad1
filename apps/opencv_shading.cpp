// This file is part of opencv_shading. License: Apache-2.0.
//
// opencv_shading: renders a mesh file (or the built-in torus knot) with cv::shading::drawMesh3d,
// framed and lit automatically, to a PNG, depth and face-id maps, a window, or a turntable video.
// Exit status: 0 done, 1 the mesh or an output failed, 2 bad arguments (usage on stderr).
#include "demo_mesh.hpp"

#include <opencv2/core.hpp>
#include <opencv2/core/utility.hpp>
#include <opencv2/highgui.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/shading.hpp>
#include <opencv2/videoio.hpp>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#ifdef _WIN32
#include <io.h>
#define OPENCV_SHADING_ISATTY(f) _isatty(_fileno(f))
#else
#include <unistd.h>
#define OPENCV_SHADING_ISATTY(f) isatty(fileno(f))
#endif

namespace {

namespace sh = cv::shading;

const char* const kSynopsis =
    "usage: opencv_shading MESH|demo [-o out.png] [--shade flat|gouraud|phong] [--size WxH]\n"
    "       [--light x,y,z,r,g,b ...] [--background r,g,b] [--up x|y|z|-x|-y|-z]\n"
    "       [--cull none|back|front] [--painter] [--depth depth.exr|depth.png] [--ids ids.png]\n"
    "       [--texture image.png]\n"
    "       [--show] [--turntable N --video out.mp4|frame_%03d.png]\n"
    "       (--help explains each option)\n";

const char* const kUsage =
    "usage: opencv_shading MESH [options]\n"
    "Renders MESH, any file cv::shading::loadMesh reads (OBJ, PLY, STL, glTF/GLB, OFF, DAE,\n"
    "FBX, 3DS, ...) or the word demo (or --demo) for the built-in torus knot, framed and lit\n"
    "automatically.\n"
    "  -o, --output FILE.png        image to write (default: MESH's name with .png, in the\n"
    "                               current folder; with --turntable only when given)\n"
    "  --shade flat|gouraud|phong   shading (default gouraud)\n"
    "  --size WxH                   image size in pixels (default 1024x768)\n"
    "  --light x,y,z,r,g,b          a point light: world position, RGB intensity; repeat for\n"
    "                               more (default: key, fill and rim lights around the model,\n"
    "                               moving with the camera)\n"
    "  --background r,g,b           background colour, RGB in [0, 1] (default 0.13,0.14,0.16)\n"
    "  --up x|y|z|-x|-y|-z          the model's up axis (default y)\n"
    "  --cull none|back|front       skip faces turned away from / towards the camera\n"
    "                               (default none)\n"
    "  --painter                    painter's algorithm (faces far to near) instead of a z-buffer\n"
    "  --depth FILE.exr|FILE.png    depth map (camera z): .exr float32, background +inf;\n"
    "                               .png 16-bit, 1..65535 spanning the visible depths,\n"
    "                               background 0\n"
    "  --ids FILE.png               face index + 1 per pixel, 0 = background: 16-bit PNG for\n"
    "                               fewer than 65535 faces, else 8-bit colour, (R<<16)|(G<<8)|B\n"
    "  --texture IMAGE              texture the mesh with IMAGE (any format cv::imread reads)\n"
    "                               through the file's texture coordinates, repeated outside\n"
    "                               [0, 1], bilinear; lit as the vertex colours would be\n"
    "  --show                       show the image in a window (press a key to close it)\n"
    "  --turntable N --video OUT    N views orbiting the up axis into OUT: a video (.mp4,\n"
    "                               mp4v codec) or, with a printf pattern, numbered images\n"
    "                               (frame_%03d.png)\n"
    "  -h, --help                   this message\n"
    "Exit status: 0 done, 1 the mesh could not be read or an output not written, 2 bad\n"
    "arguments.\n";

//! A mistake on the command line: reported with the usage, exit status 2.
struct UsageError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

//! Anything else that stops the program (unreadable mesh, unwritable output): exit status 1.
struct RunError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

struct Options {
    std::string mesh;
    std::string output;
    int shadeType = sh::SHADE_GOURAUD;
    cv::Size size{1024, 768};
    std::vector<sh::PointLight> lights;
    cv::Vec3d background{0.13, 0.14, 0.16};
    cv::Vec3d up{0, 1, 0};
    int cullMode = sh::CULL_NONE;
    bool painter = false;
    std::string depth, ids;
    std::string texture;
    bool show = false;
    int turntable = 0;
    std::string video;
    bool help = false;
};

std::string lower(std::string s)
{
    std::transform(s.begin(), s.end(), s.begin(),
                   [](unsigned char c) { return char(std::tolower(c)); });
    return s;
}

std::string extensionOf(const std::string& path)
{
    return lower(std::filesystem::path(path).extension().string());
}

//! `count` comma-separated finite numbers, or a UsageError naming `option` and `form`.
std::vector<double> parseNumbers(const std::string& text, size_t count, const std::string& option,
                                 const std::string& form)
{
    std::vector<double> values;
    size_t begin = 0;
    while (begin <= text.size()) {
        const size_t end = std::min(text.find(',', begin), text.size());
        const std::string item = text.substr(begin, end - begin);
        char* stop = nullptr;
        const double v = std::strtod(item.c_str(), &stop);
        if (item.empty() || *stop != '\0' || !std::isfinite(v))
            throw UsageError(option + ": '" + item + "' in '" + text +
                             "' is not a number (expected " + form + ")");
        values.push_back(v);
        begin = end + 1;
    }
    if (values.size() != count)
        throw UsageError(option + ": expected " + form + " (" + std::to_string(count) +
                         " numbers), got '" + text + "'");
    return values;
}

cv::Size parseSize(const std::string& text)
{
    // WxH: 1 to 5 digits, x or X, 1 to 5 digits.
    const size_t x = text.find_first_of("xX");
    auto digits = [](const std::string& t) {
        return !t.empty() && t.size() <= 5 &&
               t.find_first_not_of("0123456789") == std::string::npos;
    };
    if (x == std::string::npos || !digits(text.substr(0, x)) || !digits(text.substr(x + 1)))
        throw UsageError("--size: expected WxH in pixels (e.g. 1024x768), got '" + text + "'");
    const int w = std::stoi(text.substr(0, x)), h = std::stoi(text.substr(x + 1));
    if (w < 1 || h < 1 || w > 16384 || h > 16384)
        throw UsageError("--size: width and height must be in 1..16384, got '" + text + "'");
    return {w, h};
}

int parseChoice(const std::string& option, const std::string& text,
                const std::vector<std::pair<std::string, int>>& choices)
{
    std::string names;
    for (const auto& c : choices) {
        if (lower(text) == c.first)
            return c.second;
        names += (names.empty() ? "" : "|") + c.first;
    }
    throw UsageError(option + ": expected " + names + ", got '" + text + "'");
}

//! A printf pattern with exactly one integer conversion (%d, %03d, ...), e.g. frame_%03d.png.
bool isFramePattern(const std::string& text)
{
    return text.find('%') != std::string::npos;
}

void checkFramePattern(const std::string& text)
{
    // Exactly one %d, %0Nd or %Nd (N up to two digits); every other % doubled.
    int conversions = 0;
    bool valid = true;
    for (size_t i = 0; i < text.size() && valid; i++) {
        if (text[i] != '%')
            continue;
        if (i + 1 < text.size() && text[i + 1] == '%') {
            i++;
            continue;
        }
        size_t j = i + 1;
        if (j < text.size() && text[j] == '0')
            j++;
        const size_t width = j;
        while (j < text.size() && j - width < 2 && std::isdigit(static_cast<unsigned char>(text[j])))
            j++;
        valid = j < text.size() && text[j] == 'd';
        conversions++;
        i = j;
    }
    if (!valid || conversions != 1)
        throw UsageError("--video: '" + text + "' must hold exactly one integer conversion such "
                         "as %d or %03d (and no other %; write %% for a percent sign)");
}

Options parseOptions(int argc, char** argv)
{
    Options opt;
    std::vector<std::string> args(argv + 1, argv + argc);
    for (size_t i = 0; i < args.size(); i++) {
        std::string arg = args[i], value;
        bool hasInlineValue = false;
        if (arg.rfind("--", 0) == 0 && arg.find('=') != std::string::npos) {  // --size=640x480
            value = arg.substr(arg.find('=') + 1);
            arg = arg.substr(0, arg.find('='));
            hasInlineValue = true;
        }
        auto next = [&]() -> std::string {
            if (hasInlineValue)
                return value;
            if (i + 1 >= args.size())
                throw UsageError(arg + " needs a value");
            return args[++i];
        };
        auto flag = [&]() {
            if (hasInlineValue)
                throw UsageError(arg + " takes no value");
        };
        if (arg == "-h" || arg == "--help") {
            flag();
            opt.help = true;
        } else if (arg == "-o" || arg == "--output") {
            opt.output = next();
        } else if (arg == "--shade") {
            opt.shadeType = parseChoice(arg, next(), {{"flat", sh::SHADE_FLAT},
                                                      {"gouraud", sh::SHADE_GOURAUD},
                                                      {"phong", sh::SHADE_PHONG}});
        } else if (arg == "--size") {
            opt.size = parseSize(next());
        } else if (arg == "--light") {
            const std::vector<double> v = parseNumbers(next(), 6, arg, "x,y,z,r,g,b");
            if (v[3] < 0 || v[4] < 0 || v[5] < 0)
                throw UsageError("--light: intensities r,g,b must not be negative");
            opt.lights.emplace_back(cv::Point3d(v[0], v[1], v[2]), cv::Vec3d(v[3], v[4], v[5]));
        } else if (arg == "--background") {
            const std::string text = next();
            const std::vector<double> v = parseNumbers(text, 3, arg, "r,g,b in [0, 1]");
            for (double c : v)
                if (c < 0 || c > 1)
                    throw UsageError("--background: expected r,g,b in [0, 1], got '" + text + "'");
            opt.background = {v[0], v[1], v[2]};
        } else if (arg == "--up") {
            const int axis = parseChoice(arg, next(), {{"x", 1}, {"y", 2}, {"z", 3},
                                                       {"-x", -1}, {"-y", -2}, {"-z", -3}});
            opt.up = cv::Vec3d::all(0);
            opt.up[std::abs(axis) - 1] = axis > 0 ? 1 : -1;
        } else if (arg == "--cull") {
            opt.cullMode = parseChoice(arg, next(), {{"none", sh::CULL_NONE},
                                                     {"back", sh::CULL_BACK},
                                                     {"front", sh::CULL_FRONT}});
        } else if (arg == "--painter") {
            flag();
            opt.painter = true;
        } else if (arg == "--depth") {
            opt.depth = next();
            const std::string ext = extensionOf(opt.depth);
            if (ext != ".exr" && ext != ".png")
                throw UsageError("--depth: expected a .exr or .png file, got '" + opt.depth + "'");
        } else if (arg == "--ids") {
            opt.ids = next();
            if (extensionOf(opt.ids) != ".png")
                throw UsageError("--ids: expected a .png file, got '" + opt.ids + "'");
        } else if (arg == "--texture") {
            opt.texture = next();
        } else if (arg == "--show") {
            flag();
            opt.show = true;
        } else if (arg == "--turntable") {
            const std::string text = next();
            char* stop = nullptr;
            const long n = std::strtol(text.c_str(), &stop, 10);
            if (text.empty() || *stop != '\0' || n < 1 || n > 100000)
                throw UsageError("--turntable: expected a number of views in 1..100000, got '" +
                                 text + "'");
            opt.turntable = int(n);
        } else if (arg == "--video") {
            opt.video = next();
            if (isFramePattern(opt.video))
                checkFramePattern(opt.video);
        } else if (arg == "--demo") {
            flag();
            if (!opt.mesh.empty())
                throw UsageError("two meshes given: '" + opt.mesh + "' and --demo");
            opt.mesh = "demo";
        } else if (arg.size() > 1 && arg[0] == '-') {
            throw UsageError("unknown option '" + arg + "'");
        } else {
            if (!opt.mesh.empty())
                throw UsageError("two meshes given: '" + opt.mesh + "' and '" + arg + "'");
            opt.mesh = arg;
        }
    }
    if (opt.help)
        return opt;
    if (opt.mesh.empty())
        throw UsageError("no mesh given (a mesh file, or demo)");
    if (opt.turntable > 0 && opt.video.empty())
        throw UsageError("--turntable needs --video OUT.mp4 or --video frame_%03d.png");
    if (!opt.video.empty() && opt.turntable == 0)
        throw UsageError("--video needs --turntable N");
    if (opt.output.empty() && opt.turntable == 0)
        opt.output = (opt.mesh == "demo" ? std::string("demo")
                                         : std::filesystem::path(opt.mesh).stem().string()) +
                     ".png";
    return opt;
}

/** The mesh as drawMesh3d takes it; colours always present (grey where the file has none).
Textured: the texture (RGB, float) and texCoords in its pixels. */
struct Mesh {
    cv::Mat vertices, faces, normals, colors;
    cv::Mat texCoords, texture;
    std::string description;
};

/** Reads `imagePath` as the mesh's texture; the file's normalized (u, v) (v up, 0 and 1 at the
edges) become the texture pixels drawTexturedMesh3d takes. */
void loadTexture(const std::string& imagePath, const cv::Mat& fileTexCoords, Mesh& m)
{
    if (fileTexCoords.empty())
        throw RunError("--texture: " + m.description + " has no texture coordinates");
    const cv::Mat bgr = cv::imread(imagePath, cv::IMREAD_COLOR);
    if (bgr.empty())
        throw RunError("--texture: cannot read image '" + imagePath + "'");
    cv::Mat rgb;
    cv::cvtColor(bgr, rgb, cv::COLOR_BGR2RGB);  // the library keeps RGB
    rgb.convertTo(m.texture, CV_32F, 1.0 / 255);
    m.texCoords.create(fileTexCoords.rows, 2, CV_32F);
    for (int i = 0; i < fileTexCoords.rows; i++) {
        const float* uv = fileTexCoords.ptr<float>(i);
        m.texCoords.at<float>(i, 0) = uv[0] * m.texture.cols - 0.5f;
        m.texCoords.at<float>(i, 1) = (1 - uv[1]) * m.texture.rows - 0.5f;
    }
}

Mesh loadInput(const std::string& name, const std::string& texturePath)
{
    Mesh m;
    if (name == "demo") {
        if (!texturePath.empty())
            throw RunError("--texture: the built-in torus knot has no texture coordinates; give "
                           "a mesh file that has them (OBJ vt, glTF, PLY s/t, ...)");
        const shading_samples::Mesh3d knot = shading_samples::makeDemoMesh3d();
        m.vertices = knot.verts3d, m.faces = knot.faces, m.normals = knot.normals;
        m.colors = knot.vcolors;
        m.description = "built-in torus knot";
    } else {
        cv::Mat fileTexCoords;
        try {
            sh::loadMesh(name, m.vertices, m.faces, m.normals, m.colors, fileTexCoords);
        } catch (const cv::Exception& e) {
            throw RunError(e.err);
        }
        m.description = name;
        if (!texturePath.empty())
            loadTexture(texturePath, fileTexCoords, m);
        if (m.colors.empty())  // neutral grey: the lights give it its shape
            m.colors = cv::Mat(m.vertices.rows, 3, CV_32F, cv::Scalar::all(0.8));
    }
    return m;
}

//! The bounding sphere: centre of the finite vertices' box, radius to the farthest of them.
void boundingSphere(const cv::Mat& vertices, cv::Vec3d& centre, double& radius)
{
    cv::Vec3d lo = cv::Vec3d::all(HUGE_VAL), hi = cv::Vec3d::all(-HUGE_VAL);
    bool any = false;
    for (int i = 0; i < vertices.rows; i++) {
        const cv::Vec3d p(vertices.ptr<float>(i)[0], vertices.ptr<float>(i)[1],
                          vertices.ptr<float>(i)[2]);
        if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2]))
            continue;
        any = true;
        for (int k = 0; k < 3; k++)
            lo[k] = std::min(lo[k], p[k]), hi[k] = std::max(hi[k], p[k]);
    }
    centre = any ? (lo + hi) * 0.5 : cv::Vec3d::all(0);
    radius = 0;
    for (int i = 0; i < vertices.rows; i++) {
        const cv::Vec3d p(vertices.ptr<float>(i)[0], vertices.ptr<float>(i)[1],
                          vertices.ptr<float>(i)[2]);
        const double d = cv::norm(p - centre);
        if (std::isfinite(d))
            radius = std::max(radius, d);
    }
    if (!(radius > 0))
        radius = 1;  // a single point: any scale frames it
}

//! One view: camera pose and intrinsics framing the bounding sphere, lights placed around it.
struct View {
    cv::Matx33d K;
    cv::Mat rvec, tvec;
    std::vector<sh::PointLight> lights;
    double zNear = 1e-3;
};

const double kHalfFov = 20.0 * CV_PI / 180.0;  // a 40-degree field of view

View frameView(const Options& opt, const cv::Vec3d& centre, double radius, double turn)
{
    // A right-handed (front, right, up) frame for the model: front faces the viewer.
    const cv::Vec3d up = opt.up;
    const cv::Vec3d front = std::abs(up[2]) > 0 ? cv::Vec3d(0, -1, 0) : cv::Vec3d(0, 0, 1);
    const cv::Vec3d right = up.cross(front);
    // A three-quarter view from a little above; the turntable adds its angle to the azimuth.
    const double azimuth = 30.0 * CV_PI / 180.0 + turn, elevation = 20.0 * CV_PI / 180.0;
    const cv::Vec3d dir = std::cos(elevation) * (std::cos(azimuth) * front +
                                                 std::sin(azimuth) * right) +
                          std::sin(elevation) * up;
    // Far enough that the sphere fits the narrower side of the image with a 5% margin.
    const double dist = 1.05 * radius / std::sin(kHalfFov);
    const cv::Vec3d eye = centre + dist * dir;

    View v;
    sh::lookAt(cv::Point3d(eye), cv::Point3d(centre), up, v.rvec, v.tvec);
    const double f = 0.5 * std::min(opt.size.width, opt.size.height) / std::tan(kHalfFov);
    v.K = cv::Matx33d(f, 0, 0.5 * (opt.size.width - 1), 0, f, 0.5 * (opt.size.height - 1), 0, 0,
                      1);
    v.zNear = 0.5 * (dist - radius);  // the whole sphere lies beyond it

    if (!opt.lights.empty()) {
        v.lights = opt.lights;  // the user's, fixed in the world
        return v;
    }
    // Key (white, upper left), fill (warm, right), rim (cool, behind): in the camera's frame,
    // so a turntable shows the model turning under fixed studio lights.
    const cv::Vec3d back = dir;                                   // centre -> eye
    const cv::Vec3d camUp = cv::normalize(up - up.dot(back) * back);
    const cv::Vec3d camRight = camUp.cross(back);
    auto at = [&](double x, double y, double z) {
        const cv::Vec3d d = cv::normalize(x * camRight + y * camUp + z * back);
        return cv::Point3d(centre + 10.0 * radius * d);  // far: nearly parallel rays
    };
    v.lights = {sh::PointLight(at(-0.6, 0.7, 0.8), {0.85, 0.85, 0.85}),
                sh::PointLight(at(0.9, -0.1, 0.5), {0.32, 0.26, 0.18}),
                sh::PointLight(at(0.3, 0.8, -1.0), {0.30, 0.38, 0.55})};
    return v;
}

struct Frame {
    cv::Mat rgb;      // CV_32FC3
    cv::Mat depth;    // CV_32FC1, +inf where nothing was drawn
    cv::Mat faceIds;  // CV_32SC1, -1 where nothing was drawn
    double ms = 0;
};

Frame renderView(const Options& opt, const Mesh& mesh, const View& view, bool wantIds)
{
    sh::RenderSettings settings;
    settings.shadeType = opt.shadeType;
    settings.visibility = opt.painter ? sh::VISIBILITY_PAINTER : sh::VISIBILITY_ZBUFFER;
    settings.cullMode = opt.cullMode;
    settings.zNear = view.zNear;
    settings.lights = view.lights;
    settings.ks = 0.35;  // softer highlights than the library's default on a studio rig

    Frame fr;
    fr.rgb = cv::Mat(opt.size, CV_32FC3, cv::Scalar(opt.background));
    cv::TickMeter tm;
    tm.start();
    const cv::_OutputArray ids = wantIds ? cv::_OutputArray(fr.faceIds)
                                         : cv::_OutputArray(cv::noArray());
    if (mesh.texture.empty()) {
        sh::drawMesh3d(fr.rgb, mesh.vertices, mesh.faces, mesh.colors, view.K, view.rvec,
                       view.tvec, settings, mesh.normals, fr.depth, ids);
    } else {
        settings.textureBorder = cv::BORDER_WRAP;  // coordinates outside [0, 1] repeat, as in GL
        sh::drawTexturedMesh3d(fr.rgb, mesh.vertices, mesh.faces, mesh.texCoords, mesh.texture,
                               view.K, view.rvec, view.tvec, settings, mesh.normals, fr.depth,
                               ids);
    }
    tm.stop();
    fr.ms = tm.getTimeMilli();
    return fr;
}

cv::Mat toBgr8(const cv::Mat& rgb)
{
    cv::Mat bgr, bgr8;
    cv::cvtColor(rgb, bgr, cv::COLOR_RGB2BGR);  // the library keeps RGB; imwrite wants BGR
    bgr.convertTo(bgr8, CV_8U, 255.0);          // rounds and saturates
    return bgr8;
}

void writeImage(const std::string& path, const cv::Mat& img, const std::string& what)
{
    bool ok = false;
    std::string why;
    try {
        ok = cv::imwrite(path, img);
    } catch (const cv::Exception& e) {
        why = ": " + e.err;
    }
    if (!ok)
        throw RunError("cannot write " + what + " '" + path + "'" + why);
}

void writeDepth(const std::string& path, const cv::Mat& depth)
{
    if (extensionOf(path) == ".exr") {
        if (!cv::haveImageWriter(path))
            throw RunError("--depth: this OpenCV build cannot write OpenEXR (.exr); use "
                           "--depth FILE.png (16-bit)");
        writeImage(path, depth, "the depth map");
        std::cout << "wrote " << path << " (float32 camera z, background +inf)\n";
        return;
    }
    const cv::Mat drawn = depth < std::numeric_limits<float>::infinity();
    double zmin = 0, zmax = 0;
    if (cv::countNonZero(drawn) > 0)
        cv::minMaxLoc(depth, &zmin, &zmax, nullptr, nullptr, drawn);
    cv::Mat out(depth.size(), CV_16U, cv::Scalar(0));
    const double scale = zmax > zmin ? 65534.0 / (zmax - zmin) : 0;
    for (int y = 0; y < depth.rows; y++)
        for (int x = 0; x < depth.cols; x++) {
            const float z = depth.at<float>(y, x);
            if (z < std::numeric_limits<float>::infinity())
                out.at<ushort>(y, x) = cv::saturate_cast<ushort>(
                    zmax > zmin ? 1.0 + (z - zmin) * scale : 65535.0);
        }
    writeImage(path, out, "the depth map");
    std::cout << "wrote " << path << " (16-bit: 1..65535 = camera z " << zmin << ".." << zmax
              << ", 0 = background)\n";
}

void writeIds(const std::string& path, const cv::Mat& faceIds, int faceCount)
{
    cv::Mat out;
    if (faceCount < 65535) {
        faceIds.convertTo(out, CV_16U, 1.0, 1.0);  // -1 (nothing) becomes 0
        writeImage(path, out, "the face ids");
        std::cout << "wrote " << path << " (16-bit: face index + 1, 0 = background)\n";
        return;
    }
    out.create(faceIds.size(), CV_8UC3);
    for (int y = 0; y < faceIds.rows; y++)
        for (int x = 0; x < faceIds.cols; x++) {
            const unsigned v = unsigned(faceIds.at<int>(y, x) + 1);
            out.at<cv::Vec3b>(y, x) = cv::Vec3b(uchar(v), uchar(v >> 8), uchar(v >> 16));  // BGR
        }
    writeImage(path, out, "the face ids");
    std::cout << "wrote " << path << " (8-bit colour: face index + 1 = (R<<16)|(G<<8)|B, "
              << "0 = background)\n";
}

void show(const cv::Mat& bgr8, int waitMs)
{
#if !defined(_WIN32) && !defined(__APPLE__)
    // Some GUI backends abort the process when there is no display instead of throwing.
    if (!std::getenv("DISPLAY") && !std::getenv("WAYLAND_DISPLAY"))
        throw RunError("--show: no display (neither DISPLAY nor WAYLAND_DISPLAY is set)");
#endif
    try {
        cv::imshow("opencv_shading", bgr8);
        cv::waitKey(waitMs);
    } catch (const cv::Exception& e) {
        throw RunError("--show: cannot open a window (" + e.err + ")");
    }
}

const char* shadeName(int shadeType)
{
    return shadeType == sh::SHADE_FLAT    ? "flat"
           : shadeType == sh::SHADE_PHONG ? "Phong"
                                          : "Gouraud";
}

void progress(int done, int total, double seconds)
{
    const int width = 30;
    const int filled = int(double(width) * done / total);
    const double fps = seconds > 0 ? done / seconds : 0;
    const double left = fps > 0 ? (total - done) / fps : 0;
    std::fprintf(stderr, "\r[%s%s] %d/%d  %.1f fps  %.1f s left ",
                 std::string(size_t(filled), '#').c_str(),
                 std::string(size_t(width - filled), '.').c_str(), done, total, fps, left);
    std::fflush(stderr);
}

void runTurntable(const Options& opt, const Mesh& mesh, const cv::Vec3d& centre, double radius)
{
    const bool frames = isFramePattern(opt.video);
    cv::VideoWriter writer;
    if (!frames) {
        writer.open(opt.video, cv::VideoWriter::fourcc('m', 'p', '4', 'v'), 30.0, opt.size);
        if (!writer.isOpened())
            throw RunError("--video: cannot open '" + opt.video + "' for writing with the mp4v "
                           "codec (this OpenCV's videoio may lack an encoder for it); write "
                           "numbered images instead: --video frame_%03d.png");
    }
    const bool bar = OPENCV_SHADING_ISATTY(stderr) != 0;
    cv::TickMeter tm;
    tm.start();
    for (int i = 0; i < opt.turntable; i++) {
        const View view = frameView(opt, centre, radius, 2.0 * CV_PI * i / opt.turntable);
        const Frame fr = renderView(opt, mesh, view, false);
        const cv::Mat bgr8 = toBgr8(fr.rgb);
        if (frames)
            writeImage(cv::format(opt.video.c_str(), i), bgr8, "frame");
        else
            writer.write(bgr8);
        if (opt.show)
            show(bgr8, 1);
        if (bar) {
            tm.stop();
            progress(i + 1, opt.turntable, tm.getTimeSec());
            tm.start();
        }
    }
    writer.release();
    tm.stop();
    if (bar)
        std::fputc('\n', stderr);
    std::cout << "wrote " << opt.turntable << " turntable frames "
              << (frames ? "as " : "into ") << opt.video << " in "
              << cv::format("%.2f", tm.getTimeSec())
              << " s (" << cv::format("%.1f", opt.turntable / tm.getTimeSec()) << " frames/s)\n";
}

int run(const Options& opt)
{
    const Mesh mesh = loadInput(opt.mesh, opt.texture);
    cv::Vec3d centre;
    double radius = 0;
    boundingSphere(mesh.vertices, centre, radius);
    std::cout << "mesh: " << mesh.description << ", " << mesh.vertices.rows << " vertices, "
              << mesh.faces.rows << " triangles" << (mesh.normals.empty() ? "" : ", normals")
              << "\n";

    if (!opt.output.empty() || !opt.depth.empty() || !opt.ids.empty() ||
        (opt.show && opt.turntable == 0)) {
        const View view = frameView(opt, centre, radius, 0.0);
        const Frame fr = renderView(opt, mesh, view, !opt.ids.empty());
        std::cout << "rendered " << opt.size.width << "x" << opt.size.height << ", "
                  << shadeName(opt.shadeType) << ", " << view.lights.size() << " lights, in "
                  << cv::format("%.1f", fr.ms) << " ms\n";
        const cv::Mat bgr8 = toBgr8(fr.rgb);
        if (!opt.output.empty()) {
            writeImage(opt.output, bgr8, "the image");
            std::cout << "wrote " << opt.output << "\n";
        }
        if (!opt.depth.empty())
            writeDepth(opt.depth, fr.depth);
        if (!opt.ids.empty())
            writeIds(opt.ids, fr.faceIds, mesh.faces.rows);
        if (opt.show && opt.turntable == 0) {
            std::cout << "(press any key in the window to close it)" << std::endl;
            show(bgr8, 0);
        }
    }
    if (opt.turntable > 0)
        runTurntable(opt, mesh, centre, radius);
    return 0;
}

}  // namespace

int main(int argc, char** argv)
{
    Options opt;
    try {
        opt = parseOptions(argc, argv);
    } catch (const UsageError& e) {
        std::cerr << "opencv_shading: " << e.what() << "\n" << kSynopsis;
        return 2;
    }
    if (opt.help) {
        std::cout << kUsage;
        return 0;
    }
    // OpenCV 4.x writes OpenEXR only when asked to (OPENCV_IO_ENABLE_OPENEXR); --depth x.exr is
    // that request. A value the user set is kept.
    if (extensionOf(opt.depth) == ".exr") {
#ifdef _WIN32
        if (!std::getenv("OPENCV_IO_ENABLE_OPENEXR"))
            _putenv_s("OPENCV_IO_ENABLE_OPENEXR", "1");
#else
        setenv("OPENCV_IO_ENABLE_OPENEXR", "1", 0);
#endif
    }
    try {
        return run(opt);
    } catch (const RunError& e) {
        std::cerr << "opencv_shading: " << e.what() << "\n";
    } catch (const cv::Exception& e) {
        std::cerr << "opencv_shading: " << e.err << "\n";
    } catch (const std::exception& e) {
        std::cerr << "opencv_shading: " << e.what() << "\n";
    }
    return 1;
}
