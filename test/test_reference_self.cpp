// This file is part of opencv_shading. License: Apache-2.0.
//
// Tests of the brute-force reference itself (test/reference/shading_reference.hpp) on cases worked
// out by hand. The library is not used here: these tests make sure the yardstick is straight
// before test_vs_reference.cpp measures the library with it.
//
// Coverage pictures: one string per row y (top row first), one character per column x;
// '#' = the sample point (x, y) is covered, '.' = not covered. y grows downward.

#include <gtest/gtest.h>

#include <opencv2/core.hpp>

#include "reference/shading_reference.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

namespace {

using cv::Point2d;
using cv::Vec3d;
using Picture = std::vector<std::string>;

std::string toText(const cv::Mat& mask)
{
    std::string s;
    for (int y = 0; y < mask.rows; y++) {
        for (int x = 0; x < mask.cols; x++)
            s += mask.at<uchar>(y, x) ? '#' : '.';
        s += '\n';
    }
    return s;
}

std::string toText(const Picture& pic)
{
    std::string s;
    for (const std::string& row : pic)
        s += row + '\n';
    return s;
}

cv::Size sizeOf(const Picture& pic)
{
    return cv::Size((int)pic[0].size(), (int)pic.size());
}

// The reference's coverage of triangle (a, b, c) on a canvas the size of `expected` must be
// exactly the picture, for all 6 vertex orders.
void expectCoverage(Point2d a, Point2d b, Point2d c, const Picture& expected)
{
    const std::string want = toText(expected);
    Point2d v[3] = { a, b, c };
    std::sort(v, v + 3, [](const Point2d& p, const Point2d& q) {
        return p.x != q.x ? p.x < q.x : p.y < q.y;
    });
    do {
        SCOPED_TRACE(cv::format("vertices (%g, %g) (%g, %g) (%g, %g)", v[0].x, v[0].y, v[1].x,
                                v[1].y, v[2].x, v[2].y));
        EXPECT_EQ(want, toText(shading_ref::coverageMask(sizeOf(expected), v)));
    } while (std::next_permutation(v, v + 3, [](const Point2d& p, const Point2d& q) {
        return p.x != q.x ? p.x < q.x : p.y < q.y;
    }));
}

// True if the quad q[0..3], snapped to 1/256 px, turns strictly the same way at every corner.
bool strictlyConvexAfterSnapping(const Point2d q[4])
{
    int pos = 0, neg = 0;
    for (int k = 0; k < 4; k++) {
        shading_ref::Fixed a, b, c;
        shading_ref::snap(q[k], a);
        shading_ref::snap(q[(k + 1) % 4], b);
        shading_ref::snap(q[(k + 2) % 4], c);
        const shading_ref::Int128 e = shading_ref::edgeFunction(a, b, c);
        pos += e > 0;
        neg += e < 0;
    }
    return pos == 4 || neg == 4;
}

int countCovered(cv::Size size, Point2d a, Point2d b, Point2d c)
{
    const Point2d v[3] = { a, b, c };
    return cv::countNonZero(shading_ref::coverageMask(size, v));
}

}  // namespace

// Right triangle (0,0) (4,0) (0,4).
//  - Edge y = 0 from (0,0) to (4,0): horizontal, interior below -> TOP edge: its samples count.
//  - Edge x = 0 from (0,4) to (0,0): interior at larger x -> LEFT edge: its samples count.
//  - Hypotenuse x + y = 4: interior at smaller x -> RIGHT edge: its samples do not count.
// So the covered samples are exactly x >= 0, y >= 0, x + y <= 3: 4 + 3 + 2 + 1 = 10 pixels.
// Vertex (0,0) lies on a top and a left edge: covered. (4,0) and (0,4) lie on the hypotenuse: not.
TEST(ShadingReference, RightTriangleIntegerVertices)
{
    expectCoverage({0, 0}, {4, 0}, {0, 4}, {
        "####..",
        "###...",
        "##....",
        "#.....",
        "......",
        "......",
    });
    EXPECT_EQ(10, countCovered({6, 6}, {0, 0}, {4, 0}, {0, 4}));
}

