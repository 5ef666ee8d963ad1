// This file is part of opencv_shading. License: Apache-2.0.
//
// perf_scenes.hpp: the deterministic benchmark scenes, in the form cv::shading::render takes
// (shading_samples::MeshScene: verts2d L x 2 CV_32F, faces K x 3 CV_32S, vcolors L x 3 CV_32F in
// [0, 1], depth L x 1 CV_32F, larger is farther). Header-only so tests can reuse the scenes.
//
//   grid    128 x 128 cells split in two: 32,768 triangles tiling the whole canvas
//   sphere  UV sphere, 193 segments x 129 bands: 49,408 triangles, back faces kept, depth = z
//   random  20,000 overlapping triangles of mixed sizes, 13 layers deep on average
//   demo    the samples' torus knot (shading_samples::makeDemoScene), 10,000 triangles
//
// grid, sphere and random are built in unit coordinates ([0, 1]^2 is the canvas) and scaled to
// the canvas, so every size shows the same picture.
//
// The 3D scenes (Scene3d, for cv::shading::drawMesh3d) are closed meshes in world coordinates,
// seen by a cv::shading::lookAt camera and lit by three coloured point lights:
//
//   knot3d    the samples' torus knot as a 3D tube (shading_samples::makeDemoMesh3d): 10,000
//             triangles, 512 x 512
//   torus3d   a torus of 1000 x 500 quads: 1,000,000 triangles, 2048 x 2048
//
// makeTexturedScene3d gives either with its seams cut, texture coordinates and a 512 x 512
// checker texture, for cv::shading::drawTexturedMesh3d.
#ifndef OPENCV_SHADING_PERF_SCENES_HPP
#define OPENCV_SHADING_PERF_SCENES_HPP

#include "../../../samples/demo_scene.hpp"

#include <opencv2/core.hpp>
#include <opencv2/shading.hpp>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

