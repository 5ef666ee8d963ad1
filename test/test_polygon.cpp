// This file is part of opencv_shading. License: Apache-2.0.
//
// fillPolygons and triangulatePolygons: pixel-exact against the brute-force winding-number
// reference (reference/polygon_reference.hpp), triangles as polygons, tilings, input forms,
// errors, threads, cv::fillPoly, and triangulations that cover exactly the polygon, once.
#include "reference/polygon_reference.hpp"
#include "test_common.hpp"

#include <gtest/gtest.h>
#include <opencv2/core/utility.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/shading.hpp>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <limits>
#include <string>
#include <vector>

namespace cv {
namespace shading {
namespace detail {
//! Triangulations that fell back to snap rounding so far (polygon_arrangement.cpp).
CV_EXPORTS uint64_t snapRoundingFallbacks();
}  // namespace detail
}  // namespace shading
}  // namespace cv

using namespace cv;
using shading_test::sentinelCanvas;
using shading_test::writtenMask;

namespace {

typedef std::vector<std::vector<Point2d>> Polygons;

const Scalar kColor(0.25, 0.5, 0.75);
const Scalar kColor8(10, 200, 99);

//! fillPolygons on a sentinel canvas: the mask of written pixels (all got `color`, checked).
Mat fillMask(Size size, const Polygons& polys, int rule, int type = CV_32FC3)
{
    Mat canvas = sentinelCanvas(size, type), before = canvas.clone();
    const Scalar color = type == CV_8UC3 ? kColor8 : kColor;
    shading::fillPolygons(canvas, polys, color, rule);
    Mat mask = writtenMask(canvas, before);
    Mat expected = before.clone();
    expected.setTo(color, mask);
    EXPECT_EQ(shading_test::maxAbsDiff(canvas, expected), 0.0);
    return mask;
}

double randomCoordinate(RNG& rng, double lo, double hi, int kind)
{
    const double v = rng.uniform(lo, hi);
    switch (kind) {
    case 0: return std::round(v);              // integer
    case 1: return std::round(v * 4) / 4;      // quarter pixels: many samples on edges
    default: return v;                         // any sub-pixel position
    }
}

//! 1 to 4 random contours of 3 to 12 points: concave, crossing, holes, off-canvas parts.
//! Points integer, on quarter pixels or anywhere (`kind` 0, 1, 2; -1: at random).
Polygons randomPolygons(RNG& rng, Size size, int forcedKind = -1)
{
    Polygons polys(size_t(rng.uniform(1, 5)));
    const int randomKind = rng.uniform(0, 3), kind = forcedKind < 0 ? randomKind : forcedKind;
    for (auto& c : polys) {
        const int n = rng.uniform(3, 13);
        for (int i = 0; i < n; i++)
            c.push_back(Point2d(randomCoordinate(rng, -8, size.width + 8, kind),
                                randomCoordinate(rng, -8, size.height + 8, kind)));
        if (rng.uniform(0, 4) == 0)
            c.push_back(c.back());  // a repeated point
    }
    return polys;
}

//! A star-shaped simple contour around `center`: n jittered, evenly spaced angles (gaps below
//! 1.8 x 360 / n degrees), radii in [rMin, rMax].
std::vector<Point2d> starContour(RNG& rng, Point2d center, double rMin, double rMax, int n,
                                 bool clockwise, int kind)
{
    std::vector<double> angles;
    for (int i = 0; i < n; i++)
        angles.push_back(2 * CV_PI * (i + rng.uniform(0.0, 0.8)) / n);
    if (clockwise)
        std::reverse(angles.begin(), angles.end());
    std::vector<Point2d> c;
    for (double a : angles) {
        const double r = rng.uniform(rMin, rMax);
        Point2d p(center.x + r * std::cos(a), center.y + r * std::sin(a));
        if (kind == 0)
            p = Point2d(std::round(p.x), std::round(p.y));
        else if (kind == 1)
            p = Point2d(std::round(p.x * 4) / 4, std::round(p.y * 4) / 4);
        c.push_back(p);
    }
    return c;
}

//! Per-sample count of the faces covering it (forEachSpan's coverage: flats', as the
//! interpolator tests check).
Mat faceCounts(Size size, const Mat& vertices, const Mat& faces)
{
    Mat counts(size, CV_32S, Scalar(0));
    for (int f = 0; f < faces.rows; f++) {
        std::vector<Point2d> tri;
        for (int k = 0; k < 3; k++) {
            const int i = faces.at<int>(f, k);
            EXPECT_TRUE(i >= 0 && i < vertices.rows);
            if (i < 0 || i >= vertices.rows)
                return counts;
            tri.push_back(Point2d(vertices.at<double>(i, 0), vertices.at<double>(i, 1)));
        }
        shading::forEachSpan(size, tri, [&](int y, int xBegin, int xEnd, const Vec3d&,
                                            const Vec3d&) {
            int* row = counts.ptr<int>(y);
            for (int x = xBegin; x < xEnd; x++)
                row[x]++;
        });
    }
    return counts;
}

//! The input points snapped to the 1/256 px grid, concatenated.
std::vector<Point2d> snappedPoints(const Polygons& polys)
{
    std::vector<Point2d> all;
    for (const auto& c : polys)
        for (const Point2d& p : c)
            all.push_back(Point2d(double(std::llround(p.x * 256)), double(std::llround(p.y * 256))) /
                          256.0);
    return all;
}

/** Whether some input edge passes within 1/512 px, in x and in y, of sample (x, y): meets the
closed square of half-width 1/2 (in 1/256 px units) around it. Exact, in doubled units. */
bool nearAnEdge(const Polygons& polys, int x, int y)
{
    typedef polygon_ref::Int128 Wide;
    const long long X = 512LL * x, Y = 512LL * y;  // the sample, doubled units
    for (const auto& c : polys) {
        if (c.size() < 3)
            continue;
        for (size_t i = 0; i < c.size(); i++) {
            const Point2d& p = c[i];
            const Point2d& q = c[(i + 1) % c.size()];
            const long long A[2] = {2 * std::llround(p.x * 256), 2 * std::llround(p.y * 256)};
            const long long B[2] = {2 * std::llround(q.x * 256), 2 * std::llround(q.y * 256)};
            const long long S[2] = {X, Y};
            // t in [lo, hi] (fractions n / d, d > 0) with |A + t (B - A) - S| <= 1 per axis.
            Wide loN = 0, loD = 1, hiN = 1, hiD = 1;
            bool empty = false;
            for (int k = 0; k < 2 && !empty; k++) {
                const long long D = B[k] - A[k], L = S[k] - 1 - A[k], U = S[k] + 1 - A[k];
                if (D == 0) {
                    empty = L > 0 || U < 0;
                    continue;
                }
                Wide n0 = D > 0 ? L : U, n1 = D > 0 ? U : L, d = D > 0 ? D : -D;
                if (D < 0)
                    n0 = -n0, n1 = -n1;
                if (n0 * loD > loN * d)
                    loN = n0, loD = d;
                if (n1 * hiD < hiN * d)
                    hiN = n1, hiD = d;
            }
            if (!empty && loN * hiD <= hiN * loD)
                return true;
        }
    }
    return false;
}

struct TriangulationCheck {
    int differing = 0;  //!< samples where the triangles' coverage differs from fillPolygons'
    int differingFar = 0;  //!< of them, those farther than 1/512 px from every input edge
    int covered = 0;
    int faces = 0, addedVertices = 0;
};

/** Triangulates, checks the output's shape and that every sample is covered at most once, and
compares the coverage with fillPolygons'. */
TriangulationCheck checkTriangulation(Size size, const Polygons& polys, int rule,
                                      const std::string& what)
{
    TriangulationCheck r;
    Mat faces, vertices;
    shading::triangulatePolygons(polys, faces, rule, vertices);
    EXPECT_TRUE(faces.empty() || (faces.type() == CV_32S && faces.cols == 3)) << what;
    EXPECT_TRUE(vertices.type() == CV_64F && vertices.cols == 2) << what;
    const std::vector<Point2d> inputs = snappedPoints(polys);
    EXPECT_GE(vertices.rows, int(inputs.size())) << what;
    if (vertices.rows < int(inputs.size()))
        return r;
    for (int i = 0; i < vertices.rows; i++) {
        const Point2d v(vertices.at<double>(i, 0), vertices.at<double>(i, 1));
        if (i < int(inputs.size()))
            EXPECT_EQ(v, inputs[size_t(i)]) << what << ": vertex " << i;
        else  // added crossings lie on the grid
            EXPECT_EQ(v * 256.0, Point2d(std::round(v.x * 256), std::round(v.y * 256))) << what;
    }
    r.faces = faces.rows;
    r.addedVertices = vertices.rows - int(inputs.size());
    const Mat counts = faceCounts(size, vertices, faces);
    double maxCount = 0;
    minMaxLoc(counts, nullptr, &maxCount);
    EXPECT_LE(maxCount, 1.0) << what << ": a sample covered twice";
    const Mat covered = counts > 0, expected = fillMask(size, polys, rule);
    r.covered = countNonZero(covered);
    const Mat diff = covered != expected;
    r.differing = countNonZero(diff);
    for (int y = 0; y < size.height; y++)
        for (int x = 0; x < size.width; x++)
            if (diff.at<uchar>(y, x) && !nearAnEdge(polys, x, y))
                r.differingFar++;
    return r;
}

//! The triangulation covers exactly fillPolygons' samples, each once.
void expectExactTriangulation(Size size, const Polygons& polys, int rule, const std::string& what)
{
    const TriangulationCheck r = checkTriangulation(size, polys, rule, what);
    EXPECT_EQ(r.differing, 0) << what << ": " << r.covered << " samples covered";
}

}  // namespace

