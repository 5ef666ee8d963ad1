// drawMesh() and render(): painter's order (worked by hand), ties, skipped faces, exactly-once
// coverage of closed meshes, equality with drawing the faces one by one, thread-count
// independence, input forms, canvases and ROIs.
#include "test_common.hpp"

#include <gtest/gtest.h>
#include <opencv2/core/utility.hpp>
#include <opencv2/shading.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <numeric>
#include <string>
#include <thread>

using namespace cv;
using shading_test::maxAbsDiff;
using shading_test::writtenMask;

namespace {

// Three nested right triangles at the origin, one flat colour each (3 vertices per face).
struct Layers {
    std::vector<Point2f> verts;
    std::vector<Vec3i> faces;
    std::vector<Vec3f> colors;
    std::vector<float> depth;

    void add(float size, Vec3f color, float d)
    {
        const int base = int(verts.size());
        for (const Point2f& p : {Point2f(0, 0), Point2f(size, 0), Point2f(0, size)}) {
            verts.push_back(p);
            colors.push_back(color);
            depth.push_back(d);
        }
        faces.push_back(Vec3i(base, base + 1, base + 2));
    }
};

const Vec3f kRed(1, 0, 0), kGreen(0, 1, 0), kBlue(0, 0, 1), kWhite(1, 1, 1);

// A grid of (n x n) cells over [-2, size + 2]^2, each split along a random diagonal, interior
// vertices jittered by up to 0.2 cell (quads stay convex) (optionally snapped to whole pixels): a closed mesh that
// covers every canvas sample.
void makeGridMesh(Size size, int n, bool integerVertices, uint64 seed,
                  std::vector<Point2d>& verts, std::vector<Vec3i>& faces)
{
    RNG rng(seed);
    verts.clear();
    faces.clear();
    const double x0 = -2, y0 = -2, sx = (size.width + 4.0) / n, sy = (size.height + 4.0) / n;
    for (int j = 0; j <= n; j++)
        for (int i = 0; i <= n; i++) {
            Point2d p(x0 + i * sx, y0 + j * sy);
            if (i > 0 && i < n && j > 0 && j < n)
                p += Point2d(rng.uniform(-0.2, 0.2) * sx, rng.uniform(-0.2, 0.2) * sy);
            if (integerVertices)
                p = Point2d(std::round(p.x), std::round(p.y));
            verts.push_back(p);
        }
    for (int j = 0; j < n; j++)
        for (int i = 0; i < n; i++) {
            const int a = j * (n + 1) + i, b = a + 1, c = a + n + 1, d = c + 1;
            if (rng.uniform(0, 2))
                faces.push_back({a, b, d}), faces.push_back({a, d, c});
            else
                faces.push_back({a, b, c}), faces.push_back({b, d, c});
        }
}

std::vector<Vec3f> randomColors(size_t n, uint64 seed)
{
    RNG rng(seed);
    std::vector<Vec3f> c(n);
    for (Vec3f& v : c)
        v = Vec3f(rng.uniform(0.f, 1.f), rng.uniform(0.f, 1.f), rng.uniform(0.f, 1.f));
    return c;
}

}  // namespace

// Faces given as A (big, red, depth 5), B (medium, green, depth 3), C (small, blue, depth 9).
// Painter's order: C, A, B. So B shows wherever it covers, A elsewhere inside it, C nowhere.
TEST(ShadingMesh, PaintersOrderByHand)
{
    Layers m;
    m.add(10, kRed, 5);
    m.add(6, kGreen, 3);
    m.add(3, kBlue, 9);
    Mat img;
    shading::render(m.verts, m.faces, m.colors, m.depth, img, shading::SHADE_FLAT, Size(12, 12));
    ASSERT_EQ(img.type(), CV_32FC3);
    ASSERT_EQ(img.size(), Size(12, 12));
    EXPECT_EQ(img.at<Vec3f>(0, 0), kGreen);
    EXPECT_EQ(img.at<Vec3f>(1, 1), kGreen);
    EXPECT_EQ(img.at<Vec3f>(5, 0), kGreen);  // x + y = 5 < 6
    EXPECT_EQ(img.at<Vec3f>(6, 0), kRed);    // x + y = 6: B's right edge, A's interior
    EXPECT_EQ(img.at<Vec3f>(1, 7), kRed);
    EXPECT_EQ(img.at<Vec3f>(5, 5), kWhite);  // x + y = 10: A's right edge
    EXPECT_EQ(img.at<Vec3f>(11, 11), kWhite);
}

// Equal mean depths keep the order of `faces`: the later face is drawn last and shows.
TEST(ShadingMesh, DepthTiesKeepFaceOrder)
{
    Layers m;
    m.add(8, kRed, 2);
    m.add(8, kGreen, 2);
    Mat img;
    shading::render(m.verts, m.faces, m.colors, m.depth, img, shading::SHADE_FLAT, Size(10, 10));
    EXPECT_EQ(img.at<Vec3f>(1, 1), kGreen);
    // Mean over different vertex depths: (1 + 2 + 3) / 3 == (2 + 2 + 2) / 3.
    m.depth[3] = 1, m.depth[4] = 2, m.depth[5] = 3;
    std::swap(m.faces[0], m.faces[1]);
    shading::render(m.verts, m.faces, m.colors, m.depth, img, shading::SHADE_FLAT, Size(10, 10));
    EXPECT_EQ(img.at<Vec3f>(1, 1), kRed);
}

