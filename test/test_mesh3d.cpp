// Hand-worked cases for every convention of drawMesh3d, computeNormals and lookAt (see the
// header's "3D meshes" section), the unlit 3D == 2D identity, compositing, determinism and every
// bad argument. The comparison with the brute-force 3D reference is test_mesh3d_reference.cpp.
#include "test_common.hpp"

#include <opencv2/calib3d.hpp>
#include <opencv2/shading.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <string>
#include <vector>

namespace {

using namespace cv;
using namespace cv::shading;

const Matx33d kIdentityR = Matx33d::eye();

//! A camera at the origin looking along +z (rvec = tvec = 0), focal f, principal point c.
struct Cam {
    Matx33d K;
    Vec3d rvec{0, 0, 0}, tvec{0, 0, 0};
    explicit Cam(double f = 100, double cx = 100, double cy = 100) : K(f, 0, cx, 0, f, cy, 0, 0, 1) {}
};

Mat draw(const std::vector<Vec3d>& verts, const std::vector<Vec3i>& faces,
         const std::vector<Vec3d>& colors, const Cam& cam, const RenderSettings& s,
         Mat* depth = nullptr, Mat* ids = nullptr, Size size = Size(200, 200), int type = CV_32FC3)
{
    Mat canvas = shading_test::sentinelCanvas(size, type);
    Mat d, i;
    drawMesh3d(canvas, verts, faces, colors, cam.K, cam.rvec, cam.tvec, s, noArray(), d, i);
    if (depth)
        *depth = d;
    if (ids)
        *ids = i;
    return canvas;
}

Matx33d rotationOf(const Mat& rvec)
{
    Mat R;
    Rodrigues(rvec, R);
    return Matx33d(R);
}

TEST(LookAt, EyeOnPlusZLooksDownMinusZWithoutMirroring)
{
    Mat rvec, tvec;
    lookAt(Point3d(0, 0, 5), Point3d(0, 0, 0), Vec3d(0, 1, 0), rvec, tvec);
    // zc = (0,0,-1), yc = -(up) = (0,-1,0), xc = yc x zc = (1,0,0).
    EXPECT_LT(norm(rotationOf(rvec), Matx33d(1, 0, 0, 0, -1, 0, 0, 0, -1), NORM_INF), 1e-12);
    EXPECT_LT(norm(Vec3d(tvec), Vec3d(0, 0, 5), NORM_INF), 1e-12);
    // World +x lands right of the principal point, world +y above it.
    const Cam cam(100, 100, 100);
    std::vector<Point3d> pts = {{1, 0, 0}, {0, 1, 0}};
    std::vector<Point2d> img;
    projectPoints(pts, rvec, tvec, cam.K, noArray(), img);
    EXPECT_NEAR(img[0].x, 120, 1e-9);
    EXPECT_NEAR(img[0].y, 100, 1e-9);
    EXPECT_NEAR(img[1].x, 100, 1e-9);
    EXPECT_NEAR(img[1].y, 80, 1e-9);
}

TEST(LookAt, SideViewWithZUp)
{
    Mat rvec, tvec;
    // Eye on +x looking at the origin, z up: zc = (-1,0,0), yc = (0,0,-1), xc = yc x zc = (0,1,0).
    lookAt(Point3d(4, 0, 0), Point3d(0, 0, 0), Vec3d(0, 0, 2), rvec, tvec);
    EXPECT_LT(norm(rotationOf(rvec), Matx33d(0, 1, 0, 0, 0, -1, -1, 0, 0), NORM_INF), 1e-12);
    EXPECT_LT(norm(Vec3d(tvec), Vec3d(0, 0, 4), NORM_INF), 1e-12);
    // An up vector not orthogonal to the view is projected first.
    Mat rvec2, tvec2;
    lookAt(Point3d(4, 0, 0), Point3d(0, 0, 0), Vec3d(1, 0, 2), rvec2, tvec2);
    EXPECT_LT(norm(rvec, rvec2, NORM_INF), 1e-12);
}

TEST(LookAt, RejectsDegenerateFrames)
{
    Mat r, t;
    EXPECT_THROW(lookAt(Point3d(1, 2, 3), Point3d(1, 2, 3), Vec3d(0, 1, 0), r, t), cv::Exception);
    EXPECT_THROW(lookAt(Point3d(0, 0, 5), Point3d(0, 0, 0), Vec3d(0, 0, 1), r, t), cv::Exception);
    EXPECT_THROW(lookAt(Point3d(0, 0, 5), Point3d(0, 0, 0), Vec3d(0, 0, 0), r, t), cv::Exception);
    EXPECT_THROW(lookAt(Point3d(0, 0, NAN), Point3d(0, 0, 0), Vec3d(0, 1, 0), r, t),
                 cv::Exception);
}

TEST(ComputeNormals, FaceAndVertexNormalsByHand)
{
    // Two faces meeting at a ridge: normals (0,0,1) and (0,1,0); a degenerate face; vertex 5
    // unused.
    const std::vector<Vec3d> v = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 0, -1}, {2, 0, 0}, {9, 9, 9}};
    const std::vector<Vec3i> f = {{0, 1, 2}, {0, 1, 3}, {0, 1, 4}};
    Mat vn, fn;
    computeNormals(v, f, vn, fn);
    ASSERT_EQ(vn.type(), CV_32FC1);
    ASSERT_EQ(vn.rows, 6);
    ASSERT_EQ(fn.rows, 3);
    EXPECT_LT(norm(fn.row(0), Mat(Matx13f(0, 0, 1)), NORM_INF), 1e-7);
    EXPECT_LT(norm(fn.row(1), Mat(Matx13f(0, 1, 0)), NORM_INF), 1e-7);
    EXPECT_EQ(countNonZero(fn.row(2)), 0);  // (1,0,0) x (2,0,0) = 0
    const float h = float(std::sqrt(0.5));
    EXPECT_LT(norm(vn.row(0), Mat(Matx13f(0, h, h)), NORM_INF), 1e-7);  // both faces
    EXPECT_LT(norm(vn.row(2), Mat(Matx13f(0, 0, 1)), NORM_INF), 1e-7);
    EXPECT_LT(norm(vn.row(3), Mat(Matx13f(0, 1, 0)), NORM_INF), 1e-7);
    EXPECT_EQ(countNonZero(vn.row(4)), 0);  // only the degenerate face
    EXPECT_EQ(countNonZero(vn.row(5)), 0);  // unused
}

//! A random mesh in front of the camera: vertices with Zc in [2, 8] inside the view.
void randomMesh(std::mt19937& rng, int vertexCount, int faceCount, std::vector<Vec3d>& v,
                std::vector<Vec3i>& f, std::vector<Vec3d>& c, bool equalDepth = false)
{
    std::uniform_real_distribution<double> u(-1, 1), z(2, 8), col(0, 1);
    std::uniform_int_distribution<int> pick(0, vertexCount - 1);
    v.clear(), f.clear(), c.clear();
    for (int i = 0; i < vertexCount; i++) {
        const double d = equalDepth ? 4.0 : z(rng);
        v.emplace_back(u(rng) * d, u(rng) * d, d);
        c.emplace_back(col(rng), col(rng), col(rng));
    }
    for (int i = 0; i < faceCount; i++)
        f.emplace_back(pick(rng), pick(rng), pick(rng));
}