// ---- fillPolygons against the reference ------------------------------------------------------

TEST(Polygon, RandomPolygonsMatchTheReferenceExactly)
{
    const Size size(48, 40);
    RNG rng(19);
    for (int n = 0; n < 600; n++) {
        const Polygons polys = randomPolygons(rng, size);
        for (int rule : {shading::FILL_EVEN_ODD, shading::FILL_NONZERO})
            for (int type : {CV_32FC3, CV_8UC3}) {
                Mat canvas = sentinelCanvas(size, type), expected = canvas.clone();
                const Scalar color = type == CV_8UC3 ? Scalar(10, 200, 300) : kColor;
                shading::fillPolygons(canvas, polys, color, rule);
                polygon_ref::fill(expected, polys, color, rule == shading::FILL_EVEN_ODD);
                ASSERT_EQ(shading_test::maxAbsDiff(canvas, expected), 0.0)
                    << "polygon set " << n << ", rule " << rule << ", type " << type;
            }
    }
}

TEST(Polygon, HugeAndFarCoordinatesMatchTheReference)
{
    const Size size(40, 40);
    RNG rng(7);
    for (int n = 0; n < 200; n++) {
        Polygons polys = randomPolygons(rng, size);
        for (auto& c : polys)
            for (Point2d& p : c)
                if (rng.uniform(0, 3) == 0)
                    p = Point2d(rng.uniform(-1.0, 1.0) * 1e9, rng.uniform(-1.0, 1.0) * 1e9);
        for (int rule : {shading::FILL_EVEN_ODD, shading::FILL_NONZERO}) {
            const Mat mask = fillMask(size, polys, rule);
            const Mat ref = polygon_ref::coverage(polys, size, rule == shading::FILL_EVEN_ODD);
            ASSERT_EQ(countNonZero(mask != ref), 0) << "polygon set " << n << ", rule " << rule;
        }
    }
}