TEST(ShadingMesh, EmptyDepthDrawsInFaceOrder)
{
    Layers m;
    m.add(8, kRed, 1);
    m.add(4, kGreen, 9);
    Mat img;
    shading::render(m.verts, m.faces, m.colors, noArray(), img, shading::SHADE_FLAT, Size(10, 10));
    EXPECT_EQ(img.at<Vec3f>(1, 1), kGreen);
    EXPECT_EQ(img.at<Vec3f>(1, 5), kRed);
}

TEST(ShadingMesh, NaNDepthOrVertexSkipsOnlyThatFace)
{
    Layers m;
    m.add(8, kRed, 2);
    m.add(4, kGreen, 1);
    m.depth[4] = std::numeric_limits<float>::quiet_NaN();
    Mat img;
    shading::render(m.verts, m.faces, m.colors, m.depth, img, shading::SHADE_FLAT, Size(10, 10));
    EXPECT_EQ(img.at<Vec3f>(1, 1), kRed);
    m.depth[4] = 1;
    m.verts[5].y = std::numeric_limits<float>::infinity();
    shading::render(m.verts, m.faces, m.colors, m.depth, img, shading::SHADE_FLAT, Size(10, 10));
    EXPECT_EQ(img.at<Vec3f>(1, 1), kRed);
}

TEST(ShadingMesh, RenderFillsBackgroundAndSize)
{
    Mat img;
    shading::render(std::vector<Point2f>(), std::vector<Vec3i>(), std::vector<Vec3f>(),
                    std::vector<float>(), img, shading::SHADE_GOURAUD, Size(7, 5),
                    Scalar(0.25, 0.5, 0.75));
    ASSERT_EQ(img.size(), Size(7, 5));
    ASSERT_EQ(img.type(), CV_32FC3);
    EXPECT_EQ(countNonZero(writtenMask(img, Mat(5, 7, CV_32FC3, Scalar(0.25, 0.5, 0.75)))), 0);
    Mat def;
    shading::render(std::vector<Point2f>(), std::vector<Vec3i>(), std::vector<Vec3f>(), noArray(), def);
    EXPECT_EQ(def.size(), Size(512, 512));
    EXPECT_EQ(countNonZero(writtenMask(def, Mat(512, 512, CV_32FC3, Scalar::all(1)))), 0);
}

// Every sample of a closed mesh is covered exactly once: no gaps, no double-drawn seams.
TEST(ShadingMesh, ClosedMeshCoversEverySampleExactlyOnce)
{
    const Size size(61, 47);
    for (int variant = 0; variant < 4; variant++) {
        std::vector<Point2d> verts;
        std::vector<Vec3i> faces;
        makeGridMesh(size, 9 + variant * 4, variant % 2 == 1, 100 + variant, verts, faces);
        Mat count(size, CV_32S, Scalar(0));
        for (const Vec3i& f : faces) {
            Mat canvas(size, CV_8UC3, Scalar::all(0));
            shading::flats(canvas, std::vector<Point2d>{verts[f[0]], verts[f[1]], verts[f[2]]},
                           std::vector<Vec3f>(3, Vec3f(1, 1, 1)));
            Mat one;
            extractChannel(canvas, one, 0);
            Mat one32;
            one.convertTo(one32, CV_32S);
            count += one32;
        }
        double lo, hi;
        minMaxLoc(count, &lo, &hi);
        EXPECT_EQ(lo, 1.0) << "variant " << variant << ": a sample is not covered";
        EXPECT_EQ(hi, 1.0) << "variant " << variant << ": a sample is covered twice";
    }
}

