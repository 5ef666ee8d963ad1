// drawTexturedMesh3d by hand: perspective-correct texture coordinates on a receding floor
// (against the ray through the pixel, worked out below), a fronto-parallel face equal to the 2D
// texturedTriangles, lighting of a white texture equal to drawMesh3d's white vertex colours, and
// the same image for any thread count. The brute-force comparison is
// test_texture3d_reference.cpp.
#include "test_common.hpp"

#include <opencv2/core/utility.hpp>
#include <opencv2/shading.hpp>

#include <gtest/gtest.h>

#include <limits>
#include <vector>

namespace {

using namespace cv;
using namespace cv::shading;

//! f = 100, principal point (100, 100), camera at the origin looking along +z.
const Matx33d kK(100, 0, 100, 0, 100, 100, 0, 0, 1);
const Vec3d kZero(0, 0, 0);

/** A 101 x 101 float texture whose bilinear samples are the coordinate itself:
texel (col, row) = (col / 100, row / 100, 0.5). */
Mat rampTexture()
{
    Mat tex(101, 101, CV_32FC3);
    for (int r = 0; r < tex.rows; r++)
        for (int c = 0; c < tex.cols; c++)
            tex.at<Vec3f>(r, c) = Vec3f(c / 100.f, r / 100.f, 0.5f);
    return tex;
}

/** The floor y = 1 (camera frame, y down: below the eye) from z = 1 to z = 3, x in [-1, 1],
texture coordinate u = 50 (x + 1), v = 50 (z - 1): the ramp texture's whole range. */
struct Floor {
    std::vector<Vec3d> verts{{-1, 1, 1}, {1, 1, 1}, {-1, 1, 3}, {1, 1, 3}};
    std::vector<Vec3i> faces{{0, 1, 2}, {1, 3, 2}};
    std::vector<Point2d> uv;
    Floor()
    {
        for (const Vec3d& p : verts)
            uv.emplace_back(50 * (p[0] + 1), 50 * (p[2] - 1));
    }
};

TEST(DrawTexturedMesh3d, PerspectiveCorrectCoordinatesOnARecedingFloor)
{
    const Floor floor;
    Mat canvas(200, 200, CV_32FC3, Scalar::all(-1)), depth;
    drawTexturedMesh3d(canvas, floor.verts, floor.faces, floor.uv, rampTexture(), kK, kZero, kZero,
                       RenderSettings(), noArray(), depth);
    // The ray through pixel (x, y) is ((x - 100) / 100, (y - 100) / 100, 1) t; it meets y = 1 at
    // Z = 100 / (y - 100), X = (x - 100) / (y - 100).
    //   (100, 150): Z = 2, X = 0: u = 50, v = 50. (Affine in screen space would give v = 75:
    //               the floor spans rows 133.3 (z = 3) to 200 (z = 1).)
    //   (110, 160): Z = 5/3, X = 1/6: u = 175/3, v = 100/3.
    //   (60, 190):  Z = 10/9, X = -4/9: u = 250/9, v = 50/9.
    struct Expected {
        int x, y;
        double z, u, v;
    };
    const Expected cases[] = {{100, 150, 2.0, 50.0, 50.0},
                              {110, 160, 5.0 / 3, 175.0 / 3, 100.0 / 3},
                              {60, 190, 10.0 / 9, 250.0 / 9, 50.0 / 9}};
    for (const Expected& e : cases) {
        const Vec3f c = canvas.at<Vec3f>(e.y, e.x);
        // remap quantizes coordinates to 1/32 texel: at most 1/64 texel off, 1/6400 in colour.
        EXPECT_NEAR(c[0], e.u / 100, 1.6e-4) << e.x << "," << e.y;
        EXPECT_NEAR(c[1], e.v / 100, 1.6e-4) << e.x << "," << e.y;
        EXPECT_FLOAT_EQ(c[2], 0.5f);
        // Depth is interpolated over the snapped triangle: row 133.333 snaps to 133.332.
        EXPECT_NEAR(depth.at<float>(e.y, e.x), e.z, 1e-4);
    }
    // Above the horizon of z = 3 (row 133.3) and beside the floor nothing is drawn.
    EXPECT_EQ(canvas.at<Vec3f>(120, 100), Vec3f(-1, -1, -1));
    EXPECT_EQ(canvas.at<Vec3f>(150, 10), Vec3f(-1, -1, -1));
}

// settings.clear (shared with drawMesh3d): the textured image, depth and ids of clearing first.
TEST(DrawTexturedMesh3d, ClearEqualsClearingFirst)
{
    const Floor floor;
    for (int shade : {SHADE_FLAT, SHADE_GOURAUD, SHADE_PHONG})
        for (int vis : {VISIBILITY_ZBUFFER, VISIBILITY_PAINTER}) {
            RenderSettings s;
            s.shadeType = shade;
            s.visibility = vis;
            s.lights = {PointLight(Point3d(0, 0, 0), Vec3d(1, 1, 1))};
            s.background = Scalar(0.2, 0.4, 0.6);
            Mat expected(200, 200, CV_32FC3, s.background), expectedIds;
            Mat expectedDepth(200, 200, CV_32FC1, Scalar(std::numeric_limits<float>::infinity()));
            drawTexturedMesh3d(expected, floor.verts, floor.faces, floor.uv, rampTexture(), kK,
                               kZero, kZero, s, noArray(), expectedDepth, expectedIds);
            s.clear = true;
            Mat canvas(200, 200, CV_32FC3, Scalar::all(-1)), ids;
            Mat depth(200, 200, CV_32FC1, Scalar(0.5));  // stale: would hide the whole floor
            drawTexturedMesh3d(canvas, floor.verts, floor.faces, floor.uv, rampTexture(), kK,
                               kZero, kZero, s, noArray(), depth, ids);
            EXPECT_EQ(shading_test::maxAbsDiff(canvas, expected), 0) << shade << " " << vis;
            EXPECT_EQ(cv::norm(depth, expectedDepth, NORM_INF), 0) << shade << " " << vis;
            EXPECT_EQ(cv::norm(ids, expectedIds, NORM_INF), 0) << shade << " " << vis;
            EXPECT_EQ(canvas.at<Vec3f>(120, 100), Vec3f(0.2f, 0.4f, 0.6f));  // above the horizon
        }
}

TEST(DrawTexturedMesh3d, FrontoParallelFaceEqualsTexturedTriangles)
{
    // Every vertex at Z = 4: perspective-correct weights are the screen weights, so the 3D
    // drawing is the 2D one of the projected vertices (up to the last bit of the weights, which
    // may move a coordinate across a 1/32-texel step: at most one level at a few pixels).
    RNG rng(7);
    Mat tex(37, 53, CV_8UC3);
    rng.fill(tex, RNG::UNIFORM, 0, 256);
    for (int trial = 0; trial < 20; trial++) {
        std::vector<Vec3d> verts;
        std::vector<Point2d> projected, uv;
        for (int k = 0; k < 3; k++) {
            const Point2d p(rng.uniform(-20.0, 220.0), rng.uniform(-20.0, 220.0));
            projected.push_back(p);
            verts.emplace_back((p.x - 100) / 100 * 4, (p.y - 100) / 100 * 4, 4);
            uv.emplace_back(rng.uniform(-10.0, 60.0), rng.uniform(-10.0, 45.0));
        }
        const std::vector<Vec3i> faces{{0, 1, 2}};
        for (int interpolation : {INTER_NEAREST, INTER_LINEAR}) {
            RenderSettings s;
            s.textureInterpolation = interpolation;
            s.textureBorder = BORDER_REFLECT_101;
            Mat in3d(200, 200, CV_8UC3, Scalar::all(7)), in2d = in3d.clone();
            drawTexturedMesh3d(in3d, verts, faces, uv, tex, kK, kZero, kZero, s);
            texturedTriangles(in2d, projected, faces, uv, tex, interpolation, BORDER_REFLECT_101);
            Mat diff;
            absdiff(in3d, in2d, diff);
            diff = diff.reshape(1);
            // Nearest: a texel boundary crossed by the last bit changes the texel outright.
            const int allowed = interpolation == INTER_LINEAR ? 1 : 255;
            double maxDiff;
            minMaxLoc(diff, nullptr, &maxDiff);
            EXPECT_LE(maxDiff, allowed) << trial;
            EXPECT_LE(countNonZero(diff), 6) << trial;
        }
    }
}

TEST(DrawTexturedMesh3d, EightBitTextureOnFloatCanvasEqualsItsFloatConversion)
{
    // Read as bytes through a table, an 8-bit texture gives exactly the image of its
    // convertTo(CV_32F, 1 / 255) copy, for every shading, sampling and border.
    RNG rng(12);
    Mat tex8(29, 41, CV_8UC3), tex32;
    rng.fill(tex8, RNG::UNIFORM, 0, 256);
    tex8.convertTo(tex32, CV_32F, 1 / 255.0);
    const Floor floor;
    std::vector<Point2d> uv;
    for (size_t i = 0; i < floor.verts.size(); i++)
        uv.emplace_back(rng.uniform(-60.0, 100.0), rng.uniform(-60.0, 100.0));
    for (int shade : {SHADE_FLAT, SHADE_GOURAUD, SHADE_PHONG})
        for (int interpolation : {INTER_NEAREST, INTER_LINEAR})
            for (int border :
                 {BORDER_CONSTANT, BORDER_REPLICATE, BORDER_WRAP, BORDER_REFLECT_101}) {
                RenderSettings s;
                s.shadeType = shade;
                s.textureInterpolation = interpolation;
                s.textureBorder = border;
                s.lights = {PointLight(Point3d(0, -1, 2), Vec3d(0.6, 0.5, 0.4))};
                Mat a(200, 200, CV_32FC3, Scalar::all(0.5)), b = a.clone();
                drawTexturedMesh3d(a, floor.verts, floor.faces, uv, tex8, kK, kZero, kZero, s);
                drawTexturedMesh3d(b, floor.verts, floor.faces, uv, tex32, kK, kZero, kZero, s);
                EXPECT_EQ(norm(a, b, NORM_INF), 0)
                    << "shade " << shade << " interp " << interpolation << " border " << border;
                EXPECT_GT(norm(a, Mat(200, 200, CV_32FC3, Scalar::all(0.5)), NORM_INF), 0);
            }
}

TEST(DrawTexturedMesh3d, WhiteTextureLitEqualsWhiteVertexColours)
{
    // I = c D + S with c = 1: textured and vertex-coloured lighting agree wherever nothing
    // clamps, which dim lights ensure (D + S < 1 everywhere here).
    const Floor floor;
    const std::vector<Vec3d> white(4, Vec3d(1, 1, 1));
    const Mat tex(4, 4, CV_32FC3, Scalar::all(1));
    RenderSettings s;
    s.lights = {PointLight(Point3d(0, -1, 2), Vec3d(0.3, 0.2, 0.1)),
                PointLight(Point3d(1, 0, 1), Vec3d(0.1, 0.2, 0.3))};
    s.ks = 0.2;
    for (int shade : {SHADE_FLAT, SHADE_GOURAUD, SHADE_PHONG})
        for (int visibility : {VISIBILITY_ZBUFFER, VISIBILITY_PAINTER}) {
            s.shadeType = shade, s.visibility = visibility;
            Mat colored(200, 200, CV_32FC3, Scalar::all(-1)), textured = colored.clone();
            drawMesh3d(colored, floor.verts, floor.faces, white, kK, kZero, kZero, s);
            drawTexturedMesh3d(textured, floor.verts, floor.faces, floor.uv, tex, kK, kZero,
                               kZero, s);
            EXPECT_LT(norm(colored, textured, NORM_INF), 2e-6) << shade << " " << visibility;
            double maxLit;
            minMaxLoc(colored.reshape(1), nullptr, &maxLit);
            EXPECT_LT(maxLit, 0.95);  // nothing clamped
            EXPECT_GT(maxLit, 0.3);   // and something lit
        }
}

TEST(DrawTexturedMesh3d, SameImageForAnyThreadCount)
{
    RNG rng(11);
    std::vector<Vec3d> verts;
    std::vector<Point2d> uv;
    std::vector<Vec3i> faces;
    for (int f = 0; f < 400; f++) {
        for (int k = 0; k < 3; k++) {
            verts.emplace_back(rng.uniform(-2.0, 2.0), rng.uniform(-2.0, 2.0),
                               rng.uniform(2.0, 6.0));
            uv.emplace_back(rng.uniform(0.0, 100.0), rng.uniform(0.0, 100.0));
        }
        faces.emplace_back(3 * f, 3 * f + 1, 3 * f + 2);
    }
    RenderSettings s;
    s.lights = {PointLight(Point3d(0, -3, 0), Vec3d(1, 1, 1))};
    const Mat tex = rampTexture();
    const int threads = getNumThreads();
    for (int shade : {SHADE_FLAT, SHADE_GOURAUD, SHADE_PHONG})
        for (int visibility : {VISIBILITY_ZBUFFER, VISIBILITY_PAINTER}) {
            s.shadeType = shade, s.visibility = visibility;
            Mat images[4];
            const int counts[4] = {1, 2, 8, -2};  // -2: 2 threads, every band drawn in parts
            for (int i = 0; i < 4; i++) {
                setNumThreads(std::abs(counts[i]));
                shading_test::SplitBands parts(counts[i] < 0);
                images[i] = Mat(300, 300, CV_8UC3, Scalar::all(0));
                drawTexturedMesh3d(images[i], verts, faces, uv, tex, kK, kZero, kZero, s);
            }
            for (int i = 1; i < 4; i++)
                EXPECT_EQ(norm(images[0], images[i], NORM_INF), 0) << counts[i];
        }
    setNumThreads(threads);
}

}  // namespace