TEST(Polygon, HolesAndOrientationsByRule)
{
    const Size size(20, 20);
    const std::vector<Point2d> outer = {{2, 2}, {16, 2}, {16, 16}, {2, 16}};
    const std::vector<Point2d> same = {{6, 6}, {12, 6}, {12, 12}, {6, 12}};
    std::vector<Point2d> opposite(same.rbegin(), same.rend());
    for (const auto& hole : {same, opposite}) {
        const bool sameOrientation = hole[1] == same[1];
        const Mat evenOdd = fillMask(size, {outer, hole}, shading::FILL_EVEN_ODD);
        const Mat nonzero = fillMask(size, {outer, hole}, shading::FILL_NONZERO);
        // Top-left rule: rows 2..15, columns 2..15 of the outer; the hole's 6..11 cut out.
        EXPECT_EQ(countNonZero(evenOdd), 14 * 14 - 6 * 6);
        EXPECT_EQ(evenOdd.at<uchar>(8, 8), 0);
        EXPECT_EQ(evenOdd.at<uchar>(2, 2), 255);
        EXPECT_EQ(evenOdd.at<uchar>(16, 16), 0);
        EXPECT_EQ(countNonZero(nonzero), sameOrientation ? 14 * 14 : 14 * 14 - 6 * 6);
    }
}

TEST(Polygon, TriangleAsPolygonCoversWhatFlatsCovers)
{
    const Size size(40, 32);
    RNG rng(3);
    for (int n = 0; n < 2000; n++) {
        const int kind = rng.uniform(0, 3);
        std::vector<Point2d> tri;
        for (int k = 0; k < 3; k++)
            tri.push_back(Point2d(randomCoordinate(rng, -4, 44, kind),
                                  randomCoordinate(rng, -4, 36, kind)));
        for (int type : {CV_32FC3, CV_8UC3}) {
            Mat a = sentinelCanvas(size, type), b = a.clone();
            const Scalar color = type == CV_8UC3 ? kColor8 : kColor;
            const Vec3f c = Vec3f(float(color[0]), float(color[1]), float(color[2]));
            shading::flats(a, tri, std::vector<Vec3f>(3, c));
            for (int rule : {shading::FILL_EVEN_ODD, shading::FILL_NONZERO}) {
                Mat bb = b.clone();
                shading::fillPolygons(bb, Polygons{tri}, color, rule);
                ASSERT_EQ(shading_test::maxAbsDiff(a, bb), 0.0) << "triangle " << n;
            }
        }
    }
}

TEST(Polygon, TilingsCoverEverySampleOnce)
{
    // A perturbed grid of quads (sub-pixel corners) and each quad split into concave pieces.
    const Size size(64, 64);
    RNG rng(5);
    for (int trial = 0; trial < 20; trial++) {
        const int cells = 6;
        const double step = 12;
        std::vector<std::vector<Point2d>> corner(cells + 1, std::vector<Point2d>(cells + 1));
        for (int i = 0; i <= cells; i++)
            for (int j = 0; j <= cells; j++)
                corner[size_t(i)][size_t(j)] = Point2d(
                    -2 + j * step + (j % cells ? rng.uniform(-2.5, 2.5) : 0),
                    -2 + i * step + (i % cells ? rng.uniform(-2.5, 2.5) : 0));
        Mat counts(size, CV_32S, Scalar(0));
        for (int i = 0; i < cells; i++)
            for (int j = 0; j < cells; j++) {
                const Point2d a = corner[size_t(i)][size_t(j)];
                const Point2d b = corner[size_t(i)][size_t(j + 1)];
                const Point2d c = corner[size_t(i + 1)][size_t(j + 1)];
                const Point2d d = corner[size_t(i + 1)][size_t(j)];
                // Two concave pieces sharing the broken line a - m - c.
                const Point2d m = (a + c) * 0.5 + Point2d(rng.uniform(-1.0, 1.0), 0);
                for (const Polygons& piece : {Polygons{{a, b, c, m}}, Polygons{{a, m, c, d}}}) {
                    Mat m32;
                    fillMask(size, piece, shading::FILL_NONZERO).convertTo(m32, CV_32S, 1.0 / 255);
                    counts += m32;
                }
            }
        double lo = 0, hi = 0;
        minMaxLoc(counts, &lo, &hi);
        EXPECT_EQ(lo, 1.0) << "trial " << trial;  // the grid covers the whole canvas
        EXPECT_EQ(hi, 1.0) << "trial " << trial;
    }
}

TEST(Polygon, InputFormsAgree)
{
    const Size size(32, 32);
    const std::vector<Point> ints = {{2, 3}, {28, 5}, {14, 14}, {26, 27}, {4, 24}};
    const Polygons asDouble = {std::vector<Point2d>(ints.begin(), ints.end())};
    const Mat expected = fillMask(size, asDouble, shading::FILL_EVEN_ODD);
    ASSERT_GT(countNonZero(expected), 100);
    auto maskOf = [&](InputArrayOfArrays polys) {
        Mat canvas(size, CV_8UC3, Scalar::all(0));
        shading::fillPolygons(canvas, polys, Scalar::all(255));
        Mat m;
        extractChannel(canvas, m, 0);
        return m;
    };
    const std::vector<std::vector<Point>> vInt = {ints};
    std::vector<std::vector<Point2f>> vFloat(1);
    for (const Point& p : ints)
        vFloat[0].push_back(Point2f(p));
    Mat n2(int(ints.size()), 2, CV_64F), n1(int(ints.size()), 1, CV_32FC2);
    for (int i = 0; i < int(ints.size()); i++) {
        n2.at<double>(i, 0) = ints[size_t(i)].x, n2.at<double>(i, 1) = ints[size_t(i)].y;
        n1.at<Vec2f>(i) = Vec2f(float(ints[size_t(i)].x), float(ints[size_t(i)].y));
    }
    const std::vector<Mat> mats = {n2}, mats1 = {n1}, matsInt = {Mat(ints)};
    EXPECT_EQ(countNonZero(maskOf(vInt) != expected), 0);
    EXPECT_EQ(countNonZero(maskOf(vFloat) != expected), 0);
    EXPECT_EQ(countNonZero(maskOf(mats) != expected), 0);
    EXPECT_EQ(countNonZero(maskOf(mats1) != expected), 0);
    EXPECT_EQ(countNonZero(maskOf(matsInt) != expected), 0);
    EXPECT_EQ(countNonZero(maskOf(ints) != expected), 0);  // a single contour
}