namespace shading_perf {

using shading_samples::MeshScene;

//! A named scene on a square canvas.
struct Scene {
    std::string name;  //!< kind and size, e.g. "grid512"
    cv::Size size;     //!< canvas size
    MeshScene mesh;
};

namespace detail {

// Periodic RGB palette in [0.15, 0.95]: a hue wheel for t in [0, 1).
inline cv::Vec3f hue(double t)
{
    cv::Vec3f c;
    for (int k = 0; k < 3; ++k)
        c[k] = static_cast<float>(0.55 + 0.4 * std::cos(2.0 * CV_PI * (t + k / 3.0)));
    return c;
}

// Allocates the per-vertex matrices of a scene with `vertices` vertices.
inline MeshScene allocate(int vertices)
{
    MeshScene s;
    s.verts2d.create(vertices, 2, CV_32F);
    s.vcolors.create(vertices, 3, CV_32F);
    s.depth.create(vertices, 1, CV_32F);
    return s;
}

// Sets vertex v: unit position (x, y), colour and depth.
inline void setVertex(MeshScene& s, int v, double x, double y, const cv::Vec3f& color, double z)
{
    s.verts2d.at<cv::Vec2f>(v) = cv::Vec2f(static_cast<float>(x), static_cast<float>(y));
    s.vcolors.at<cv::Vec3f>(v) = color;
    s.depth.at<float>(v) = static_cast<float>(z);
}

}  // namespace detail

/** Grid: `cells` x `cells` squares tiling the unit square, each split into two triangles along
alternating diagonals. Depth is a smooth height field (a terrain seen from above). */
inline MeshScene makeGrid(int cells = 128)
{
    const int n = cells + 1;  // vertices per row
    MeshScene s = detail::allocate(n * n);
    for (int j = 0; j < n; ++j) {
        for (int i = 0; i < n; ++i) {
            const double u = double(i) / cells, v = double(j) / cells;
            const double z = 1.0 + 0.25 * std::sin(3.0 * CV_PI * u) * std::cos(2.0 * CV_PI * v);
            detail::setVertex(s, j * n + i, u, v, detail::hue(0.7 * u + 0.3 * v), z);
        }
    }
    std::vector<cv::Vec3i> faces;
    faces.reserve(2 * static_cast<size_t>(cells) * cells);
    for (int j = 0; j < cells; ++j) {
        for (int i = 0; i < cells; ++i) {
            const int a = j * n + i, b = a + 1, c = a + n + 1, d = a + n;  // cell corners
            if ((i + j) % 2 == 0) {
                faces.emplace_back(a, b, c);
                faces.emplace_back(a, c, d);
            } else {
                faces.emplace_back(a, b, d);
                faces.emplace_back(b, c, d);
            }
        }
    }
    s.faces = cv::Mat(faces, true).reshape(1);
    return s;
}

/** UV sphere of radius 0.46 centred in the unit square, seen orthographically and tilted so
both poles' caps show at an angle. `segments` around, `bands` from pole to pole (the two pole
bands are triangle fans): 2 * segments * (bands - 1) triangles, 49,408 by default. Back faces are
kept; depth is the view-space z (larger is farther), colours are a hue by longitude, lit. */
inline MeshScene makeSphere(int segments = 193, int bands = 129)
{
    const int rings = bands - 1;  // rings of `segments` vertices between the poles
    const int north = 0, south = 1 + rings * segments;
    MeshScene s = detail::allocate(south + 1);
    const double tilt = 0.45, radius = 0.46;
    const cv::Vec3d light = cv::normalize(cv::Vec3d(-0.5, -0.6, -0.62));  // upper left, eye side
    auto put = [&](int v, double theta, double phi) {
        const cv::Vec3d p0(std::sin(theta) * std::cos(phi), -std::cos(theta),
                           std::sin(theta) * std::sin(phi));
        const cv::Vec3d p(p0[0], std::cos(tilt) * p0[1] - std::sin(tilt) * p0[2],
                          std::sin(tilt) * p0[1] + std::cos(tilt) * p0[2]);  // about x
        const double lit = 0.25 + 0.75 * std::max(0.0, p.dot(light));
        detail::setVertex(s, v, 0.5 + radius * p[0], 0.5 + radius * p[1],
                          detail::hue(phi / (2.0 * CV_PI)) * lit, p[2]);
    };
    put(north, 0.0, 0.0);
    put(south, CV_PI, 0.0);
    for (int r = 0; r < rings; ++r)
        for (int k = 0; k < segments; ++k)
            put(1 + r * segments + k, CV_PI * (r + 1) / bands, 2.0 * CV_PI * k / segments);

    auto at = [&](int r, int k) { return 1 + r * segments + k % segments; };
    std::vector<cv::Vec3i> faces;
    faces.reserve(2 * static_cast<size_t>(segments) * rings);
    for (int k = 0; k < segments; ++k)
        faces.emplace_back(north, at(0, k + 1), at(0, k));
    for (int r = 0; r + 1 < rings; ++r) {
        for (int k = 0; k < segments; ++k) {
            faces.emplace_back(at(r, k), at(r, k + 1), at(r + 1, k + 1));
            faces.emplace_back(at(r, k), at(r + 1, k + 1), at(r + 1, k));
        }
    }
    for (int k = 0; k < segments; ++k)
        faces.emplace_back(south, at(rings - 1, k), at(rings - 1, k + 1));
    s.faces = cv::Mat(faces, true).reshape(1);
    return s;
}

/** Random overlapping triangles: each around its own centre, with a log-uniform size spread of
25x (mixed sizes), random vertex colours and depths. Sizes are scaled so that the triangles'
total area is `layers` times the unit square's, and every triangle lies inside the square: on
average each pixel is covered `layers` times. */
inline MeshScene makeRandom(int count = 20000, double layers = 13.0, uint64 seed = 20240611)
{
    cv::RNG rng(seed);
    std::vector<cv::Point2d> shape(3 * static_cast<size_t>(count));
    double totalArea = 0;
    for (int t = 0; t < count; ++t) {
        const double size = std::exp(rng.uniform(std::log(0.004), std::log(0.1)));
        cv::Point2d* p = &shape[3 * static_cast<size_t>(t)];
        for (int k = 0; k < 3; ++k) {
            const double angle = rng.uniform(0.0, 2.0 * CV_PI);
            p[k] = size * rng.uniform(0.6, 1.0) * cv::Point2d(std::cos(angle), std::sin(angle));
        }
        totalArea += 0.5 * std::abs((p[1] - p[0]).cross(p[2] - p[0]));
    }
    const double scale = std::sqrt(layers / totalArea);

    MeshScene s = detail::allocate(3 * count);
    for (int v = 0; v < 3 * count; v += 3) {
        // Place the scaled triangle's bounding box uniformly inside the unit square.
        for (int k = 0; k < 3; ++k)
            shape[v + k] *= scale;
        cv::Point2d lo = shape[v], hi = shape[v];
        for (int k = 1; k < 3; ++k) {
            lo = {std::min(lo.x, shape[v + k].x), std::min(lo.y, shape[v + k].y)};
            hi = {std::max(hi.x, shape[v + k].x), std::max(hi.y, shape[v + k].y)};
        }
        if (hi.x - lo.x >= 1.0 || hi.y - lo.y >= 1.0)
            throw std::logic_error("makeRandom: a triangle does not fit the canvas");
        // (One draw per statement: argument evaluation order is unspecified.)
        const double x = rng.uniform(-lo.x, 1.0 - hi.x);
        const double y = rng.uniform(-lo.y, 1.0 - hi.y);
        for (int k = 0; k < 3; ++k) {
            cv::Vec3f color;
            for (int c = 0; c < 3; ++c)
                color[c] = rng.uniform(0.f, 1.f);
            const cv::Point2d p = cv::Point2d(x, y) + shape[v + k];
            detail::setVertex(s, v + k, p.x, p.y, color, rng.uniform(0.0, 1.0));
        }
    }
    s.faces.create(count, 3, CV_32S);
    for (int t = 0; t < count; ++t)
        s.faces.at<cv::Vec3i>(t) = cv::Vec3i(3 * t, 3 * t + 1, 3 * t + 2);
    return s;
}

/** The scene `kind` ("grid", "sphere", "random", "demo", or the million-face "biggrid" and
"bigsphere") on a `side` x `side` canvas. */
inline Scene makeScene(const std::string& kind, int side)
{
    Scene sc{kind + std::to_string(side), cv::Size(side, side), {}};
    if (kind == "demo") {
        sc.mesh = shading_samples::makeDemoScene(sc.size);
        return sc;
    }
    if (kind == "grid")
        sc.mesh = makeGrid();
    else if (kind == "biggrid")  // 708 x 708 cells: 1,002,528 faces of 4 pixels at 2048
        sc.mesh = makeGrid(708);
    else if (kind == "sphere")
        sc.mesh = makeSphere();
    else if (kind == "bigsphere")  // closed, back faces kept: 1,000,000 faces
        sc.mesh = makeSphere(1000, 501);
    else if (kind == "random")
        sc.mesh = makeRandom();
    else
        throw std::invalid_argument("makeScene: unknown scene '" + kind + "'");
    sc.mesh.verts2d *= side;  // unit square -> canvas
    return sc;
}

using shading_samples::Mesh3d;

namespace detail {

// Rotation matrix of a Rodrigues vector (cv::Rodrigues is in calib3d, which we do not link).
inline cv::Matx33d rodrigues(const cv::Vec3d& r)
{
    const double angle = cv::norm(r);
    if (angle < 1e-15)
        return cv::Matx33d::eye();
    const cv::Vec3d k = r / angle;
    const cv::Matx33d cross(0, -k[2], k[1], k[2], 0, -k[0], -k[1], k[0], 0);
    return cv::Matx33d::eye() + std::sin(angle) * cross +
           (1 - std::cos(angle)) * (cross * cross);
}

}  // namespace detail

/** A torus about the z axis (radii 2 and 0.8): `along` quads around the axis by `around` around
the tube, 1,000,000 triangles by default, wound counter-clockwise seen from outside, with exact
unit normals. Colours: hue bands around the axis, tinted by the angle around the tube. */
inline Mesh3d makeTorusMesh3d(int along = 1000, int around = 500)
{
    const double major = 2.0, minor = 0.8;
    Mesh3d m;
    m.verts3d.create(along * around, 3, CV_32F);
    m.vcolors.create(along * around, 3, CV_32F);
    m.normals.create(along * around, 3, CV_32F);
    for (int i = 0; i < along; ++i) {
        const double u = 2.0 * CV_PI * i / along;
        for (int j = 0; j < around; ++j) {
            const double v = 2.0 * CV_PI * j / around;
            const cv::Vec3d n(std::cos(v) * std::cos(u), std::cos(v) * std::sin(u), std::sin(v));
            const cv::Vec3d p = major * cv::Vec3d(std::cos(u), std::sin(u), 0) + minor * n;
            const int k = i * around + j;
            m.verts3d.at<cv::Vec3f>(k) = cv::Vec3f(p);
            m.normals.at<cv::Vec3f>(k) = cv::Vec3f(n);
            m.vcolors.at<cv::Vec3f>(k) = detail::hue(3.0 * u / (2.0 * CV_PI) +
                                                     0.15 * std::cos(v));
        }
    }
    // Quad (a, b, c, d) = (i, j), (i + 1, j), (i + 1, j + 1), (i, j + 1): d/du x d/dv points
    // out, so (a, b, c) and (a, c, d) turn counter-clockwise seen from outside.
    m.faces.create(2 * along * around, 3, CV_32S);
    int* f = m.faces.ptr<int>();
    for (int i = 0; i < along; ++i) {
        for (int j = 0; j < around; ++j) {
            const int i1 = (i + 1) % along, j1 = (j + 1) % around;
            const int a = i * around + j, b = i1 * around + j, c = i1 * around + j1,
                      d = i * around + j1;
            const int tri[6] = {a, b, c, a, c, d};
            f = std::copy(tri, tri + 6, f);
        }
    }
    return m;
}

/** A 3D scene: mesh, camera, lights and material. `settings` holds the lights and material
(ka 0.2, kd 0.7, ks 0.5, shininess 16, ambient 1); benchmarks set its shading and visibility. */
struct Scene3d {
    std::string name;          //!< kind, "3d" and size, e.g. "knot3d512"
    cv::Size size;             //!< canvas size
    Mesh3d mesh;               //!< with its exact unit vertex normals
    cv::Matx33d cameraMatrix;  //!< fx = fy = side, principal point at the centre
    cv::Mat rvec, tvec;        //!< from cv::shading::lookAt
    cv::Matx33d rotation;      //!< R of rvec: world to camera, Xc = R Xw + t
    cv::Vec3d eye;             //!< camera centre, world coordinates
    cv::shading::RenderSettings settings;
};

/** The 3D scene `kind` ("knot3d" or "torus3d") on a `side` x `side` canvas. */
inline Scene3d makeScene3d(const std::string& kind, int side)
{
    Scene3d sc;
    sc.name = kind + std::to_string(side);
    sc.size = cv::Size(side, side);
    double scale;  // the mesh's extent: the camera and lights are placed relative to it
    cv::Vec3d up;
    if (kind == "knot3d") {
        sc.mesh = shading_samples::makeDemoMesh3d();  // 10,000 triangles
        scale = 3.42;
        sc.eye = cv::Vec3d(2.4, -5.0, 7.2);  // a 3/4 view from above the knot's plane
        up = cv::Vec3d(0, 1, 0);
    } else if (kind == "torus3d") {
        sc.mesh = makeTorusMesh3d();
        scale = 2.8;
        sc.eye = cv::Vec3d(0.8, -5.6, 4.2);  // the hole and the far side show
        up = cv::Vec3d(0, 0, 1);
    } else {
        throw std::invalid_argument("makeScene3d: unknown scene '" + kind + "'");
    }
    // fx = fy = side: a 53-degree field of view. Pixel centres are integers: centre (side-1)/2.
    const double f = side, c = 0.5 * (side - 1);
    sc.cameraMatrix = cv::Matx33d(f, 0, c, 0, f, c, 0, 0, 1);
    cv::shading::lookAt(cv::Point3d(sc.eye), cv::Point3d(0, 0, 0), up, sc.rvec, sc.tvec);
    sc.rotation = detail::rodrigues(cv::Vec3d(sc.rvec.ptr<double>()));

    cv::shading::RenderSettings& s = sc.settings;
    s.zNear = 1.0;  // every vertex is farther; the GL peer's near plane too
    s.ka = 0.2;
    s.kd = 0.7;
    s.ks = 0.5;
    s.shininess = 16;
    s.ambient = cv::Vec3d(1, 1, 1);
    // Warm key light upper left, cool fill from the right, reddish rim light from behind.
    s.lights = {cv::shading::PointLight(cv::Point3d(-1.8, 1.6, 2.4) * scale, {0.85, 0.7, 0.55}),
                cv::shading::PointLight(cv::Point3d(2.2, 0.4, 1.2) * scale, {0.3, 0.5, 0.85}),
                cv::shading::PointLight(cv::Point3d(0.2, 2.5, -1.5) * scale, {0.6, 0.25, 0.3})};
    return sc;
}

/** A 3D scene with texture coordinates and a texture, for cv::shading::drawTexturedMesh3d. The
mesh is the scene's own (same positions, normals, faces in the same order and winding, so the
same pixels are covered) with its seams cut: both meshes are wrapped grids (vertex i * around + j,
ring i along, j around), and here the grid has one more ring and one more column, copies of the
first ones, which the faces that closed the tube now use. A vertex (i, j) of that
(along + 1) x (around + 1) grid has texture coordinates (u, v) = (i repeatsU cols / along,
j repeatsV rows / around) in texture pixels: the texture repeats repeatsU times along and
repeatsV times around, so the coordinates run past the texture and need BORDER_WRAP (GL_REPEAT),
and the seams are where u or v is a whole number of texture widths: no face spans them. */
struct TexturedScene3d {
    Scene3d scene;       //!< the seam-cut mesh; name, size, camera, lights as makeScene3d's
    cv::Mat texCoords;   //!< L x 2 CV_32F, texture pixels ((0, 0): centre of the top-left texel)
    cv::Mat texture8u;   //!< rows x cols CV_8UC3, RGB (the channel order of the canvas)
    cv::Mat texture32f;  //!< texture8u / 255, CV_32FC3: the float canvas's units
    int repeatsU = 1, repeatsV = 1;
};

namespace detail {

/** A 512 x 512 texture: an 8 x 8 checker (64-texel cells) of light and dark shades of a colour
that varies smoothly and periodically over the texture (so it tiles without a seam). */
inline cv::Mat makeCheckerTexture(int side = 512, int cells = 8)
{
    cv::Mat tex(side, side, CV_8UC3);
    const int cell = side / cells;
    for (int y = 0; y < side; ++y) {
        for (int x = 0; x < side; ++x) {
            const double s = double(x) / side, t = double(y) / side;
            const cv::Vec3f base = hue(s + 0.25 * std::sin(2.0 * CV_PI * t));  // in [0.15, 0.95]
            const bool light = ((x / cell) + (y / cell)) % 2 == 0;
            cv::Vec3b& out = tex.at<cv::Vec3b>(y, x);
            for (int k = 0; k < 3; ++k) {
                const double c = light ? 0.3 + 0.7 * base[k] : 0.35 * base[k];
                out[k] = cv::saturate_cast<uchar>(255.0 * c);
            }
        }
    }
    return tex;
}

}  // namespace detail

/** The textured variant of makeScene3d(kind, side): the knot with the texture 4 times along and
once around the tube, the torus 4 times around its axis and twice around the tube: about 2.8
texels to a pixel's width on the knot (minified, mostly across the thin tube; no mipmaps in
either peer) and 0.9 on the torus (medians over the faces). Throws if the
mesh is not a wrapped grid of two triangles per cell (the grid's `around` is read from face 0,
which is (0, around + 1, around) for the knot and (0, around, around + 1) for the torus). */
inline TexturedScene3d makeTexturedScene3d(const std::string& kind, int side)
{
    TexturedScene3d ts;
    ts.scene = makeScene3d(kind, side);
    ts.repeatsU = 4;
    ts.repeatsV = kind == "knot3d" ? 1 : 2;
    ts.texture8u = detail::makeCheckerTexture();
    ts.texture8u.convertTo(ts.texture32f, CV_32F, 1.0 / 255.0);

    Mesh3d& m = ts.scene.mesh;
    const Mesh3d wrapped = m;  // the matrices are replaced below, not written through
    const int count = wrapped.verts3d.rows;
    const cv::Vec3i face0 = wrapped.faces.at<cv::Vec3i>(0);
    const int around = std::min(face0[1], face0[2]);
    if (face0[0] != 0 || around < 3 || count % around != 0)
        throw std::logic_error("makeTexturedScene3d: the mesh is not a wrapped grid");
    const int along = count / around;
    const int columns = around + 1;

    // The faces, on the cut grid: a face with corners on ring along-1 and ring 0 takes ring 0's
    // copy (ring `along`), likewise for the columns.
    m.faces = cv::Mat(wrapped.faces.size(), CV_32S);
    for (int f = 0; f < wrapped.faces.rows; ++f) {
        const cv::Vec3i face = wrapped.faces.at<cv::Vec3i>(f);
        int i[3], j[3];
        for (int k = 0; k < 3; ++k)
            i[k] = face[k] / around, j[k] = face[k] % around;
        const int iSpan = *std::max_element(i, i + 3) - *std::min_element(i, i + 3);
        const int jSpan = *std::max_element(j, j + 3) - *std::min_element(j, j + 3);
        const bool iWraps = iSpan == along - 1, jWraps = jSpan == around - 1;
        if ((iSpan > 1 && !iWraps) || (jSpan > 1 && !jWraps))
            throw std::logic_error("makeTexturedScene3d: a face is not in one grid cell");
        cv::Vec3i& out = m.faces.at<cv::Vec3i>(f);
        for (int k = 0; k < 3; ++k)
            out[k] = (iWraps && i[k] == 0 ? along : i[k]) * columns +
                     (jWraps && j[k] == 0 ? around : j[k]);
    }

    const int cutCount = (along + 1) * columns;
    m.verts3d.create(cutCount, 3, CV_32F);
    m.normals.create(cutCount, 3, CV_32F);
    m.vcolors.create(cutCount, 3, CV_32F);
    ts.texCoords.create(cutCount, 2, CV_32F);
    const double du = double(ts.repeatsU) * ts.texture8u.cols / along;
    const double dv = double(ts.repeatsV) * ts.texture8u.rows / around;
    for (int i = 0; i <= along; ++i) {
        for (int j = 0; j <= around; ++j) {
            const int v = i * columns + j, source = (i % along) * around + j % around;
            m.verts3d.at<cv::Vec3f>(v) = wrapped.verts3d.at<cv::Vec3f>(source);
            m.normals.at<cv::Vec3f>(v) = wrapped.normals.at<cv::Vec3f>(source);
            m.vcolors.at<cv::Vec3f>(v) = wrapped.vcolors.at<cv::Vec3f>(source);
            ts.texCoords.at<cv::Vec2f>(v) = cv::Vec2f(float(i * du), float(j * dv));
        }
    }
    return ts;
}

}  // namespace shading_perf

#endif  // OPENCV_SHADING_PERF_SCENES_HPP