// Top edge: (1,1) (7,1) (4,4). Edge y = 1 has the interior below it: top edge, so row 1 is drawn
// from x = 1 to 6. Left edge y = x (interior to its right) is drawn; right edge x + y = 8 is not:
//   row 1: x = 1..6   (x = 7 is the vertex on the right edge)
//   row 2: x = 2..5   (x = 2 on the left edge; x = 6 on the right edge)
//   row 3: x = 3..4
//   row 4: the apex (4,4) lies on the left and the right edge -> not covered.
TEST(ShadingReference, TopEdgeIsDrawn)
{
    expectCoverage({1, 1}, {7, 1}, {4, 4}, {
        ".........",
        ".######..",
        "..####...",
        "...##....",
        ".........",
        ".........",
    });
}

// Bottom edge: the same triangle upside down, (1,4) (7,4) (4,1). Edge y = 4 has the interior
// above it: a bottom edge, so row 4 is not drawn. Left edge x + y = 5, right edge y = x - 3:
//   row 1: the apex (4,1) lies on the left and the right edge -> not covered.
//   row 2: x = 3..4   (x = 3 on the left edge; x = 5 on the right edge)
//   row 3: x = 2..5
//   row 4: on the bottom edge -> nothing.
TEST(ShadingReference, BottomEdgeIsNotDrawn)
{
    expectCoverage({1, 4}, {7, 4}, {4, 1}, {
        ".........",
        ".........",
        "...##....",
        "..####...",
        ".........",
        ".........",
    });
}

// A vertical LEFT edge x = 2 (interior to its right): (2,0) (2,6) (5,3).
// Its samples (2,1)..(2,5) are covered. The two sloped edges y = x - 2 and x + y = 8 have the
// interior to their left: right edges, so (3,1), (4,2), (4,4), (3,5) are not covered, nor the
// vertices (2,0), (2,6) (each also on a right edge) and (5,3) (on two right edges).
TEST(ShadingReference, LeftEdgeIsDrawn)
{
    expectCoverage({2, 0}, {2, 6}, {5, 3}, {
        ".......",
        "..#....",
        "..##...",
        "..###..",
        "..##...",
        "..#....",
        ".......",
    });
}

// The mirror image: a vertical RIGHT edge x = 5 (interior to its left): (5,0) (5,6) (2,3).
// Column 5 is not covered. The sloped edges x + y = 5 and y = x + 1 are left edges, so (4,1),
// (3,2), (3,4), (4,5) are covered, and so is the vertex (2,3), which lies on two left edges.
TEST(ShadingReference, RightEdgeIsNotDrawn)
{
    expectCoverage({5, 0}, {5, 6}, {2, 3}, {
        ".......",
        "....#..",
        "...##..",
        "..###..",
        "...##..",
        "....#..",
        ".......",
    });
}

// A sample on a vertex is covered only when every edge through it is a top or left edge.
TEST(ShadingReference, VertexSamples)
{
    const Point2d right[3] = { {0, 0}, {4, 0}, {0, 4} };
    EXPECT_TRUE(shading_ref::covers(right, 0, 0));   // top + left
    EXPECT_FALSE(shading_ref::covers(right, 4, 0));  // top + right (hypotenuse)
    EXPECT_FALSE(shading_ref::covers(right, 0, 4));  // left + right (hypotenuse)

    const Point2d leftPointing[3] = { {5, 0}, {5, 6}, {2, 3} };
    EXPECT_TRUE(shading_ref::covers(leftPointing, 2, 3));   // left + left
    EXPECT_FALSE(shading_ref::covers(leftPointing, 5, 0));  // right + left
    EXPECT_FALSE(shading_ref::covers(leftPointing, 5, 6));  // right + left

    const Point2d rightPointing[3] = { {2, 0}, {2, 6}, {5, 3} };
    EXPECT_FALSE(shading_ref::covers(rightPointing, 5, 3));  // right + right

    // Square corner at the bottom right: (0,4) (4,4) (4,0) has a bottom edge y = 4 and a right
    // edge x = 4; its hypotenuse x + y = 4 has the interior at larger x: a left edge.
    const Point2d lowerRight[3] = { {0, 4}, {4, 4}, {4, 0} };
    EXPECT_FALSE(shading_ref::covers(lowerRight, 4, 4));  // bottom + right
    EXPECT_FALSE(shading_ref::covers(lowerRight, 0, 4));  // bottom + left
    EXPECT_FALSE(shading_ref::covers(lowerRight, 4, 0));  // right + left
    EXPECT_TRUE(shading_ref::covers(lowerRight, 2, 2));   // on the left edge only
    EXPECT_TRUE(shading_ref::covers(lowerRight, 3, 3));   // strictly inside
}