TEST(Polygon, ShortContoursAndEmptyInputDrawNothing)
{
    const Size size(16, 16);
    Mat canvas = sentinelCanvas(size), before = canvas.clone();
    shading::fillPolygons(canvas, Polygons{}, kColor);
    shading::fillPolygons(canvas, Polygons{{}, {{1, 1}}, {{1, 1}, {10, 10}}}, kColor);
    shading::fillPolygons(canvas, Polygons{{{1, 1}, {10, 1}, {10, 1}, {1, 1}}}, kColor);  // flat
    EXPECT_EQ(shading_test::maxAbsDiff(canvas, before), 0.0);
    // A short contour next to a real one changes nothing.
    const Polygons tri = {{{1, 1}, {12, 2}, {3, 12}}};
    Polygons withShort = tri;
    withShort.push_back({{0, 0}, {15, 15}});
    EXPECT_EQ(countNonZero(fillMask(size, tri, 0) != fillMask(size, withShort, 0)), 0);
}

TEST(Polygon, BadArgumentsRaiseAndLeaveTheCanvasUntouched)
{
    const Size size(16, 16);
    Mat canvas = sentinelCanvas(size), before = canvas.clone();
    const std::vector<Point2d> ok = {{1, 1}, {12, 2}, {3, 12}};
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const double inf = std::numeric_limits<double>::infinity();
    auto expectError = [&](InputArrayOfArrays polys, int rule, const std::string& needle) {
        try {
            shading::fillPolygons(canvas, polys, kColor, rule);
            ADD_FAILURE() << "no exception; expected one mentioning '" << needle << "'";
        } catch (const cv::Exception& e) {
            EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
        }
        EXPECT_EQ(shading_test::maxAbsDiff(canvas, before), 0.0);
    };
    expectError(Polygons{ok, ok, {{1, 1}, {2, nan}, {3, 3}}}, 0, "contour 2, point 1");
    expectError(Polygons{ok, {{inf, 1}, {2, 2}, {3, 3}}}, 0, "contour 1, point 0");
    expectError(Polygons{ok, {{1, 1}, {2, 2}, {3, 3e12}}}, 0, "contour 1, point 2");
    expectError(Polygons{ok}, 2, "fillRule");
    const std::vector<Mat> badType = {Mat(ok), Mat(3, 2, CV_8U, Scalar(1))};
    expectError(badType, 0, "polygons[1]");
    const std::vector<Mat> badShape = {Mat(3, 3, CV_32F, Scalar(1))};
    expectError(badShape, 0, "polygons[0]");
    Mat gray(size, CV_8UC1, Scalar(0));
    EXPECT_THROW(shading::fillPolygons(gray, Polygons{ok}, kColor), cv::Exception);
    Mat empty;
    EXPECT_THROW(shading::fillPolygons(empty, Polygons{ok}, kColor), cv::Exception);
    Mat faces;
    EXPECT_THROW(shading::triangulatePolygons(Polygons{ok, {{nan, 1}, {2, 2}, {3, 3}}}, faces),
                 cv::Exception);
    EXPECT_THROW(shading::triangulatePolygons(Polygons{ok}, faces, 5), cv::Exception);
}

TEST(Polygon, ResultDoesNotDependOnThreadCount)
{
    const Size size(700, 600);
    RNG rng(11);
    const Polygons polys = {starContour(rng, {350, 300}, 50, 330, 3000, false, 2),
                            starContour(rng, {350, 300}, 10, 120, 500, true, 2)};
    const int previous = getNumThreads();
    Mat references[2];
    for (int threads : {1, 2, 3, 8}) {
        setNumThreads(threads);
        for (int rule : {shading::FILL_EVEN_ODD, shading::FILL_NONZERO}) {
            Mat canvas(size, CV_32FC3, Scalar::all(0));
            shading::fillPolygons(canvas, polys, kColor, rule);
            if (threads == 1) {
                references[rule] = canvas.clone();
            } else {
                EXPECT_EQ(shading_test::maxAbsDiff(canvas, references[rule]), 0.0) << threads;
            }
        }
    }
    const Mat& reference = references[0];
    setNumThreads(previous);
    // And the banded scan agrees with the reference on a sampled area.
    const Rect roi(300, 250, 60, 40);
    Polygons shifted = polys;
    for (auto& c : shifted)
        for (Point2d& p : c)
            p -= Point2d(roi.x, roi.y);
    const Mat ref = polygon_ref::coverage(shifted, roi.size(), true);
    Mat got;
    compare(reference(roi).reshape(1), 0, got, CMP_NE);
    extractChannel(got.reshape(3), got, 0);
    EXPECT_EQ(countNonZero(got != ref), 0);
}

TEST(Polygon, WithinOnePixelOfCvFillPoly)
{
    // Integer vertices on the canvas: everything fillPolygons covers, cv::fillPoly (LINE_8)
    // paints too; fillPoly's extra pixels (it paints the boundary) lie within a pixel of an edge
    // in chessboard distance. Simple star-shaped polygons, where both mean the same inside.
    const Size size(64, 64);
    RNG rng(23);
    for (int n = 0; n < 300; n++) {
        std::vector<Point2d> c = starContour(rng, {32, 32}, 4, 30, rng.uniform(3, 20), false, 0);
        std::vector<Point> ci;
        for (const Point2d& p : c)
            ci.push_back(Point(int(p.x), int(p.y)));
        const Mat ours = fillMask(size, {c}, shading::FILL_EVEN_ODD);
        Mat theirs(size, CV_8U, Scalar(0));
        fillPoly(theirs, std::vector<std::vector<Point>>{ci}, Scalar(255), LINE_8);
        ASSERT_EQ(countNonZero(ours & ~theirs), 0) << "polygon " << n;
        const Mat extra = theirs & ~ours;
        for (int y = 0; y < size.height; y++)
            for (int x = 0; x < size.width; x++) {
                if (!extra.at<uchar>(y, x))
                    continue;
                double d = 1e9;
                for (size_t k = 0; k < ci.size(); k++) {
                    const Point2d a = ci[k], b = ci[(k + 1) % ci.size()], p(x, y);
                    for (int s = 0; s <= 200; s++) {  // sampled chessboard distance
                        const Point2d q = a + (b - a) * (s / 200.0);
                        d = std::min(d, std::max(std::abs(q.x - p.x), std::abs(q.y - p.y)));
                    }
                }
                ASSERT_LE(d, 1.0 + 1e-6) << "polygon " << n << " pixel " << x << "," << y;
            }
    }
}