TEST(DrawMesh3d, UnlitEqualsDrawMeshOfProjectPoints)
{
    std::mt19937 rng(7);
    const Cam cam(90.5, 99.25, 101.75);
    for (int round = 0; round < 20; round++) {
        std::vector<Vec3d> v, c;
        std::vector<Vec3i> f;
        randomMesh(rng, 40, 60, v, f, c);
        std::vector<Point2d> projected;
        projectPoints(v, cam.rvec, cam.tvec, cam.K, noArray(), projected);
        std::vector<double> depth;
        for (const Vec3d& p : v)
            depth.push_back(p[2]);
        for (int type : {CV_32FC3, CV_8UC3}) {
            // Painter's order by mean Zc is drawMesh's order by mean depth: the same image.
            RenderSettings s;
            s.shadeType = SHADE_FLAT;
            s.visibility = VISIBILITY_PAINTER;
            const Mat got = draw(v, f, c, cam, s, nullptr, nullptr, Size(200, 200), type);
            Mat expected = shading_test::sentinelCanvas(Size(200, 200), type);
            drawMesh(expected, projected, f, c, depth, SHADE_FLAT);
            ASSERT_EQ(shading_test::maxAbsDiff(got, expected), 0) << "round " << round;
        }
    }
}

TEST(DrawMesh3d, UnlitGouraudEqualsDrawMeshWhereDepthIsEqual)
{
    std::mt19937 rng(11);
    const Cam cam;
    std::vector<Vec3d> v, c;
    std::vector<Vec3i> f;
    randomMesh(rng, 30, 50, v, f, c, true);  // every vertex at Zc = 4
    std::vector<Point2d> projected;
    projectPoints(v, cam.rvec, cam.tvec, cam.K, noArray(), projected);
    RenderSettings s;
    s.visibility = VISIBILITY_ZBUFFER;  // all depths equal: the first face wins everywhere
    Mat ids;
    const Mat got = draw(v, f, c, cam, s, nullptr, &ids);
    // drawMesh in face order paints the last face on top: reverse the faces.
    const std::vector<Vec3i> reversed(f.rbegin(), f.rend());
    Mat expected = shading_test::sentinelCanvas(Size(200, 200));
    drawMesh(expected, projected, reversed, c, noArray(), SHADE_GOURAUD);
    const Mat blank = shading_test::sentinelCanvas(Size(200, 200));
    EXPECT_EQ(countNonZero(shading_test::writtenMask(got, blank) !=
                           shading_test::writtenMask(expected, blank)), 0);
    EXPECT_LT(shading_test::maxAbsDiff(got, expected), 2e-6);
}

TEST(DrawMesh3d, DepthIsCameraZ)
{
    const Cam cam;
    const std::vector<Vec3d> v = {{-1, -1, 5}, {2, -1, 5}, {-1, 2, 5}};
    const std::vector<Vec3d> c(3, Vec3d(0.5, 0.5, 0.5));
    Mat depth, ids;
    draw(v, {Vec3i(0, 1, 2)}, c, cam, RenderSettings(), &depth, &ids);
    ASSERT_EQ(depth.type(), CV_32FC1);
    ASSERT_EQ(ids.type(), CV_32SC1);
    int covered = 0;
    for (int y = 0; y < 200; y++)
        for (int x = 0; x < 200; x++) {
            if (ids.at<int>(y, x) == 0) {
                EXPECT_EQ(depth.at<float>(y, x), 5.0f);
                covered++;
            } else {
                EXPECT_EQ(ids.at<int>(y, x), -1);
                EXPECT_EQ(depth.at<float>(y, x), std::numeric_limits<float>::infinity());
            }
        }
    // Image: (80,80), (140,80), (80,140): half of 60 x 60.
    EXPECT_NEAR(covered, 1800, 70);
}

// The outputs a call creates are filled everywhere (depth +inf, ids -1), in both visibilities,
// and an ids image passed in is overwritten even where nothing is drawn.
TEST(DrawMesh3d, CreatedOutputsAreFilledEverywhere)
{
    const Cam cam;
    const std::vector<Vec3d> v = {{-1, -1, 5}, {2, -1, 5}, {-1, 2, 5}};
    const std::vector<Vec3d> c(3, Vec3d(0.5, 0.5, 0.5));
    for (int vis : {VISIBILITY_ZBUFFER, VISIBILITY_PAINTER}) {
        RenderSettings s;
        s.visibility = vis;
        Mat canvas = shading_test::sentinelCanvas(Size(150, 300)), depth;
        Mat ids(300, 150, CV_32SC1, Scalar(7));  // stale content, right size and type
        const std::vector<Vec3i> f = {Vec3i(0, 1, 2)};
        drawMesh3d(canvas, v, f, c, cam.K, cam.rvec, cam.tvec, s, noArray(), depth, ids);
        int covered = 0;
        for (int y = 0; y < 300; y++)
            for (int x = 0; x < 150; x++) {
                const int id = ids.at<int>(y, x);
                ASSERT_TRUE(id == 0 || id == -1) << vis << " " << x << "," << y;
                ASSERT_EQ(depth.at<float>(y, x),
                          id == 0 ? 5.0f : std::numeric_limits<float>::infinity());
                covered += id == 0;
            }
        EXPECT_NEAR(covered, 1800, 70) << vis;  // as DepthIsCameraZ: the same triangle
    }
}

TEST(DrawMesh3d, PerspectiveCorrectNotAffine)
{
    // A floor triangle y = 1 receding from Zc = 2 (A, B) to 8 (C); C alone is red. On the floor
    // the 3D weight of C is (Zc - 2) / 6, and row v sees Zc = 100 / (v - 100). The vertices
    // project onto the 1/256 grid (rows 150 and 112.5), so snapping moves nothing.
    const Cam cam;
    const std::vector<Vec3d> v = {{-2, 1, 2}, {2, 1, 2}, {0, 1, 8}};
    const std::vector<Vec3d> c = {{0, 0, 0}, {0, 0, 0}, {1, 0, 0}};
    Mat depth;
    const Mat img = draw(v, {Vec3i(0, 1, 2)}, c, cam, RenderSettings(), &depth);
    for (int row : {120, 125, 140}) {
        const double z = 100.0 / (row - 100);
        const double perspective = (z - 2) / 6;
        const double affine = (150.0 - row) / (150.0 - 112.5);  // screen weight of C
        EXPECT_NEAR(depth.at<float>(row, 100), z, 1e-6 * z);
        EXPECT_NEAR(img.at<Vec3f>(row, 100)[0], perspective, 1e-6) << "row " << row;
        EXPECT_GT(std::abs(affine - perspective), 0.1);
    }
}

