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
#ifndef OPENCV_SHADING_PERF_SCENES_HPP
#define OPENCV_SHADING_PERF_SCENES_HPP

#include "../../../samples/demo_scene.hpp"

#include <opencv2/core.hpp>

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

/** The scene `kind` ("grid", "sphere", "random" or "demo") on a `side` x `side` canvas. */
inline Scene makeScene(const std::string& kind, int side)
{
    Scene sc{kind + std::to_string(side), cv::Size(side, side), {}};
    if (kind == "demo") {
        sc.mesh = shading_samples::makeDemoScene(sc.size);
        return sc;
    }
    if (kind == "grid")
        sc.mesh = makeGrid();
    else if (kind == "sphere")
        sc.mesh = makeSphere();
    else if (kind == "random")
        sc.mesh = makeRandom();
    else
        throw std::invalid_argument("makeScene: unknown scene '" + kind + "'");
    sc.mesh.verts2d *= side;  // unit square -> canvas
    return sc;
}

}  // namespace shading_perf

#endif  // OPENCV_SHADING_PERF_SCENES_HPP