TEST(Polygon, InsideCvFillPolyForCrossingContoursToo)
{
    // Random self-intersecting sets of 1 or 2 integer contours, even-odd (fillPoly's rule):
    // fillPoly still paints everything fillPolygons covers.
    const Size size(64, 64);
    RNG rng(37);
    for (int n = 0; n < 1000; n++) {
        std::vector<std::vector<Point>> polys(size_t(rng.uniform(1, 3)));
        for (auto& c : polys)
            for (int i = rng.uniform(3, 10); i > 0; i--)
                c.push_back(Point(rng.uniform(0, 64), rng.uniform(0, 64)));
        Mat ours(size, CV_8UC3, Scalar::all(0)), theirs(size, CV_8U, Scalar(0)), o;
        shading::fillPolygons(ours, polys, Scalar::all(255));
        extractChannel(ours, o, 0);
        fillPoly(theirs, polys, Scalar(255), LINE_8);
        ASSERT_EQ(countNonZero(o & ~theirs), 0) << "polygon set " << n;
    }
}

// ---- triangulatePolygons -------------------------------------------------------------------

TEST(PolygonTriangulation, TriangleGivesOneFace)
{
    Mat faces;
    shading::triangulatePolygons(Polygons{{{1, 1}, {12, 2}, {3, 12}}}, faces);
    ASSERT_EQ(faces.rows, 1);
    std::vector<int> f = {faces.at<int>(0, 0), faces.at<int>(0, 1), faces.at<int>(0, 2)};
    std::sort(f.begin(), f.end());
    EXPECT_EQ(f, (std::vector<int>{0, 1, 2}));
    std::vector<Vec3i> v;
    shading::triangulatePolygons(Polygons{{{1, 1}, {12, 2}, {3, 12}}}, v);
    EXPECT_EQ(v.size(), 1u);
}

TEST(PolygonTriangulation, StarPolygonsWithHolesAreExact)
{
    const Size size(64, 64);
    RNG rng(29);
    for (int n = 0; n < 300; n++) {
        const int kind = rng.uniform(0, 3);
        // Outer: radii 20..31, gaps below 54 degrees, so it holds the disc of radius 17.
        const int holes = rng.uniform(0, 4);
        Polygons polys = {starContour(rng, {32, 32}, 20, 31, rng.uniform(holes ? 12 : 3, 30),
                                      rng.uniform(0, 2) == 1, kind)};
        for (int h = 0; h < holes; h++) {
            const double a = h * 2 * CV_PI / 3 + rng.uniform(0.0, 0.5);
            const Point2d c(32 + 11 * std::cos(a), 32 + 11 * std::sin(a));
            // Holes of radius up to 4.5 (not rounded: rounding could fold such small ones).
            polys.push_back(starContour(rng, c, 1.5, 4.5, rng.uniform(6, 11),
                                        rng.uniform(0, 2) == 1, 2));
            if (rng.uniform(0, 3) == 0)  // an island inside the hole
                polys.push_back({c + Point2d(-0.4, -0.4), c + Point2d(0.5, -0.3),
                                 c + Point2d(0, 0.5)});
        }
        for (int rule : {shading::FILL_EVEN_ODD, shading::FILL_NONZERO})
            expectExactTriangulation(size, polys, rule,
                                     "set " + std::to_string(n) + " rule " + std::to_string(rule));
    }
}

TEST(PolygonTriangulation, CollinearAndRepeatedPointsAndTheIgnoredContours)
{
    const Size size(24, 24);
    const Polygons square = {{{2, 2}, {6, 2}, {6, 2}, {10, 2}, {18, 2}, {18, 10}, {18, 18},
                              {10, 18}, {2, 18}, {2, 18}, {2, 10}}};
    expectExactTriangulation(size, square, shading::FILL_EVEN_ODD, "square");
    Mat faces;
    shading::triangulatePolygons(square, faces);
    EXPECT_EQ(faces.rows, 2);
    // Nonzero: a hole with the outer's orientation is covered; even-odd cuts it out.
    const Polygons nested = {{{2, 2}, {20, 2}, {20, 20}, {2, 20}},
                             {{7, 7}, {14, 7}, {14, 14}, {7, 14}}};
    for (int rule : {shading::FILL_EVEN_ODD, shading::FILL_NONZERO})
        expectExactTriangulation(size, nested, rule, "nested " + std::to_string(rule));
    shading::triangulatePolygons(nested, faces, shading::FILL_NONZERO);
    EXPECT_EQ(faces.rows, 2);
    // A concave comb with a spike.
    const Polygons comb = {{{1, 1}, {22, 1}, {22, 22}, {18, 22}, {18, 6}, {15, 6}, {15, 22},
                            {15, 10}, {15, 22}, {9, 22}, {9, 6}, {6, 6}, {6, 22}, {1, 22}}};
    expectExactTriangulation(size, comb, shading::FILL_EVEN_ODD, "comb");
}

