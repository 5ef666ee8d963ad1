// Hand-worked cases for flats() and gouraud(): the fill rule, the seed's special cases, sub-pixel
// snapping, clipping, skipped non-finite input, canvases and input forms. Every expectation here
// was worked out by hand from the conventions in the header, not produced by the library.
#include "test_common.hpp"

#include <gtest/gtest.h>
#include <opencv2/shading.hpp>

#include <cmath>
#include <cstring>
#include <limits>

using namespace cv;
using shading_test::flatCoverage;
using shading_test::sentinelCanvas;
using shading_test::writtenMask;
using Pixels = std::set<std::pair<int, int>>;

namespace {

const std::vector<Vec3f> kRGB = {Vec3f(1, 0, 0), Vec3f(0, 1, 0), Vec3f(0, 0, 1)};

}  // namespace

// Right triangle (0,0) (4,0) (0,4). Top edge y = 0 and left edge x = 0 are owned; the
// hypotenuse x + y = 4 has the interior on its left, so it is a right edge and not owned.
// Covered: x >= 0, y >= 0, x + y < 4.
TEST(ShadingTriangle, TopAndLeftEdgesOwnedHypotenuseNot)
{
    const Pixels expected = {{0, 0}, {1, 0}, {2, 0}, {3, 0}, {0, 1}, {1, 1},
                             {2, 1}, {0, 2}, {1, 2}, {0, 3}};
    EXPECT_EQ(flatCoverage({6, 6}, {{0, 0}, {4, 0}, {0, 4}}), expected);
}

// The other half of the square: (4,4) (0,4) (4,0). Bottom edge y = 4 and right edge x = 4 are
// not owned; the hypotenuse now has the interior to its right (a left edge) and is owned.
// Covered: x < 4, y < 4, x + y >= 4.
TEST(ShadingTriangle, BottomAndRightEdgesNotOwned)
{
    const Pixels expected = {{3, 1}, {2, 2}, {3, 2}, {1, 3}, {2, 3}, {3, 3}};
    EXPECT_EQ(flatCoverage({6, 6}, {{4, 4}, {0, 4}, {4, 0}}), expected);
}

TEST(ShadingTriangle, TwoHalvesTileTheSquareExactlyOnce)
{
    Pixels a = flatCoverage({6, 6}, {{0, 0}, {4, 0}, {0, 4}});
    const Pixels b = flatCoverage({6, 6}, {{4, 4}, {0, 4}, {4, 0}});
    for (const auto& p : b)
        EXPECT_TRUE(a.insert(p).second) << "pixel drawn twice: " << p.first << "," << p.second;
    Pixels square;
    for (int y = 0; y < 4; y++)
        for (int x = 0; x < 4; x++)
            square.insert({x, y});
    EXPECT_EQ(a, square);
}

// Scan line y = 2 passes through the vertex (4,2), where the right boundary switches from
// x = 2y to x = 8 - 2y. Covered: x >= 0 and x < 2y (y <= 2) or x < 8 - 2y (y >= 2). The top and
// bottom vertices (rows 0 and 4) are single samples on a right edge: not covered.
TEST(ShadingTriangle, ScanLineThroughMiddleVertex)
{
    const Pixels expected = {{0, 1}, {1, 1}, {0, 2}, {1, 2}, {2, 2}, {3, 2}, {0, 3}, {1, 3}};
    EXPECT_EQ(flatCoverage({6, 6}, {{0, 0}, {4, 2}, {0, 4}}), expected);
}

// A triangle with a horizontal bottom edge and apex on top: (2,0) (0,4) (4,4)... the apex
// sample (2,0) lies on both slanted edges; the right one does not own it.
TEST(ShadingTriangle, ApexSampleNotOwnedBottomEdgeNotOwned)
{
    // Left edge x = 2 - y/2 (owned), right edge x = 2 + y/2 (not owned), bottom y = 4 (not).
    const Pixels expected = {{2, 1}, {1, 2}, {2, 2}, {1, 3}, {2, 3}, {3, 3}};
    EXPECT_EQ(flatCoverage({6, 6}, {{2, 0}, {0, 4}, {4, 4}}), expected);
}