// drawMesh equals drawing the faces one at a time in painter's order (the order computed here
// independently), for any thread count, flat and Gouraud, float and 8-bit canvases.
TEST(ShadingMesh, EqualsSequentialPaintersForAnyThreadCount)
{
    const Size size(96, 80);
    RNG rng(7);
    const int L = 600;
    std::vector<Point2d> verts(L);
    std::vector<double> depth(L);
    for (int i = 0; i < L; i++) {
        verts[i] = Point2d(rng.uniform(-20.0, 116.0), rng.uniform(-20.0, 100.0));
        depth[i] = std::floor(rng.uniform(0.0, 8.0));  // many ties
    }
    std::vector<Vec3i> faces;
    for (int k = 0; k < 900; k++) {
        const int a = rng.uniform(0, L);
        // Mostly small faces: neighbours of a in a random direction.
        int b = rng.uniform(0, L), c = rng.uniform(0, L);
        if (k % 3) {
            verts.push_back(verts[a] + Point2d(rng.uniform(-9.0, 9.0), rng.uniform(-9.0, 9.0)));
            verts.push_back(verts[a] + Point2d(rng.uniform(-9.0, 9.0), rng.uniform(-9.0, 9.0)));
            depth.push_back(depth[a]);
            depth.push_back(std::floor(rng.uniform(0.0, 8.0)));
            b = int(verts.size()) - 2, c = int(verts.size()) - 1;
        }
        faces.push_back({a, b, c});
    }
    const std::vector<Vec3f> colors = randomColors(verts.size(), 8);

    std::vector<double> mean(faces.size());
    for (size_t i = 0; i < faces.size(); i++)
        mean[i] = (depth[faces[i][0]] + depth[faces[i][1]] + depth[faces[i][2]]) / 3.0;
    std::vector<int> order(faces.size());
    std::iota(order.begin(), order.end(), 0);
    std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return mean[a] > mean[b]; });

    const int savedThreads = getNumThreads();
    for (int type : {CV_32FC3, CV_8UC3}) {
        const double scale = type == CV_8UC3 ? 255.0 : 1.0;
        std::vector<Vec3d> scaled(colors.size());
        for (size_t i = 0; i < colors.size(); i++)
            scaled[i] = Vec3d(colors[i]) * scale;
        for (int shade : {shading::SHADE_FLAT, shading::SHADE_GOURAUD}) {
            Mat expected(size, type, Scalar::all(3));
            for (int f : order) {
                const std::vector<Point2d> v = {verts[faces[f][0]], verts[faces[f][1]], verts[faces[f][2]]};
                const std::vector<Vec3d> c = {scaled[faces[f][0]], scaled[faces[f][1]], scaled[faces[f][2]]};
                if (shade == shading::SHADE_FLAT)
                    shading::flats(expected, v, c);
                else
                    shading::gouraud(expected, v, c);
            }
            for (int threads : {1, 2, 8}) {
                setNumThreads(threads);
                Mat canvas(size, type, Scalar::all(3));
                shading::drawMesh(canvas, verts, faces, scaled, depth, shade);
                EXPECT_EQ(maxAbsDiff(canvas, expected), 0.0)
                    << "type " << type << " shade " << shade << " threads " << threads;
            }
        }
    }
    setNumThreads(savedThreads);
}

namespace {

// A sphere of radius 120 around (128, 128) seen from the side, with both of its windings (its
// depth the view axis): 70 rings of 140 segments.
void makeSideSphere(std::vector<Point2d>& verts, std::vector<Vec3i>& faces,
                    std::vector<double>& depth)
{
    const int rings = 70, segments = 140;
    for (int i = 0; i <= rings; i++)
        for (int j = 0; j < segments; j++) {
            const double th = CV_PI * i / rings, ph = 2 * CV_PI * j / segments;
            verts.push_back(Point2d(128 + 120 * std::sin(th) * std::cos(ph),
                                    128 + 120 * std::cos(th)));
            depth.push_back(std::sin(th) * std::sin(ph));
        }
    for (int i = 0; i < rings; i++)
        for (int j = 0; j < segments; j++) {
            const int a = i * segments + j, b = i * segments + (j + 1) % segments;
            faces.push_back({a, b, a + segments});
            faces.push_back({b, b + segments, a + segments});
        }
}

// Draws the mesh on a float canvas and on an 8-bit one, both of background 3, at 1 and 2
// threads, and expects every 8-bit pixel to be the float image's, converted (rounded and
// saturated) by Mat::convertTo. Returns that expected 8-bit image.
Mat expectEightBitEqualsFloatConverted(Size size, const std::vector<Point2d>& verts,
                                       const std::vector<Vec3i>& faces,
                                       const std::vector<Vec3d>& colors,
                                       const std::vector<double>& depth, int shade,
                                       const std::string& what)
{
    Mat asFloat(size, CV_32FC3, Scalar::all(3)), expected;
    shading::drawMesh(asFloat, verts, faces, colors, depth, shade);
    asFloat.convertTo(expected, CV_8U);
    const int savedThreads = getNumThreads();
    for (int threads : {1, 2}) {
        setNumThreads(threads);
        Mat canvas(size, CV_8UC3, Scalar::all(3));
        shading::drawMesh(canvas, verts, faces, colors, depth, shade);
        EXPECT_EQ(maxAbsDiff(canvas, expected), 0.0) << what << ", " << threads << " threads";
    }
    setNumThreads(savedThreads);
    return expected;
}

}  // namespace