TEST(PolygonTriangulation, BowTieCrossingOnTheGridByHand)
{
    // The crossing (7, 7) is a grid point: one added vertex, two triangles, exact coverage.
    const Size size(16, 16);
    const Polygons bowtie = {{{2, 2}, {12, 12}, {12, 2}, {2, 12}}};
    for (int rule : {shading::FILL_EVEN_ODD, shading::FILL_NONZERO}) {
        Mat faces, vertices;
        shading::triangulatePolygons(bowtie, faces, rule, vertices);
        ASSERT_EQ(vertices.rows, 5);
        EXPECT_EQ(vertices.at<double>(4, 0), 7.0);
        EXPECT_EQ(vertices.at<double>(4, 1), 7.0);
        ASSERT_EQ(faces.rows, 2);
        std::vector<std::vector<int>> tris;
        for (int f = 0; f < 2; f++) {
            std::vector<int> t = {faces.at<int>(f, 0), faces.at<int>(f, 1), faces.at<int>(f, 2)};
            std::sort(t.begin(), t.end());
            tris.push_back(t);
        }
        std::sort(tris.begin(), tris.end());
        // Left: (2, 2), crossing, (2, 12); right: (12, 12), (12, 2), crossing.
        EXPECT_EQ(tris, (std::vector<std::vector<int>>{{0, 3, 4}, {1, 2, 4}}));
        const TriangulationCheck r = checkTriangulation(size, bowtie, rule, "bow-tie");
        EXPECT_EQ(r.differing, 0);
        // Top-left rule, by hand: the left triangle covers columns 2..6 of rows 2..11 within
        // |y - 7| < 7 - x (x = 2..6): 9 + 7 + 5 + 3 + 1 samples; the right one mirrored.
        EXPECT_EQ(r.covered, 2 * (9 + 7 + 5 + 3 + 1));
    }
}

TEST(PolygonTriangulation, PentagramCentreByRule)
{
    // The five crossings are off the grid (moved to grid points, exactly): even-odd leaves the
    // centre pentagon out (five tips, one face each), nonzero fills it (a ten-sided outline,
    // eight faces). Turned a little so that no edge is horizontal (two crossings on one would
    // give a face less).
    const Size size(64, 64);
    Polygons star(1);
    for (int k = 0; k < 5; k++) {
        const double a = 0.1 - CV_PI / 2 + 2 * CV_PI * ((2 * k) % 5) / 5;
        star[0].push_back(Point2d(32 + 28 * std::cos(a), 32 + 28 * std::sin(a)));
    }
    for (int rule : {shading::FILL_EVEN_ODD, shading::FILL_NONZERO}) {
        Mat faces, vertices;
        shading::triangulatePolygons(star, faces, rule, vertices);
        EXPECT_EQ(vertices.rows, 10);
        EXPECT_EQ(faces.rows, rule == shading::FILL_EVEN_ODD ? 5 : 8);
        const Mat counts = faceCounts(size, vertices, faces);
        EXPECT_EQ(counts.at<int>(32, 32), rule == shading::FILL_EVEN_ODD ? 0 : 1);
        const TriangulationCheck r = checkTriangulation(size, star, rule, "pentagram");
        EXPECT_EQ(r.differing, 0);
        // The added points are grid points within a few 1/256 px of the exact crossings.
        for (int i = 5; i < vertices.rows; i++) {
            const Point2d v(vertices.at<double>(i, 0), vertices.at<double>(i, 1));
            EXPECT_NEAR(cv::norm(v - Point2d(32, 32)), 28 * std::cos(2 * CV_PI / 5) /
                                                           std::cos(CV_PI / 5), 3.0 / 256);
        }
    }
}

//! 1 to 3 contours with edges horizontal, vertical or diagonal between integer points: every
//! crossing is on the 1/256 px grid (a multiple of 1/2), and contours overlap and touch often.
Polygons octilinearPolygons(RNG& rng, Size size)
{
    Polygons polys(size_t(rng.uniform(1, 4)));
    for (auto& c : polys) {
        const int n = rng.uniform(2, 7);
        std::vector<Point> corners;
        for (int i = 0; i < n; i++)
            corners.push_back(Point(rng.uniform(-2, size.width + 2), rng.uniform(-2, size.height + 2)));
        for (int i = 0; i < n; i++) {
            const Point p = corners[size_t(i)], q = corners[size_t((i + 1) % n)];
            const int dx = q.x - p.x, dy = q.y - p.y, d = std::min(std::abs(dx), std::abs(dy));
            c.push_back(Point2d(p));
            if (rng.uniform(0, 2) == 0)  // diagonal first, or straight first
                c.push_back(Point2d(p.x + (dx > 0 ? d : -d), p.y + (dy > 0 ? d : -d)));
            else
                c.push_back(Point2d(q.x - (dx > 0 ? d : -d), q.y - (dy > 0 ? d : -d)));
        }
    }
    return polys;
}

TEST(PolygonTriangulation, CrossingsOnTheGridAreExact)
{
    // Self-intersecting, overlapping and touching contours whose crossings all lie on the grid,
    // and random axis-aligned rectangles sharing edges and corners: exactly fillPolygons.
    const Size size(40, 32);
    RNG rng(41);
    for (int n = 0; n < 400; n++) {
        Polygons polys = octilinearPolygons(rng, size);
        if (n % 2) {
            polys.clear();
            for (int k = rng.uniform(2, 6); k > 0; k--) {
                const int x0 = rng.uniform(0, 30), y0 = rng.uniform(0, 24);
                const int x1 = x0 + rng.uniform(1, 10), y1 = y0 + rng.uniform(1, 8);
                polys.push_back({{double(x0), double(y0)}, {double(x1), double(y0)},
                                 {double(x1), double(y1)}, {double(x0), double(y1)}});
                if (rng.uniform(0, 2))
                    std::reverse(polys.back().begin(), polys.back().end());
            }
        }
        for (int rule : {shading::FILL_EVEN_ODD, shading::FILL_NONZERO})
            expectExactTriangulation(size, polys, rule,
                                     "set " + std::to_string(n) + " rule " + std::to_string(rule));
    }
}