TEST(DrawMesh3d, NearPlaneClipsToTheHandWorkedPolygon)
{
    // A floor triangle from Zc = 1 to Zc = -1 (through the camera plane), zNear = 0.5: the part
    // Zc >= 0.5 is the quad (-1,.5,1), (1,.5,1), (.75,.5,.5), (-.75,.5,.5), which projects (f 100,
    // c 100) to (0,150), (200,150), (250,200), (-50,200).
    const Cam cam;
    const std::vector<Vec3d> v = {{-1, 0.5, 1}, {1, 0.5, 1}, {0, 0.5, -1}};
    const std::vector<Vec3d> c(3, Vec3d(0.25, 0.5, 0.75));
    RenderSettings s;
    s.zNear = 0.5;
    s.shadeType = SHADE_FLAT;
    Mat depth, ids;
    const Size size(200, 260);
    draw(v, {Vec3i(0, 1, 2)}, c, cam, s, &depth, &ids, size);
    Mat expected = shading_test::sentinelCanvas(size), before = expected.clone();
    const std::vector<Vec3d> col(3, Vec3d(1, 1, 1));
    flats(expected, std::vector<Point2d>{{0, 150}, {200, 150}, {250, 200}}, col);
    flats(expected, std::vector<Point2d>{{0, 150}, {250, 200}, {-50, 200}}, col);
    const Mat expectedMask = shading_test::writtenMask(expected, before);
    Mat gotMask = ids >= 0;
    EXPECT_EQ(countNonZero(expectedMask != gotMask), 0);
    EXPECT_GT(countNonZero(gotMask), 9000);
    double minDepth;
    minMaxLoc(depth, &minDepth);
    EXPECT_GE(minDepth, 0.5 * (1 - 1e-6));

    // Wholly behind the near plane: nothing is drawn, the depth buffer is left alone.
    const std::vector<Vec3d> behind = {{-1, 0.5, 0.4}, {1, 0.5, 0.4}, {0, 0.5, -1}};
    Mat depth2, ids2;
    draw(behind, {Vec3i(0, 1, 2)}, c, cam, s, &depth2, &ids2, size);
    EXPECT_EQ(countNonZero(ids2 >= 0), 0);
}

TEST(DrawMesh3d, CullingSigns)
{
    Mat rvec, tvec;
    lookAt(Point3d(0, 0, 5), Point3d(0, 0, 0), Vec3d(0, 1, 0), rvec, tvec);
    Cam cam;
    cam.rvec = Vec3d(rvec);
    cam.tvec = Vec3d(tvec);
    // n = (v1 - v0) x (v2 - v0) = (0,0,1) faces the eye at (0,0,5): front-facing.
    const std::vector<Vec3d> v = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    const std::vector<Vec3d> c(3, Vec3d(1, 0, 0));
    const std::vector<Vec3i> front = {{0, 1, 2}}, back = {{0, 2, 1}};
    auto drawn = [&](const std::vector<Vec3i>& f, int cull) {
        RenderSettings s;
        s.cullMode = cull;
        Mat ids;
        draw(v, f, c, cam, s, nullptr, &ids);
        return countNonZero(ids >= 0);
    };
    EXPECT_GT(drawn(front, CULL_NONE), 100);
    EXPECT_GT(drawn(front, CULL_BACK), 100);
    EXPECT_EQ(drawn(front, CULL_FRONT), 0);
    EXPECT_EQ(drawn(back, CULL_BACK), 0);
    EXPECT_GT(drawn(back, CULL_FRONT), 100);
    EXPECT_GT(drawn(back, CULL_NONE), 100);
}

TEST(DrawMesh3d, TiesZBufferFirstFacePainterLastFace)
{
    const Cam cam;
    const std::vector<Vec3d> v = {{-1, -1, 3}, {1, -1, 3}, {0, 1, 3}};
    const std::vector<Vec3d> c(3, Vec3d(0.5, 0.5, 0.5));
    const std::vector<Vec3i> f = {{0, 1, 2}, {1, 2, 0}, {2, 0, 1}};
    RenderSettings s;
    Mat ids;
    draw(v, f, c, cam, s, nullptr, &ids);
    EXPECT_GT(countNonZero(ids == 0), 500);
    EXPECT_EQ(countNonZero(ids > 0), 0);
    s.visibility = VISIBILITY_PAINTER;  // ties keep face order: the last is painted on top
    draw(v, f, c, cam, s, nullptr, &ids);
    EXPECT_GT(countNonZero(ids == 2), 500);
    EXPECT_EQ(countNonZero((ids == 0) | (ids == 1)), 0);
}

TEST(DrawMesh3d, PainterOrderIsByMeanDepthNotPerSample)
{
    // Two crossing faces: B's mean depth (4.5) is larger than A's (4) but B is nearer on its
    // left. The z-buffer shows the nearer one per sample; the painter's shows A wherever they
    // overlap, and its depth.
    const Cam cam;
    const std::vector<Vec3d> v = {{-1, -1, 4}, {1, -1, 4}, {0, 1, 4},       // A at Zc 4
                                  {-1, -1, 3}, {1, -1, 6}, {0, 1, 4.5}};    // B: mean 4.5
    const std::vector<Vec3d> c(6, Vec3d(0.5, 0.5, 0.5));
    const std::vector<Vec3i> f = {{0, 1, 2}, {3, 4, 5}};
    Mat depthA, depthB, idsA, idsB;
    draw(v, {f[0]}, c, cam, RenderSettings(), &depthA, &idsA);
    draw(v, {f[1]}, c, cam, RenderSettings(), &depthB, &idsB);
    RenderSettings s;
    Mat ids, depth, idsP, depthP;
    draw(v, f, c, cam, s, &depth, &ids);
    s.visibility = VISIBILITY_PAINTER;
    draw(v, f, c, cam, s, &depthP, &idsP);
    int bNearer = 0, aNearer = 0;
    for (int y = 0; y < 200; y++)
        for (int x = 0; x < 200; x++) {
            if (idsA.at<int>(y, x) < 0 || idsB.at<int>(y, x) < 0)
                continue;
            const float a = depthA.at<float>(y, x), b = depthB.at<float>(y, x);
            if (a == b)
                continue;
            (b < a ? bNearer : aNearer)++;
            EXPECT_EQ(ids.at<int>(y, x), b < a ? 1 : 0);
            EXPECT_EQ(depth.at<float>(y, x), std::min(a, b));
            EXPECT_EQ(idsP.at<int>(y, x), 0);
            EXPECT_EQ(depthP.at<float>(y, x), a);
        }
    EXPECT_GT(bNearer, 50);
    EXPECT_GT(aNearer, 50);
}