// Half-pixel vertices. The square [0.5, 3.5]^2 holds the samples x, y in 1..3.
//  A = (0.5,0.5) (3.5,0.5) (0.5,3.5): x >= 1, y >= 1 and x + y < 4 (x + y = 4 is its right
//      edge): (1,1) (2,1) (1,2).
//  B = (3.5,0.5) (3.5,3.5) (0.5,3.5): x <= 3, y <= 3 and x + y >= 4 (x + y = 4 is its left
//      edge): (3,1) (2,2) (3,2) (1,3) (2,3) (3,3).
// Together: all 9 samples of the square, each once.
TEST(ShadingReference, HalfPixelVertices)
{
    expectCoverage({0.5, 0.5}, {3.5, 0.5}, {0.5, 3.5}, {
        ".....",
        ".##..",
        ".#...",
        ".....",
        ".....",
    });
    expectCoverage({3.5, 0.5}, {3.5, 3.5}, {0.5, 3.5}, {
        ".....",
        "...#.",
        "..##.",
        ".###.",
        ".....",
    });
}

// Snapping to 1/256 px happens before the edge tests.
//  - x = 2 + 1/1024 snaps to 2 + llround(0.25)/256 = 2: identical to LeftEdgeIsDrawn.
//  - x = 2 + 1/256 is a real shift: column 2 is now left of the edge; the right edges move right
//    by less than a pixel, e.g. at y = 2 to x = (x0 + 10)/3 = 4.0013, so (4,2) becomes inside.
//  - x = 2 + 1/512 is exactly half-way (512.5 units): llround rounds half away from zero, to
//    2 + 1/256 (round-half-even would give 2 and draw column 2).
TEST(ShadingReference, SnapToSubpixelGrid)
{
    const Picture same = {
        ".......",
        "..#....",
        "..##...",
        "..###..",
        "..##...",
        "..#....",
        ".......",
    };
    const Picture shifted = {
        ".......",
        "...#...",
        "...##..",
        "...##..",
        "...##..",
        "...#...",
        ".......",
    };
    const double q = 1.0 / 1024, s = 1.0 / 256, h = 1.0 / 512;
    expectCoverage({2 + q, 0}, {2 + q, 6}, {5, 3}, same);
    expectCoverage({2 + s, 0}, {2 + s, 6}, {5, 3}, shifted);
    expectCoverage({2 + h, 0}, {2 + h, 6}, {5, 3}, shifted);
}

// Half-way values round away from zero on the negative side too. The left edge from
// P = (0, -2) to Q = (2, 2) passes through the sample (1, 0) (covered: left edge, R = (6, 2)).
//  - P.y = -2 - 1/512 = -512.5 units -> -513 (away from zero): the edge moves right of (1, 0), so
//    (1, 0) is outside. (floor(v + 0.5) and round-half-even would give -512: on the edge.)
//  - P.y = -2 + 1/512 = -511.5 units -> -512: back on the edge, covered.
TEST(ShadingReference, SnapRoundsHalfAwayFromZero)
{
    const Point2d onEdge[3] = { {0, -2}, {2, 2}, {6, 2} };
    EXPECT_TRUE(shading_ref::covers(onEdge, 1, 0));
    const Point2d below[3] = { {0, -2 - 1.0 / 512}, {2, 2}, {6, 2} };
    EXPECT_FALSE(shading_ref::covers(below, 1, 0));
    const Point2d above[3] = { {0, -2 + 1.0 / 512}, {2, 2}, {6, 2} };
    EXPECT_TRUE(shading_ref::covers(above, 1, 0));
    EXPECT_EQ(-513, std::llround((-2 - 1.0 / 512) * 256));

    // The same in x. Triangle (-2,0) (2,2) (2,6): the edge from (-2,0) to (2,2) passes through
    // the sample (0,1) with the interior to its left (a right edge): not covered.
    //  - P.x = -2 + 1/512 = -511.5 units -> -512 (away from zero): still on the edge, not covered
    //    (floor(v + 0.5) would give -511: the edge moves right of (0,1), which becomes inside).
    //  - P.x = -2 + 1/256: a real shift right, (0,1) is inside.
    const Point2d onRight[3] = { {-2, 0}, {2, 2}, {2, 6} };
    EXPECT_FALSE(shading_ref::covers(onRight, 0, 1));
    const Point2d half[3] = { {-2 + 1.0 / 512, 0}, {2, 2}, {2, 6} };
    EXPECT_FALSE(shading_ref::covers(half, 0, 1));
    const Point2d whole[3] = { {-2 + 1.0 / 256, 0}, {2, 2}, {2, 6} };
    EXPECT_TRUE(shading_ref::covers(whole, 0, 1));
}