TEST(ShadingTriangle, ResultIndependentOfVertexOrderAndWinding)
{
    const std::vector<Point2d> v = {{0.3, 0.7}, {9.6, 2.2}, {3.1, 8.9}};
    const Pixels expected = flatCoverage({12, 12}, v);
    EXPECT_FALSE(expected.empty());
    const int perms[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
    Mat first;
    for (const auto& p : perms) {
        const std::vector<Point2d> w = {v[p[0]], v[p[1]], v[p[2]]};
        EXPECT_EQ(flatCoverage({12, 12}, w), expected);
        // Gouraud values are bit-identical too: the plane is built from a canonical order.
        Mat canvas(12, 12, CV_32FC3, Scalar::all(-1));
        const std::vector<Vec3f> c = {kRGB[p[0]], kRGB[p[1]], kRGB[p[2]]};
        shading::gouraud(canvas, w, c);
        if (first.empty())
            first = canvas;
        else
            EXPECT_EQ(shading_test::maxAbsDiff(canvas, first), 0.0);
    }
}

TEST(ShadingTriangle, DegenerateTrianglesDrawNothing)
{
    EXPECT_TRUE(flatCoverage({8, 8}, {{2, 2}, {2, 2}, {2, 2}}).empty());  // one point
    EXPECT_TRUE(flatCoverage({8, 8}, {{1, 1}, {1, 1}, {5, 3}}).empty());  // coincident pair
    EXPECT_TRUE(flatCoverage({8, 8}, {{0, 0}, {2, 2}, {4, 4}}).empty());  // collinear
    EXPECT_TRUE(flatCoverage({8, 8}, {{0, 3}, {6, 3}, {2, 3}}).empty());  // horizontal line
    // Collinear after snapping to 1/256: 0.001 rounds to 0.
    EXPECT_TRUE(flatCoverage({8, 8}, {{0, 0}, {4, 0.001}, {7, 0}}).empty());
}

// A sliver between two sample rows covers no sample at all.
TEST(ShadingTriangle, SliverBetweenSamplesDrawsNothing)
{
    EXPECT_TRUE(flatCoverage({8, 8}, {{0, 1.2}, {7, 1.3}, {3, 1.9}}).empty());
}

// Half-pixel vertices: (0.5,0.5) (3.5,0.5) (0.5,3.5). No edge passes through a sample except the
// hypotenuse x + y = 4 (a right edge), so: x >= 1, y >= 1, x + y < 4.
TEST(ShadingTriangle, HalfPixelVertices)
{
    const Pixels expected = {{1, 1}, {2, 1}, {1, 2}};
    EXPECT_EQ(flatCoverage({6, 6}, {{0.5, 0.5}, {3.5, 0.5}, {0.5, 3.5}}), expected);
}

// Snapping is llround(v * 256): 0.001 snaps onto column 0 (owned left edge), 0.003 snaps to
// 1/256 and leaves column 0 outside.
TEST(ShadingTriangle, SubpixelSnapping)
{
    const Pixels onEdge = flatCoverage({6, 6}, {{0.001, 0}, {4, 0}, {0.001, 4}});
    const Pixels inside = flatCoverage({6, 6}, {{0.003, 0}, {4, 0}, {0.003, 4}});
    EXPECT_EQ(onEdge.count({0, 2}), 1u);
    EXPECT_EQ(inside.count({0, 2}), 0u);
    EXPECT_EQ(inside.count({1, 2}), 1u);
}

// Gouraud on (0,0) (4,0) (0,4) with red, green, blue: colour = (1 - x/4 - y/4, x/4, y/4).
TEST(ShadingTriangle, GouraudInterpolatesAffinely)
{
    Mat canvas(6, 6, CV_32FC3, Scalar::all(-1));
    shading::gouraud(canvas, std::vector<Point>{{0, 0}, {4, 0}, {0, 4}}, kRGB);
    const Vec3f v00 = canvas.at<Vec3f>(0, 0), v30 = canvas.at<Vec3f>(0, 3),
                v12 = canvas.at<Vec3f>(2, 1), v03 = canvas.at<Vec3f>(3, 0);
    const float tol = 1e-6f;
    EXPECT_NEAR(v00[0], 1.0f, tol); EXPECT_NEAR(v00[1], 0.0f, tol); EXPECT_NEAR(v00[2], 0.0f, tol);
    EXPECT_NEAR(v30[0], 0.25f, tol); EXPECT_NEAR(v30[1], 0.75f, tol); EXPECT_NEAR(v30[2], 0.0f, tol);
    EXPECT_NEAR(v12[0], 0.25f, tol); EXPECT_NEAR(v12[1], 0.25f, tol); EXPECT_NEAR(v12[2], 0.5f, tol);
    EXPECT_NEAR(v03[0], 0.25f, tol); EXPECT_NEAR(v03[1], 0.0f, tol); EXPECT_NEAR(v03[2], 0.75f, tol);
    EXPECT_EQ(canvas.at<Vec3f>(1, 3), Vec3f(-1, -1, -1));  // x + y = 4: not covered
}

TEST(ShadingTriangle, FlatUsesMeanColour)
{
    Mat canvas(6, 6, CV_32FC3, Scalar::all(-1));
    shading::flats(canvas, std::vector<Point>{{0, 0}, {4, 0}, {0, 4}},
                   std::vector<Vec3f>{{0.3f, 0.f, 1.f}, {0.6f, 0.f, 1.f}, {0.f, 0.9f, 1.f}});
    for (int y = 0; y < 4; y++)
        for (int x = 0; x + y < 4; x++) {
            const Vec3f c = canvas.at<Vec3f>(y, x);
            EXPECT_NEAR(c[0], 0.3f, 1e-6f);
            EXPECT_NEAR(c[1], 0.3f, 1e-6f);
            EXPECT_NEAR(c[2], 1.0f, 1e-6f);
        }
}

// 8-bit canvases take colours in 0..255, rounded and saturated.
TEST(ShadingTriangle, EightBitCanvasRoundsAndSaturates)
{
    Mat canvas(6, 6, CV_8UC3, Scalar::all(7));
    shading::flats(canvas, std::vector<Point>{{0, 0}, {4, 0}, {0, 4}},
                   std::vector<Vec3d>{{10, 300, -5}, {20, 300, -5}, {31, 300, -5}});
    EXPECT_EQ(canvas.at<Vec3b>(1, 1), Vec3b(20, 255, 0));  // mean 20.33 rounds to 20
    EXPECT_EQ(canvas.at<Vec3b>(3, 3), Vec3b(7, 7, 7));
    Mat g(6, 6, CV_8UC3, Scalar::all(7));
    shading::gouraud(g, std::vector<Point>{{0, 0}, {4, 0}, {0, 4}},
                     std::vector<Vec3d>{{0, 0, 0}, {255, 0, 0}, {0, 255, 0}});
    EXPECT_EQ(g.at<Vec3b>(0, 1), Vec3b(64, 0, 0));   // 63.75 -> 64
    EXPECT_EQ(g.at<Vec3b>(1, 1), Vec3b(64, 64, 0));  // (63.75, 63.75) -> (64, 64)
}

// A triangle far larger than the canvas with vertices near +-1e9 is clipped exactly. Its long
// edge is the line x - y = 0.5 and the interior lies where x - y < 0.5: covered iff x <= y.
TEST(ShadingTriangle, HugeCoordinatesClipExactly)
{
    const std::vector<Point2d> v = {{-1e9 + 0.5, -1e9}, {1e9 + 0.5, 1e9}, {-1e9, 1e9}};
    const Pixels covered = flatCoverage({40, 30}, v);
    Pixels expected;
    for (int y = 0; y < 30; y++)
        for (int x = 0; x <= y && x < 40; x++)
            expected.insert({x, y});
    EXPECT_EQ(covered, expected);
    // Covering the whole canvas.
    EXPECT_EQ(flatCoverage({40, 30}, {{-1e9, -1e9}, {3e9, -1e9}, {-1e9, 3e9}}).size(), 1200u);
    // Wholly off canvas.
    EXPECT_TRUE(flatCoverage({40, 30}, {{1e9, 1e9}, {2e9, 1e9}, {1e9, 2e9}}).empty());
    EXPECT_TRUE(flatCoverage({40, 30}, {{-50, 0}, {-1, 0}, {-1, 29}}).empty());
}

TEST(ShadingTriangle, NonFiniteOrOutOfRangeVerticesAreSkipped)
{
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const double inf = std::numeric_limits<double>::infinity();
    for (double bad : {nan, inf, -inf, 1e13, -1e300}) {
        EXPECT_TRUE(flatCoverage({8, 8}, {{0, 0}, {bad, 0}, {0, 6}}).empty()) << bad;
        EXPECT_TRUE(flatCoverage({8, 8}, {{0, 0}, {6, 0}, {0, bad}}).empty()) << bad;
        Mat canvas = sentinelCanvas({8, 8}), before = canvas.clone();
        shading::gouraud(canvas, std::vector<Point2d>{{0, 0}, {6, 0}, {bad, bad}}, kRGB);
        EXPECT_EQ(countNonZero(writtenMask(canvas, before)), 0);
    }
}

// An ROI canvas: coordinates are relative to the ROI and nothing outside it changes.
TEST(ShadingTriangle, RoiCanvasIsClippedToTheRoi)
{
    Mat big(20, 20, CV_32FC3, Scalar::all(-1));
    Mat before = big.clone();
    Mat roi = big(Rect(5, 6, 8, 7));
    shading::flats(roi, std::vector<Point2d>{{-10, -10}, {30, -10}, {-10, 30}}, kRGB);
    const Mat written = writtenMask(big, before);
    EXPECT_EQ(countNonZero(written), 8 * 7);
    EXPECT_EQ(countNonZero(written(Rect(5, 6, 8, 7))), 8 * 7);
}

// Every accepted input form gives the same pixels.
TEST(ShadingTriangle, AllInputFormsAgree)
{
    Mat expected(10, 10, CV_32FC3, Scalar::all(-1));
    shading::gouraud(expected, std::vector<Point2d>{{1, 1}, {8, 2}, {3, 9}}, kRGB);

    Mat m32f = (Mat_<float>(3, 2) << 1, 1, 8, 2, 3, 9);
    Mat m64f, m32s;
    m32f.convertTo(m64f, CV_64F);
    m32f.convertTo(m32s, CV_32S);
    Mat colors32f = (Mat_<float>(3, 3) << 1, 0, 0, 0, 1, 0, 0, 0, 1);
    Mat colors64f, colors32s;
    colors32f.convertTo(colors64f, CV_64F);
    colors32f.convertTo(colors32s, CV_32S);
    const Mat rowOfPoints = m32f.reshape(2, 1), columnOfPoints = m64f.reshape(2, 3);
    const Mat rowOfColors = colors32f.reshape(3, 1);
    const std::vector<Point2f> points2f = {{1, 1}, {8, 2}, {3, 9}};
    const std::vector<Point> points2i = {{1, 1}, {8, 2}, {3, 9}};
    const std::vector<Vec3d> colors3d = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    const std::vector<_InputArray> vertexForms = {
        _InputArray(points2f), _InputArray(points2i),
        _InputArray(m32f), _InputArray(m64f), _InputArray(m32s),
        _InputArray(rowOfPoints), _InputArray(columnOfPoints)};
    const std::vector<_InputArray> colorForms = {
        _InputArray(kRGB), _InputArray(colors3d),
        _InputArray(colors32f), _InputArray(colors64f), _InputArray(colors32s),
        _InputArray(rowOfColors)};
    for (size_t i = 0; i < vertexForms.size(); i++)
        for (size_t j = 0; j < colorForms.size(); j++) {
            Mat canvas(10, 10, CV_32FC3, Scalar::all(-1));
            shading::gouraud(canvas, vertexForms[i], colorForms[j]);
            EXPECT_EQ(shading_test::maxAbsDiff(canvas, expected), 0.0) << "forms " << i << "," << j;
        }
}

// Found by the fuzzer: a colour far beyond float's range made the Gouraud x-step infinite, and
// the first pixel of a span (step * 0) NaN. The sample on vertex (3, 18) must get that vertex's
// colour exactly: green 2.5, which rounds (half to even) to 2.
TEST(ShadingTriangle, GouraudColoursBeyondFloatRange)
{
    Mat canvas(40, 10, CV_8UC3, Scalar::all(7));
    shading::gouraud(canvas, std::vector<Point2d>{{3, 18}, {3, 30}, {4, 16.5}},
                     std::vector<Vec3d>{{89, 2.5, 64}, {8.7, 239.3, 13.1}, {62.9, -1.7e48, 190.4}});
    EXPECT_EQ(canvas.at<Vec3b>(18, 3), Vec3b(89, 2, 64));
}

// Found by the fuzzer: with a colour of -2.8e40, the span's first value is below float's range
// (-inf) and stepping by a huge positive step gave -inf + inf = NaN. Such colours are evaluated per
// pixel: the sample (10, 16) is -2.8e40 * 0.01156... = -3.2085e38, within float's range (worked out
// from its barycentric weight: the vertex at (~0, 22) weighs 0.0115607 there).
TEST(ShadingTriangle, GouraudHugeColoursNeverNaN)
{
    Mat canvas(24, 16, CV_32FC3, Scalar::all(0));
    shading::gouraud(canvas,
                     std::vector<Point2d>{{2.7863571129009264e-313, 22}, {14, -3}, {10, 16.5}},
                     std::vector<Vec3d>{{-4, -2.7753559049153819e+40, -4}, {-4, -4, -4}, {-4, -4, -4}});
    for (int y = 0; y < canvas.rows; y++)
        for (int x = 0; x < canvas.cols; x++)
            for (int k = 0; k < 3; k++)
                ASSERT_FALSE(std::isnan(canvas.at<Vec3f>(y, x)[k])) << x << "," << y << "," << k;
    EXPECT_NEAR(canvas.at<Vec3f>(16, 10)[1], -3.2085e38, 1e34);
    EXPECT_EQ(canvas.at<Vec3f>(16, 10)[0], -4.f);
}

// The same huge colour in each channel in turn, and at each vertex: the per-pixel path is taken
// whichever of the nine values is out of range.
TEST(ShadingTriangle, GouraudHugeColourInAnyChannelNeverNaN)
{
    const std::vector<Point2d> verts = {{2.7863571129009264e-313, 22}, {14, -3}, {10, 16.5}};
    for (int vertex = 0; vertex < 3; vertex++)
        for (int k = 0; k < 3; k++) {
            std::vector<Vec3d> colors(3, Vec3d(-4, -4, -4));
            colors[vertex][k] = -2.7753559049153819e+40;
            Mat canvas(24, 16, CV_32FC3, Scalar::all(0));
            shading::gouraud(canvas, verts, colors);
            for (int y = 0; y < canvas.rows; y++)
                for (int x = 0; x < canvas.cols; x++)
                    ASSERT_FALSE(std::isnan(canvas.at<Vec3f>(y, x)[k]))
                        << "vertex " << vertex << ", channel " << k << " at " << x << "," << y;
            if (vertex == 0) {  // worked out above: weight 0.0115607 at (10, 16)
                EXPECT_NEAR(canvas.at<Vec3f>(16, 10)[k], -3.2085e38, 1e34) << k;
            }
        }
}

// A mesh checks its colours' range once per draw (no face then checks its own): a huge colour at
// one vertex still sends the faces that use it down the per-pixel path, and the mesh draws what
// gouraud() draws face by face (no NaN; the other faces stepped as usual).
TEST(ShadingTriangle, MeshWithOneHugeColourEqualsFaceByFace)
{
    const std::vector<Point2d> verts = {{1, 1}, {20, 2}, {3, 22}, {22, 21}, {12, 30}};
    const std::vector<Vec3i> faces = {{0, 1, 2}, {1, 3, 2}, {2, 3, 4}};  // no overlap
    for (int vertex = 0; vertex < 5; vertex++) {
        std::vector<Vec3d> colors = {
            {0.1, 0.2, 0.3}, {0.9, 0.1, 0.4}, {0.3, 0.8, 0.2}, {0.5, 0.5, 0.9}, {0.7, 0.3, 0.1}};
        colors[vertex][vertex % 3] = -2.7753559049153819e+40;
        Mat mesh(32, 24, CV_32FC3, Scalar::all(0)), byFace = mesh.clone();
        shading::drawMesh(mesh, verts, faces, colors, noArray(), shading::SHADE_GOURAUD);
        for (const Vec3i& f : faces)
            shading::gouraud(byFace, std::vector<Point2d>{verts[f[0]], verts[f[1]], verts[f[2]]},
                             std::vector<Vec3d>{colors[f[0]], colors[f[1]], colors[f[2]]});
        EXPECT_EQ(cv::norm(mesh, byFace, NORM_INF), 0) << "huge colour at vertex " << vertex;
        for (int y = 0; y < mesh.rows; y++)
            for (int x = 0; x < mesh.cols; x++)
                for (int k = 0; k < 3; k++)
                    ASSERT_FALSE(std::isnan(mesh.at<Vec3f>(y, x)[k])) << x << "," << y;
    }
}

// The same for a mesh big enough that its colours are converted (and their range checked) in
// parallel slices of 32,768 values: a huge colour (or a NaN) in the last slice only, given as
// doubles or as floats, still reaches the faces that use it.
TEST(ShadingTriangle, BigMeshWithOneHugeColourInItsLastSliceEqualsFaceByFace)
{
    const int n = 120, m = 100;  // 121 x 101 vertices: 36,663 colour values
    std::vector<Point2d> verts;
    for (int j = 0; j <= m; j++)
        for (int i = 0; i <= n; i++)
            verts.push_back(Point2d(6 * i + 0.3, 6 * j + 0.6));  // spans of up to 6 steps
    std::vector<Vec3i> faces;
    for (int j = 0; j < m; j++)
        for (int i = 0; i < n; i++) {
            const int a = j * (n + 1) + i, b = a + 1, c = a + n + 1, d = c + 1;
            faces.push_back(Vec3i(a, b, d));
            faces.push_back(Vec3i(a, d, c));
        }
    const int last = int(verts.size()) - 1 - 50;  // past value 32,768, away from the border
    for (double odd : {-2.7753559049153819e+40, 3e38, std::numeric_limits<double>::quiet_NaN()})
        for (int depth : {CV_64F, CV_32F}) {
            if (depth == CV_32F && std::abs(odd) > std::numeric_limits<float>::max())
                continue;  // not a float
            Mat colors(int(verts.size()), 3, CV_64F);
            for (int v = 0; v < colors.rows; v++)
                for (int k = 0; k < 3; k++)
                    colors.at<double>(v, k) = 0.25 + 0.5 * ((v * 7 + k * 3) % 11) / 11.0;
            colors.at<double>(last, 1) = odd;
            Mat given, asDrawn;  // asDrawn: the values the mesh draws (floats are exact)
            colors.convertTo(given, depth);
            given.convertTo(asDrawn, CV_64F);
            Mat mesh(6 * m + 2, 6 * n + 2, CV_32FC3, Scalar::all(0)), byFace = mesh.clone();
            shading::drawMesh(mesh, verts, faces, given, noArray(), shading::SHADE_GOURAUD);
            for (const Vec3i& f : faces) {
                const std::vector<Vec3d> c = {asDrawn.at<Vec3d>(f[0]), asDrawn.at<Vec3d>(f[1]),
                                              asDrawn.at<Vec3d>(f[2])};
                shading::gouraud(byFace,
                                 std::vector<Point2d>{verts[f[0]], verts[f[1]], verts[f[2]]}, c);
            }
            // Bit for bit (NaN pixels included, which no norm compares).
            EXPECT_EQ(std::memcmp(mesh.data, byFace.data, mesh.total() * mesh.elemSize()), 0)
                << "colour " << odd << ", depth " << depth;
            if (std::isnan(odd))
                continue;
            for (int y = 0; y < mesh.rows; y++)
                for (int x = 0; x < mesh.cols; x++)
                    for (int k = 0; k < 3; k++)
                        ASSERT_FALSE(std::isnan(mesh.at<Vec3f>(y, x)[k])) << x << "," << y;
        }
}