TEST(DrawMesh3d, FlatLightingByHand)
{
    // Face normal (0,0,1), centroid at the origin, eye and light on +z: N.L = R.V = 1, so
    // I = c (ka Ia + kd I_l) + ks I_l.
    Mat rvec, tvec;
    lookAt(Point3d(0, 0, 5), Point3d(0, 0, 0), Vec3d(0, 1, 0), rvec, tvec);
    Cam cam;
    cam.rvec = Vec3d(rvec);
    cam.tvec = Vec3d(tvec);
    const std::vector<Vec3d> v = {{-1, -1, 0}, {1, -1, 0}, {0, 2, 0}};
    RenderSettings s;
    s.shadeType = SHADE_FLAT;
    s.lights = {PointLight(Point3d(0, 0, 5), Vec3d(1, 0.5, 0.25))};
    s.ambient = Vec3d(1, 1, 1);
    s.ka = 0.2, s.kd = 0.7, s.ks = 0.5, s.shininess = 7;
    const Vec3d expected(0.5 * (0.2 + 0.7) + 0.5, 0.2 * (0.2 + 0.35) + 0.25,
                         0.1 * (0.2 + 0.175) + 0.125);
    // Vertex colours whose mean is (0.5, 0.2, 0.1).
    const std::vector<Vec3d> c = {{0.4, 0.1, 0.1}, {0.6, 0.3, 0.0}, {0.5, 0.2, 0.2}};
    const Mat img = draw(v, {Vec3i(0, 1, 2)}, c, cam, s);
    const Vec3f px = img.at<Vec3f>(100, 100);
    for (int k = 0; k < 3; k++)
        EXPECT_NEAR(px[k], expected[k], 1e-6);
    // 8-bit: the same on c / 255, times 255, rounded.
    std::vector<Vec3d> c8;
    for (const Vec3d& x : c)
        c8.push_back(x * 255.0);
    const Mat img8 = draw(v, {Vec3i(0, 1, 2)}, c8, cam, s, nullptr, nullptr, Size(200, 200),
                          CV_8UC3);
    for (int k = 0; k < 3; k++)
        EXPECT_EQ(img8.at<Vec3b>(100, 100)[k], cvRound(expected[k] * 255));
    // Clamped to [0, 1]: a strong highlight saturates.
    s.ks = 2;
    EXPECT_EQ(draw(v, {Vec3i(0, 1, 2)}, c, cam, s).at<Vec3f>(100, 100)[0], 1.0f);
    // Light behind the face: ambient only (no specular either).
    s.lights[0].position = Point3d(0, 0, -5);
    const Vec3f dark = draw(v, {Vec3i(0, 1, 2)}, c, cam, s).at<Vec3f>(100, 100);
    EXPECT_NEAR(dark[0], 0.5 * 0.2, 1e-6);
    EXPECT_NEAR(dark[2], 0.1 * 0.2, 1e-6);
}

TEST(DrawMesh3d, PhongZeroNormalGetsAmbientOnly)
{
    const Cam cam;
    const std::vector<Vec3d> v = {{-1, -1, 4}, {1, -1, 4}, {0, 1, 4}};
    const std::vector<Vec3d> c(3, Vec3d(0.5, 0.5, 0.5));
    const std::vector<Vec3d> zero(3, Vec3d(0, 0, 0));
    RenderSettings s;
    s.shadeType = SHADE_PHONG;
    s.lights = {PointLight(Point3d(0, 0, 0), Vec3d(1, 1, 1))};
    Mat canvas = shading_test::sentinelCanvas(Size(200, 200));
    drawMesh3d(canvas, v, std::vector<Vec3i>{{0, 1, 2}}, c, cam.K, cam.rvec, cam.tvec, s, zero);
    EXPECT_NEAR(canvas.at<Vec3f>(100, 100)[1], 0.5 * s.ka, 1e-6);
}

TEST(DrawMesh3d, TwoMeshesCompositeThroughOneDepthBuffer)
{
    std::mt19937 rng(3);
    const Cam cam;
    std::vector<Vec3d> v1, c1, v2, c2;
    std::vector<Vec3i> f1, f2;
    randomMesh(rng, 30, 40, v1, f1, c1);
    randomMesh(rng, 30, 40, v2, f2, c2);
    RenderSettings s;
    s.shadeType = SHADE_PHONG;
    s.lights = {PointLight(Point3d(1, -2, 0), Vec3d(1, 0.8, 0.6))};
    // Both at once...
    std::vector<Vec3d> v = v1, c = c1;
    v.insert(v.end(), v2.begin(), v2.end());
    c.insert(c.end(), c2.begin(), c2.end());
    std::vector<Vec3i> f = f1;
    for (const Vec3i& x : f2)
        f.push_back(x + Vec3i(30, 30, 30));
    std::vector<Vec3d> n1, n2, n;  // normals of the combined mesh, split per call
    Mat nm;
    computeNormals(v, f, nm);
    for (int i = 0; i < 60; i++)
        (i < 30 ? n1 : n2).push_back(Vec3d(nm.at<Vec3f>(i)));
    Mat once = shading_test::sentinelCanvas(Size(200, 200)), depthOnce;
    drawMesh3d(once, v, f, c, cam.K, cam.rvec, cam.tvec, s, nm, depthOnce);
    // ... or in two calls sharing the depth buffer.
    Mat twice = shading_test::sentinelCanvas(Size(200, 200)), depth;
    drawMesh3d(twice, v1, f1, c1, cam.K, cam.rvec, cam.tvec, s, n1, depth);
    drawMesh3d(twice, v2, f2, c2, cam.K, cam.rvec, cam.tvec, s, n2, depth);
    EXPECT_EQ(shading_test::maxAbsDiff(once, twice), 0);
    EXPECT_EQ(cv::norm(depthOnce, depth, NORM_INF), 0);
}

TEST(DrawMesh3d, SameImageForAnyThreadCount)
{
    std::mt19937 rng(5);
    const Cam cam(150, 128, 128);
    std::vector<Vec3d> v, c;
    std::vector<Vec3i> f;
    randomMesh(rng, 1000, 1500, v, f, c);
    const int threads = getNumThreads();
    for (int shade : {SHADE_FLAT, SHADE_GOURAUD, SHADE_PHONG})
        for (int vis : {VISIBILITY_ZBUFFER, VISIBILITY_PAINTER}) {
            RenderSettings s;
            s.shadeType = shade;
            s.visibility = vis;
            s.lights = {PointLight(Point3d(0, -3, 0), Vec3d(1, 1, 1))};
            Mat first, firstDepth, firstIds;
            for (int n : {1, 2, 8, -2}) {  // -2: 2 threads, every band drawn in parts
                setNumThreads(std::abs(n));
                shading_test::SplitBands parts(n < 0);
                Mat depth, ids;
                const Mat img = draw(v, f, c, cam, s, &depth, &ids, Size(256, 256));
                if (first.empty()) {
                    first = img, firstDepth = depth, firstIds = ids;
                    continue;
                }
                EXPECT_EQ(shading_test::maxAbsDiff(img, first), 0) << shade << vis << n;
                EXPECT_EQ(cv::norm(depth, firstDepth, NORM_INF), 0);
                EXPECT_EQ(cv::norm(ids, firstIds, NORM_INF), 0);
            }
        }
    setNumThreads(threads);
}