// Zero twice-area covers nothing: collinear, repeated, or collapsed by snapping. A sliver that
// stays 1/256 px tall is a real triangle: its top edge y = 0 gives row 0 from x = 0 to 9.
TEST(ShadingReference, DegenerateTriangles)
{
    const cv::Size sz(12, 4);
    EXPECT_EQ(0, countCovered(sz, {0, 0}, {2, 2}, {4, 4}));          // collinear
    EXPECT_EQ(0, countCovered(sz, {0, 0}, {10, 0}, {5, 0}));         // collinear, horizontal
    EXPECT_EQ(0, countCovered(sz, {1, 1}, {1, 1}, {5, 3}));          // repeated vertex
    EXPECT_EQ(0, countCovered(sz, {2, 2}, {2, 2}, {2, 2}));          // a point
    EXPECT_EQ(0, countCovered(sz, {0, 0}, {10, 0}, {5, 1.0 / 1024})); // snaps to y = 0
    EXPECT_EQ(0, countCovered(sz, {0.5, 0.5}, {1.5, 1.5}, {3.0000001, 3})); // snaps collinear
    expectCoverage({0, 0}, {10, 0}, {5, 1.0 / 256}, {
        "##########..",
        "............",
        "............",
        "............",
    });
}

// Non-finite or too large (|v| > 2^40) coordinates: nothing. Exactly 2^40 is fine: the triangle
// (0,0) (2^40,0) (0,8) covers rows 0..7 of a small canvas (its hypotenuse is at y = 8 - tiny).
TEST(ShadingReference, CoordinateLimits)
{
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const double inf = std::numeric_limits<double>::infinity();
    const double big = 1099511627776.0;  // 2^40
    const double tooBig = std::nextafter(big, 2 * big);
    const cv::Size sz(16, 10);
    EXPECT_EQ(0, countCovered(sz, {nan, 0}, {8, 0}, {0, 8}));
    EXPECT_EQ(0, countCovered(sz, {0, 0}, {8, nan}, {0, 8}));
    EXPECT_EQ(0, countCovered(sz, {0, 0}, {8, 0}, {inf, 8}));
    EXPECT_EQ(0, countCovered(sz, {0, -inf}, {8, 0}, {0, 8}));
    EXPECT_EQ(0, countCovered(sz, {0, 0}, {tooBig, 0}, {0, 8}));
    EXPECT_EQ(0, countCovered(sz, {0, 0}, {8, 0}, {0, -tooBig}));
    EXPECT_EQ(16 * 8, countCovered(sz, {0, 0}, {big, 0}, {0, 8}));
    EXPECT_EQ(16 * 8, countCovered(sz, {0, -big}, {big, 8}, {-big, 8}));  // y in [0, 7]

    // Huge triangles are clipped by the bounding box, and the arithmetic stays exact: a
    // horizontal top edge at y = 3 from x = -1e9 to 1e9 still draws row 3.
    const Point2d wide[3] = { {-1e9, 3}, {1e9, 3}, {0, 1e9} };
    const cv::Mat m = shading_ref::coverageMask(sz, wide);
    EXPECT_EQ(0, cv::countNonZero(m.rowRange(0, 3)));
    EXPECT_EQ(16 * 7, cv::countNonZero(m.rowRange(3, 10)));
}

// Winding and vertex order do not matter, for random fractional triangles too.
TEST(ShadingReference, WindingIndependence)
{
    cv::RNG rng(12345);
    const cv::Size sz(24, 20);
    for (int i = 0; i < 300; i++) {
        Point2d v[3];
        for (Point2d& p : v)  // half of them on the half-pixel grid, to hit edges often
            p = (i % 2) ? Point2d(rng.uniform(-4, 56) / 2.0, rng.uniform(-4, 46) / 2.0)
                        : Point2d(rng.uniform(-2.0, 26.0), rng.uniform(-2.0, 22.0));
        const cv::Mat m0 = shading_ref::coverageMask(sz, v);
        const int perm[6][3] = { {0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0} };
        for (const auto& p : perm) {
            const Point2d w[3] = { v[p[0]], v[p[1]], v[p[2]] };
            EXPECT_EQ(0, cv::norm(m0, shading_ref::coverageMask(sz, w), cv::NORM_INF)) << i;
        }
    }
}