// Flat faces on an 8-bit canvas take the same sample paths as on a float one (the 4 x 4 blocks
// of a grid's tiny faces, a closed surface's 8 x 8 blocks), with a pen of three byte stores: the
// 8-bit image must be the float image of the same integer colours, rounded. (A mean of three
// integers never ends in .5, so rounding cannot differ between the two.) A jittered grid of
// 2.7-pixel cells with tied depths, and a sphere seen from the side with both of its windings.
TEST(ShadingMesh, EightBitFlatEqualsFloatRounded)
{
    const Size size(256, 256);
    RNG rng(77);
    for (int mesh = 0; mesh < 2; mesh++) {
        std::vector<Point2d> verts;
        std::vector<Vec3i> faces;
        std::vector<double> depth;
        if (mesh == 0) {
            makeGridMesh(size, 96, false, 78, verts, faces);
            for (size_t i = 0; i < verts.size(); i++)
                depth.push_back(std::floor(rng.uniform(0.0, 6.0)));
        } else {
            makeSideSphere(verts, faces, depth);
        }
        std::vector<Vec3d> colors(verts.size());
        for (Vec3d& c : colors)
            c = Vec3d(rng.uniform(0, 256), rng.uniform(0, 256), rng.uniform(0, 256));
        const Mat expected = expectEightBitEqualsFloatConverted(
            size, verts, faces, colors, depth, shading::SHADE_FLAT, "mesh " + std::to_string(mesh));
        // Teeth: most of the canvas drawn (the grid covers all of it, the sphere's disc 69%).
        int drawn = 0;
        for (auto it = expected.begin<Vec3b>(); it != expected.end<Vec3b>(); ++it)
            drawn += *it != Vec3b(3, 3, 3);
        EXPECT_GT(drawn, mesh == 0 ? 60000 : 40000) << "mesh " << mesh;
    }
}

// Gouraud on an 8-bit canvas takes the float canvas's sample paths too (the 4 x 4 blocks of a
// grid's tiny faces, the tiny spans' per-sample test), with a pen that rounds and saturates in
// SIMD lanes: each 8-bit pixel must be the float image's value rounded as cv::saturate_cast
// rounds it (Mat::convertTo), which the row shader's scalar toChannel does; so must its runs
// stored in groups of pixels (storeBytePixelGroups). Colours from -40 to 300, so that the interpolated
// values need both saturations; the same two meshes as above, and overlapping random faces of 1
// to 120 pixels across.
TEST(ShadingMesh, EightBitGouraudEqualsFloatRounded)
{
    const Size size(256, 256);
    RNG rng(79);
    for (int mesh = 0; mesh < 3; mesh++) {
        std::vector<Point2d> verts;
        std::vector<Vec3i> faces;
        std::vector<double> depth;
        if (mesh == 0) {
            makeGridMesh(size, 96, false, 80, verts, faces);
            for (size_t i = 0; i < verts.size(); i++)
                depth.push_back(std::floor(rng.uniform(0.0, 6.0)));
        } else if (mesh == 1) {
            makeSideSphere(verts, faces, depth);
        } else {
            for (int f = 0; f < 6000; f++) {
                const Point2d centre(rng.uniform(0.0, 256.0), rng.uniform(0.0, 256.0));
                const double radius = std::exp(rng.uniform(std::log(0.8), std::log(60.0)));
                for (int k = 0; k < 3; k++) {
                    const double angle = rng.uniform(0.0, 2 * CV_PI);
                    verts.push_back(centre + radius * Point2d(std::cos(angle), std::sin(angle)));
                    depth.push_back(rng.uniform(0.0, 1.0));
                }
                faces.push_back({3 * f, 3 * f + 1, 3 * f + 2});
            }
        }
        std::vector<Vec3d> colors(verts.size());
        for (Vec3d& c : colors)
            c = Vec3d(rng.uniform(-40.0, 300.0), rng.uniform(-40.0, 300.0),
                      rng.uniform(-40.0, 300.0));
        const Mat expected = expectEightBitEqualsFloatConverted(
            size, verts, faces, colors, depth, shading::SHADE_GOURAUD, "mesh " + std::to_string(mesh));
        // Teeth: most of the canvas drawn, in many values, both saturations among them.
        int drawn = 0, saturated[2] = {0, 0};
        for (auto it = expected.begin<Vec3b>(); it != expected.end<Vec3b>(); ++it) {
            drawn += *it != Vec3b(3, 3, 3);
            for (int k = 0; k < 3; k++)
                saturated[0] += (*it)[k] == 0, saturated[1] += (*it)[k] == 255;
        }
        EXPECT_GT(drawn, 40000) << "mesh " << mesh;
        EXPECT_GT(saturated[0], 100) << "mesh " << mesh;
        EXPECT_GT(saturated[1], 100) << "mesh " << mesh;
    }
}