// Flat faces in painter's order with no depth or id output are drawn by the 2D flat shader, set
// to each face's colour (the engine's sample blocks then serve them); with an id output they are
// drawn by the 3D surface shader, which computes each sample's depth. A closed sphere of tiny
// faces, its back faces kept (the closed-surface bands, faces of up to 8 x 8 samples), and a
// heightfield of faces within 4 x 4 samples (the tiny-face blocks): the same image either way,
// lit and unlit, float and 8-bit, at any thread count.
TEST(DrawMesh3d, PainterFlatColourOnlyEqualsTheSurfaceShader)
{
    std::vector<Vec3d> sphereV, sphereC;
    std::vector<Vec3i> sphereF;
    const int rings = 60, segments = 120;
    for (int i = 0; i <= rings; i++)
        for (int j = 0; j < segments; j++) {
            const double th = CV_PI * i / rings, ph = 2 * CV_PI * j / segments;
            sphereV.push_back(Vec3d(std::sin(th) * std::cos(ph), std::cos(th),
                                    2.6 + std::sin(th) * std::sin(ph)));
            sphereC.push_back(Vec3d(0.5 + 0.5 * std::cos(3 * ph), double(i) / rings, 0.3));
        }
    for (int i = 0; i < rings; i++)
        for (int j = 0; j < segments; j++) {
            const int a = i * segments + j, b = i * segments + (j + 1) % segments;
            sphereF.push_back(Vec3i(a, b, a + segments));
            sphereF.push_back(Vec3i(b, b + segments, a + segments));
        }
    std::vector<Vec3d> fieldV, fieldC;
    std::vector<Vec3i> fieldF;
    const int n = 100;
    for (int i = 0; i <= n; i++)
        for (int j = 0; j <= n; j++) {
            const double x = 2.0 * j / n - 1, y = 2.0 * i / n - 1;
            const double z = 2.2 + 0.2 * std::sin(5 * x) * std::cos(4 * y);
            fieldV.push_back(Vec3d(1.2 * x, 1.2 * y, z));
            fieldC.push_back(Vec3d(double(j) / n, double(i) / n, 0.7));
        }
    for (int i = 0; i < n; i++)
        for (int j = 0; j < n; j++) {
            const int a = i * (n + 1) + j;
            fieldF.push_back(Vec3i(a, a + 1, a + n + 2));
            fieldF.push_back(Vec3i(a, a + n + 2, a + n + 1));
        }
    const Cam cam(220, 128, 128);
    const int threads = getNumThreads();
    for (int mesh = 0; mesh < 2; mesh++)
        for (int type : {CV_32FC3, CV_8UC3})
            for (bool lit : {false, true})
                for (int t : {1, 2}) {
                    setNumThreads(t);
                    const std::vector<Vec3d>& v = mesh ? fieldV : sphereV;
                    std::vector<Vec3d> c = mesh ? fieldC : sphereC;
                    if (type == CV_8UC3)
                        for (Vec3d& colour : c)
                            colour *= 255;
                    RenderSettings s;
                    s.shadeType = SHADE_FLAT;
                    s.visibility = VISIBILITY_PAINTER;
                    if (lit)
                        s.lights = {PointLight(Point3d(2, -3, 0), Vec3d(1, 0.9, 0.8))};
                    const std::string what =
                        format("mesh %d, type %d, lit %d, %d threads", mesh, type, int(lit), t);
                    Mat colourOnly = shading_test::sentinelCanvas(Size(256, 256), type);
                    Mat withIds = colourOnly.clone(), ids;
                    drawMesh3d(colourOnly, v, mesh ? fieldF : sphereF, c, cam.K, cam.rvec,
                               cam.tvec, s);
                    drawMesh3d(withIds, v, mesh ? fieldF : sphereF, c, cam.K, cam.rvec, cam.tvec,
                               s, noArray(), noArray(), ids);
                    EXPECT_EQ(shading_test::maxAbsDiff(colourOnly, withIds), 0) << what;
                    // Teeth: many samples and faces drawn (the sphere shows about a third of its faces).
                    const int drawn = countNonZero(ids >= 0);
                    EXPECT_GT(drawn, mesh ? 35000 : 10000) << what;
                    std::vector<int> idList(ids.begin<int>(), ids.end<int>());
                    std::sort(idList.begin(), idList.end());
                    const long distinct =
                        std::unique(idList.begin(), idList.end()) - idList.begin();
                    EXPECT_GT(distinct, mesh ? 15000 : 2500) << what;
                }
    setNumThreads(threads);
}

// Vertices, colours and normals given as continuous CV_32F, and faces as continuous CV_32S, are
// read where the caller keeps them; other forms are converted. Every form of the same values
// must draw the same image, depth and ids, through every pass that reads them: lighting (flat,
// per vertex, per sample), normals computed when none are given, culling and near clipping.
TEST(DrawMesh3d, InputFormsAgree)
{
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> u(-1, 1), z(2, 8), unit(0, 1);
    const int vertexCount = 12000, faceCount = 20000;  // over 32,768 values: converted in slices
    Mat verts(vertexCount, 3, CV_32F), colors(vertexCount, 3, CV_32F), normals(vertexCount, 3, CV_32F);
    for (int i = 0; i < vertexCount; i++) {
        const float d = i % 997 == 0 ? -1.f : z(rng);  // a few behind the camera: clipped faces
        verts.at<Vec3f>(i) = Vec3f(u(rng) * d, u(rng) * d, d);
        colors.at<Vec3f>(i) = Vec3f(unit(rng), unit(rng), unit(rng));
        normals.at<Vec3f>(i) = Vec3f(u(rng), u(rng), u(rng));
    }
    Mat faces(faceCount, 3, CV_32S);
    std::uniform_int_distribution<int> pick(0, vertexCount - 1);
    for (int i = 0; i < faceCount; i++)
        faces.at<Vec3i>(i) = Vec3i(pick(rng), pick(rng), pick(rng));
    // The same values as doubles (faces as floating-point indices), as vectors, and as
    // non-continuous column ranges of wider matrices.
    Mat verts64, colors64, normals64, faces64;
    verts.convertTo(verts64, CV_64F), colors.convertTo(colors64, CV_64F);
    normals.convertTo(normals64, CV_64F), faces.convertTo(faces64, CV_64F);
    auto roi = [](const Mat& m) {
        Mat wide(m.rows, m.cols + 1, m.type(), Scalar::all(0));
        m.copyTo(wide.colRange(0, m.cols));
        return wide.colRange(0, m.cols);
    };
    const std::vector<Point3f> vertVector = verts.reshape(3);
    const std::vector<Vec3f> colorVector = colors.reshape(3), normalVector = normals.reshape(3);
    const std::vector<Vec3i> faceVector = faces.reshape(3);
    struct Form {
        const char* name;
        _InputArray verts, faces, colors, normals;
    };
    const Mat vertsRoi = roi(verts), colorsRoi = roi(colors), normalsRoi = roi(normals),
              facesRoi = roi(faces);
    ASSERT_FALSE(vertsRoi.isContinuous());
    const Form forms[] = {{"CV_32F / CV_32S matrices", verts, faces, colors, normals},
                          {"CV_64F matrices", verts64, faces64, colors64, normals64},
                          {"vectors", vertVector, faceVector, colorVector, normalVector},
                          {"column ranges", vertsRoi, facesRoi, colorsRoi, normalsRoi}};
    const Cam cam(150, 128, 128);
    for (int shade : {SHADE_FLAT, SHADE_GOURAUD, SHADE_PHONG})
        for (int vis : {VISIBILITY_ZBUFFER, VISIBILITY_PAINTER})
            for (int variant = 0; variant < 3; variant++) {  // lit; unlit and culled; no normals
                RenderSettings s;
                s.shadeType = shade;
                s.visibility = vis;
                if (variant != 1)
                    s.lights = {PointLight(Point3d(0, -3, 0), Vec3d(1, 0.9, 0.8))};
                if (variant == 1)
                    s.cullMode = CULL_BACK;
                Mat first[3];
                for (const Form& form : forms) {
                    Mat canvas = shading_test::sentinelCanvas(Size(256, 256), CV_32FC3), depth, ids;
                    drawMesh3d(canvas, form.verts, form.faces, form.colors, cam.K, cam.rvec,
                               cam.tvec, s, variant == 2 ? _InputArray() : form.normals, depth,
                               ids);
                    if (first[0].empty()) {
                        first[0] = canvas, first[1] = depth, first[2] = ids;
                        ASSERT_GT(countNonZero(ids.reshape(1) >= 0), 1000);
                        continue;
                    }
                    const std::string what = std::string(form.name) + ", shade " +
                                             std::to_string(shade) + ", visibility " +
                                             std::to_string(vis) + ", variant " +
                                             std::to_string(variant);
                    EXPECT_EQ(shading_test::maxAbsDiff(canvas, first[0]), 0) << what;
                    EXPECT_EQ(cv::norm(depth, first[1], NORM_INF), 0) << what;
                    EXPECT_EQ(cv::norm(ids, first[2], NORM_INF), 0) << what;
                }
            }
}

