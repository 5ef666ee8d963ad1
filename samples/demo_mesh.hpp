// This file is part of opencv_shading. License: Apache-2.0.
//
// demo_mesh.hpp: the built-in demo mesh (a trefoil torus knot, 10,000 triangles) as a 3D mesh,
// header-only and needing only opencv2/core. The samples (through demo_scene.hpp) and the
// opencv_shading command-line program (`opencv_shading demo`) share it.
#ifndef OPENCV_SHADING_SAMPLES_DEMO_MESH_HPP
#define OPENCV_SHADING_SAMPLES_DEMO_MESH_HPP

#include <opencv2/core.hpp>

#include <algorithm>
#include <cmath>
#include <vector>

namespace shading_samples {

//! A 3D triangle mesh in the form cv::shading::drawMesh3d takes.
struct Mesh3d {
    cv::Mat verts3d;  //!< L x 3 CV_32F: world coordinates
    cv::Mat faces;    //!< K x 3 CV_32S: zero-based indices into verts3d
    cv::Mat vcolors;  //!< L x 3 CV_32F: RGB in [0, 1], unlit (drawMesh3d lights them)
    cv::Mat normals;  //!< L x 3 CV_32F unit vertex normals, or empty: drawMesh3d computes them
};

namespace detail {

inline cv::Vec3d normalized(const cv::Vec3d& v) { return v * (1.0 / cv::norm(v)); }

// The (2, 3) torus knot (a trefoil) wound on a torus of radii 2 and 1, centred at the origin.
inline cv::Vec3d trefoil(double t)
{
    const double r = 2.0 + std::cos(3.0 * t);
    return {r * std::cos(2.0 * t), r * std::sin(2.0 * t), std::sin(3.0 * t)};
}

// Smooth periodic palette (a cosine palette): u in [0, 1) -> soft RGB hues, equal at 0 and 1.
inline cv::Vec3d palette(double u)
{
    const double twoPi = 2.0 * CV_PI;
    return {0.55 + 0.40 * std::cos(twoPi * (u + 0.00)),
            0.55 + 0.40 * std::cos(twoPi * (u + 0.33)),
            0.55 + 0.40 * std::cos(twoPi * (u + 0.67))};
}

// The demo knot as a closed tube in world space: what makeDemoScene projects and makeDemoMesh3d
// returns. Vertex i * around + j lies on ring i (knot parameter t = 2 pi i / along), at angle
// 2 pi j / around about the knot.
struct KnotTube {
    int along = 0, around = 0;
    std::vector<cv::Vec3d> centre;  // per vertex: the point of the knot its ring surrounds
    std::vector<cv::Vec3d> radial;  // per vertex: unit outward normal of the tube
    cv::Mat faces;                  // K x 3 CV_32S, counter-clockwise about the outward normal
};

const double kTubeRadius = 0.42;

inline KnotTube makeKnotTube(int approxTriangles)
{
    CV_Assert(approxTriangles > 0);
    KnotTube tube;
    // Triangles = 2 * along * around; ~12 quads along per quad around keeps them near-square.
    tube.around = std::max(3, static_cast<int>(std::lround(std::sqrt(approxTriangles / 25.0))));
    tube.along = std::max(3, static_cast<int>(std::lround(approxTriangles / (2.0 * tube.around))));
    const int along = tube.along, around = tube.around;
    tube.centre.reserve(static_cast<size_t>(along) * around);
    tube.radial.reserve(static_cast<size_t>(along) * around);

    const double h = 1e-3;  // step for the curve's derivatives (central differences)
    for (int i = 0; i < along; ++i) {
        const double t = 2.0 * CV_PI * i / along;
        // Frenet frame: the trefoil's curvature never vanishes, so it is well defined.
        const cv::Vec3d c = trefoil(t);
        const cv::Vec3d d1 = trefoil(t + h) - trefoil(t - h);
        const cv::Vec3d d2 = trefoil(t + h) - 2.0 * c + trefoil(t - h);
        const cv::Vec3d tangent = normalized(d1);
        const cv::Vec3d normal = normalized(d2 - d2.dot(tangent) * tangent);
        const cv::Vec3d binormal = tangent.cross(normal);
        for (int j = 0; j < around; ++j) {
            const double a = 2.0 * CV_PI * j / around;
            tube.centre.push_back(c);
            tube.radial.push_back(std::cos(a) * normal + std::sin(a) * binormal);
        }
    }

    // Two triangles per quad of the (along x around) grid, wrapping both ways: a closed tube.
    // (tangent, d radial / d a, radial) is right-handed, so (a, c, b) and (a, d, c) turn
    // counter-clockwise seen from outside.
    std::vector<cv::Vec3i> faces;
    faces.reserve(2 * static_cast<size_t>(along) * around);
    for (int i = 0; i < along; ++i) {
        for (int j = 0; j < around; ++j) {
            const int a = i * around + j;
            const int b = ((i + 1) % along) * around + j;
            const int c = ((i + 1) % along) * around + (j + 1) % around;
            const int d = i * around + (j + 1) % around;
            faces.emplace_back(a, c, b);
            faces.emplace_back(a, d, c);
        }
    }
    tube.faces = cv::Mat(faces, true).reshape(1);  // K x 3 CV_32S
    return tube;
}

}  // namespace detail

/** The demo knot as a 3D mesh for cv::shading::drawMesh3d: a closed tube of radius 0.42 about a
trefoil knot, centred at the origin (3-fold symmetric about the z axis), fitting in a sphere of
radius 3.42. About `approxTriangles` triangles (exactly 10,000 for the default), each wound
counter-clockwise seen from outside, so cv::shading::CULL_BACK drops the hidden half. Colours
are the same hue running along the knot, unlit; normals are the tube's exact surface normals. */
inline Mesh3d makeDemoMesh3d(int approxTriangles = 10000)
{
    const detail::KnotTube tube = detail::makeKnotTube(approxTriangles);
    const int nverts = tube.along * tube.around;
    Mesh3d m;
    m.verts3d.create(nverts, 3, CV_32F);
    m.vcolors.create(nverts, 3, CV_32F);
    m.normals.create(nverts, 3, CV_32F);
    m.faces = tube.faces;
    for (int v = 0; v < nverts; ++v) {
        const cv::Vec3d& radial = tube.radial[static_cast<size_t>(v)];
        const cv::Vec3d p = tube.centre[static_cast<size_t>(v)] + detail::kTubeRadius * radial;
        const cv::Vec3d base = detail::palette(static_cast<double>(v / tube.around) / tube.along);
        *m.verts3d.ptr<cv::Vec3f>(v) = p;  // an L x 3 CV_32F row is one Vec3f
        *m.vcolors.ptr<cv::Vec3f>(v) = base;
        *m.normals.ptr<cv::Vec3f>(v) = radial;
    }
    return m;
}

}  // namespace shading_samples

#endif  // OPENCV_SHADING_SAMPLES_DEMO_MESH_HPP
