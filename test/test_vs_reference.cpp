// This file is part of opencv_shading. License: Apache-2.0.
//
// The library against the brute-force reference (test/reference/shading_reference.hpp), pixel
// by pixel, on thousands of random triangles and meshes with fixed seeds.
//
// Coverage must match exactly. To see which pixels the library wrote, every canvas starts filled
// with a sentinel colour no triangle uses. 8-bit canvases can receive any value, so the library
// draws twice, over sentinels 0 and 255: a pixel is written iff it differs from its sentinel in
// either canvas (no colour equals both). Float canvases do the same over -1 and -2, which no
// colour in [0, 1] produces.
// Colours: float Gouraud within 1e-4, float flat within 1e-6, 8-bit within 1.

#include <gtest/gtest.h>

#include <opencv2/core.hpp>
#include <opencv2/shading.hpp>

#include "reference/shading_reference.hpp"
#include "test_common.hpp"

#include <algorithm>
#include <cstdlib>
#include <cmath>
#include <functional>
#include <limits>
#include <map>
#include <sstream>
#include <string>
#include <vector>

namespace {

using cv::Point2d;
using cv::Vec3d;

const cv::Size kSmall(64, 48);  // canvas of the many-triangles loops

// ---------------------------------------------------------------------------------------------
// Triangles and how they are handed to the library

// How the vertices / colours are passed to the library (all must give the same result).
enum class Form { Double, Float, Int };  // vector<Point2d>, vector<Point2f>, vector<Point>

struct Tri {
    Point2d v[3];
    Vec3d c[3];
    Form form = Form::Double;
    bool vec3f = false;  // colours as std::vector<Vec3f> (then they are float-representable)
};

std::string describe(const Tri& t)
{
    std::ostringstream s;
    s.precision(17);
    s << "vertices {";
    for (int i = 0; i < 3; i++)
        s << (i ? ", " : "") << "{" << t.v[i].x << ", " << t.v[i].y << "}";
    s << "} colours {";
    for (int i = 0; i < 3; i++)
        s << (i ? ", " : "") << "{" << t.c[i][0] << ", " << t.c[i][1] << ", " << t.c[i][2] << "}";
    s << "} as " << (t.form == Form::Int ? "vector<Point>"
                     : t.form == Form::Float ? "vector<Point2f>" : "vector<Point2d>")
      << (t.vec3f ? " + vector<Vec3f>" : " + vector<Vec3d>");
    return s.str();
}

Tri swapped(const Tri& t)  // the other winding: vertices 1 and 2 (and their colours) exchanged
{
    Tri u = t;
    std::swap(u.v[1], u.v[2]);
    std::swap(u.c[1], u.c[2]);
    return u;
}

void libFill(cv::Mat& canvas, const Tri& t, bool gouraud)
{
    auto fill = [&](const auto& verts) {
        auto draw = [&](const auto& cols) {
            if (gouraud)
                cv::shading::gouraud(canvas, verts, cols);
            else
                cv::shading::flats(canvas, verts, cols);
        };
        if (t.vec3f) {
            std::vector<cv::Vec3f> c;
            for (const Vec3d& ci : t.c)
                c.push_back(cv::Vec3f((float)ci[0], (float)ci[1], (float)ci[2]));
            draw(c);
        } else {
            draw(std::vector<Vec3d>(t.c, t.c + 3));
        }
    };
    if (t.form == Form::Int) {
        std::vector<cv::Point> v;
        for (const Point2d& p : t.v)
            v.push_back(cv::Point((int)p.x, (int)p.y));
        fill(v);
    } else if (t.form == Form::Float) {
        std::vector<cv::Point2f> v;
        for (const Point2d& p : t.v)
            v.push_back(cv::Point2f((float)p.x, (float)p.y));
        fill(v);
    } else {
        fill(std::vector<Point2d>(t.v, t.v + 3));
    }
}

// ---------------------------------------------------------------------------------------------
// Pixel-by-pixel comparison

struct Sentinels {
    cv::Scalar a, b;
};

Sentinels sentinelsFor(int type)
{
    return type == CV_32FC3 ? Sentinels{ cv::Scalar::all(-1), cv::Scalar::all(-2) }
                            : Sentinels{ cv::Scalar::all(0), cv::Scalar::all(255) };
}

// A new canvas filled with `value`. (Cloned from a cached one: filling 3-channel images through
// Mat::operator=(Scalar) is slow enough to dominate these tests.)
cv::Mat filled(cv::Size size, int type, const cv::Scalar& value)
{
    static std::map<std::vector<double>, cv::Mat> cache;
    const std::vector<double> key = { (double)size.width, (double)size.height, (double)type,
                                      value[0], value[1], value[2] };
    cv::Mat& m = cache[key];
    if (m.empty())
        m = cv::Mat(size, type, value);
    return m.clone();
}

Vec3d pixel(const cv::Mat& m, int x, int y)
{
    if (m.type() == CV_32FC3) {
        const cv::Vec3f p = m.at<cv::Vec3f>(y, x);
        return Vec3d(p[0], p[1], p[2]);
    }
    const cv::Vec3b p = m.at<cv::Vec3b>(y, x);
    return Vec3d(p[0], p[1], p[2]);
}

bool isSentinel(const cv::Mat& m, int x, int y, const cv::Scalar& s)
{
    const Vec3d p = pixel(m, x, y);
    return p[0] == s[0] && p[1] == s[1] && p[2] == s[2];
}

std::string str(const Vec3d& c)
{
    return cv::format("(%.9g, %.9g, %.9g)", c[0], c[1], c[2]);
}

// Compares what the library drew (libA over sentinel a, libB over sentinel b) with the reference
// image `ref` (drawn over sentinel a) and the reference coverage `mask`. All four are the same
// size. Lists the first few mismatching pixels.
::testing::AssertionResult compareCanvases(const cv::Mat& libA, const cv::Mat& libB,
                                           const Sentinels& s, const cv::Mat& ref,
                                           const cv::Mat& mask, double tol)
{
    // Fast path with whole-image operations; the pixel loop below only explains a failure.
    {
        cv::Mat eqA, eqB;
        cv::inRange(libA, s.a, s.a, eqA);  // 255 where all channels equal the sentinel
        cv::inRange(libB, s.b, s.b, eqB);
        const cv::Mat libMask = ~(eqA & eqB);
        const cv::Mat refMask = mask != 0;
        if (cv::countNonZero(libMask != refMask) == 0 &&
            cv::norm(libA, ref, cv::NORM_INF, refMask) <= tol)
            return ::testing::AssertionSuccess();
    }
    int missing = 0, extra = 0, wrongColour = 0;
    double worst = 0;
    std::ostringstream first;
    int listed = 0;
    for (int y = 0; y < ref.rows; y++)
        for (int x = 0; x < ref.cols; x++) {
            const bool want = mask.at<uchar>(y, x) != 0;
            const bool got = !isSentinel(libA, x, y, s.a) || !isSentinel(libB, x, y, s.b);
            const Vec3d r = pixel(ref, x, y), l = pixel(libA, x, y);
            std::string what;
            if (want && !got) {
                missing++;
                what = "not drawn, expected " + str(r);
            } else if (!want && got) {
                extra++;
                what = "drawn but should not be: got " + str(l);
            } else if (want) {
                const double d = cv::norm(r, l, cv::NORM_INF);
                worst = std::max(worst, d);
                if (!(d <= tol)) {
                    wrongColour++;
                    what = "expected " + str(r) + " got " + str(l);
                }
            }
            if (!what.empty() && listed++ < 4)
                first << "\n    pixel (x=" << x << ", y=" << y << "): " << what;
        }
    if (missing + extra + wrongColour == 0)
        return ::testing::AssertionSuccess();
    return ::testing::AssertionFailure()
           << missing << " pixels missing, " << extra << " extra, " << wrongColour
           << " with colour off by more than " << tol << " (worst " << worst << "):"
           << first.str();
}

double tolerance(int type, bool gouraud)
{
    if (type == CV_8UC3)
        return 1.0;
    return gouraud ? 1e-4 : 1e-6;
}

// One triangle on fresh canvases of `size` and `type`: library vs reference.
::testing::AssertionResult matchesReference(const Tri& t, cv::Size size, int type, bool gouraud)
{
    const Sentinels s = sentinelsFor(type);
    cv::Mat libA = filled(size, type, s.a), libB = filled(size, type, s.b);
    cv::Mat ref = filled(size, type, s.a);
    try {
        libFill(libA, t, gouraud);
        libFill(libB, t, gouraud);
    } catch (const cv::Exception& e) {
        return ::testing::AssertionFailure() << "library threw: " << e.what();
    }
    shading_ref::fillTriangle(ref, t.v, t.c, gouraud);
    const cv::Mat mask = shading_ref::coverageMask(size, t.v);
    return compareCanvases(libA, libB, s, ref, mask, tolerance(type, gouraud));
}

// matchesReference for the triangle drawn as a one-face mesh (drawMesh): the band pass, in the
// build the CPU runs (AVX2 where it can), where flats and gouraud take the baseline's walk.
::testing::AssertionResult meshMatchesReference(const Tri& t, cv::Size size, bool gouraud)
{
    const Sentinels s = sentinelsFor(CV_32FC3);
    cv::Mat libA = filled(size, CV_32FC3, s.a), libB = filled(size, CV_32FC3, s.b);
    cv::Mat ref = filled(size, CV_32FC3, s.a);
    const std::vector<Point2d> verts(t.v, t.v + 3);
    const std::vector<Vec3d> colours(t.c, t.c + 3);
    const std::vector<cv::Vec3i> faces{cv::Vec3i(0, 1, 2)};
    const int shade = gouraud ? cv::shading::SHADE_GOURAUD : cv::shading::SHADE_FLAT;
    cv::shading::drawMesh(libA, verts, faces, colours, cv::noArray(), shade);
    cv::shading::drawMesh(libB, verts, faces, colours, cv::noArray(), shade);
    shading_ref::fillTriangle(ref, t.v, t.c, gouraud);
    const cv::Mat mask = shading_ref::coverageMask(size, t.v);
    return compareCanvases(libA, libB, s, ref, mask, tolerance(CV_32FC3, gouraud));
}

// Iteration counts are kept small for a quick suite; set SHADING_REF_SCALE=N in the environment to
// run N times as many random cases (and with other seeds) for a soak test.
int scaled(int count)
{
    const char* env = std::getenv("SHADING_REF_SCALE");
    const int k = env ? std::max(1, std::atoi(env)) : 1;
    return count * k;
}

uint64 scaledSeed(uint64 seed)
{
    const char* env = std::getenv("SHADING_REF_SCALE");
    return env && std::atoi(env) > 1 ? seed * 7919 + (uint64)std::atoi(env) : seed;
}

// Runs `count` (scaled) triangles from `make` through both windings, the given canvas types and
// shading; stops reporting after a few failing triangles.
void checkMany(int count, const std::function<Tri(cv::RNG&)>& make, uint64 seed,
               std::initializer_list<int> types, bool gouraud, cv::Size size = kSmall)
{
    cv::RNG rng(scaledSeed(seed));
    int failures = 0;
    for (int i = 0, n = scaled(count); i < n && failures < 3; i++) {
        const Tri t = make(rng);
        for (int type : types)
            for (const Tri& u : { t, swapped(t) }) {
                const ::testing::AssertionResult r = matchesReference(u, size, type, gouraud);
                if (!r) {
                    failures++;
                    ADD_FAILURE() << "triangle #" << i << " on " << size.width << "x"
                                  << size.height << (type == CV_32FC3 ? " CV_32FC3" : " CV_8UC3")
                                  << (gouraud ? " gouraud" : " flats") << "\n  " << describe(u)
                                  << "\n  " << r.message();
                    break;
                }
            }
    }
}

// ---------------------------------------------------------------------------------------------
// Random triangles

// Random colours: [0, 1] for float canvases, [0, 255] for 8-bit ones; rounded to float so that
// they can also be passed as Vec3f.
Vec3d randomColour(cv::RNG& rng, double lo, double hi)
{
    Vec3d c;
    for (int k = 0; k < 3; k++)
        c[k] = (double)(float)rng.uniform(lo, hi);
    return c;
}

enum class Grid { Integer, Half, Subpixel, Double };

double randomCoord(cv::RNG& rng, Grid g, double lo, double hi)
{
    switch (g) {
    case Grid::Integer: return (double)rng.uniform((int)std::floor(lo), (int)std::floor(hi) + 1);
    case Grid::Half: return rng.uniform((int)std::floor(2 * lo), (int)std::floor(2 * hi) + 1) / 2.0;
    case Grid::Subpixel:
        return rng.uniform((int)std::floor(256 * lo), (int)std::floor(256 * hi) + 1) / 256.0;
    default: return rng.uniform(lo, hi);
    }
}

// Colours for the canvas type: float canvases take [0, 1], 8-bit ones [0, 255].
Tri withColours(cv::RNG& rng, Tri t, bool eightBit)
{
    for (Vec3d& c : t.c)
        c = eightBit ? randomColour(rng, 0, 255) : randomColour(rng, 0, 1);
    return t;
}

// A triangle with vertices on grid g in [lo, hi] (same range for x as a fraction of the width).
Tri randomTriangle(cv::RNG& rng, Grid g, double margin, cv::Size size = kSmall)
{
    Tri t;
    for (Point2d& p : t.v)
        p = Point2d(randomCoord(rng, g, -margin, size.width - 1 + margin),
                    randomCoord(rng, g, -margin, size.height - 1 + margin));
    t.form = g == Grid::Integer ? Form::Int : g == Grid::Half ? Form::Float : Form::Double;
    t.vec3f = rng.uniform(0, 2) == 1;
    return t;
}

// Random triangles for both canvas types: the colours are chosen per type inside.
void checkGrid(Grid g, double margin, int count, uint64 seed, bool gouraud)
{
    for (int type : { CV_32FC3, CV_8UC3 })
        checkMany(count, [&](cv::RNG& rng) {
            return withColours(rng, randomTriangle(rng, g, margin), type == CV_8UC3);
        }, seed + (type == CV_8UC3 ? 1000 : 0), { type }, gouraud);
}

// A vertex of a huge triangle: far away along a random direction, or exactly on a line that
// crosses the canvas, so that huge edges do pass through the canvas.
Tri hugeTriangle(cv::RNG& rng, double limit, cv::Size size = kSmall)
{
    const double far = limit * 0.999;  // stay within the accepted range after the extensions
    auto farHalf = [&]() { return std::round(rng.uniform(-far, far) * 2) / 2; };
    Tri t;
    const int mode = rng.uniform(0, 4);
    auto nearPoint = [&]() {
        return Point2d(randomCoord(rng, Grid::Half, 0, size.width - 1),
                       randomCoord(rng, Grid::Half, 0, size.height - 1));
    };
    auto farPoint = [&]() {
        return Point2d(std::round(rng.uniform(-far, far)), std::round(rng.uniform(-far, far)));
    };
    if (mode == 0) {  // all three far away at random: mostly covers all or nothing
        for (Point2d& p : t.v)
            p = farPoint();
    } else if (mode == 1) {  // an edge through two canvas points, extended far both ways
        const Point2d a = nearPoint(), b = nearPoint();
        const Point2d d = b - a;
        const double n = std::max(std::abs(d.x), std::abs(d.y));
        const double k = n > 0 ? std::round(far / n) : 0;
        t.v[0] = a - d * k;
        t.v[1] = b + d * k;
        t.v[2] = rng.uniform(0, 2) ? nearPoint() : farPoint();
    } else if (mode == 2) {  // one vertex on the canvas, two far away
        t.v[0] = nearPoint();
        t.v[1] = farPoint();
        t.v[2] = farPoint();
    } else {  // a horizontal or vertical huge edge exactly through a row or column of samples
        const Point2d a = nearPoint();
        const double s = rng.uniform(0, 2) ? 1.0 : -1.0;
        if (rng.uniform(0, 2)) {
            const double y = std::round(a.y);
            t.v[0] = Point2d(-far, y);
            t.v[1] = Point2d(far, y);
            t.v[2] = Point2d(farHalf(), y + s * rng.uniform(1.0, far));
        } else {
            const double x = std::round(a.x);
            t.v[0] = Point2d(x, -far);
            t.v[1] = Point2d(x, far);
            t.v[2] = Point2d(x + s * rng.uniform(1.0, far), farHalf());
        }
    }
    return t;
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// Single triangles: flats and gouraud

TEST(ShadingVsReference, FlatRandomIntegerTriangles)
{
    checkGrid(Grid::Integer, 4, 600, 1, false);
}

TEST(ShadingVsReference, GouraudRandomIntegerTriangles)
{
    checkGrid(Grid::Integer, 4, 600, 2, true);
}

TEST(ShadingVsReference, FlatRandomHalfPixelTriangles)
{
    checkGrid(Grid::Half, 4, 600, 3, false);
}

TEST(ShadingVsReference, GouraudRandomHalfPixelTriangles)
{
    checkGrid(Grid::Half, 4, 600, 4, true);
}

TEST(ShadingVsReference, FlatRandomSubpixelTriangles)
{
    checkGrid(Grid::Subpixel, 4, 600, 5, false);
}

TEST(ShadingVsReference, GouraudRandomSubpixelTriangles)
{
    checkGrid(Grid::Subpixel, 4, 600, 6, true);
}

TEST(ShadingVsReference, FlatRandomDoubleTriangles)
{
    checkGrid(Grid::Double, 4, 600, 7, false);
}

TEST(ShadingVsReference, GouraudRandomDoubleTriangles)
{
    checkGrid(Grid::Double, 4, 600, 8, true);
}

// A triangle of at most `extent` pixels each way on grid g, around the canvas (its edges
// included), with colours for a float canvas.
Tri smallTriangle(cv::RNG& rng, Grid g, int extent)
{
    Tri t;
    const Point2d o(rng.uniform(-2.0 - extent / 2, 66.0), rng.uniform(-2.0 - extent / 2, 50.0));
    for (Point2d& p : t.v)
        p = Point2d(randomCoord(rng, g, std::round(o.x), std::round(o.x) + extent),
                    randomCoord(rng, g, std::round(o.y), std::round(o.y) + extent));
    return withColours(rng, t, false);
}

// smallTriangle()s on every grid, flat and Gouraud.
void checkSmallTriangles(int extent, int count, uint64 seed)
{
    for (bool gouraud : { false, true })
        for (Grid g : { Grid::Integer, Grid::Half, Grid::Subpixel, Grid::Double })
            checkMany(count, [&](cv::RNG& rng) { return smallTriangle(rng, g, extent); },
                      seed + (int)g + (gouraud ? 10 : 0), { CV_32FC3 }, gouraud);
}

// Small triangles (a few pixels), where every edge and vertex case shows up at close range.
TEST(ShadingVsReference, SmallTriangles)
{
    checkSmallTriangles(4, 300, 100);
}

// Up to 20 pixels: faces up to 16 columns wide are walked by edge functions, one or more
// vectors of columns at a time, wider or taller ones by edge walkers. Both as single triangles
// (the baseline's walk) and as one-face meshes (the band pass's build).
TEST(ShadingVsReference, SmallTrianglesOfEveryWalk)
{
    for (int extent : { 7, 8, 9, 12, 15, 16, 17, 20 }) {
        checkSmallTriangles(extent, 150, 200 + 20 * extent);
        cv::RNG rng(scaledSeed(300 + extent));
        int failures = 0;
        for (int i = 0, n = scaled(300); i < n && failures < 3; i++) {
            const Tri t = smallTriangle(rng, Grid(i % 4), extent);
            for (bool gouraud : { false, true }) {
                const ::testing::AssertionResult r = meshMatchesReference(t, kSmall, gouraud);
                if (!r) {
                    failures++;
                    ADD_FAILURE() << "mesh face #" << i << " of extent " << extent
                                  << (gouraud ? " gouraud" : " flat") << "\n  " << describe(t)
                                  << "\n  " << r.message();
                }
            }
        }
    }
}

// Vertices far outside on all sides: large parts are clipped away.
TEST(ShadingVsReference, PartlyOffCanvas)
{
    for (bool gouraud : { false, true }) {
        checkGrid(Grid::Half, 64, 250, 20 + gouraud, gouraud);
        checkGrid(Grid::Double, 64, 250, 22 + gouraud, gouraud);
    }
}

// Triangles beside the canvas (possibly touching its border lines): usually nothing drawn,
// and a vertical/horizontal edge at x = 0, y = 0, x = w - 1 or y = h - 1 follows the rule.
TEST(ShadingVsReference, WhollyOffCanvas)
{
    for (bool gouraud : { false, true })
        for (int type : { CV_32FC3, CV_8UC3 })
            checkMany(300, [&](cv::RNG& rng) {
                const int side = rng.uniform(0, 4);
                const Grid g = rng.uniform(0, 2) ? Grid::Half : Grid::Double;
                Tri t;
                for (Point2d& p : t.v) {
                    const double a = randomCoord(rng, g, -40, 100);
                    const double b = randomCoord(rng, g, 0, 40);
                    const double w = kSmall.width - 1, h = kSmall.height - 1;
                    p = side == 0 ? Point2d(-b, a) : side == 1 ? Point2d(w + b, a)
                      : side == 2 ? Point2d(a, -b) : Point2d(a, h + b);
                }
                // Left of x = 0 or above y = 0 nothing can be drawn (at most the last column or
                // row, through a left or top edge lying on it, on the other two sides).
                if (side == 0 || side == 2) {
                    EXPECT_EQ(0, cv::countNonZero(shading_ref::coverageMask(kSmall, t.v)));
                }
                return withColours(rng, t, type == CV_8UC3);
            }, 30 + gouraud * 2 + (type == CV_8UC3), { type }, gouraud);
}

// Coordinates around +-1e9 and +-2^40: exact edges, clipped, and quick.
TEST(ShadingVsReference, HugeCoordinates)
{
    for (double far : { 1e9, 1099511627776.0 /* 2^40 */ })
        for (bool gouraud : { false, true })
            for (int type : { CV_32FC3, CV_8UC3 })
                checkMany(150, [&](cv::RNG& rng) {
                    return withColours(rng, hugeTriangle(rng, far), type == CV_8UC3);
                }, 40 + (far > 1e10) * 4 + gouraud * 2 + (type == CV_8UC3), { type }, gouraud);
}

// A few hand-made huge triangles whose edges pass exactly through samples.
TEST(ShadingVsReference, HugeTrianglesThroughSamples)
{
    const double F = 1e9;
    const Point2d tris[][3] = {
        { {-F, 10}, {F, 10}, {0, F} },       // top edge on row 10
        { {-F, 10}, {F, 10}, {0, -F} },      // bottom edge on row 10
        { {7, -F}, {7, F}, {F, 0} },         // left edge on column 7
        { {7, -F}, {7, F}, {-F, 0} },        // right edge on column 7
        { {-F, -F}, {F, F}, {F, -F} },       // diagonal x = y through samples
        { {-F, -F}, {F, F}, {-F, F} },
        { {-F, -F + 3}, {F, F + 3}, {0, F} },  // y = x + 3
        { {20.5, 7}, {F, 7}, {20.5, F} },    // corner inside the canvas, huge legs
        { {-F, 2 * F}, {F, -2 * F + 1}, {F, F} },  // long edge through half-pixel points
    };
    for (const auto& v : tris)
        for (bool gouraud : { false, true })
            for (int type : { CV_32FC3, CV_8UC3 }) {
                Tri t;
                std::copy(v, v + 3, t.v);
                t.c[0] = type == CV_8UC3 ? Vec3d(255, 0, 0) : Vec3d(1, 0, 0);
                t.c[1] = type == CV_8UC3 ? Vec3d(0, 255, 0) : Vec3d(0, 1, 0);
                t.c[2] = type == CV_8UC3 ? Vec3d(0, 0, 255) : Vec3d(0, 0, 1);
                for (const Tri& u : { t, swapped(t) })
                    EXPECT_TRUE(matchesReference(u, kSmall, type, gouraud)) << describe(u);
            }
}

// Gouraud colours stay within 1e-4 for needle triangles with coordinates near 2^40 (found by a
// SHADING_REF_SCALE=40 soak run of HugeCoordinates). The first case, checked with exact rational
// arithmetic: at pixel (27, 22) the weight of vertex 2 is exactly 5/19 = 0.2631579, so channel 2
// must be 0.2631579.
TEST(ShadingVsReference, GouraudPrecisionNear2To40)
{
    const Point2d tris[][3] = {
        { {-1098412116116.5, 633699297797}, {1098412116200.5, -633699297770.5}, {11, 31.5} },
        { {976366325485, -1098412116116}, {-976366325447, 1098412116182.5}, {18, 33} },
        { {-610228953362.5, 1098412116178.5}, {610228953475, -1098412116129}, {54, 29.5} },
        { {-1099511627776, -962072674284}, {1099511627776, 962072674324}, {11, 31.5} },
    };
    for (const auto& v : tris) {
        Tri t;
        std::copy(v, v + 3, t.v);
        t.c[0] = Vec3d(1, 0, 0);
        t.c[1] = Vec3d(0, 1, 0);
        t.c[2] = Vec3d(0, 0, 1);
        for (const Tri& u : { t, swapped(t) })
            EXPECT_TRUE(matchesReference(u, kSmall, CV_32FC3, true)) << describe(u);
    }
}

// NaN, infinite and > 2^40 coordinates draw nothing (and do not throw); 2^40 itself draws.
TEST(ShadingVsReference, CoordinateLimits)
{
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const double inf = std::numeric_limits<double>::infinity();
    const double big = 1099511627776.0;  // 2^40
    const double tooBig = std::nextafter(big, 2 * big);
    const Point2d tris[][3] = {
        { {nan, 0}, {40, 0}, {0, 40} },      { {0, 0}, {40, nan}, {0, 40} },
        { {0, 0}, {40, 0}, {inf, 40} },      { {0, -inf}, {40, 0}, {0, 40} },
        { {0, 0}, {tooBig, 0}, {0, 40} },    { {0, 0}, {40, 0}, {0, -tooBig} },
        { {-tooBig, -tooBig}, {tooBig, 0}, {0, tooBig} },
        { {0, 0}, {big, 0}, {0, 40} },       { {0, -big}, {big, 40}, {-big, 40} },
        { {-big, -big}, {big, -big}, {0, big} }, { {-big, 5}, {big, 5}, {3, 7} },
    };
    for (const auto& v : tris)
        for (bool gouraud : { false, true })
            for (int type : { CV_32FC3, CV_8UC3 }) {
                Tri t;
                std::copy(v, v + 3, t.v);
                cv::RNG crng(9);
                t = withColours(crng, t, type == CV_8UC3);
                EXPECT_TRUE(matchesReference(t, kSmall, type, gouraud)) << describe(t);
            }
}

// Every coordinate exactly half-way between two 1/256 grid points: snapping rounds half away
// from zero (std::llround), on both sides of zero.
TEST(ShadingVsReference, SnapTiesRoundAwayFromZero)
{
    for (bool gouraud : { false, true })
        checkMany(600, [&](cv::RNG& rng) {
            Tri t;
            for (Point2d& p : t.v)
                p = Point2d((rng.uniform(-8 * 256, 72 * 256) + 0.5) / 256.0,
                            (rng.uniform(-8 * 256, 56 * 256) + 0.5) / 256.0);
            return withColours(rng, t, false);
        }, 50 + gouraud, { CV_32FC3 }, gouraud);

    // The hand-worked cases of ShadingReference.SnapRoundsHalfAwayFromZero.
    const Point2d tris[][3] = {
        { {0, -2 - 1.0 / 512}, {2, 2}, {6, 2} }, { {0, -2 + 1.0 / 512}, {2, 2}, {6, 2} },
        { {-2 + 1.0 / 512, 0}, {2, 2}, {2, 6} }, { {2 + 1.0 / 512, 0}, {2 + 1.0 / 512, 6}, {5, 3} },
    };
    for (const auto& v : tris) {
        Tri t;
        std::copy(v, v + 3, t.v);
        cv::RNG crng(5);
        t = withColours(crng, t, false);
        for (const Tri& u : { t, swapped(t) })
            EXPECT_TRUE(matchesReference(u, cv::Size(10, 8), CV_32FC3, false)) << describe(u);
    }
}

// Zero-area, collinear, repeated-vertex and 1/256-thin sliver triangles.
TEST(ShadingVsReference, DegenerateAndSliverTriangles)
{
    for (bool gouraud : { false, true })
        checkMany(600, [&](cv::RNG& rng) {
            Tri t;
            const Point2d a(randomCoord(rng, Grid::Half, -4, 68),
                            randomCoord(rng, Grid::Half, -4, 52));
            const Point2d d(rng.uniform(-20, 21) / 2.0, rng.uniform(-20, 21) / 2.0);
            switch (rng.uniform(0, 5)) {
            case 0:  // collinear
                t.v[0] = a; t.v[1] = a + d; t.v[2] = a + d * rng.uniform(-3, 4);
                break;
            case 1:  // repeated vertex
                t.v[0] = a; t.v[1] = a; t.v[2] = a + d;
                break;
            case 2:  // collinear but for less than half a grid step: zero area after snapping
                t.v[0] = a; t.v[1] = a + d;
                t.v[2] = a + d * 2 +
                         Point2d(rng.uniform(-1.0, 1.0), rng.uniform(-1.0, 1.0)) / 1024.0;
                break;
            case 3:  // collinear plus exactly one grid step: a real sliver
                t.v[0] = a; t.v[1] = a + d;
                t.v[2] = a + d * rng.uniform(-3, 4) +
                         Point2d(rng.uniform(-1, 2), rng.uniform(-1, 2)) / 256.0;
                break;
            default:  // long thin random sliver
                t.v[0] = a; t.v[1] = a + d * 8;
                t.v[2] = a + d * rng.uniform(0.0, 8.0) + Point2d(rng.uniform(-0.3, 0.3), 0);
            }
            return withColours(rng, t, false);
        }, 60 + gouraud, { CV_32FC3 }, gouraud);
}

// 8-bit canvases with colours outside [0, 255]: rounded and saturated.
TEST(ShadingVsReference, EightBitSaturation)
{
    for (bool gouraud : { false, true })
        checkMany(300, [&](cv::RNG& rng) {
            Tri t = randomTriangle(rng, Grid::Double, 8);
            for (Vec3d& c : t.c)
                c = randomColour(rng, -300, 600);
            return t;
        }, 70 + gouraud, { CV_8UC3 }, gouraud);
}

// Drawing into an ROI of a larger image: ROI coordinates, and nothing outside the ROI changes.
TEST(ShadingVsReference, RoiOfLargerImage)
{
    const cv::Rect roiRect(13, 7, kSmall.width, kSmall.height);
    const cv::Size bigSize(kSmall.width + 30, kSmall.height + 20);
    cv::Mat outside(bigSize, CV_8UC1, cv::Scalar(1));
    outside(roiRect).setTo(0);
    for (bool gouraud : { false, true })
        for (int type : { CV_32FC3, CV_8UC3 }) {
            cv::RNG rng(scaledSeed(80 + gouraud * 2 + (type == CV_8UC3)));
            const Sentinels s = sentinelsFor(type);
            int failures = 0;
            for (int i = 0, n = scaled(250); i < n && failures < 3; i++) {
                const Grid g = i % 2 ? Grid::Half : Grid::Double;
                const Tri t = withColours(rng, randomTriangle(rng, g, 20), type == CV_8UC3);
                cv::Mat bigA = filled(bigSize, type, s.a), bigB = filled(bigSize, type, s.b);
                cv::Mat bigRef = filled(bigSize, type, s.a);
                cv::Mat roiA = bigA(roiRect), roiB = bigB(roiRect), roiRef = bigRef(roiRect);
                libFill(roiA, t, gouraud);
                libFill(roiB, t, gouraud);
                shading_ref::fillTriangle(roiRef, t.v, t.c, gouraud);
                const cv::Mat mask = shading_ref::coverageMask(kSmall, t.v);
                const ::testing::AssertionResult r =
                    compareCanvases(roiA, roiB, s, roiRef, mask, tolerance(type, gouraud));
                const cv::Mat sentA = filled(bigSize, type, s.a);
                const cv::Mat sentB = filled(bigSize, type, s.b);
                const double outA = cv::norm(bigA, sentA, cv::NORM_INF, outside);
                const double outB = cv::norm(bigB, sentB, cv::NORM_INF, outside);
                if (!r || outA != 0 || outB != 0) {
                    failures++;
                    ADD_FAILURE() << "ROI " << roiRect << (gouraud ? " gouraud" : " flats")
                                  << (type == CV_32FC3 ? " CV_32FC3" : " CV_8UC3") << "\n  "
                                  << describe(t) << "\n  " << r.message()
                                  << (outA != 0 || outB != 0 ? "\n  wrote outside the ROI" : "");
                }
            }
        }
}

// ---------------------------------------------------------------------------------------------
// Meshes: drawMesh and render against the reference painter's algorithm

namespace {

// Ties: small integers, many equal means. Random: doubles. Tenths: multiples of 0.1, whose
// mathematically equal means can differ in the last bit depending on the order of the sum
// (the reference sums d[i] + d[j] + d[k] in face order). Crowded: clusters of means closer than
// 1e-11 next to a few depths of +-1e300 and -infinity, so that sorting by a coarse key is not
// enough. Infinite: 1, 2 or +infinity (no NaN means: the reference does not skip those).
// None: no depth.
enum class Depths { Ties, Random, Tenths, Crowded, Infinite, None };

struct Mesh {
    std::vector<Point2d> verts;
    std::vector<cv::Vec3i> faces;
    std::vector<Vec3d> colors;
    std::vector<double> depth;
};

// nf faces over nv vertices spread over (and a little beyond) the canvas: big triangles that
// overlap many times. A few faces repeat an index (zero area).
Mesh randomMesh(cv::RNG& rng, cv::Size size, int nv, int nf, Depths depths, bool eightBit)
{
    Mesh m;
    for (int i = 0; i < nv; i++) {
        const Grid g = (Grid)rng.uniform(0, 4);
        m.verts.push_back(Point2d(randomCoord(rng, g, -size.width / 4.0, size.width * 1.25),
                                  randomCoord(rng, g, -size.height / 4.0, size.height * 1.25)));
        m.colors.push_back(eightBit ? randomColour(rng, 0, 255) : randomColour(rng, 0, 1));
        if (depths == Depths::Ties)
            m.depth.push_back((double)rng.uniform(0, 4));  // many equal means
        else if (depths == Depths::Random)
            m.depth.push_back(rng.uniform(-10.0, 10.0));
        else if (depths == Depths::Tenths)
            m.depth.push_back(rng.uniform(0, 10) / 10.0);
        else if (depths == Depths::Crowded)
            m.depth.push_back(i < 2 ? (i ? 1e300 : -1e300)
                              : i < 4 ? -std::numeric_limits<double>::infinity()
                                    : rng.uniform(0, 8) + rng.uniform(0, 8) * std::ldexp(1.0, -40));
        else if (depths == Depths::Infinite) {
            const double choices[] = { 1, 2, std::numeric_limits<double>::infinity() };
            m.depth.push_back(choices[rng.uniform(0, 3)]);
        }
    }
    for (int f = 0; f < nf; f++) {
        cv::Vec3i t(rng.uniform(0, nv), rng.uniform(0, nv), rng.uniform(0, nv));
        if (rng.uniform(0, 40) != 0)  // mostly distinct indices
            while (t[1] == t[0] || t[2] == t[0] || t[2] == t[1])
                t = cv::Vec3i(rng.uniform(0, nv), rng.uniform(0, nv), rng.uniform(0, nv));
        m.faces.push_back(t);
    }
    return m;
}

// Replaces a few vertices by ones the library must skip (NaN, infinite, beyond 2^40) or clip
// (+-1e9, +-2^40).
void addWildVertices(cv::RNG& rng, Mesh& m)
{
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const double inf = std::numeric_limits<double>::infinity();
    const double big = 1099511627776.0;
    const double wild[] = { nan, inf, -inf, std::nextafter(big, 2 * big), 1e9, -1e9, big, -big };
    for (int i = 0; i < (int)m.verts.size() / 10; i++) {
        Point2d& p = m.verts[rng.uniform(0, (int)m.verts.size())];
        (rng.uniform(0, 2) ? p.x : p.y) = wild[rng.uniform(0, 8)];
    }
}

// Rounds every number of the mesh to float, so that float inputs describe the same mesh.
Mesh floatExact(Mesh m)
{
    for (Point2d& p : m.verts)
        p = Point2d((float)p.x, (float)p.y);
    for (Vec3d& c : m.colors)
        c = Vec3d((float)c[0], (float)c[1], (float)c[2]);
    for (double& d : m.depth)
        d = (float)d;
    return m;
}

cv::Mat meshCoverage(cv::Size size, const Mesh& m)
{
    cv::Mat mask(size, CV_8UC1, cv::Scalar(0));
    for (const cv::Vec3i& f : m.faces) {
        const Point2d v[3] = { m.verts[f[0]], m.verts[f[1]], m.verts[f[2]] };
        mask |= shading_ref::coverageMask(size, v);
    }
    return mask;
}

std::string describeMesh(const Mesh& m, const char* what, bool gouraud, int type)
{
    return cv::format("%s %s %s: %d vertices, %d faces, %s depth", what,
                      gouraud ? "SHADE_GOURAUD" : "SHADE_FLAT",
                      type == CV_32FC3 ? "CV_32FC3" : "CV_8UC3", (int)m.verts.size(),
                      (int)m.faces.size(), m.depth.empty() ? "no" : "with");
}

// Library drawMesh vs reference drawMesh on sentinel-filled canvases.
enum class MeshForm { Vectors, Mats, FloatVectors };

// `drawnAs`: the mesh the reference draws instead of m (m less the faces the library skips).
::testing::AssertionResult meshMatches(const Mesh& m, cv::Size size, int type, bool gouraud,
                                       MeshForm form = MeshForm::Vectors,
                                       const Mesh* drawnAs = nullptr)
{
    const Sentinels s = sentinelsFor(type);
    cv::Mat libA = filled(size, type, s.a), libB = filled(size, type, s.b);
    cv::Mat ref = filled(size, type, s.a);
    const int shade = gouraud ? cv::shading::SHADE_GOURAUD : cv::shading::SHADE_FLAT;
    try {
        for (cv::Mat* canvas : { &libA, &libB }) {
            if (form == MeshForm::Mats) {  // N x 2, N x 3 CV_32S, N x 3, 1 x N (CV_64F)
                const cv::Mat v = cv::Mat(m.verts).reshape(1);
                const cv::Mat f = cv::Mat(m.faces).reshape(1);
                const cv::Mat c = cv::Mat(m.colors).reshape(1);
                const cv::Mat d = cv::Mat(m.depth).reshape(1, 1);
                cv::shading::drawMesh(*canvas, v, f, c, d, shade);
            } else if (form == MeshForm::FloatVectors) {  // the mesh must be float-exact
                std::vector<cv::Point2f> v(m.verts.begin(), m.verts.end());
                std::vector<cv::Vec3f> c;
                for (const Vec3d& x : m.colors)
                    c.push_back(cv::Vec3f((float)x[0], (float)x[1], (float)x[2]));
                std::vector<float> d(m.depth.begin(), m.depth.end());
                cv::shading::drawMesh(*canvas, v, m.faces, c, d, shade);
            } else if (m.depth.empty()) {
                cv::shading::drawMesh(*canvas, m.verts, m.faces, m.colors, cv::noArray(), shade);
            } else {
                cv::shading::drawMesh(*canvas, m.verts, m.faces, m.colors, m.depth, shade);
            }
        }
    } catch (const cv::Exception& e) {
        return ::testing::AssertionFailure() << "library threw: " << e.what();
    }
    const Mesh& r = drawnAs ? *drawnAs : m;
    shading_ref::drawMesh(ref, r.verts, r.faces, r.colors, r.depth, gouraud);
    return compareCanvases(libA, libB, s, ref, meshCoverage(size, r), tolerance(type, gouraud));
}

}  // namespace

TEST(ShadingVsReference, DrawMeshFlatRandomDepthTies)
{
    cv::RNG rng(scaledSeed(90));
    for (int i = 0, n = scaled(6); i < n; i++) {
        const Mesh m = randomMesh(rng, cv::Size(96, 72), 150, 200, Depths::Ties, false);
        EXPECT_TRUE(meshMatches(m, cv::Size(96, 72), CV_32FC3, false))
            << describeMesh(m, "drawMesh", false, CV_32FC3) << " #" << i;
    }
}

TEST(ShadingVsReference, DrawMeshGouraudRandomDepthTies)
{
    cv::RNG rng(scaledSeed(91));
    for (int i = 0, n = scaled(6); i < n; i++) {
        const Mesh m = randomMesh(rng, cv::Size(96, 72), 150, 200, Depths::Ties, false);
        EXPECT_TRUE(meshMatches(m, cv::Size(96, 72), CV_32FC3, true))
            << describeMesh(m, "drawMesh", true, CV_32FC3) << " #" << i;
    }
}

namespace {

// Random 96 x 72 meshes of 150 vertices and 200 faces with the given depths, flat and Gouraud,
// n of each: drawMesh equals the reference.
void expectRandomMeshesMatch(uint64 seed, int n, Depths depths)
{
    cv::RNG rng(seed);
    for (bool gouraud : { false, true })
        for (int i = 0; i < n; i++) {
            const Mesh m = randomMesh(rng, cv::Size(96, 72), 150, 200, depths, false);
            EXPECT_TRUE(meshMatches(m, cv::Size(96, 72), CV_32FC3, gouraud))
                << describeMesh(m, "drawMesh", gouraud, CV_32FC3) << " #" << i;
        }
}

}  // namespace

TEST(ShadingVsReference, DrawMeshRandomDepths)
{
    expectRandomMeshesMatch(scaledSeed(92), scaled(4), Depths::Random);
}

TEST(ShadingVsReference, DrawMeshCrowdedDepths)
{
    expectRandomMeshesMatch(scaledSeed(131), scaled(4), Depths::Crowded);
}

TEST(ShadingVsReference, DrawMeshInfiniteDepths)
{
    expectRandomMeshesMatch(scaledSeed(137), scaled(3), Depths::Infinite);
}

// Bands of more than 8192 faces sort on 24-bit keys instead of 16 (mesh.hpp): 12,000 random
// faces on a 64 x 40 canvas, two bands, each reached by most faces.
TEST(ShadingVsReference, DrawMeshBandsOfManyFaces)
{
    cv::RNG rng(scaledSeed(139));
    for (Depths depths : { Depths::Random, Depths::Ties, Depths::Crowded })
        for (bool gouraud : { false, true }) {
            const Mesh m = randomMesh(rng, cv::Size(64, 40), 2000, 12000, depths, false);
            EXPECT_TRUE(meshMatches(m, cv::Size(64, 40), CV_32FC3, gouraud))
                << describeMesh(m, "drawMesh", gouraud, CV_32FC3) << " depths " << int(depths);
        }
}

namespace {

// nf small triangles (a few pixels, subpixel corners, all wound the same way) scattered over the
// canvas, each with its own vertices: little overdraw, but many overlaps, which the library draws
// in face order with a depth test per sample instead of sorting (mesh.hpp).
Mesh smallFacesMesh(cv::RNG& rng, cv::Size size, int nf, Depths depths)
{
    Mesh m;
    const double inf = std::numeric_limits<double>::infinity();
    for (int f = 0; f < nf; f++) {
        const Point2d c(rng.uniform(-2.0, size.width + 2.0), rng.uniform(-2.0, size.height + 2.0));
        Point2d p[3];
        for (Point2d& q : p)
            q = c + Point2d(std::round(rng.uniform(-3.0, 3.0) * 4) / 4,
                            std::round(rng.uniform(-3.0, 3.0) * 4) / 4);
        if ((p[1] - p[0]).cross(p[2] - p[0]) < 0)
            std::swap(p[1], p[2]);
        const Vec3d colour = randomColour(rng, 0, 1);
        const double faceDepth = depths == Depths::Ties     ? double(rng.uniform(0, 3))
                                 : depths == Depths::Infinite ? (rng.uniform(0, 3) ? 1.0 : inf)
                                                              : rng.uniform(-1.0, 1.0);
        for (int k = 0; k < 3; k++) {
            m.verts.push_back(p[k]);
            m.colors.push_back(k ? randomColour(rng, 0, 1) : colour);
            // Equal vertex depths give the face exactly that mean, so Ties ties exactly.
            if (depths != Depths::None)
                m.depth.push_back(depths == Depths::Random ? faceDepth + rng.uniform(-0.1, 0.1)
                                                           : faceDepth);
        }
        m.faces.push_back(cv::Vec3i(3 * f, 3 * f + 1, 3 * f + 2));
    }
    return m;
}

}  // namespace

// Bands with little overdraw are drawn in face order, each sample keeping the nearest face so far
// (the later one on a tie): small faces overlapping a few times, on a canvas of one band and on a
// wide one of two, with random, tied and infinite depths, and none (face order alone).
TEST(ShadingVsReference, DrawMeshSmallFacesInFaceOrder)
{
    cv::RNG rng(scaledSeed(141));
    for (const cv::Size size : { cv::Size(96, 72), cv::Size(2048, 40) })
        for (Depths depths : { Depths::Random, Depths::Ties, Depths::Infinite, Depths::None })
            for (bool gouraud : { false, true }) {
                const int faces = size.area() / 5;  // about 1.5 layers of 7-pixel faces
                const Mesh m = smallFacesMesh(rng, size, faces, depths);
                EXPECT_TRUE(meshMatches(m, size, CV_32FC3, gouraud))
                    << describeMesh(m, "drawMesh", gouraud, CV_32FC3) << " depths "
                    << int(depths) << " canvas " << size;
            }
}

namespace {

// `layers` jittered grids of cells about 2.7 px wide, each face with its own vertices (corners
// on a quarter-pixel grid, +-0.5 px from the cell's), reaching 3 px past every edge of the
// canvas: faces of about 3.6 samples, every box within 4 x 4 samples, the million-face grid's
// kind. Layers are interleaved face by face, so later faces overlap earlier ones.
Mesh tinyGridMesh(cv::RNG& rng, cv::Size size, int layers, Depths depths)
{
    Mesh m;
    const double inf = std::numeric_limits<double>::infinity();
    const double cell = 2.7;
    const int nx = int((size.width + 6) / cell), ny = int((size.height + 6) / cell);
    auto jitter = [&] { return std::round(rng.uniform(-0.5, 0.5) * 4) / 4; };
    for (int j = 0; j < ny; j++)
        for (int i = 0; i < nx; i++)
            for (int layer = 0; layer < layers; layer++)
                for (int half = 0; half < 2; half++) {
                    const double x = -3 + i * cell + 0.9 * layer, y = -3 + j * cell + 0.6 * layer;
                    const Point2d corner[4] = {{x, y}, {x + cell, y}, {x + cell, y + cell},
                                               {x, y + cell}};
                    const int pick[2][3] = {{0, 1, 2}, {0, 2, 3}};
                    const double faceDepth =
                        depths == Depths::Ties       ? double(rng.uniform(0, 3))
                        : depths == Depths::Infinite ? (rng.uniform(0, 3) ? 1.0 : inf)
                                                     : rng.uniform(-1.0, 1.0);
                    const int first = int(m.verts.size());
                    for (int k = 0; k < 3; k++) {
                        const Point2d& q = corner[pick[half][k]];
                        m.verts.push_back(Point2d(q.x + jitter(), q.y + jitter()));
                        m.colors.push_back(randomColour(rng, 0, 1));
                        if (depths != Depths::None)
                            m.depth.push_back(depths == Depths::Random
                                                  ? faceDepth + rng.uniform(-0.1, 0.1)
                                                  : faceDepth);
                    }
                    m.faces.push_back(cv::Vec3i(first, first + 1, first + 2));
                }
    // Among them, faces whose sample boxes the canvas clips to a few samples though they reach
    // 3,000 px past it (slivers from the left, needles from above and below): not tiny, walked
    // (areas of about 500 px, which leave the bands' means under 5 samples a face).
    for (int k = 0; k < 12; k++) {
        const double u = rng.uniform(0.0, 1.0), far = 3000;
        Point2d p[3];
        if (k % 3 == 0) {  // 0.3 px tall, from x = -3000 to the first 2 columns
            const double y = rng.uniform(1.0, size.height - 2.0) + 0.1;
            p[0] = Point2d(-far, y), p[1] = Point2d(1.5 + u, y + 0.15), p[2] = Point2d(1 + u, y + 0.3);
        } else {  // 0.4 px wide, from 3000 px above (or below) to the first (last) rows
            const double x = rng.uniform(1.0, size.width - 2.0) + 0.1;
            const bool above = k % 3 == 1;
            const double end = above ? 1.5 + u : size.height - 2.5 - u;
            p[0] = Point2d(x, above ? -far : size.height + far), p[1] = Point2d(x + 0.4, end);
            p[2] = Point2d(x + 0.2, end + (above ? 0.5 : -0.5));
        }
        if ((p[1] - p[0]).cross(p[2] - p[0]) < 0)
            std::swap(p[1], p[2]);
        const int first = int(m.verts.size());
        for (int j = 0; j < 3; j++) {
            m.verts.push_back(p[j]);
            m.colors.push_back(randomColour(rng, 0, 1));
            if (depths != Depths::None)
                m.depth.push_back(depths == Depths::Infinite ? 1.0 : rng.uniform(-1.0, 1.0));
        }
        // Placed among the grid's faces, where a batch of them is mostly tiny.
        const size_t at = size_t(rng.uniform(0, int(m.faces.size())));
        m.faces.insert(m.faces.begin() + long(at), cv::Vec3i(first, first + 1, first + 2));
    }
    return m;
}

}  // namespace

// Bands in face order whose faces average at most 5 samples take their tiny faces' samples from
// a 4 x 4 block test of 8 faces at once (mesh.hpp: paintTinyBlocks; flat, float canvases): one
// and two layers of tiny faces, with random, tied and infinite depths, on a canvas of two bands
// (faces across the band edge) and a wide one (faces past its right edge), with a few huge faces
// that the canvas clips to tiny boxes among them, in flat (the blocks) and Gouraud (the walk),
// float and 8-bit.
TEST(ShadingVsReference, DrawMeshTinyFacesInFaceOrder)
{
    cv::RNG rng(scaledSeed(149));
    for (const cv::Size size : { cv::Size(97, 70), cv::Size(2049, 21) })
        for (int layers : { 1, 2 })
            for (Depths depths : { Depths::Random, Depths::Ties, Depths::Infinite })
                for (bool gouraud : { false, true })
                    for (int type : { CV_32FC3, CV_8UC3 }) {
                        if (type == CV_8UC3 && (gouraud || layers == 1))
                            continue;
                        const Mesh m = tinyGridMesh(rng, size, layers, depths);
                        EXPECT_TRUE(meshMatches(m, size, type, gouraud))
                            << describeMesh(m, "drawMesh", gouraud, type) << " depths "
                            << int(depths) << " layers " << layers << " canvas " << size;
                    }
}

// render() of bands drawn in face order with depths paints the background after the faces,
// where no face took the sample (mesh.hpp: kUntouchedDepth, paintUntouched): tiny faces (the
// block test), small ones (the pen) and bigger ones (runs), one and two layers, with a fifth of
// the faces left out (holes of single cells and runs of them, background between faces),
// random, tied and infinite depths (a face at +inf still takes its samples), on a small canvas
// (whose bands fill the background first) and, at one thread, on one of 8 whole bands whose rows
// hold more than 1 MB each (background last; fewer bands would be drawn in parts of 16 rows,
// which fill first); each pixel as the reference draws it, and the background exactly bg
// elsewhere.
TEST(ShadingVsReference, RenderFaceOrderBandsPaintTheBackgroundLast)
{
    cv::RNG rng(scaledSeed(157));
    const cv::Scalar bg(-1, -0.5, -0.25);  // no face colour; distinct per channel
    auto withHoles = [&](const Mesh& full) {
        Mesh m = full;
        m.faces.clear();
        for (size_t f = 0; f < full.faces.size(); f++)
            if ((f / 7) % 5 != 0 || rng.uniform(0, 2))  // runs of 7 faces, half of them gone
                m.faces.push_back(full.faces[f]);
        return m;
    };
    const int savedThreads = cv::getNumThreads();
    for (const cv::Size size : { cv::Size(97, 70), cv::Size(1400, 456) })
        for (Depths depths : { Depths::Random, Depths::Ties, Depths::Infinite })
            for (int kind = 0; kind < 3; kind++)
                for (bool gouraud : { false, true }) {
                    const bool wide = size.width > 1000;  // 64 x 1400 x 12 bytes a band
                    if (wide && (kind == 1 || depths == Depths::Ties))
                        continue;  // the small canvas has them; the wide one is costly
                    cv::setNumThreads(wide ? 1 : savedThreads);
                    const Mesh m = withHoles(kind == 2 ? smallFacesMesh(rng, size,
                                                                        size.area() / 8, depths)
                                                       : tinyGridMesh(rng, size, kind + 1, depths));
                    const int shade =
                        gouraud ? cv::shading::SHADE_GOURAUD : cv::shading::SHADE_FLAT;
                    cv::Mat img;
                    cv::shading::render(m.verts, m.faces, m.colors, m.depth, img, shade, size, bg);
                    const cv::Mat ref =
                        shading_ref::render(m.verts, m.faces, m.colors, m.depth, gouraud, size, bg);
                    // Covered: where the reference drew (no face colour is bg), which costs
                    // less than a coverage mask per face on the wide canvas.
                    cv::Mat background;
                    cv::inRange(ref, bg, bg, background);
                    const Sentinels s{ bg, bg };
                    EXPECT_TRUE(compareCanvases(img, img, s, ref, ~background,
                                                tolerance(CV_32FC3, gouraud)))
                        << describeMesh(m, "render", gouraud, CV_32FC3) << " depths "
                        << int(depths) << " kind " << kind << " canvas " << size;
                }
    cv::setNumThreads(savedThreads);
}

// The tiny faces of a band drawn in face order are set up 8 at a time, without sorting their
// vertices, where they fit one vector of columns (mesh.hpp, raster.hpp: smallEdgesEight); the
// rest one at a time. Here: small faces wound both ways (a minority reversed, so the band is
// still drawn in face order) among needles a few columns wide but 10^5 pixels tall, and slivers
// from the canvas's first columns to 8 10^5 pixels left of it, whose areas and edge functions
// need more than 32 bits: each face as the reference draws it.
TEST(ShadingVsReference, DrawMeshNeedlesAmongSmallFacesInFaceOrder)
{
    cv::RNG rng(scaledSeed(147));
    const cv::Size size(2048, 40);
    for (bool gouraud : { false, true }) {
        Mesh m = smallFacesMesh(rng, size, size.area() / 5, Depths::Random);
        for (size_t f = 0; f < m.faces.size(); f += 7)
            std::swap(m.faces[f][1], m.faces[f][2]);
        for (int i = 0; i < 8; i++) {
            const double y = rng.uniform(2, size.height - 4) - 0.2;
            const double far = 1e5 * (i % 4 < 2 ? 1 : -1);
            Point2d p[3];
            if (i % 2 == 0) {  // tall, 0.4 px wide: it reaches columns x and x + 1 at most
                const double x = rng.uniform(0.0, size.width - 2.0);
                p[0] = Point2d(x, y - far), p[1] = Point2d(x + 0.4, y);
                p[2] = Point2d(x + 0.1, y + 3);
            } else {  // 0.1 px tall, from x = -8 10^5 to the first few columns
                const double x = rng.uniform(0.0, 5.0);
                p[0] = Point2d(-8 * std::abs(far), y + 0.15), p[1] = Point2d(x, y + 0.25),
                p[2] = Point2d(x + 2, y + 0.2);
            }
            if (i % 4 == 0)
                std::swap(p[1], p[2]);
            const int first = int(m.verts.size());
            for (const Point2d& q : p) {
                m.verts.push_back(q);
                m.colors.push_back(randomColour(rng, 0, 1));
                m.depth.push_back(rng.uniform(-1.0, 1.0));
            }
            // Among the small faces, so that they share 8-face steps.
            m.faces.insert(m.faces.begin() + rng.uniform(0, int(m.faces.size())),
                           cv::Vec3i(first, first + 1, first + 2));
        }
        EXPECT_TRUE(meshMatches(m, size, CV_32FC3, gouraud))
            << describeMesh(m, "drawMesh", gouraud, CV_32FC3);
    }
}

namespace {

// Two layers of a jittered grid of `cell` x `cell`-pixel cells a little beyond the canvas, the
// second shifted by a fraction of a cell and wound the other way, their faces interleaved in a
// random order: a closed surface seen with its back faces, whose bands of more than 4,096 faces
// the library draws in face order, the nearer winding first and then the other's faces not
// hidden by it (mesh.hpp). Depths: Random, the front layer in [0, 1) and the back one in
// [0.5, 1.5) (some back faces show); Ties, the front at 1 and the back's vertices at 1 or 2
// (faces of equal mean depth meet, whose order decides); Infinite, each vertex either finite or
// infinite. Cells of 2 pixels give boxes of 2-4 columns, cells of 5 boxes of 5-8 columns and up
// to 8 rows, cells of 13 x 2 pixels slivers whose boxes are 12-15 columns wide.
Mesh closedSurfaceMesh(cv::RNG& rng, cv::Size size, Depths depths, cv::Size cell = cv::Size(2, 2))
{
    Mesh m;
    const double inf = std::numeric_limits<double>::infinity();
    const int nx = size.width / cell.width + 2, ny = size.height / cell.height + 2;
    std::vector<cv::Vec3i> layerFaces[2];
    for (int layer = 0; layer < 2; layer++) {
        const int first = (int)m.verts.size();
        const Point2d shift = layer ? Point2d(0.75, 0.25) : Point2d(0, 0);
        for (int j = 0; j <= ny; j++)
            for (int i = 0; i <= nx; i++) {
                const Point2d jitter(std::round(rng.uniform(-0.4, 0.4) * 4) / 4,
                                     std::round(rng.uniform(-0.4, 0.4) * 4) / 4);
                m.verts.push_back(Point2d(cell.width * (i - 1), cell.height * (j - 1)) + shift +
                                  jitter);
                m.colors.push_back(randomColour(rng, 0, 1));
                double d = 0;
                if (depths == Depths::Random)
                    d = layer ? rng.uniform(0.5, 1.5) : rng.uniform(0.0, 1.0);
                else if (depths == Depths::Ties)
                    d = layer ? (double)rng.uniform(1, 3) : 1.0;
                else
                    d = rng.uniform(0, 4) ? 1.0 + layer : inf;
                m.depth.push_back(d);
            }
        for (int j = 0; j < ny; j++)
            for (int i = 0; i < nx; i++) {
                const int a = first + j * (nx + 1) + i, b = a + 1, c = a + nx + 1, d = c + 1;
                for (cv::Vec3i f : { cv::Vec3i(a, b, d), cv::Vec3i(a, d, c) }) {
                    if (layer)
                        std::swap(f[1], f[2]);
                    layerFaces[layer].push_back(f);
                }
            }
    }
    size_t next[2] = { 0, 0 };
    while (next[0] < layerFaces[0].size() || next[1] < layerFaces[1].size()) {
        const int layer = next[1] == layerFaces[1].size() ? 0
                          : next[0] == layerFaces[0].size() ? 1
                                                            : rng.uniform(0, 2);
        m.faces.push_back(layerFaces[layer][next[layer]++]);
    }
    return m;
}

}  // namespace

TEST(ShadingVsReference, DrawMeshClosedSurfaceInFaceOrder)
{
    cv::RNG rng(scaledSeed(151));
    // One band of 64 rows (10,240 faces and more), and two, the second partly on the canvas;
    // every band whole, then in parts. Then bigger faces: one band of 5,000 faces whose boxes
    // are 5-8 samples wide, and one of 6,900 slivers whose boxes are 12-15 samples wide (the
    // hidden-face test of boxes wider than 8, four samples a step with the last step masked).
    struct Surface {
        cv::Size size, cell;
    };
    for (const Surface surface : { Surface{ cv::Size(160, 64), cv::Size(2, 2) },
                                   Surface{ cv::Size(150, 100), cv::Size(2, 2) },
                                   Surface{ cv::Size(400, 64), cv::Size(5, 5) },
                                   Surface{ cv::Size(640, 64), cv::Size(13, 2) } })
        for (Depths depths : { Depths::Random, Depths::Ties, Depths::Infinite })
            for (bool inParts : { false, true })
                for (bool gouraud : { false, true }) {
                    const cv::Size size = surface.size;
                    const Mesh m = closedSurfaceMesh(rng, size, depths, surface.cell);
                    const shading_test::SplitBands split(inParts);
                    EXPECT_TRUE(meshMatches(m, size, CV_32FC3, gouraud))
                        << describeMesh(m, "drawMesh", gouraud, CV_32FC3) << " depths "
                        << int(depths) << " canvas " << size << (inParts ? " in parts" : "");
                }
    // 8-bit canvases, and render's cleared canvas (a band drawn again on a tie clears again).
    for (Depths depths : { Depths::Random, Depths::Ties }) {
        const cv::Size size(160, 64);
        const Mesh m = closedSurfaceMesh(rng, size, depths);
        EXPECT_TRUE(meshMatches(m, size, CV_8UC3, false))
            << describeMesh(m, "drawMesh", false, CV_8UC3) << " depths " << int(depths);
        const cv::Scalar bg(-1, -0.5, -0.25);
        cv::Mat img;
        cv::shading::render(m.verts, m.faces, m.colors, m.depth, img, cv::shading::SHADE_FLAT,
                            size, bg);
        const cv::Mat ref =
            shading_ref::render(m.verts, m.faces, m.colors, m.depth, false, size, bg);
        const Sentinels s{ bg, bg };
        EXPECT_TRUE(compareCanvases(img, img, s, ref, meshCoverage(size, m),
                                    tolerance(CV_32FC3, false)))
            << describeMesh(m, "render", false, CV_32FC3) << " depths " << int(depths);
    }
}

// A band drawn front to back skips the rows that are final everywhere: here a near rectangle
// covers the top rows of the canvas, so the tiny faces behind it that reach below it are walked
// from a row after their first (their edge functions stepped there), wound both ways (a closed
// surface's band, drawn front to back).
TEST(ShadingVsReference, DrawMeshSmallFacesBelowFinalRows)
{
    cv::RNG rng(scaledSeed(149));
    const cv::Size size(64, 32);
    for (bool gouraud : { false, true }) {
        Mesh m = smallFacesMesh(rng, cv::Size(size.width, 6), 200, Depths::Random);
        for (size_t f = 0; f < m.faces.size(); f += 2)
            std::swap(m.faces[f][1], m.faces[f][2]);
        for (size_t v = 0; v < m.verts.size(); v++) {
            m.verts[v].y += 8;  // rows 6 to 16
            m.depth[v] += 3;    // behind the rectangle
        }
        const int first = int(m.verts.size());
        for (const Point2d& q : { Point2d(-1, -1), Point2d(size.width + 1, -1),
                                  Point2d(size.width + 1, 10.5), Point2d(-1, 10.5) }) {
            m.verts.push_back(q);
            m.colors.push_back(randomColour(rng, 0, 1));
            m.depth.push_back(0);
        }
        m.faces.push_back(cv::Vec3i(first, first + 1, first + 2));
        m.faces.push_back(cv::Vec3i(first, first + 2, first + 3));
        EXPECT_TRUE(meshMatches(m, size, CV_32FC3, gouraud))
            << describeMesh(m, "drawMesh", gouraud, CV_32FC3);
    }
}

// A face with a NaN vertex depth has no place in the painter's order and is not drawn (the
// reference, which has no NaN rule, draws the mesh without those faces): random big faces, drawn
// sorted, and small ones, drawn in face order; a few NaN vertices, so that most steps of 8 faces
// in the first pass mix faces with and without a key.
TEST(ShadingVsReference, DrawMeshNaNDepthsSkipTheirFaces)
{
    cv::RNG rng(scaledSeed(143));
    const cv::Size size(96, 72);
    for (bool small : { false, true })
        for (bool gouraud : { false, true }) {
            Mesh m = small ? smallFacesMesh(rng, size, size.area() / 5, Depths::Random)
                           : randomMesh(rng, size, 150, 200, Depths::Random, false);
            std::vector<bool> nan(m.verts.size(), false);
            for (size_t i = 0; i < m.depth.size(); i++)
                if (rng.uniform(0, small ? 12 : 40) == 0) {
                    m.depth[i] = std::numeric_limits<double>::quiet_NaN();
                    nan[i] = true;
                }
            Mesh kept = m;
            kept.faces.clear();
            for (const cv::Vec3i& f : m.faces)
                if (!nan[f[0]] && !nan[f[1]] && !nan[f[2]])
                    kept.faces.push_back(f);
            for (size_t i = 0; i < kept.depth.size(); i++)
                if (nan[i])
                    kept.depth[i] = 0;  // no kept face uses it
            ASSERT_LT(kept.faces.size(), m.faces.size());
            EXPECT_TRUE(meshMatches(m, size, CV_32FC3, gouraud, MeshForm::Vectors, &kept))
                << describeMesh(m, "drawMesh", gouraud, CV_32FC3) << " small " << small;
        }
}

TEST(ShadingVsReference, DrawMeshEmptyDepthKeepsFaceOrder)
{
    expectRandomMeshesMatch(scaledSeed(93), scaled(4), Depths::None);
}

TEST(ShadingVsReference, DrawMeshEightBit)
{
    cv::RNG rng(scaledSeed(94));
    for (bool gouraud : { false, true })
        for (int i = 0, n = scaled(4); i < n; i++) {
            const Mesh m = randomMesh(rng, cv::Size(96, 72), 150, 200,
                                      i % 2 ? Depths::Random : Depths::Ties, true);
            EXPECT_TRUE(meshMatches(m, cv::Size(96, 72), CV_8UC3, gouraud))
                << describeMesh(m, "drawMesh", gouraud, CV_8UC3) << " #" << i;
        }
}

// The same meshes handed over as Mat arguments.
TEST(ShadingVsReference, DrawMeshMatInputs)
{
    cv::RNG rng(scaledSeed(95));
    for (bool gouraud : { false, true }) {
        const Mesh m = randomMesh(rng, cv::Size(96, 72), 150, 200, Depths::Ties, false);
        EXPECT_TRUE(meshMatches(m, cv::Size(96, 72), CV_32FC3, gouraud, MeshForm::Mats))
            << describeMesh(m, "drawMesh (Mat inputs)", gouraud, CV_32FC3);
    }
}

// Float inputs: vector<Point2f>, vector<Vec3f>, vector<float> depths.
TEST(ShadingVsReference, DrawMeshFloatInputs)
{
    cv::RNG rng(scaledSeed(100));
    for (bool gouraud : { false, true })
        for (Depths d : { Depths::Ties, Depths::Random }) {
            const Mesh m = floatExact(randomMesh(rng, cv::Size(96, 72), 150, 200, d, false));
            EXPECT_TRUE(meshMatches(m, cv::Size(96, 72), CV_32FC3, gouraud, MeshForm::FloatVectors))
                << describeMesh(m, "drawMesh (float vectors)", gouraud, CV_32FC3);
        }
}

// Depths in tenths: the mean is (d[i] + d[j] + d[k]) / 3.0 summed in face order, and faces
// whose means are equal as computed keep their order.
TEST(ShadingVsReference, DrawMeshDepthTenths)
{
    expectRandomMeshesMatch(scaledSeed(101), scaled(3), Depths::Tenths);
}

// Faces with NaN, infinite or too large vertices are skipped; faces with +-1e9 or 2^40
// vertices are clipped; the rest of the mesh is drawn as usual.
TEST(ShadingVsReference, DrawMeshWildVertices)
{
    cv::RNG rng(scaledSeed(102));
    for (bool gouraud : { false, true })
        for (int i = 0, n = scaled(3); i < n; i++) {
            Mesh m = randomMesh(rng, cv::Size(96, 72), 150, 200, Depths::Ties, false);
            addWildVertices(rng, m);
            EXPECT_TRUE(meshMatches(m, cv::Size(96, 72), CV_32FC3, gouraud))
                << describeMesh(m, "drawMesh (wild vertices)", gouraud, CV_32FC3) << " #" << i;
        }
}

// A closed mesh: a jittered grid, two triangles per cell, with random depths. No face overlaps
// another, so every sample inside is drawn by exactly one face whatever the order.
TEST(ShadingVsReference, DrawMeshClosedGrid)
{
    cv::RNG rng(96);
    const int nx = 9, ny = 7;
    Mesh m;
    for (int j = 0; j < ny; j++)
        for (int i = 0; i < nx; i++) {
            const double jx = (i > 0 && i < nx - 1) ? rng.uniform(-2.0, 2.0) : 0;
            const double jy = (j > 0 && j < ny - 1) ? rng.uniform(-2.0, 2.0) : 0;
            m.verts.push_back(Point2d(2 + i * 11.0 + jx, 1 + j * 11.0 + jy));
            m.colors.push_back(randomColour(rng, 0, 1));
            m.depth.push_back(rng.uniform(0.0, 1.0));
        }
    for (int j = 0; j + 1 < ny; j++)
        for (int i = 0; i + 1 < nx; i++) {
            const int a = j * nx + i, b = a + 1, c = a + nx, d = c + 1;
            m.faces.push_back(cv::Vec3i(a, b, d));
            m.faces.push_back(cv::Vec3i(a, d, c));
        }
    for (bool gouraud : { false, true })
        EXPECT_TRUE(meshMatches(m, cv::Size(96, 72), CV_32FC3, gouraud))
            << describeMesh(m, "drawMesh grid", gouraud, CV_32FC3);
}

// drawMesh into an ROI writes nothing outside it.
TEST(ShadingVsReference, DrawMeshRoi)
{
    cv::RNG rng(scaledSeed(97));
    const cv::Rect roiRect(11, 5, 96, 72);
    for (bool gouraud : { false, true }) {
        const Mesh m = randomMesh(rng, roiRect.size(), 150, 200, Depths::Ties, false);
        cv::Mat big(roiRect.height + 20, roiRect.width + 30, CV_32FC3, cv::Scalar::all(-1));
        cv::Mat ref = big.clone();
        cv::Mat roi = big(roiRect), refRoi = ref(roiRect);
        cv::shading::drawMesh(roi, m.verts, m.faces, m.colors, m.depth,
                              gouraud ? cv::shading::SHADE_GOURAUD : cv::shading::SHADE_FLAT);
        shading_ref::drawMesh(refRoi, m.verts, m.faces, m.colors, m.depth, gouraud);
        const Sentinels s{ cv::Scalar::all(-1), cv::Scalar::all(-1) };
        EXPECT_TRUE(compareCanvases(roi, roi, s, refRoi,
                                    meshCoverage(roiRect.size(), m), tolerance(CV_32FC3, gouraud)))
            << describeMesh(m, "drawMesh ROI", gouraud, CV_32FC3);
        cv::Mat outside(big.size(), CV_8UC1, cv::Scalar(1));
        outside(roiRect).setTo(0);
        EXPECT_EQ(0, cv::norm(big, cv::Mat(big.size(), CV_32FC3, cv::Scalar::all(-1)),
                              cv::NORM_INF, outside)) << "drawMesh wrote outside the ROI";
    }
}

// Same pictures whatever the number of threads.
TEST(ShadingVsReference, DrawMeshThreadCounts)
{
    const int saved = cv::getNumThreads();
    cv::RNG rng(scaledSeed(98));
    const Mesh m = randomMesh(rng, cv::Size(96, 72), 150, 200, Depths::Ties, false);
    for (bool gouraud : { false, true })
        for (int threads : { 1, 2, 8 }) {
            cv::setNumThreads(threads);
            EXPECT_TRUE(meshMatches(m, cv::Size(96, 72), CV_32FC3, gouraud))
                << describeMesh(m, "drawMesh", gouraud, CV_32FC3) << ", " << threads
                << " threads";
        }
    cv::setNumThreads(saved);
}

// render: a new CV_32FC3 image filled with the background (channel order kept), then drawMesh.
TEST(ShadingVsReference, RenderRandomMeshes)
{
    cv::RNG rng(scaledSeed(99));
    const cv::Scalar bg(-1, -0.5, -0.25);  // no face colour; distinct per channel
    for (bool gouraud : { false, true })
        for (Depths d : { Depths::Ties, Depths::Random, Depths::None }) {
            const cv::Size size(96, 72);
            const Mesh m = randomMesh(rng, size, 150, 200, d, false);
            cv::Mat img;
            if (d == Depths::None)
                cv::shading::render(m.verts, m.faces, m.colors, cv::noArray(), img,
                                    gouraud ? cv::shading::SHADE_GOURAUD : cv::shading::SHADE_FLAT,
                                    size, bg);
            else
                cv::shading::render(m.verts, m.faces, m.colors, m.depth, img,
                                    gouraud ? cv::shading::SHADE_GOURAUD : cv::shading::SHADE_FLAT,
                                    size, bg);
            ASSERT_EQ(CV_32FC3, img.type());
            ASSERT_EQ(size, img.size());
            const cv::Mat ref = shading_ref::render(m.verts, m.faces, m.colors, m.depth, gouraud,
                                                    size, bg);
            // Background pixels must be exactly bg; render's "sentinel" is the background.
            const Sentinels s{ bg, bg };
            EXPECT_TRUE(compareCanvases(img, img, s, ref, meshCoverage(size, m),
                                        tolerance(CV_32FC3, gouraud)))
                << describeMesh(m, "render", gouraud, CV_32FC3);
        }
}

// render with its default white background: a quad of two triangles, the rest exactly white.
TEST(ShadingVsReference, RenderDefaultBackground)
{
    const std::vector<Point2d> verts = { {3.5, 2.25}, {60.75, 4}, {58, 45.5}, {5, 40} };
    const std::vector<cv::Vec3i> faces = { {0, 1, 2}, {0, 2, 3} };
    const std::vector<Vec3d> colors = { {0.9, 0.1, 0.2}, {0.1, 0.8, 0.3}, {0.2, 0.3, 0.7},
                                        {0.5, 0.5, 0.0} };
    const std::vector<double> depth = { 1, 2, 3, 4 };
    cv::Mat img;
    cv::shading::render(verts, faces, colors, depth, img, cv::shading::SHADE_GOURAUD, kSmall);
    const cv::Mat ref = shading_ref::render(verts, faces, colors, depth, true, kSmall);
    EXPECT_LE(cv::norm(img, ref, cv::NORM_INF), 1e-4);
    EXPECT_EQ(kSmall, img.size());
}