// A mesh wholly in front of the near plane skips the clipping passes: its faces are the caller's
// and their sort keys come from the vertices. One unused vertex behind the camera sends the same
// faces through the clipping passes instead; both must give the same image, depth and ids, lit
// and unlit, at both canvas depths.
TEST(DrawMesh3d, UnusedVertexBehindTheCameraChangesNothing)
{
    std::mt19937 rng(11);
    const Cam cam(150, 128, 128);
    std::vector<Vec3d> v, c;
    std::vector<Vec3i> f;
    randomMesh(rng, 600, 900, v, f, c);
    std::vector<Vec3d> vBehind = v, cBehind = c;
    vBehind.emplace_back(0.5, 0.5, -3);
    cBehind.emplace_back(1, 0, 0);
    for (int type : {CV_32FC3, CV_8UC3})
        for (bool lit : {false, true})
            for (int shade : {SHADE_FLAT, SHADE_GOURAUD, SHADE_PHONG})
                for (int vis : {VISIBILITY_ZBUFFER, VISIBILITY_PAINTER}) {
                    RenderSettings s;
                    s.shadeType = shade;
                    s.visibility = vis;
                    if (lit)
                        s.lights = {PointLight(Point3d(0, -3, 0), Vec3d(1, 0.8, 0.6))};
                    const double scale = type == CV_8UC3 ? 255 : 1;
                    std::vector<Vec3d> c1 = c, c2 = cBehind;
                    for (Vec3d& x : c1)
                        x *= scale;
                    for (Vec3d& x : c2)
                        x *= scale;
                    Mat depth1, ids1, depth2, ids2;
                    const Mat a = draw(v, f, c1, cam, s, &depth1, &ids1, Size(256, 256), type);
                    const Mat b =
                        draw(vBehind, f, c2, cam, s, &depth2, &ids2, Size(256, 256), type);
                    const std::string where = format("type %d lit %d shade %d vis %d", type, lit,
                                                     shade, vis);
                    EXPECT_GT(countNonZero(ids1 >= 0), 10000) << where;
                    EXPECT_EQ(shading_test::maxAbsDiff(a, b), 0) << where;
                    EXPECT_EQ(cv::norm(depth1, depth2, NORM_INF), 0) << where;
                    EXPECT_EQ(cv::norm(ids1, ids2, NORM_INF), 0) << where;
                }
}

// Given normals are used as unit normals: scaling them changes nothing. A mesh big enough for the
// normals to be normalized in parallel chunks, at several thread counts.
TEST(DrawMesh3d, GivenNormalsAreNormalizedAtAnyThreadCount)
{
    std::mt19937 rng(11);
    const Cam cam(150, 128, 128);
    std::vector<Vec3d> v, c;
    std::vector<Vec3i> f;
    randomMesh(rng, 300000, 3000, v, f, c);  // many vertices: the workers take chunks too
    std::uniform_real_distribution<double> u(-1, 1), scale(0.1, 9);
    std::vector<Vec3d> unit, scaled;
    for (size_t i = 0; i < v.size(); i++) {
        const Vec3d n = cv::normalize(Vec3d(u(rng), u(rng), u(rng)) + Vec3d(0, 0, -1.5));
        unit.push_back(n);
        scaled.push_back(n * scale(rng));
    }
    const int threads = getNumThreads();
    for (int shade : {SHADE_GOURAUD, SHADE_PHONG}) {
        RenderSettings s;
        s.shadeType = shade;
        s.lights = {PointLight(Point3d(0, -3, 0), Vec3d(1, 0.8, 0.6))};
        setNumThreads(1);
        Mat expected = shading_test::sentinelCanvas(Size(256, 256));
        drawMesh3d(expected, v, f, c, cam.K, cam.rvec, cam.tvec, s, unit);
        for (int n : {1, 2, 8}) {
            setNumThreads(n);
            Mat img = shading_test::sentinelCanvas(Size(256, 256));
            drawMesh3d(img, v, f, c, cam.K, cam.rvec, cam.tvec, s, scaled);
            // Normalizing a scaled unit vector may move its last bit: colours agree to rounding.
            EXPECT_LE(shading_test::maxAbsDiff(img, expected), 1e-5) << shade << " " << n;
        }
    }
    setNumThreads(threads);
}