// coverageMask and fillTriangle visit only the clipped bounding box; a plain loop over every
// pixel with covers() must agree, for small, clipped and huge triangles.
TEST(ShadingReference, BoundingBoxClippingIsHarmless)
{
    cv::RNG rng(2024);
    const cv::Size sz(20, 16);
    for (int i = 0; i < 600; i++) {
        const double range = i < 200 ? 12.0 : i < 400 ? 60.0 : 1e9;
        Point2d v[3];
        for (Point2d& p : v)
            p = Point2d(std::round(rng.uniform(-range, range) * 2) / 2,
                        std::round(rng.uniform(-range, range) * 2) / 2);
        cv::Mat full(sz, CV_8UC1, cv::Scalar(0));
        for (int y = 0; y < sz.height; y++)
            for (int x = 0; x < sz.width; x++)
                full.at<uchar>(y, x) = shading_ref::covers(v, x, y) ? 1 : 0;
        EXPECT_EQ(toText(full), toText(shading_ref::coverageMask(sz, v))) << i;
        cv::Mat canvas(sz, CV_32FC3, cv::Scalar::all(-1));
        const Vec3d c[3] = { {1, 1, 1}, {1, 1, 1}, {1, 1, 1} };
        shading_ref::fillTriangle(canvas, v, c, false);
        cv::Mat drawn;
        cv::inRange(canvas, cv::Scalar::all(1), cv::Scalar::all(1), drawn);
        EXPECT_EQ(toText(full), toText(drawn)) << i;
    }
}

// Two triangles sharing the diagonal of the square [1,5]^2 cover its 16 samples x, y in 1..4
// (top edge y = 1 and left edge x = 1 in, right edge x = 5 and bottom edge y = 5 out) once each,
// whichever diagonal is used.
TEST(ShadingReference, SharedDiagonalCoversSquareOnce)
{
    const cv::Size sz(7, 7);
    const Picture square = {
        ".......",
        ".####..",
        ".####..",
        ".####..",
        ".####..",
        ".......",
        ".......",
    };
    const Point2d a(1, 1), b(5, 1), c(5, 5), d(1, 5);
    const Point2d splits[2][2][3] = { { {a, b, c}, {a, c, d} }, { {a, b, d}, {b, c, d} } };
    for (const auto& split : splits) {
        const cv::Mat m1 = shading_ref::coverageMask(sz, split[0]);
        const cv::Mat m2 = shading_ref::coverageMask(sz, split[1]);
        EXPECT_EQ(0, cv::countNonZero(m1 & m2));  // no sample twice
        EXPECT_EQ(toText(square), toText(m1 | m2));
    }
}

// Random convex quads with fractional corners: both diagonal splits cover the same samples,
// each exactly once.
TEST(ShadingReference, SharedDiagonalRandomQuads)
{
    cv::RNG rng(777);
    const cv::Size sz(32, 32);
    for (int i = 0; i < 200; i++) {
        // A convex quad: 4 points on an ellipse at increasing angles.
        const Point2d ctr(rng.uniform(4.0, 28.0), rng.uniform(4.0, 28.0));
        const double rx = rng.uniform(2.0, 20.0), ry = rng.uniform(2.0, 20.0);
        double ang[4];
        for (double& t : ang)
            t = rng.uniform(0.0, 2 * CV_PI);
        std::sort(ang, ang + 4);
        Point2d q[4];
        for (int k = 0; k < 4; k++) {
            q[k] = ctr + Point2d(rx * std::cos(ang[k]), ry * std::sin(ang[k]));
            if (i % 2)  // odd: snap corners to the half-pixel grid to hit samples exactly
                q[k] = Point2d(std::round(q[k].x * 2) / 2, std::round(q[k].y * 2) / 2);
        }
        if (!strictlyConvexAfterSnapping(q))
            continue;  // corners too close together: the two splits would differ legitimately
        const Point2d t1[3] = { q[0], q[1], q[2] }, t2[3] = { q[0], q[2], q[3] };
        const Point2d t3[3] = { q[0], q[1], q[3] }, t4[3] = { q[1], q[2], q[3] };
        const cv::Mat m1 = shading_ref::coverageMask(sz, t1);
        const cv::Mat m2 = shading_ref::coverageMask(sz, t2);
        const cv::Mat m3 = shading_ref::coverageMask(sz, t3);
        const cv::Mat m4 = shading_ref::coverageMask(sz, t4);
        EXPECT_EQ(0, cv::countNonZero(m1 & m2)) << i;
        EXPECT_EQ(0, cv::countNonZero(m3 & m4)) << i;
        EXPECT_EQ(toText(m1 | m2), toText(m3 | m4)) << i;
    }
}