// Gouraud sums w0 c0 + w1 c1 + w2 c2 in the vertices' canonical order (top, mid, bottom), so that
// a face's pixels never depend on the path that draws it. Tiny faces of a mesh are set up eight
// at a time (AVX2 build); here each is compared with the same face drawn alone, bit for bit, in
// bands drawn in face order (one winding; with depths, the 4 x 4 block test) and front to back
// (both windings, as a closed surface's). Colours linear in x or y, zero at a span's first
// column or along a row, make the sums cancel to rounding noise there, which any other order of
// the sums changes; axis-aligned
// cells give vertices of equal y, whose order the sort's tie-break decides. Colours beyond
// +-1e37 are computed per pixel, never stepped in float, which could overflow.
TEST(ShadingMesh, TinyGouraudFacesEqualFacesDrawnAlone)
{
    const Size size(61, 47);
    std::vector<Point2d> verts;
    const int n = 20, m = 16;  // cells of 3 x 3 pixels, corners a quarter pixel off the samples
    RNG rng(11);
    for (int j = 0; j <= m; j++)
        for (int i = 0; i <= n; i++) {
            // From row 12 on, corners moved up or down a little, on the 1/256 grid (so that
            // the colours below are exactly linear in the snapped vertices).
            const double dy = 3 * j > 12 ? rng.uniform(-100, 101) / 256.0 : 0.0;
            verts.push_back(Point2d(3 * i - 0.75, 3 * j - 0.75 + dy));
        }
    for (bool bothWindings : {false, true}) {
        std::vector<Vec3i> faces;
        for (int j = 0; j < m; j++)
            for (int i = 0; i < n; i++) {
                const int a = j * (n + 1) + i, b = a + 1, c = a + n + 1, d = c + 1;
                // Both diagonals, and each face's vertices given in a random rotation.
                Vec3i f0(a, b, d), f1(a, d, c);
                if (rng.uniform(0, 2))
                    f0 = Vec3i(a, b, c), f1 = Vec3i(b, d, c);
                for (Vec3i f : {f0, f1}) {
                    const int r = rng.uniform(0, 3);
                    faces.push_back(Vec3i(f[r], f[(r + 1) % 3], f[(r + 2) % 3]));
                    if (bothWindings && rng.uniform(0, 2))
                        std::swap(faces.back()[1], faces.back()[2]);
                }
            }
        for (bool huge : {false, true}) {
            std::vector<Vec3d> colors;
            // Zero at columns 9 and 21, where spans start, and along row 20, where the steps
            // along x (zero but for rounding, where no edge is horizontal) and the spans' first
            // values cancel; or up to 3e38.
            for (const Point2d& v : verts)
                colors.push_back(huge ? Vec3d(1e37 * (v.x - 30), -3e38 * (2 * (int(v.x) % 2) - 1),
                                              1e36 * v.y)
                                      : Vec3d(1e6 * (v.x - 9), -3e5 * (v.x - 21),
                                              7e4 * (v.y - 20)));
            Mat expected(size, CV_32FC3, Scalar::all(0));
            for (const Vec3i& f : faces) {
                const std::vector<Point2d> v = {verts[f[0]], verts[f[1]], verts[f[2]]};
                const std::vector<Vec3d> c = {colors[f[0]], colors[f[1]], colors[f[2]]};
                shading::gouraud(expected, v, c);
            }
            // Without depths, and with them (the faces do not overlap, so any order draws the
            // same image), which send one winding's bands to the 4 x 4 block test.
            std::vector<double> depth;
            for (size_t v = 0; v < verts.size(); v++)
                depth.push_back(rng.uniform(0.0, 1.0));
            for (bool withDepth : {false, true}) {
                Mat canvas(size, CV_32FC3, Scalar::all(0));
                shading::drawMesh(canvas, verts, faces, colors,
                                  withDepth ? _InputArray(depth) : _InputArray(noArray()),
                                  shading::SHADE_GOURAUD);
                EXPECT_EQ(std::memcmp(canvas.data, expected.data,
                                      canvas.total() * canvas.elemSize()),
                          0)
                    << "both windings " << bothWindings << ", huge colours " << huge
                    << ", depths " << withDepth;
            }
        }
    }
}

TEST(ShadingMesh, DrawMeshIntoRoiTouchesOnlyTheRoi)
{
    std::vector<Point2d> verts;
    std::vector<Vec3i> faces;
    makeGridMesh(Size(20, 15), 6, false, 3, verts, faces);
    const std::vector<Vec3f> colors = randomColors(verts.size(), 4);
    Mat big(40, 50, CV_32FC3, Scalar::all(-1)), before = big.clone();
    Mat roi = big(Rect(10, 12, 20, 15));
    shading::drawMesh(roi, verts, faces, colors, noArray());
    const Mat written = writtenMask(big, before);
    EXPECT_EQ(countNonZero(written), 20 * 15);
    EXPECT_EQ(countNonZero(written(Rect(10, 12, 20, 15))), 20 * 15);
    // Same pixels as drawing into a standalone canvas of the ROI's size.
    Mat alone(15, 20, CV_32FC3, Scalar::all(-1));
    shading::drawMesh(alone, verts, faces, colors, noArray());
    EXPECT_EQ(maxAbsDiff(alone, roi), 0.0);
}