// settings.clear gives exactly the image, depth and ids of clearing first (canvas.setTo(background),
// depthBuffer.setTo(+inf)) and drawing over: every shading and visibility, both canvas types, a
// given and a created depth buffer, an ROI (nothing outside it touched), few faces or many, an
// empty mesh, and a canvas big enough (over 16 MB) for the painter's bands to be streamed.
TEST(DrawMesh3d, ClearEqualsClearingFirst)
{
    std::mt19937 rng(23);
    struct Scene {
        int vertices, faces;
        Size size;
    };
    for (const Scene& scene : {Scene{40, 30, Size(256, 200)}, Scene{1000, 1500, Size(256, 200)},
                               Scene{0, 0, Size(64, 48)}, Scene{1000, 1500, Size(1200, 1200)}}) {
        std::vector<Vec3d> v, c;
        std::vector<Vec3i> f;
        if (scene.vertices > 0)
            randomMesh(rng, scene.vertices, scene.faces, v, f, c);
        const Cam cam(0.6 * scene.size.width, 0.5 * scene.size.width, 0.5 * scene.size.height);
        const bool big = scene.size.width > 1000;
        for (int type : {CV_32FC3, CV_8UC3})
            for (int shade : {SHADE_FLAT, SHADE_GOURAUD, SHADE_PHONG})
                for (int vis : {VISIBILITY_ZBUFFER, VISIBILITY_PAINTER})
                    for (bool givenDepth : {true, false}) {
                        if (big && (type != CV_32FC3 || vis != VISIBILITY_PAINTER || !givenDepth))
                            continue;  // the big canvas is for the streamed painter's bands
                        RenderSettings s;
                        s.shadeType = shade;
                        s.visibility = vis;
                        s.lights = {PointLight(Point3d(0, -3, 0), Vec3d(1, 0.9, 0.8))};
                        s.background = type == CV_8UC3 ? Scalar(20, 200, 90) : Scalar(0.1, 0.8, 0.35);
                        // The canvas is an ROI of a bigger image, whose border must stay as it is.
                        const Rect roi(3, 2, scene.size.width, scene.size.height);
                        const Size outer(scene.size.width + 5, scene.size.height + 4);
                        const Mat garbage = shading_test::sentinelCanvas(outer, type);
                        const Mat staleDepth(scene.size, CV_32FC1, Scalar(0.5));
                        Mat expected = garbage.clone(), expectedDepth, expectedIds;
                        expected(roi).setTo(s.background);
                        if (givenDepth)
                            expectedDepth = Mat(scene.size, CV_32FC1,
                                                Scalar(std::numeric_limits<float>::infinity()));
                        Mat expectedCanvas = expected(roi);
                        drawMesh3d(expectedCanvas, v, f, c, cam.K, cam.rvec, cam.tvec, s,
                                   noArray(), expectedDepth, expectedIds);
                        s.clear = true;
                        Mat img = garbage.clone(), depth, ids;
                        if (givenDepth)
                            depth = staleDepth.clone();
                        Mat canvas = img(roi);
                        drawMesh3d(canvas, v, f, c, cam.K, cam.rvec, cam.tvec, s, noArray(),
                                   depth, ids);
                        const std::string what = std::to_string(scene.faces) + " faces, type " +
                                                 std::to_string(type) + ", shade " +
                                                 std::to_string(shade) + ", visibility " +
                                                 std::to_string(vis) +
                                                 (givenDepth ? ", depth given" : "");
                        EXPECT_EQ(shading_test::maxAbsDiff(img, expected), 0) << what;
                        EXPECT_EQ(cv::norm(depth, expectedDepth, NORM_INF), 0) << what;
                        EXPECT_EQ(cv::norm(ids, expectedIds, NORM_INF), 0) << what;
                    }
    }
}

TEST(DrawMesh3d, NonFiniteVerticesSkipTheirFaces)
{
    const Cam cam;
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const double inf = std::numeric_limits<double>::infinity();
    const std::vector<Vec3d> v = {{-1, -1, 4}, {1, -1, 4}, {0, 1, 4}, {nan, 0, 4}, {0, inf, 4}};
    const std::vector<Vec3d> c(5, Vec3d(0.5, 0.5, 0.5));
    const std::vector<Vec3i> f = {{0, 1, 3}, {0, 1, 2}, {4, 1, 2}};
    Mat ids;
    draw(v, f, c, cam, RenderSettings(), nullptr, &ids);
    EXPECT_GT(countNonZero(ids == 1), 100);
    EXPECT_EQ(countNonZero((ids == 0) | (ids == 2)), 0);
}

TEST(DrawMesh3d, RoiCanvasAndEightBit)
{
    const Cam cam(50, 50, 50);
    const std::vector<Vec3d> v = {{-5, -5, 4}, {5, -5, 4}, {0, 5, 4}};
    const std::vector<Vec3d> c(3, Vec3d(200, 100, 50));
    Mat big(200, 200, CV_8UC3, Scalar(7, 7, 7));
    Mat roi = big(Rect(50, 50, 100, 100));
    Mat before = big.clone();
    drawMesh3d(roi, v, std::vector<Vec3i>{{0, 1, 2}}, c, cam.K, cam.rvec, cam.tvec);
    Mat outside = big.clone();
    before(Rect(50, 50, 100, 100)).copyTo(outside(Rect(50, 50, 100, 100)));
    EXPECT_EQ(cv::norm(outside, before, NORM_INF), 0);  // nothing outside the ROI changed
    EXPECT_EQ(roi.at<Vec3b>(50, 50), Vec3b(200, 100, 50));
}

