// This file is part of opencv_shading. License: Apache-2.0.
//
// Tests of the 3D brute-force reference itself (test/reference/shading3d_reference.hpp) on cases
// worked out by hand. The library is not called: these make sure the yardstick is straight before
// test_mesh3d_reference.cpp measures the library with it.

#include <gtest/gtest.h>

#include <opencv2/core.hpp>

#include "reference/shading3d_reference.hpp"

#include <cmath>
#include <limits>
#include <vector>

namespace {

using shading_ref3d::Matx33d;
using shading_ref3d::Scene;
using shading_ref3d::Vec3d;

double maxDiff(const Matx33d& a, const Matx33d& b) { return cv::norm(a - b, cv::NORM_INF); }

TEST(Reference3dSelf, Rodrigues)
{
    EXPECT_EQ(0, maxDiff(shading_ref3d::rodrigues(Vec3d(0, 0, 0)), Matx33d::eye()));
    // A quarter turn about z takes x to y.
    EXPECT_LT(maxDiff(shading_ref3d::rodrigues(Vec3d(0, 0, CV_PI / 2)),
                      Matx33d(0, -1, 0, 1, 0, 0, 0, 0, 1)), 1e-15);
    // A half turn about x.
    EXPECT_LT(maxDiff(shading_ref3d::rodrigues(Vec3d(CV_PI, 0, 0)),
                      Matx33d(1, 0, 0, 0, -1, 0, 0, 0, -1)), 1e-15);
    // A third of a turn about (1, 1, 1) cycles the axes: x -> y -> z -> x.
    const double a = 2 * CV_PI / 3 / std::sqrt(3.0);
    EXPECT_LT(maxDiff(shading_ref3d::rodrigues(Vec3d(a, a, a)),
                      Matx33d(0, 0, 1, 1, 0, 0, 0, 1, 0)), 1e-15);
}

// eye (0, 0, 5) looking at 0 with up +y: zc = -z, yc = -y, xc = yc x zc = +x. World +x goes
// right and +y up in the image (not mirrored); t = -R eye = (0, 0, 5).
// eye (5, 0, 0) looking at 0 with up +z: zc = -x, yc = -z, xc = (0, 0, -1) x (-1, 0, 0) = +y.
TEST(Reference3dSelf, LookAtHandFrames)
{
    Matx33d R;
    Vec3d t;
    shading_ref3d::lookAt(Vec3d(0, 0, 5), Vec3d(0, 0, 0), Vec3d(0, 1, 0), R, t);
    EXPECT_EQ(0, maxDiff(R, Matx33d(1, 0, 0, 0, -1, 0, 0, 0, -1)));
    EXPECT_EQ(Vec3d(0, 0, 5), t);
    shading_ref3d::lookAt(Vec3d(5, 0, 0), Vec3d(0, 0, 0), Vec3d(0, 0, 3), R, t);
    EXPECT_EQ(0, maxDiff(R, Matx33d(0, 1, 0, 0, 0, -1, -1, 0, 0)));
    EXPECT_EQ(Vec3d(0, 0, 5), t);
    // up need not be orthogonal to the view: only its orthogonal part counts.
    shading_ref3d::lookAt(Vec3d(0, 0, 5), Vec3d(0, 0, 0), Vec3d(0, 1, 7), R, t);
    EXPECT_LT(maxDiff(R, Matx33d(1, 0, 0, 0, -1, 0, 0, 0, -1)), 1e-15);
    EXPECT_THROW(shading_ref3d::lookAt(Vec3d(1, 1, 1), Vec3d(1, 1, 1), Vec3d(0, 1, 0), R, t),
                 cv::Exception);
    EXPECT_THROW(shading_ref3d::lookAt(Vec3d(0, 0, 5), Vec3d(0, 0, 0), Vec3d(0, 0, -1), R, t),
                 cv::Exception);
    // Projection: the world point (1, 0, 0) seen from (0, 0, 5) is right of the centre, (0, 1, 0)
    // above it.
    shading_ref3d::Camera cam;
    shading_ref3d::lookAt(Vec3d(0, 0, 5), Vec3d(0, 0, 0), Vec3d(0, 1, 0), cam.R, cam.t);
    cam.fx = cam.fy = 10;
    cam.cx = cam.cy = 50;
    EXPECT_EQ(cv::Point2d(52, 50), cam.project(cam.toCamera(Vec3d(1, 0, 0))));
    EXPECT_EQ(cv::Point2d(50, 48), cam.project(cam.toCamera(Vec3d(0, 1, 0))));
    EXPECT_EQ(Vec3d(0, 0, 5), cam.eye());
}

TEST(Reference3dSelf, Normals)
{
    // A unit square in z = 0, wound counter-clockwise seen from +z: normals +z.
    const std::vector<Vec3d> v = { { 0, 0, 0 }, { 1, 0, 0 }, { 1, 1, 0 }, { 0, 1, 0 },
                                   { 5, 5, 5 } };
    std::vector<Vec3d> fn;
    std::vector<Vec3d> vn =
        shading_ref3d::computeNormals(v, { { 0, 1, 2 }, { 0, 2, 3 } }, &fn);
    EXPECT_EQ(Vec3d(0, 0, 1), fn[0]);
    EXPECT_EQ(Vec3d(0, 0, 1), vn[0]);
    EXPECT_EQ(Vec3d(0, 0, 1), vn[3]);
    EXPECT_EQ(Vec3d(0, 0, 0), vn[4]);  // unused
    // A right-angle fold: the two unit normals +z and +x average to (1, 0, 1) / sqrt 2 on the
    // shared edge; each face counts once per corner, not by area.
    const std::vector<Vec3d> w = { { 0, 0, 0 }, { 0, 1, 0 }, { -3, 0, 0 }, { 0, 0, -1 } };
    vn = shading_ref3d::computeNormals(w, { { 0, 1, 2 }, { 0, 3, 1 } }, &fn);
    EXPECT_EQ(Vec3d(0, 0, 1), fn[0]);
    EXPECT_EQ(Vec3d(1, 0, 0), fn[1]);
    EXPECT_LT(cv::norm(vn[0] - Vec3d(1, 0, 1) / std::sqrt(2.0)), 1e-15);
    // A degenerate face has a zero normal.
    vn = shading_ref3d::computeNormals(w, { { 0, 1, 1 } }, &fn);
    EXPECT_EQ(Vec3d(0, 0, 0), fn[0]);
}

// The Phong formula on a case worked by hand: N = +z, light straight above at distance 1, eye
// on the mirror direction of a 45-degree light... kept simple: light and eye both along N.
// I = c (ka Ia + kd I) + ks I = 0.5 (0.2 + 0.7) + 0.5 = 0.95; light below the surface: ambient
// only, 0.1; light at 60 degrees (N.L = 0.5), eye along N: R.V = 2 0.5 0.5 - 0.5 = 0.5, so
// I = 0.5 (0.2 + 0.35) + 0.5 * 0.5^16.
TEST(Reference3dSelf, PhongFormula)
{
    shading_ref3d::Settings s;
    s.lights.push_back({ Vec3d(0, 0, 1), Vec3d(1, 1, 1) });
    const Vec3d P(0, 0, 0), N(0, 0, 1), c(0.5, 0.5, 0.5), E(0, 0, 3);
    EXPECT_NEAR(0.95, shading_ref3d::phong(P, N, c, E, s)[0], 1e-15);
    s.lights[0].position = Vec3d(0, 0, -1);
    EXPECT_NEAR(0.1, shading_ref3d::phong(P, N, c, E, s)[0], 1e-15);
    s.lights[0].position = Vec3d(std::sqrt(3.0), 0, 1);
    EXPECT_NEAR(0.5 * 0.55 + 0.5 * std::pow(0.5, 16), shading_ref3d::phong(P, N, c, E, s)[1],
                1e-15);
    // Zero normal: ambient only. Clamping to [0, 1].
    EXPECT_NEAR(0.1, shading_ref3d::phong(P, Vec3d(0, 0, 0), c, E, s)[2], 1e-15);
    s.lights[0] = { Vec3d(0, 0, 1), Vec3d(3, 3, 3) };
    EXPECT_EQ(1.0, shading_ref3d::phong(P, N, c, E, s)[0]);
}

// The steep floor Y = 1, Z from 1 to 8, fx = fy = 16, c = (12, 2): row v sees Z = 16 / (v - 2);
// the far edge projects to row 4, every vertex onto the 1/256 grid.
Scene floorScene(double zFrom, double zNear)
{
    Scene sc;
    sc.verts = { { -1, 1, zFrom }, { 1, 1, zFrom }, { 1, 1, 8 }, { -1, 1, 8 } };
    sc.faces = std::vector<cv::Vec3i>{ cv::Vec3i(0, 1, 2), cv::Vec3i(0, 2, 3) };
    const double c0 = (zFrom - 1) / 7;
    sc.colors = { { c0, c0, c0 }, { c0, c0, c0 }, { 1, 1, 1 }, { 1, 1, 1 } };
    sc.cam.fx = sc.cam.fy = 16;
    sc.cam.cx = 12;
    sc.cam.cy = 2;
    sc.settings.zNear = zNear;
    return sc;
}

TEST(Reference3dSelf, PerspectiveCorrectDepthAndColour)
{
    for (double zFrom : { 1.0, -5.0 }) {  // -5: clipped at zNear 0.5, same picture below row 3
        const Scene sc = floorScene(zFrom, 0.5);
        const cv::Mat canvas(20, 24, CV_32FC3, cv::Scalar::all(-1));
        const shading_ref3d::Result r = shading_ref3d::render(sc, canvas);
        for (int y = 4; y < 18; y++) {
            const double z = 16.0 / (y - 2);
            EXPECT_NEAR(z, r.depth.at<float>(y, 12), 1e-6 * z) << y;
            EXPECT_NEAR((z - 1) / 7, r.canvas.at<cv::Vec3f>(y, 12)[0], 1e-6) << y;
            // Both readings of the fragment agree here (the vertices snap exactly).
            const auto& fr = r.fragments[(size_t)y * 24 + 12];
            ASSERT_EQ(1u, fr.size());
            EXPECT_NEAR(fr[0].lo(), fr[0].hi(), 1e-12 * z);
        }
        for (int x = 0; x < 24; x++)
            for (int y = 0; y <= 3; y++)
                EXPECT_EQ(-1, r.faceIds.at<int>(y, x));  // above the far edge (row 4)
    }
}

// Clipping: a triangle with one vertex behind the camera. Its drawn part is exactly the part
// with Zc >= zNear; a fronto-parallel triangle wholly behind the plane draws nothing.
TEST(Reference3dSelf, NearPlane)
{
    Scene sc;
    sc.verts = { { -1, -1, 2 }, { 1, -1, 2 }, { -1, 1, 2 }, { 0, 0, 0.4 }, { 1, 0, 0.4 },
                 { 0, 1, 0.4 } };
    sc.faces = std::vector<cv::Vec3i>{ cv::Vec3i(3, 4, 5) };
    sc.colors.assign(6, Vec3d(1, 1, 1));
    sc.cam.fx = sc.cam.fy = 10;
    sc.cam.cx = sc.cam.cy = 10;
    sc.settings.zNear = 0.5;
    const cv::Mat canvas(20, 20, CV_32FC3, cv::Scalar::all(-1));
    EXPECT_EQ(0, cv::countNonZero(shading_ref3d::render(sc, canvas).faceIds >= 0));
    // A triangle with apex behind the camera: every drawn sample has Zc >= zNear.
    sc.verts = { { -1, 1, 2 }, { 1, 1, 2 }, { 0, 1, -3 } };
    sc.faces = std::vector<cv::Vec3i>{ cv::Vec3i(0, 1, 2) };
    const shading_ref3d::Result r = shading_ref3d::render(sc, canvas);
    int drawn = 0;
    for (int y = 0; y < 20; y++)
        for (int x = 0; x < 20; x++)
            if (r.faceIds.at<int>(y, x) >= 0) {
                drawn++;
                EXPECT_GE(r.depth.at<float>(y, x), 0.5f - 1e-6f);
            }
    EXPECT_GT(drawn, 0);
}

}  // namespace