TEST(ShadingMesh, AllInputFormsAgree)
{
    Layers m;
    m.add(9, kRed, 5);
    m.add(6, kGreen, 3);
    m.add(3, kBlue, 9);
    Mat expected;
    shading::render(m.verts, m.faces, m.colors, m.depth, expected, shading::SHADE_GOURAUD, Size(12, 12));

    const Mat verts32f = Mat(m.verts).reshape(1).clone();
    Mat verts64f, verts32s, faces32s = Mat(m.faces).reshape(1).clone(), faces64f, faces32f;
    verts32f.convertTo(verts64f, CV_64F);
    verts32f.convertTo(verts32s, CV_32S);
    faces32s.convertTo(faces64f, CV_64F);
    faces32s.convertTo(faces32f, CV_32F);
    const Mat colors64f = [&] { Mat c; Mat(m.colors).reshape(1).convertTo(c, CV_64F); return c; }();
    const Mat depthRow = Mat(m.depth).reshape(1, 1).clone();
    const std::vector<double> depth64(m.depth.begin(), m.depth.end());
    std::vector<Point2d> verts2d(m.verts.begin(), m.verts.end());

    const std::vector<_InputArray> vertForms = {_InputArray(verts32f), _InputArray(verts64f),
                                                _InputArray(verts32s), _InputArray(verts2d)};
    const std::vector<_InputArray> faceForms = {_InputArray(faces32s), _InputArray(faces64f),
                                                _InputArray(faces32f), _InputArray(m.faces)};
    const std::vector<_InputArray> depthForms = {_InputArray(depthRow), _InputArray(depth64),
                                                 _InputArray(m.depth)};
    for (size_t i = 0; i < vertForms.size(); i++)
        for (size_t j = 0; j < faceForms.size(); j++)
            for (size_t k = 0; k < depthForms.size(); k++) {
                Mat img;
                shading::render(vertForms[i], faceForms[j], colors64f, depthForms[k], img,
                                shading::SHADE_GOURAUD, Size(12, 12));
                EXPECT_EQ(maxAbsDiff(img, expected), 0.0) << i << "," << j << "," << k;
            }
}

// Inputs above 32768 values are converted in parallel slices: every form, continuous or not, one
// row or many, gives the image that the same mesh drawn in small pieces gives.
TEST(ShadingMesh, LargeInputFormsAgree)
{
    const Size size(190, 110);
    std::vector<Point2d> verts;
    std::vector<Vec3i> faces;
    makeGridMesh(size, 140, false, 31, verts, faces);  // 19,881 vertices, 39,200 faces
    for (Point2d& p : verts)  // quarter pixels: exact as float too
        p = Point2d(std::round(p.x * 4) / 4, std::round(p.y * 4) / 4);
    const std::vector<Vec3f> colors = randomColors(verts.size(), 32);
    RNG rng(33);
    std::vector<double> depth(verts.size());
    for (double& d : depth)  // floats, so that the float form below holds the same values
        d = double(float(rng.uniform(0.0, 8.0)));
    const std::vector<float> depthFloat(depth.begin(), depth.end());  // read where they are

    // The expectation: pieces of faces by mean depth, far to near (the painter's order), each with
    // its own vertices, all few enough to be converted at once.
    std::vector<double> mean(faces.size());
    for (size_t i = 0; i < faces.size(); i++)
        mean[i] = (depth[faces[i][0]] + depth[faces[i][1]] + depth[faces[i][2]]) / 3.0;
    Mat expected(size, CV_32FC3, Scalar::all(1.0));
    for (int bin = 63; bin >= 0; bin--) {
        std::vector<Point2d> pieceVerts;
        std::vector<Vec3f> pieceColors;
        std::vector<double> pieceDepth;
        std::vector<Vec3i> pieceFaces;
        for (size_t i = 0; i < faces.size(); i++) {
            if (mean[i] < bin / 8.0 || mean[i] >= (bin + 1) / 8.0)
                continue;
            Vec3i f;
            for (int k = 0; k < 3; k++) {  // a copy of each corner: depths stay the same
                f[k] = int(pieceVerts.size());
                pieceVerts.push_back(verts[faces[i][k]]);
                pieceColors.push_back(colors[faces[i][k]]);
                pieceDepth.push_back(depth[faces[i][k]]);
            }
            pieceFaces.push_back(f);
        }
        ASSERT_LE(pieceColors.size() * 3, size_t(32768));
        shading::drawMesh(expected, pieceVerts, pieceFaces, pieceColors, pieceDepth,
                          shading::SHADE_GOURAUD);
    }

    Mat vertsWide(int(verts.size()), 4, CV_64F);  // its left half is not continuous
    Mat(verts).reshape(1).copyTo(vertsWide.colRange(0, 2));
    const Mat vertsStrided = vertsWide.colRange(0, 2);
    const Mat vertsRow = Mat(verts).reshape(2, 1).clone();  // 1 x N, two channels
    Mat vertsFloat, colorsDouble, facesDouble;
    Mat(verts).reshape(1).convertTo(vertsFloat, CV_32F);
    Mat(colors).reshape(1).convertTo(colorsDouble, CV_64F);
    Mat(faces).reshape(1).convertTo(facesDouble, CV_64F);
    const Mat depthRow = Mat(depth).reshape(1, 1).clone();

    const std::vector<_InputArray> vertForms = {_InputArray(verts), _InputArray(vertsFloat),
                                                _InputArray(vertsStrided),
                                                _InputArray(vertsRow)};
    for (size_t i = 0; i < vertForms.size(); i++)
        for (int j = 0; j < 3; j++) {
            Mat img;
            const _InputArray depthForm = j == 0   ? _InputArray(depth)
                                          : j == 1 ? _InputArray(depthRow)
                                                   : _InputArray(depthFloat);
            shading::render(vertForms[i], j == 1 ? _InputArray(facesDouble) : _InputArray(faces),
                            j == 1 ? _InputArray(colorsDouble) : _InputArray(colors), depthForm,
                            img, shading::SHADE_GOURAUD, size, Scalar::all(1.0));
            EXPECT_EQ(maxAbsDiff(img, expected), 0.0)
                << "vertex form " << i << ", other forms " << j;
        }
}