// Every bad argument raises cv::Exception naming it, with canvas and depth buffer untouched.
TEST(DrawMesh3dErrors, EveryBadArgumentLeavesCanvasAndDepthUntouched)
{
    const Cam cam;
    const std::vector<Vec3d> v = {{-1, -1, 4}, {1, -1, 4}, {0, 1, 4}};
    const std::vector<Vec3d> c(3, Vec3d(0.5, 0.5, 0.5));
    const std::vector<Vec3i> f = {{0, 1, 2}};
    struct Case {
        std::string name, expect;
        Mat K;
        Mat rvec, tvec;
        RenderSettings s;
        Mat normals, depth;
        std::vector<Vec3i> faces;
    };
    auto base = [&](const std::string& name, const std::string& expect) {
        Case k{name, expect, Mat(cam.K), Mat(cam.rvec), Mat(cam.tvec), RenderSettings(),
               Mat(), Mat(200, 200, CV_32FC1, Scalar(3)), f};
        return k;
    };
    std::vector<Case> cases;
    cases.push_back(base("K 2x3", "cameraMatrix"));
    cases.back().K = Mat::eye(2, 3, CV_64F);
    cases.push_back(base("K NaN", "cameraMatrix"));
    cases.back().K.at<double>(0, 2) = NAN;
    cases.push_back(base("K zero focal", "cameraMatrix"));
    cases.back().K.at<double>(1, 1) = 0;
    cases.push_back(base("K int", "cameraMatrix"));
    cases.back().K = Mat::eye(3, 3, CV_32S);
    cases.push_back(base("rvec 4x1", "rvec"));
    cases.back().rvec = Mat::zeros(4, 1, CV_64F);
    cases.push_back(base("rvec not rotation", "rvec"));
    cases.back().rvec = Mat::eye(3, 3, CV_64F) * 2;
    cases.push_back(base("rvec NaN", "rvec"));
    cases.back().rvec.at<double>(1) = NAN;
    cases.push_back(base("tvec 2x1", "tvec"));
    cases.back().tvec = Mat::zeros(2, 1, CV_64F);
    cases.push_back(base("tvec inf", "tvec"));
    cases.back().tvec.at<double>(2) = INFINITY;
    cases.push_back(base("normals count", "normals"));
    cases.back().normals = Mat::ones(2, 3, CV_32F);
    cases.push_back(base("normals NaN", "normals"));
    cases.back().normals = Mat::ones(3, 3, CV_32F);
    cases.back().normals.at<float>(1, 1) = NAN;
    cases.push_back(base("shadeType", "settings.shadeType"));
    cases.back().s.shadeType = 3;
    cases.push_back(base("visibility", "settings.visibility"));
    cases.back().s.visibility = 2;
    cases.push_back(base("cullMode", "settings.cullMode"));
    cases.back().s.cullMode = -1;
    cases.push_back(base("zNear 0", "settings.zNear"));
    cases.back().s.zNear = 0;
    cases.push_back(base("zNear NaN", "settings.zNear"));
    cases.back().s.zNear = NAN;
    cases.push_back(base("ka negative", "settings.ka"));
    cases.back().s.ka = -0.1;
    cases.push_back(base("shininess NaN", "settings.shininess"));
    cases.back().s.shininess = NAN;
    cases.push_back(base("kd inf", "settings.kd"));
    cases.back().s.kd = INFINITY;
    cases.push_back(base("ambient NaN", "settings.ambient"));
    cases.back().s.ambient = Vec3d(0, NAN, 0);
    cases.push_back(base("background inf", "settings.background"));
    cases.back().s.clear = true;
    cases.back().s.background = Scalar(0, 0, INFINITY);
    cases.push_back(base("light NaN", "settings.lights[1]"));
    cases.back().s.lights = {PointLight(), PointLight(Point3d(0, NAN, 0), Vec3d(1, 1, 1))};
    cases.push_back(base("depth size", "depthBuffer"));
    cases.back().depth = Mat(100, 200, CV_32FC1, Scalar(3));
    cases.push_back(base("depth type", "depthBuffer"));
    cases.back().depth = Mat(200, 200, CV_64FC1, Scalar(3));
    cases.push_back(base("faces range", "faces"));
    cases.back().faces = {Vec3i(0, 1, 3)};
    for (Case& k : cases) {
        Mat canvas(200, 200, CV_32FC3, Scalar(0.25, 0.5, 0.75));
        const Mat canvasBefore = canvas.clone(), depthBefore = k.depth.clone();
        Mat ids;
        try {
            drawMesh3d(canvas, v, k.faces, c, k.K, k.rvec, k.tvec, k.s, k.normals, k.depth, ids);
            ADD_FAILURE() << k.name << ": no exception";
        } catch (const cv::Exception& e) {
            EXPECT_NE(e.err.find(k.expect), std::string::npos) << k.name << ": " << e.err;
        }
        EXPECT_EQ(shading_test::maxAbsDiff(canvas, canvasBefore), 0) << k.name;
        if (k.depth.size() == depthBefore.size() && k.depth.type() == depthBefore.type()) {
            EXPECT_EQ(cv::norm(k.depth, depthBefore, NORM_INF), 0) << k.name;
        }
        EXPECT_TRUE(ids.empty()) << k.name;
    }
    // Wrong canvas types.
    Mat gray(200, 200, CV_8UC1, Scalar(1));
    EXPECT_THROW(drawMesh3d(gray, v, f, c, cam.K, cam.rvec, cam.tvec), cv::Exception);
    Mat canvas(200, 200, CV_32FC3, Scalar(1));
    EXPECT_THROW(drawMesh3d(canvas, v, f, std::vector<Vec3d>(2), cam.K, cam.rvec, cam.tvec),
                 cv::Exception);
    // The 2D functions take no SHADE_PHONG.
    EXPECT_THROW(drawMesh(canvas, std::vector<Point2d>(3), f, c, noArray(), SHADE_PHONG),
                 cv::Exception);
}

// Big inputs are converted in slices in parallel and checked as each slice arrives: a bad face
// index or normal in any slice, the last one included, is reported by its position, and the
// canvas is left alone.
TEST(DrawMesh3dErrors, BadValuesFoundInEverySliceOfABigMesh)
{
    const Cam cam;
    const int vertexCount = 40000, faceCount = 40000;  // 120,000 values each: four slices
    std::vector<Vec3d> v(vertexCount), c(vertexCount, Vec3d(0.5, 0.5, 0.5));
    std::vector<Vec3f> n(vertexCount, Vec3f(0, 0, -1));
    for (int i = 0; i < vertexCount; i++)
        v[i] = Vec3d(-1 + 2.0 * (i % 200) / 199, -1 + 2.0 * (i / 200) / 199, 4);
    std::vector<Vec3i> f(faceCount);
    for (int i = 0; i < faceCount; i++)
        f[i] = Vec3i(i % (vertexCount - 201), i % (vertexCount - 201) + 1,
                     i % (vertexCount - 201) + 200);
    RenderSettings s;
    s.lights = {PointLight(Point3d(0, 0, 0), Vec3d(1, 1, 1))};
    // The call must raise an error containing `expected` and leave the canvas as it was.
    auto expectRejected = [&](const std::vector<Vec3i>& faces, const std::vector<Vec3f>& normals,
                              const std::string& expected) {
        Mat canvas(200, 200, CV_32FC3, Scalar(0.25, 0.5, 0.75));
        const Mat before = canvas.clone();
        try {
            drawMesh3d(canvas, v, faces, c, cam.K, cam.rvec, cam.tvec, s, normals);
            ADD_FAILURE() << expected << ": no exception";
        } catch (const cv::Exception& e) {
            EXPECT_NE(e.err.find(expected), std::string::npos) << e.err;
        }
        EXPECT_EQ(shading_test::maxAbsDiff(canvas, before), 0) << expected;
    };
    for (int at : {0, 50000, 3 * faceCount - 1}) {
        std::vector<Vec3i> bad = f;
        bad[at / 3][at % 3] = at % 2 ? -1 : vertexCount;
        expectRejected(bad, n, "faces: face " + std::to_string(at / 3) + " ");
    }
    for (int at : {1, 60001, 3 * vertexCount - 1}) {
        std::vector<Vec3f> bad = n;
        bad[at / 3][at % 3] = at % 2 ? std::numeric_limits<float>::infinity()
                                     : std::numeric_limits<float>::quiet_NaN();
        expectRejected(f, bad, "normals: normal " + std::to_string(at / 3) + " ");
    }
    // And with good values the same mesh draws.
    Mat canvas(200, 200, CV_32FC3, Scalar(0.25, 0.5, 0.75));
    EXPECT_NO_THROW(drawMesh3d(canvas, v, f, c, cam.K, cam.rvec, cam.tvec, s, n));
    EXPECT_GT(shading_test::maxAbsDiff(canvas, Mat(200, 200, CV_32FC3, Scalar(0.25, 0.5, 0.75))),
              0);
}

}  // namespace
