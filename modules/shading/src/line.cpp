// This file is part of opencv_shading. License: Apache-2.0.
//
// Line segments: Bresenham's midpoint algorithm and an exact fixed-point DDA, one walker for
// both. A segment becomes "minor(i) = floor((P + i Q) / R)" over integer major-axis positions i;
// stepping that numerator by Q and carrying when its remainder passes R is the midpoint decision
// variable (unit 1: Q = 2 dy, R = 2 dx, Bresenham's) or the DDA's exact minor coordinate (unit
// 1/256 px). Clipping solves the same inequality for i, so far-off endpoints cost nothing.
#include <opencv2/shading.hpp>

#include "input.hpp"
#include "raster.hpp"

#include <opencv2/core/utility.hpp>

#include <algorithm>
#include <climits>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <vector>

namespace cv {
namespace shading {

using namespace detail;

namespace {

//! floor(n / d), d != 0, in 64 bits when both fit (the usual case: a 128-bit division is slow).
inline Int128 floorDivAny(Int128 n, Int128 d)
{
    if (d < 0)
        n = -n, d = -d;
    if (n >= INT64_MIN && n <= INT64_MAX && d <= INT64_MAX)
        return floorDiv<int64_t>(int64_t(n), int64_t(d));
    return floorDiv<Int128>(n, d);
}

inline Int128 ceilDivAny(Int128 n, Int128 d)
{
    return -floorDivAny(-n, d);
}

/** One segment ready to walk. Major-axis positions i in [iFirst, iLast] are drawn, pixel
(i, minor(i)) (x major) or (minor(i), i) (y major), minor(i) = floor((P + i Q) / R), R > 0. */
struct LineSetup {
    Int128 P;
    int64_t Q, R;
    int64_t iFirst, iLast;
    bool xMajor;
    bool constant;          //!< both colours equal: no interpolation per pixel
    int64_t unit;           //!< fixed-point units per pixel: 1 (Bresenham) or 256 (DDA)
    int64_t colorOrigin;    //!< the first endpoint's major coordinate, in units
    double invLength;       //!< 1 / (second - first major coordinate), 0 for a point
    int rowMin, rowMax;     //!< rows the segment may touch (a superset), for banding
    Vec3d c0, dc;           //!< colour at t = 0 and its change to t = 1
};

//! Rounds to the nearest integer, halves to even (cvRound's rule) beyond int's range too.
inline int64_t roundHalfEven(double v)
{
    return int64_t(std::nearbyint(v));  // the default rounding mode: to nearest, ties to even
}

inline bool validPoint(const Point2d& p)
{
    return std::abs(p.x) <= kMaxCoordinate && std::abs(p.y) <= kMaxCoordinate;
}

//! Sets up segment a -> b. False for an invalid one (NaN, infinite, beyond 2^40).
bool setupLine(const Point2d& a, const Point2d& b, const Vec3d& ca, const Vec3d& cb, bool dda,
               LineSetup& s)
{
    if (!validPoint(a) || !validPoint(b))
        return false;
    const int64_t u = dda ? kSubpixelOne : 1;
    int64_t x0, y0, x1, y1;
    if (dda) {
        const FixedPoint p = snapToGrid(a), q = snapToGrid(b);
        x0 = p.x, y0 = p.y, x1 = q.x, y1 = q.y;
    } else {
        x0 = roundHalfEven(a.x), y0 = roundHalfEven(a.y);
        x1 = roundHalfEven(b.x), y1 = roundHalfEven(b.y);
    }
    s.xMajor = std::abs(x1 - x0) >= std::abs(y1 - y0);
    int64_t maj0 = s.xMajor ? x0 : y0, min0 = s.xMajor ? y0 : x0;
    int64_t maj1 = s.xMajor ? x1 : y1, min1 = s.xMajor ? y1 : x1;
    s.unit = u;
    s.colorOrigin = maj0;
    s.invLength = maj1 != maj0 ? 1.0 / double(maj1 - maj0) : 0.0;
    s.c0 = ca;
    s.dc = cb - ca;
    s.constant = ca == cb;
    if (maj1 < maj0) {  // walk from the smaller major coordinate
        std::swap(maj0, maj1);
        std::swap(min0, min1);
    }
    const int64_t dMaj = maj1 - maj0, dMin = min1 - min0;
    // Positions round(start) .. round(end), round(v) = floor(v + 1/2) (exact for Bresenham).
    s.iFirst = floorDiv<int64_t>(2 * maj0 + u, 2 * u);
    s.iLast = floorDiv<int64_t>(2 * maj1 + u, 2 * u);
    // Ties go toward the left end: up on x-major segments whose y falls to the right, else down.
    const int64_t down = (s.xMajor && dMin < 0) ? 0 : 1;
    if (dMaj == 0) {  // a point: minor = round(min0 / u)
        s.P = Int128(2 * min0 + u - down);
        s.Q = 0;
        s.R = 2 * u;
    } else {
        // minor(i) = round((min0 dMaj + (u i - maj0) dMin) / (u dMaj)) as floor((P + i Q) / R)
        s.P = 2 * Int128(min0) * dMaj - 2 * Int128(maj0) * dMin + Int128(u) * dMaj - down;
        s.Q = 2 * u * dMin;
        s.R = 2 * u * dMaj;
    }
    // Rows touched: the rounded endpoints' rows, one more each way for safety.
    const int64_t rowA = floorDiv<int64_t>(y0, u), rowB = floorDiv<int64_t>(y1, u);
    const int64_t lo = std::min(rowA, rowB) - 1, hi = std::max(rowA, rowB) + 1;
    s.rowMin = int(std::clamp<int64_t>(lo, INT_MIN / 2, INT_MAX / 2));
    s.rowMax = int(std::clamp<int64_t>(hi, INT_MIN / 2, INT_MAX / 2));
    return true;
}

/** Draws the part of segment s within rows [rowBegin, rowEnd) and all columns of the canvas:
the positions whose pixel lies there are found arithmetically, then walked. */
template <typename T>
void drawLine(Mat& canvas, const LineSetup& s, int rowBegin, int rowEnd)
{
    if (s.rowMax < rowBegin || s.rowMin >= rowEnd)
        return;
    const int64_t majLo = s.xMajor ? 0 : rowBegin, majHi = s.xMajor ? canvas.cols : rowEnd;
    const int64_t minLo = s.xMajor ? rowBegin : 0, minHi = s.xMajor ? rowEnd : canvas.cols;
    Int128 lo = std::max<int64_t>(s.iFirst, majLo), hi = std::min<int64_t>(s.iLast, majHi - 1);
    if (lo > hi)
        return;
    // minLo <= floor((P + i Q) / R) < minHi  <=>  minLo R <= P + i Q < minHi R.
    const Int128 low = Int128(minLo) * s.R - s.P, high = Int128(minHi) * s.R - s.P;
    if (s.Q > 0) {  // i Q >= low and i Q <= high - 1
        lo = std::max(lo, ceilDivAny(low, s.Q));
        hi = std::min(hi, floorDivAny(high - 1, s.Q));
    } else if (s.Q < 0) {  // dividing by Q < 0 turns both around
        lo = std::max(lo, ceilDivAny(high - 1, s.Q));
        hi = std::min(hi, floorDivAny(low, s.Q));
    } else if (low > 0 || high <= 0) {
        return;
    }
    if (lo > hi)
        return;
    const int64_t first = int64_t(lo), count = int64_t(hi - lo) + 1;
    const Int128 n = s.P + Int128(first) * s.Q;
    int64_t minor = int64_t(floorDivAny(n, s.R));
    int64_t rem = int64_t(n - Int128(minor) * s.R);  // in [0, R)
    const int64_t qDiv = floorDiv<int64_t>(s.Q, s.R), qRem = s.Q - qDiv * s.R;

    const size_t rowStep = canvas.step[0], pixel = 3 * sizeof(T);
    const ptrdiff_t majorStep = s.xMajor ? ptrdiff_t(pixel) : ptrdiff_t(rowStep);
    const ptrdiff_t minorStep = s.xMajor ? ptrdiff_t(rowStep) : ptrdiff_t(pixel);
    uchar* p = canvas.data + first * majorStep + minor * minorStep;
    const ptrdiff_t advance = majorStep + qDiv * minorStep;

    if (s.constant) {
        const T color[3] = {saturate_cast<T>(s.c0[0]), saturate_cast<T>(s.c0[1]),
                            saturate_cast<T>(s.c0[2])};
        for (int64_t k = 1;; k++) {
            std::memcpy(p, color, sizeof(color));
            if (k == count)  // no step past the last pixel: p stays within the canvas
                return;
            rem += qRem;  // the midpoint decision, branch-free: the carry is unpredictable
            const int64_t carry = -int64_t(rem >= s.R);
            rem -= s.R & carry;
            p += advance + (minorStep & carry);
        }
    }
    // t = (i u - origin) / length: exact integers in double until the one multiplication.
    double along = double(first * s.unit - s.colorOrigin);
    const double stepAlong = double(s.unit);
    for (int64_t k = 1;; k++, along += stepAlong) {
        const double t = std::min(std::max(along * s.invLength, 0.0), 1.0);
        T* px = reinterpret_cast<T*>(p);
        px[0] = saturate_cast<T>(s.c0[0] + s.dc[0] * t);
        px[1] = saturate_cast<T>(s.c0[1] + s.dc[1] * t);
        px[2] = saturate_cast<T>(s.c0[2] + s.dc[2] * t);
        if (k == count)
            return;
        rem += qRem;
        const int64_t carry = -int64_t(rem >= s.R);
        rem -= s.R & carry;
        p += advance + (minorStep & carry);
    }
}

//! Pixels below which the segments are drawn on the calling thread alone.
constexpr double kParallelPixels = 1 << 16;
constexpr int kMinBandRows = 16;

template <typename T>
void drawLines(Mat& canvas, const std::vector<LineSetup>& segs)
{
    // Estimated work: each segment's on-canvas length at most.
    double pixels = 0;
    const double limit = double(std::max(canvas.rows, canvas.cols));
    for (const LineSetup& s : segs)
        pixels += std::min(double(s.iLast - s.iFirst + 1), limit);
    const int threads = getNumThreads();
    const int bands = std::min(canvas.rows / kMinBandRows, 4 * threads);
    if (threads <= 1 || bands <= 1 || pixels < kParallelPixels) {
        for (const LineSetup& s : segs)
            drawLine<T>(canvas, s, 0, canvas.rows);
        return;
    }
    // Row bands, each drawing every segment clipped to its rows, in order: a pixel ends with the
    // colour of the last segment covering it, as when drawn sequentially.
    parallel_for_(Range(0, bands), [&](const Range& r) {
        for (int b = r.start; b < r.end; b++) {
            const int rowBegin = int(int64_t(canvas.rows) * b / bands);
            const int rowEnd = int(int64_t(canvas.rows) * (b + 1) / bands);
            for (const LineSetup& s : segs)
                drawLine<T>(canvas, s, rowBegin, rowEnd);
        }
    });
}

}  // namespace

void lines(InputOutputArray canvasArr, InputArray points, InputArray colors, int algorithm)
{
    checkCanvas(canvasArr, "canvas");
    if (algorithm != LINE_BRESENHAM && algorithm != LINE_DDA)
        CV_Error(Error::StsBadFlag,
                 format("algorithm: expected LINE_BRESENHAM (0) or LINE_DDA (1), got %d",
                        algorithm));
    std::vector<Point2d> pts;
    std::vector<Vec3d> cols;
    readPoints(points, "points", -1, pts);
    if (pts.size() % 2 != 0)
        CV_Error(Error::StsBadSize,
                 format("points: expected an even number of points (two per segment), got %zu",
                        pts.size()));
    readColors(colors, "colors", int(pts.size()), cols);
    std::vector<LineSetup> segs;
    segs.reserve(pts.size() / 2);
    for (size_t i = 0; i + 1 < pts.size(); i += 2) {
        LineSetup s;
        if (setupLine(pts[i], pts[i + 1], cols[i], cols[i + 1], algorithm == LINE_DDA, s))
            segs.push_back(s);
    }
    Mat canvas = canvasArr.getMat();
    if (canvas.depth() == CV_8U)
        drawLines<uchar>(canvas, segs);
    else
        drawLines<float>(canvas, segs);
}

}  // namespace shading
}  // namespace cv