// Float vertices are snapped where they are, not copied into doubles first: every float form
// (continuous or not) gives the image of the same values given as doubles, for coordinates on
// the rounding ties of the 1/256 grid, NaN, infinite and out-of-range ones, an odd count (the
// snap's tail) and a vertex far outside the canvas (off the narrow grid's 8-face paths).
TEST(ShadingMesh, FloatVerticesDrawAsTheirDoubles)
{
    const Size size(300, 200);
    RNG rng(41);
    const int n = 200, m = 100;      // cells of 1.5 x 2 pixels
    const int count = (n + 1) * m + 1;  // odd: the snap's tail, the last vertex alone
    for (bool farVertex : {false, true}) {
        std::vector<Point2f> verts;
        for (int j = 0; j < m; j++)
            for (int i = 0; i <= n; i++) {
                // Off the grid by multiples of 1/512 (ties of the 1/256 grid) or anything.
                auto jitter = [&] {
                    return rng.uniform(0, 2) ? float(rng.uniform(-256, 257) / 512.0)
                                             : rng.uniform(-0.5f, 0.5f);
                };
                verts.push_back(Point2f(1.5f * i + jitter(), 2.0f * j + jitter()));
            }
        verts.push_back(Point2f(299 + 0.5f / 256, 199 + 1.5f / 256));  // the tail, on ties
        ASSERT_EQ(int(verts.size()), count);
        verts[n + 17].x = std::numeric_limits<float>::quiet_NaN();
        verts[n + 40].y = std::numeric_limits<float>::infinity();
        verts[n + 80].x = 3e30f;  // beyond the subpixel grid's range
        if (farVertex)
            verts[2 * n + 50] = Point2f(-3e6f, 1e6f);
        std::vector<Vec3i> faces;
        for (int j = 0; j + 1 < m; j++)
            for (int i = 0; i < n; i++) {
                const int a = j * (n + 1) + i, b = a + 1, c = a + n + 1, d = c + 1;
                faces.push_back(Vec3i(a, b, d));
                faces.push_back(Vec3i(a, d, c));
            }
        faces.push_back(Vec3i(count - 1, count - 2, count - 3 - n));  // through the tail
        const std::vector<Vec3f> colors = randomColors(verts.size(), 42);
        const std::vector<Point2d> asDoubles(verts.begin(), verts.end());

        const Mat column = Mat(verts).reshape(1).clone();  // N x 2
        const Mat row = Mat(verts).reshape(2, 1).clone();  // 1 x N, two channels
        Mat wide(count, 3, CV_32F, Scalar::all(0));        // its left part is not continuous
        column.copyTo(wide.colRange(0, 2));
        const Mat strided = wide.colRange(0, 2);
        const std::vector<_InputArray> floatForms = {_InputArray(verts), _InputArray(column),
                                                     _InputArray(row), _InputArray(strided)};
        for (int shade : {shading::SHADE_FLAT, shading::SHADE_GOURAUD}) {
            Mat expected;
            shading::render(asDoubles, faces, colors, noArray(), expected, shade, size);
            for (size_t i = 0; i < floatForms.size(); i++) {
                Mat img;
                shading::render(floatForms[i], faces, colors, noArray(), img, shade, size);
                EXPECT_EQ(std::memcmp(img.data, expected.data, img.total() * img.elemSize()), 0)
                    << "float form " << i << ", shade " << shade << ", far vertex " << farVertex;
            }
        }
    }
}