// A closed fan (a convex polygon cut into triangles around an inner point): no sample is covered
// twice, and every sample strictly inside the polygon is covered.
TEST(ShadingReference, FanCoversPolygonOnce)
{
    cv::RNG rng(4242);
    const cv::Size sz(40, 40);
    for (int i = 0; i < 50; i++) {
        // A regular n-gon with corners rounded to the half-pixel grid (still convex: the
        // rounding moves a corner by < 0.36 px, far less than its 2.3+ px bulge).
        const int n = rng.uniform(3, 9);
        const Point2d ctr(rng.uniform(15.0, 25.0), rng.uniform(15.0, 25.0));
        const double r = rng.uniform(8.0, 14.0), phase = rng.uniform(0.0, 1.0);
        std::vector<Point2d> poly(n);
        for (int k = 0; k < n; k++) {
            const double t = 2 * CV_PI * (k + phase) / n;
            const Point2d p = ctr + Point2d(r * std::cos(t), r * std::sin(t));
            poly[k] = Point2d(std::round(p.x * 2) / 2, std::round(p.y * 2) / 2);
        }
        const Point2d hub = ctr + Point2d(rng.uniform(-1.0, 1.0), rng.uniform(-1.0, 1.0));
        cv::Mat count(sz, CV_8UC1, cv::Scalar(0));
        for (int k = 0; k < n; k++) {
            const Point2d t[3] = { hub, poly[k], poly[(k + 1) % n] };
            count += shading_ref::coverageMask(sz, t);
        }
        double maxCount = 0;
        cv::minMaxLoc(count, nullptr, &maxCount);
        EXPECT_LE(maxCount, 1) << i;
        // Strictly inside the (counter-clockwise on screen or not) polygon: same strict side of
        // every edge, tested in plain double geometry.
        for (int y = 0; y < sz.height; y++)
            for (int x = 0; x < sz.width; x++) {
                int pos = 0, neg = 0;
                for (int k = 0; k < n; k++) {
                    const Point2d a = poly[k], b = poly[(k + 1) % n];
                    const double e = (b.x - a.x) * (y - a.y) - (b.y - a.y) * (x - a.x);
                    pos += e > 1e-9;
                    neg += e < -1e-9;
                }
                if (pos == n || neg == n) {
                    EXPECT_EQ(1, count.at<uchar>(y, x)) << i << " at " << x << "," << y;
                }
            }
    }
}

// Flat colour is the mean of the vertex colours, written to every covered pixel and nowhere else.
TEST(ShadingReference, FlatColorIsMean)
{
    const Point2d v[3] = { {0, 0}, {4, 0}, {0, 4} };
    const Vec3d c[3] = { {0.1, 0.2, 0.3}, {0.4, 0.5, 0.6}, {0.7, 0.9, 0.0} };
    cv::Mat canvas(6, 6, CV_32FC3, cv::Scalar::all(-1));
    shading_ref::fillTriangle(canvas, v, c, false);
    const cv::Mat mask = shading_ref::coverageMask(canvas.size(), v);
    for (int y = 0; y < 6; y++)
        for (int x = 0; x < 6; x++) {
            const cv::Vec3f got = canvas.at<cv::Vec3f>(y, x);
            const cv::Vec3f want = mask.at<uchar>(y, x) ? cv::Vec3f(0.4f, 0.5333333f, 0.3f)
                                                        : cv::Vec3f(-1, -1, -1);
            EXPECT_LE(cv::norm(got, want, cv::NORM_INF), 1e-6) << x << "," << y;
        }
}