TEST(PolygonTriangulation, SelfIntersectingPolygonsAreExact)
{
    // Random crossing contours with integer, quarter-pixel and any sub-pixel points (crossings
    // mostly off the grid, samples often on edges): exactly fillPolygons' coverage, each sample
    // once, without falling back to snap rounding. The added crossings are counted and printed.
    const Size size(48, 40);
    RNG rng(43);
    long long covered[3] = {0, 0, 0}, added[3] = {0, 0, 0}, fellBack[3] = {0, 0, 0};
    for (int n = 0; n < 600; n++) {
        const int kind = n % 3;
        const Polygons polys = randomPolygons(rng, size, kind);
        for (int rule : {shading::FILL_EVEN_ODD, shading::FILL_NONZERO}) {
            const uint64_t before = shading::detail::snapRoundingFallbacks();
            const TriangulationCheck r = checkTriangulation(
                size, polys, rule, "set " + std::to_string(n) + " rule " + std::to_string(rule));
            const uint64_t fallbacks = shading::detail::snapRoundingFallbacks() - before;
            EXPECT_EQ(r.differing, 0) << "set " << n << " rule " << rule;
            EXPECT_EQ(fallbacks, 0u) << "set " << n << " rule " << rule;
            covered[kind] += r.covered, added[kind] += r.addedVertices;
            fellBack[kind] += (long long)fallbacks;
        }
    }
    const char* names[3] = {"integer", "quarter-pixel", "sub-pixel"};
    for (int kind = 0; kind < 3; kind++)
        std::cout << "[ measured ] " << names[kind] << " points, 400 triangulations, "
                  << added[kind] << " crossings added, " << covered[kind]
                  << " samples covered, all as fillPolygons; " << fellBack[kind]
                  << " fell back to snap rounding\n";
}

TEST(PolygonTriangulation, DenseSelfCrossingStarsAreExact)
{
    // Stars whose jittered spikes cross thousands of times within a small canvas: edges run a
    // few hundredths of a pixel apart, so crossings placed on the grid keep making new ones
    // nearby (many passes, many rounds of the check; the 30,000-point one needed more than 16
    // of each, and fell back to snap rounding before they were cheap). Still exact, each
    // sample once.
    for (int n : {3000, 30000}) {
        const Size size = n < 10000 ? Size(160, 160) : Size(1024, 1024);
        RNG rng(uint64(900 + n));
        Polygons star(1);
        for (int i = 0; i < n; i++) {
            const double a = 2 * CV_PI * (i + rng.uniform(-3.0, 3.0)) / n;
            const double r = size.width * rng.uniform(0.15, 0.48);
            star[0].push_back(Point2d(size.width / 2 + r * std::cos(a),
                                      size.height / 2 + r * std::sin(a)));
        }
        for (int rule : {shading::FILL_EVEN_ODD, shading::FILL_NONZERO}) {
            if (n > 10000 && rule == shading::FILL_NONZERO)
                continue;  // one rule is enough at this size
            const uint64_t before = shading::detail::snapRoundingFallbacks();
            const TriangulationCheck r = checkTriangulation(size, star, rule, "dense star");
            EXPECT_EQ(r.differing, 0) << n << " points, rule " << rule;
            EXPECT_EQ(shading::detail::snapRoundingFallbacks(), before) << n << " points";
            std::cout << "[ measured ] " << n << "-point star, rule " << rule << ": "
                      << r.addedVertices << " points added, " << r.covered << " samples covered, "
                      << r.differing << " differing from fillPolygons\n";
        }
    }
}

TEST(PolygonTriangulation, CrossingsNearSamplesAndAtTinyAnglesAreExact)
{
    // Integer edges through many samples, crossing within 1/1000 px of a sample; nearly
    // parallel edges crossing at tiny angles (their lines within a hair of samples on both
    // sides of the crossing); all crossings off the grid.
    const Size size(64, 48);
    std::vector<std::pair<std::string, Polygons>> cases;
    // A long near-horizontal edge (slope 1/1000) crossing the vertical x = 1, through samples,
    // at (1, 10.001): 1/1000 px from sample (1, 10); and diagonal edges through samples.
    cases.push_back({"near-horizontal", {{{0, 10}, {1000, 11}, {40, 30}},
                                         {{1, -1}, {1, 40}, {20, 40}},
                                         {{20, -1}, {41, 20}, {5, 40}, {31, 5}, {33, 44}}}});
    cases.push_back({"through samples", {{{1, 1}, {60, 2}, {60, 40}, {2, 41}},
                                         {{0, 20}, {62, 21}, {31, 46}, {30, 0}}}});
    // Nearly parallel: slopes 1/60 and 1/61, crossing at a tiny angle.
    cases.push_back({"tiny angle", {{{0, 10}, {61, 11}, {61, 30}, {0, 30}},
                                    {{0, 10.5}, {60, 11.5 - 1.0 / 61}, {60, 40}, {1, 40}}}});
    cases.push_back({"sliver star", {{{2, 20}, {62, 21}, {3, 21}, {61, 20.25}, {30, 45}}}});
    RNG rng(53);
    for (int k = 0; k < 40; k++) {
        // Fans of nearly parallel integer edges through a common region.
        Polygons fan(1);
        for (int i = 0; i < 7; i++) {
            const int y = rng.uniform(5, 43), dy = rng.uniform(-2, 3);
            fan[0].push_back(Point2d(i % 2 ? 63 : 0, y));
            fan[0].push_back(Point2d(i % 2 ? 0 : 63, y + dy));
        }
        cases.push_back({"fan " + std::to_string(k), fan});
    }
    long long added = 0, fallbacks = 0;
    for (const auto& c : cases)
        for (int rule : {shading::FILL_EVEN_ODD, shading::FILL_NONZERO}) {
            const uint64_t before = shading::detail::snapRoundingFallbacks();
            const TriangulationCheck r = checkTriangulation(size, c.second, rule, c.first);
            EXPECT_EQ(r.differing, 0) << c.first << " rule " << rule;
            added += r.addedVertices;
            fallbacks += (long long)(shading::detail::snapRoundingFallbacks() - before);
        }
    EXPECT_EQ(fallbacks, 0);
    std::cout << "[ measured ] " << cases.size() << " adversarial sets, " << added
              << " crossings added, " << fallbacks << " fell back to snap rounding\n";
}