// Float colours are read where they are in flat shading (the mesh's face means computed in
// double from them): every float form gives the image of the same values given as doubles, on
// float and 8-bit canvases, with channels whose sums round differently in float.
TEST(ShadingMesh, FloatColoursDrawAsTheirDoubles)
{
    const Size size(190, 110);
    std::vector<Point2d> verts;
    std::vector<Vec3i> faces;
    makeGridMesh(size, 140, false, 51, verts, faces);  // 19,881 vertices: parallel slices
    RNG rng(52);
    std::vector<Vec3f> colors(verts.size());
    for (Vec3f& c : colors)  // 2^24 + small: the sum of three in float would round
        c = Vec3f(rng.uniform(0.0f, 1.0f), float(rng.uniform(-3, 4)) * 16777216.0f + 1.0f,
                  rng.uniform(-2.0f, 2.0f) * 1e30f);
    const std::vector<Vec3d> asDoubles(colors.begin(), colors.end());
    const Mat column = Mat(colors).reshape(1).clone();  // N x 3
    const Mat row = Mat(colors).reshape(3, 1).clone();  // 1 x N, three channels
    Mat wide(int(colors.size()), 4, CV_32F, Scalar::all(0));  // its left part is not continuous
    column.copyTo(wide.colRange(0, 3));
    const Mat strided = wide.colRange(0, 3);
    const std::vector<_InputArray> floatForms = {_InputArray(colors), _InputArray(column),
                                                 _InputArray(row), _InputArray(strided)};
    for (int type : {CV_32FC3, CV_8UC3})
        for (int shade : {shading::SHADE_FLAT, shading::SHADE_GOURAUD}) {
            Mat expected(size, type, Scalar::all(7));
            shading::drawMesh(expected, verts, faces, asDoubles, noArray(), shade);
            for (size_t i = 0; i < floatForms.size(); i++) {
                Mat img(size, type, Scalar::all(7));
                shading::drawMesh(img, verts, faces, floatForms[i], noArray(), shade);
                EXPECT_EQ(std::memcmp(img.data, expected.data, img.total() * img.elemSize()), 0)
                    << "float form " << i << ", type " << type << ", shade " << shade;
            }
        }
}

// Many callers at once, each into its own canvas (while the library also runs its own parallel
// loops): every result equals the one computed alone.
TEST(ShadingMesh, ConcurrentCallsIntoSeparateCanvases)
{
    std::vector<Point2d> verts;
    std::vector<Vec3i> faces;
    makeGridMesh(Size(120, 90), 20, false, 21, verts, faces);
    const std::vector<Vec3f> colors = randomColors(verts.size(), 22);
    RNG rng(23);
    std::vector<float> depth(verts.size());
    for (float& d : depth)
        d = float(rng.uniform(0, 4));
    Mat expected;
    shading::render(verts, faces, colors, depth, expected, shading::SHADE_GOURAUD, Size(120, 90));

    constexpr int kCallers = 6, kRepeats = 20;
    std::vector<Mat> results(kCallers * kRepeats);
    std::vector<std::thread> callers;
    for (int t = 0; t < kCallers; t++)
        callers.emplace_back([&, t] {
            for (int r = 0; r < kRepeats; r++)
                shading::render(verts, faces, colors, depth, results[t * kRepeats + r],
                                shading::SHADE_GOURAUD, Size(120, 90));
        });
    for (std::thread& c : callers)
        c.join();
    for (const Mat& m : results)
        EXPECT_EQ(maxAbsDiff(m, expected), 0.0);
}

// Occlusion by boxes: behind a near rectangle, farther rectangles peek out by exactly one sample
// column on its right or left, at 64-pixel word edges and inside words. The front-to-back pass
// skips a face only when every sample of its box is final, so that one column must still show
// the nearest far rectangle; everything else is the near one. Expected pixels worked by hand.
TEST(ShadingMesh, FacesPeekingOutByOneColumnStayVisible)
{
    const Size size(200, 40);
    for (int edge : {30, 62, 63, 64, 127, 128}) {
        for (bool peekRight : {true, false}) {
            // Samples [first, last] of every row: x from first - 0.5 to last + 0.5.
            std::vector<Point2d> verts;
            std::vector<Vec3i> faces;
            std::vector<Vec3d> colors;
            std::vector<double> depth;
            auto addRect = [&](int first, int last, const Vec3d& color, double d) {
                const int base = int(verts.size());
                for (const Point2d& p : {Point2d(first - 0.5, -1), Point2d(last + 0.5, -1),
                                         Point2d(first - 0.5, size.height + 1),
                                         Point2d(last + 0.5, size.height + 1)}) {
                    verts.push_back(p);
                    colors.push_back(color);
                    depth.push_back(d);
                }
                faces.push_back({base, base + 1, base + 3});
                faces.push_back({base, base + 3, base + 2});
            };
            const int nearFirst = peekRight ? 0 : edge + 1;
            const int nearLast = peekRight ? edge : size.width - 1;
            const int peek = peekRight ? edge + 1 : edge;
            // Many far layers, so the band has enough overdraw for the front-to-back pass; the
            // nearest (depth 1) is listed last.
            for (int layer = 40; layer >= 1; layer--)
                addRect(peekRight ? 0 : peek, peekRight ? peek : size.width - 1,
                        Vec3d(0, layer / 64.0, 0), layer);  // exact in float
            addRect(nearFirst, nearLast, Vec3d(1, 0, 0), 0);
            Mat img;
            shading::render(verts, faces, colors, depth, img, shading::SHADE_FLAT, size,
                            Scalar::all(1));
            Mat expected(size, CV_32FC3, Scalar::all(1));
            expected.colRange(nearFirst, nearLast + 1).setTo(Scalar(1, 0, 0));
            expected.col(peek).setTo(Scalar(0, 1 / 64.0, 0));
            EXPECT_EQ(maxAbsDiff(img, expected), 0.0)
                << "edge " << edge << (peekRight ? " right" : " left");
        }
    }
}