// Gouraud colour is affine. With vertices (0,0) (8,0) (0,8) and colours chosen as samples of
// f(x, y) = (x, y, 1 + x + 2y), i.e. (0,0,1), (8,0,9), (0,8,17), every covered pixel (x, y)
// must hold exactly f(x, y). A vertex sample gets its vertex colour.
TEST(ShadingReference, GouraudIsAffine)
{
    const Vec3d c[3] = { {0, 0, 1}, {8, 0, 9}, {0, 8, 17} };
    const Point2d v[3] = { {0, 0}, {8, 0}, {0, 8} };
    // The same triangle with the first vertex 1/1024 px off: it snaps to (0,0), so the colours
    // are the same (without snapping channel 0 would be off by about 5e-4 in the middle).
    const Point2d vOff[3] = { {1.0 / 1024, 0}, {8, 0}, {0, 8} };
    for (const Point2d* tri : { v, vOff }) {
        cv::Mat canvas(10, 10, CV_32FC3, cv::Scalar::all(-1));
        shading_ref::fillTriangle(canvas, tri, c, true);
        int covered = 0;
        for (int y = 0; y < 10; y++)
            for (int x = 0; x < 10; x++) {
                const cv::Vec3f got = canvas.at<cv::Vec3f>(y, x);
                if (x + y <= 7) {  // covered: x, y >= 0 and x + y < 8
                    EXPECT_LE(cv::norm(got, cv::Vec3f((float)x, (float)y, 1.f + x + 2.f * y),
                                       cv::NORM_INF), 1e-5) << x << "," << y;
                    covered++;
                } else {
                    EXPECT_EQ(cv::Vec3f(-1, -1, -1), got) << x << "," << y;
                }
            }
        EXPECT_EQ(36, covered);  // 8 + 7 + ... + 1
        EXPECT_EQ(cv::Vec3f(0, 0, 1), canvas.at<cv::Vec3f>(0, 0));  // vertex colour
    }
}

// The colour of a pixel does not depend on the vertex order (colours travel with vertices).
TEST(ShadingReference, GouraudWindingIndependence)
{
    const Point2d v[3] = { {1.25, 0.5}, {13.75, 4.0}, {3.5, 11.0} };
    const Vec3d c[3] = { {1, 0, 0}, {0, 1, 0}, {0, 0, 1} };
    cv::Mat a(12, 15, CV_32FC3, cv::Scalar::all(-1)), b = a.clone();
    shading_ref::fillTriangle(a, v, c, true);
    const Point2d w[3] = { v[2], v[1], v[0] };
    const Vec3d d[3] = { c[2], c[1], c[0] };
    shading_ref::fillTriangle(b, w, d, true);
    EXPECT_LE(cv::norm(a, b, cv::NORM_INF), 1e-6);
    EXPECT_GT(cv::countNonZero(shading_ref::coverageMask(a.size(), v)), 40);
}

// 8-bit canvases: values are rounded and saturated (saturate_cast<uchar>).
TEST(ShadingReference, EightBitRoundsAndSaturates)
{
    const Point2d v[3] = { {0, 0}, {4, 0}, {0, 4} };
    const Vec3d c[3] = { {100.2, 300, -7}, {100.8, 300, -7}, {101.0, 300, -7} };  // mean 100.67
    cv::Mat canvas(5, 5, CV_8UC3, cv::Scalar(1, 2, 3));
    shading_ref::fillTriangle(canvas, v, c, false);
    EXPECT_EQ(cv::Vec3b(101, 255, 0), canvas.at<cv::Vec3b>(0, 0));
    EXPECT_EQ(cv::Vec3b(101, 255, 0), canvas.at<cv::Vec3b>(2, 1));
    EXPECT_EQ(cv::Vec3b(1, 2, 3), canvas.at<cv::Vec3b>(4, 0));  // untouched

    // Gouraud, channel 0 = 10 + 10x: pixel (2,1) gets 30 exactly, (1,0) 20.
    const Vec3d g[3] = { {10, 0, 0}, {50, 0, 0}, {10, 0, 0} };
    shading_ref::fillTriangle(canvas, v, g, true);
    EXPECT_EQ(30, canvas.at<cv::Vec3b>(1, 2)[0]);
    EXPECT_EQ(20, canvas.at<cv::Vec3b>(0, 1)[0]);
}

// Triangles in an ROI: the reference writes only inside the ROI, at ROI coordinates.
TEST(ShadingReference, RoiIsRespected)
{
    cv::Mat big(10, 12, CV_32FC3, cv::Scalar::all(-1));
    cv::Mat roi = big(cv::Rect(3, 2, 6, 6));
    const Point2d v[3] = { {-5, -5}, {20, -5}, {-5, 20} };  // covers the whole ROI
    const Vec3d c[3] = { {0.5, 0.5, 0.5}, {0.5, 0.5, 0.5}, {0.5, 0.5, 0.5} };
    shading_ref::fillTriangle(roi, v, c, false);
    cv::Mat expected(10, 12, CV_32FC3, cv::Scalar::all(-1));
    expected(cv::Rect(3, 2, 6, 6)).setTo(cv::Scalar::all(0.5));
    EXPECT_EQ(0, cv::norm(big, expected, cv::NORM_INF));
}