TEST(PolygonTriangulation, CrossingContoursFarAndHugeCoordinates)
{
    // Long edges from far off the canvas cross on it. Checking such edges exactly would visit
    // about a sample per pixel of their length, so these fall back to snap rounding (this test
    // exercises that path): coverage still differs only within 1/512 px of an input edge.
    const Size size(40, 40);
    RNG rng(47);
    long long fallbacks = 0, exact = 0, sets = 0;
    for (int n = 0; n < 150; n++) {
        Polygons polys = randomPolygons(rng, size);
        for (auto& c : polys)
            for (Point2d& p : c)
                if (rng.uniform(0, 4) == 0)
                    p = Point2d(rng.uniform(-1.0, 1.0) * 1e9, rng.uniform(-1.0, 1.0) * 1e9);
        for (int rule : {shading::FILL_EVEN_ODD, shading::FILL_NONZERO}) {
            const uint64_t before = shading::detail::snapRoundingFallbacks();
            const TriangulationCheck r = checkTriangulation(size, polys, rule, "far");
            ASSERT_EQ(r.differingFar, 0) << "set " << n << " rule " << rule;
            const bool fellBack = shading::detail::snapRoundingFallbacks() != before;
            fallbacks += fellBack, sets++;
            exact += r.differing == 0;
            if (!fellBack) {
                EXPECT_EQ(r.differing, 0) << "set " << n << " rule " << rule;
            }
        }
    }
    EXPECT_GT(fallbacks, 0);
    std::cout << "[ measured ] far coordinates: " << fallbacks << " of " << sets
              << " triangulations fell back to snap rounding; " << exact << " exact\n";
}

TEST(PolygonTriangulation, VerticesOutputAndDeterminism)
{
    // Sub-pixel inputs come back snapped; the same input gives the same output; the vector
    // forms work; an overlapping pair of squares (crossings on the grid) adds two vertices.
    const Polygons squares = {{{0.3, 0.3}, {10.3, 0.3}, {10.3, 10.3}, {0.3, 10.3}},
                              {{5.1, 5.1}, {15.1, 5.1}, {15.1, 15.1}, {5.1, 15.1}}};
    Mat f1, v1, f2, v2;
    shading::triangulatePolygons(squares, f1, shading::FILL_NONZERO, v1);
    shading::triangulatePolygons(squares, f2, shading::FILL_NONZERO, v2);
    EXPECT_EQ(countNonZero(f1 != f2), 0);
    EXPECT_EQ(shading_test::maxAbsDiff(v1, v2), 0.0);
    ASSERT_EQ(v1.rows, 10);
    EXPECT_EQ(v1.at<double>(0, 0), std::llround(0.3 * 256) / 256.0);
    EXPECT_EQ(Point2d(v1.at<double>(8, 0), v1.at<double>(8, 1)),
              Point2d(std::llround(10.3 * 256), std::llround(5.1 * 256)) / 256.0);
    EXPECT_EQ(Point2d(v1.at<double>(9, 0), v1.at<double>(9, 1)),
              Point2d(std::llround(5.1 * 256), std::llround(10.3 * 256)) / 256.0);
    expectExactTriangulation(Size(20, 20), squares, shading::FILL_NONZERO, "squares");
    expectExactTriangulation(Size(20, 20), squares, shading::FILL_EVEN_ODD, "squares");
    std::vector<Vec3i> fv;
    std::vector<Point2d> vv;
    shading::triangulatePolygons(squares, fv, shading::FILL_NONZERO, vv);
    ASSERT_EQ(fv.size(), size_t(f1.rows));
    ASSERT_EQ(vv.size(), size_t(v1.rows));
    EXPECT_EQ(vv[9], Point2d(v1.at<double>(9, 0), v1.at<double>(9, 1)));
    // Without crossings nothing is added and the vertices are the inputs.
    Mat faces, vertices;
    shading::triangulatePolygons(Polygons{{{1, 1}, {12, 2}, {3, 12}}}, faces, 0, vertices);
    EXPECT_EQ(vertices.rows, 3);
}

TEST(PolygonTriangulation, ManyAlignedHolesAndSpirals)
{
    const Size size(64, 64);
    RNG rng(31);
    for (int n = 0; n < 60; n++) {
        // A square with a 5 x 5 grid of holes: squares and diamonds, many sharing their
        // rightmost x (ties in the bridging order) and bridges along collinear points.
        const double j = n % 2 ? 0.0 : 0.25;
        Polygons polys = {{{1, 1}, {62, 1}, {62, 62}, {1, 62}}};
        for (int i = 0; i < 5; i++)
            for (int k = 0; k < 5; k++) {
                const Point2d c(7 + 12 * k + rng.uniform(-j, j), 7 + 12 * i + rng.uniform(-j, j));
                const double r = rng.uniform(2.0, 4.5);
                if ((i + k + n) % 3 == 0)
                    polys.push_back({c + Point2d(-r, 0), c + Point2d(0, r), c + Point2d(r, 0),
                                     c + Point2d(0, -r)});
                else
                    polys.push_back({c + Point2d(-r, -r), c + Point2d(r, -r), c + Point2d(r, r),
                                     c + Point2d(-r, r)});
            }
        for (int rule : {shading::FILL_EVEN_ODD, shading::FILL_NONZERO})
            expectExactTriangulation(size, polys, rule, "grid " + std::to_string(n));
    }
    for (int n = 0; n < 40; n++) {
        // A spiral band: deeply non-star-shaped, two long chains close to each other.
        const int turns = 2 + n % 3, steps = 20 * turns;
        const double width = rng.uniform(1.5, 3.0), a0 = rng.uniform(0.0, 6.3);
        std::vector<Point2d> inner, outer;
        for (int s = 0; s <= steps; s++) {
            const double t = double(s) / steps, a = a0 + t * turns * 2 * CV_PI;
            const double r = 4 + t * 22;  // 7 px or more per turn, wider than the band
            inner.push_back(Point2d(32 + r * std::cos(a), 32 + r * std::sin(a)));
            const double ro = r + width;
            outer.push_back(Point2d(32 + ro * std::cos(a), 32 + ro * std::sin(a)));
        }
        std::vector<Point2d> band(inner.begin(), inner.end());
        band.insert(band.end(), outer.rbegin(), outer.rend());
        for (int rule : {shading::FILL_EVEN_ODD, shading::FILL_NONZERO})
            expectExactTriangulation(size, {band}, rule, "spiral " + std::to_string(n));
    }
}