// Painter's order: by mean vertex depth, largest first, ties in face order.
TEST(ShadingReference, PaintersOrder)
{
    // Depths per face: face 0 (0,0,9) mean 3 (its max 9 is the largest: the mean decides, not
    // the max); face 1 (4,4,4) mean 4; face 2 (3,3,3) mean 3; face 3 (0,4,3) mean 7/3.
    const std::vector<cv::Vec3i> faces = { {0, 1, 2}, {3, 4, 5}, {6, 7, 8}, {0, 4, 8} };
    const std::vector<double> depth = { 0, 0, 9, 4, 4, 4, 3, 3, 3 };
    // Far to near: face 1 (4), then faces 0 and 2 tied at 3 in face order, then face 3.
    EXPECT_EQ((std::vector<int>{ 1, 0, 2, 3 }), shading_ref::paintersOrder(faces, depth));
    EXPECT_EQ((std::vector<int>{ 0, 1, 2, 3 }), shading_ref::paintersOrder(faces, {}));
}

// Two overlapping triangles: the nearer one (smaller mean depth) is drawn last and wins; with
// equal depths the later face wins; render fills the background first.
TEST(ShadingReference, MeshPaintersOverlap)
{
    // Face 0 covers x, y >= 0, x + y < 8; face 1 covers x, y >= 2, x + y < 11: both (3,3).
    const std::vector<Point2d> verts = { {0, 0}, {8, 0}, {0, 8}, {2, 2}, {9, 2}, {2, 9} };
    const std::vector<cv::Vec3i> faces = { {0, 1, 2}, {3, 4, 5} };
    const std::vector<Vec3d> colors = { {1, 0, 0}, {1, 0, 0}, {1, 0, 0},
                                        {0, 1, 0}, {0, 1, 0}, {0, 1, 0} };
    const cv::Size sz(10, 10);
    const cv::Scalar bg(0.25, 0.5, 0.75);
    auto at = [](const cv::Mat& m, int x, int y) { return m.at<cv::Vec3f>(y, x); };

    // Face 0 near (depth 0), face 1 far (depth 5): face 0 on top at (3,3).
    cv::Mat img = shading_ref::render(verts, faces, colors, { 0, 0, 0, 5, 5, 5 }, false, sz, bg);
    EXPECT_EQ(cv::Vec3f(1, 0, 0), at(img, 3, 3));
    EXPECT_EQ(cv::Vec3f(0, 1, 0), at(img, 6, 3));             // only face 1
    EXPECT_EQ(cv::Vec3f(0.25f, 0.5f, 0.75f), at(img, 9, 9));  // nobody

    // Face 0 far: face 1 on top.
    img = shading_ref::render(verts, faces, colors, { 5, 5, 5, 0, 0, 0 }, false, sz, bg);
    EXPECT_EQ(cv::Vec3f(0, 1, 0), at(img, 3, 3));

    // Tie, and no depth: face order, the later face 1 on top.
    img = shading_ref::render(verts, faces, colors, { 1, 1, 1, 1, 1, 1 }, false, sz, bg);
    EXPECT_EQ(cv::Vec3f(0, 1, 0), at(img, 3, 3));
    img = shading_ref::render(verts, faces, colors, {}, false, sz, bg);
    EXPECT_EQ(cv::Vec3f(0, 1, 0), at(img, 3, 3));

    // drawMesh leaves uncovered pixels as they were.
    cv::Mat canvas(sz, CV_8UC3, cv::Scalar(7, 8, 9));
    const std::vector<Vec3d> colors8 = { {255, 0, 0}, {255, 0, 0}, {255, 0, 0},
                                         {0, 255, 0}, {0, 255, 0}, {0, 255, 0} };
    shading_ref::drawMesh(canvas, verts, faces, colors8, { 0, 0, 0, 5, 5, 5 }, true);
    EXPECT_EQ(cv::Vec3b(255, 0, 0), canvas.at<cv::Vec3b>(3, 3));
    EXPECT_EQ(cv::Vec3b(7, 8, 9), canvas.at<cv::Vec3b>(9, 9));
}
