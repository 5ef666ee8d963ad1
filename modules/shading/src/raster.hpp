// This file is part of opencv_shading. License: Apache-2.0.
//
// The rasterization core: exact fixed-point triangle setup and the scan-line walk that turns a
// triangle into horizontal spans [xBegin, xEnd) per row. Every drawing feature is a span shader
// on top of this walk; nothing else decides which samples a triangle covers.
#ifndef OPENCV_SHADING_RASTER_HPP
#define OPENCV_SHADING_RASTER_HPP

#include "isa.hpp"

#include <opencv2/core.hpp>
#include <opencv2/core/hal/intrin.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <utility>

/** 1: the span shaders and helpers use OpenCV's universal intrinsics where the platform has them;
0: their scalar paths only (CMake option OPENCV_SHADING_SCALAR, which scripts/scalar.sh builds
and tests, so that both paths stay exact). */
#ifndef OPENCV_SHADING_SIMD128
#define OPENCV_SHADING_SIMD128 CV_SIMD128
#endif

namespace cv {
namespace shading {
namespace detail {

//! A vertex on the subpixel grid (snapToGrid). Outside the ISA namespace: the builds hand
//! snapped vertices to each other (MeshData::snapped).
struct FixedPoint {
    int64_t x, y;
};

//! The Gouraud shader steps colours within +-this in float; beyond it (or NaN) it computes
//! them per pixel, where stepping could overflow (gouraudInRange).
constexpr double kGouraudColorLimit = 1e37;

OPENCV_SHADING_ISA_BEGIN

// GCC and Clang provide 128-bit integers; __extension__ keeps -Wpedantic quiet about it.
__extension__ typedef __int128 Int128;
__extension__ typedef unsigned __int128 UInt128;

//! Vertices live on a 1/256 pixel grid, as on GPUs: coverage is then decided exactly.
constexpr int kSubpixelBits = 8;
constexpr int64_t kSubpixelOne = int64_t(1) << kSubpixelBits;
//! Largest accepted |coordinate| (2^40 px). With it every setup product fits in 128 bits and
//! every per-row quantity in 64 bits, so far off-canvas vertices clip exactly.
constexpr double kMaxCoordinate = 1099511627776.0;

//! Coordinates and canvas sizes below 2^28 subpixels (2^20 px) keep every walker and edge
//! function quantity within 64 bits.
constexpr int64_t kNarrowLimit = int64_t(1) << 28;

//! std::llround (halves away from zero) without the library call; exact, since v - trunc(v)
//! is exact in binary floating point. |v| must be below 2^62.
inline int64_t roundHalfAway(double v)
{
    const int64_t t = int64_t(v);  // truncates toward zero
    const double frac = v - double(t);
    return t + (frac >= 0.5 ? 1 : 0) - (frac <= -0.5 ? 1 : 0);
}

//! Marks a vertex that cannot be drawn (non-finite or out of range): no real one is that far.
constexpr int64_t kInvalidCoordinate = INT64_MIN;

//! Snaps (x, y) to the subpixel grid; NaN, infinite or out-of-range coordinates give a point
//! with x == kInvalidCoordinate, which every triangle setup rejects.
inline FixedPoint snapToGrid(const Point2d& v)
{
    if (!(std::abs(v.x) <= kMaxCoordinate && std::abs(v.y) <= kMaxCoordinate))
        return {kInvalidCoordinate, 0};
    return {roundHalfAway(v.x * double(kSubpixelOne)), roundHalfAway(v.y * double(kSubpixelOne))};
}

/** A point no face uses (drawMesh3d's vertices behind the near plane, whose faces are cut or
dropped): invalid like the others, and marked so that the band pass's check that every point is
on the narrow grid can pass it by. */
constexpr FixedPoint kUnusedPoint = {kInvalidCoordinate, 1};

inline bool isUnusedPoint(const FixedPoint& p)
{
    return p.x == kUnusedPoint.x && p.y == kUnusedPoint.y;
}

inline bool isValid(const FixedPoint p[3])
{
    return p[0].x != kInvalidCoordinate && p[1].x != kInvalidCoordinate &&
           p[2].x != kInvalidCoordinate;
}

template <typename T>
inline T floorDiv(T a, T b)  // b > 0
{
    T q = a / b;
    return (a % b != 0 && a < 0) ? q - 1 : q;
}

template <typename T>
inline T ceilDiv(T a, T b)  // b > 0
{
    return -floorDiv<T>(-a, b);
}

/** ceil(n / d) for d > 0, |n| < 2^60 and |n / d| < 2^40, with rem = result * d - n in [0, d),
from `quotient`, n / d computed in floating point (within 1/4 of the true value for these ranges).
Its ceiling is within one of the answer and is corrected exactly in integers, without branches
(the correction's direction is data-dependent): several times faster than a 64-bit integer
division. */
inline int64_t ceilDivNarrow(int64_t n, int64_t d, double quotient, int64_t& rem)
{
    int64_t q = int64_t(quotient);  // truncated toward zero ...
    q += double(q) < quotient;      // ... and now ceil(quotient)
    int64_t r = n - q * d;          // exact; the answer needs r in (-d, 0]
    const int64_t up = r > 0;       // q * d < n: one more
    q += up;
    r -= up * d;
    const int64_t down = r <= -d;  // (q - 1) * d >= n: one less
    q -= down;
    r += down * d;
    rem = -r;
    return q;
}

/** Walks one non-horizontal edge down the scan lines (the seed's active boundary point,
x += 1/m, done in exact integers).

For row y the edge crosses at c(y) = N(y) / D pixels, N stepping by a constant per row. The
walker holds x = ceil(c(y)), the first sample at or right of the crossing: a left edge covers
[x, ...), a right edge covers [..., x), which is exactly the top-left rule for on-edge samples.
*/
struct EdgeWalker {
    int64_t x;        //!< ceil of the crossing for the current row
    int64_t rem;      //!< N = x * den - rem, 0 <= rem < den
    int64_t step;     //!< ceil(per-row increment / den)
    int64_t stepRem;  //!< step * den - increment, in [0, den)
    int64_t den;

    /** Positions the walker at pixel row `row` for the edge a -> b (a.y < b.y). `narrow`: all
    coordinates and the row are below kNarrowLimit subpixels, so 64 bits suffice (the common
    case; 128-bit division is several times slower). */
    void start(const FixedPoint& a, const FixedPoint& b, int64_t row, bool narrow)
    {
        const int64_t dy = b.y - a.y, dx = b.x - a.x;
        den = dy * kSubpixelOne;
        const int64_t inc = dx * kSubpixelOne;
        if (narrow) {
            // One division for both quotients: the product's extra rounding is far below 1/4.
            const double invDen = 1.0 / double(den);
            const int64_t n = a.x * dy + (row * kSubpixelOne - a.y) * dx;
            x = ceilDivNarrow(n, den, double(n) * invDen, rem);
            step = ceilDivNarrow(inc, den, double(inc) * invDen, stepRem);
        } else {
            const Int128 n = Int128(a.x) * dy + Int128(row * kSubpixelOne - a.y) * dx;
            const Int128 q = ceilDiv<Int128>(n, den);
            x = int64_t(q);
            rem = int64_t(q * den - n);
            step = ceilDiv<int64_t>(inc, den);
            stepRem = step * den - inc;
        }
    }

    void nextRow()  // branch-free: the carry is data-dependent and mispredicts often
    {
        rem += stepRem;
        const int64_t carry = rem >= den;
        x += step - carry;
        rem -= carry * den;
    }
};

/** A triangle ready to walk: vertices sorted top to bottom and its rows clipped to the target.

Rows [rowBegin, rowMid) lie between the top and middle vertex (active edges: long and upper
short), rows [rowMid, rowEnd) between the middle and bottom vertex (long and lower short). A
horizontal edge spans no rows, so it never becomes active: the seed's special cases (horizontal
edges, scan lines through vertices, coincident vertices) all fall out of the ceil() row bounds.
*/
struct TriangleSetup {
    FixedPoint top, mid, bottom;
    int rowBegin, rowMid, rowEnd;  //!< clipped to [0, height]
    bool longEdgeLeft;             //!< the top-bottom edge bounds spans on the left
    bool narrow;                   //!< walkers may use 64-bit arithmetic (see EdgeWalker)
    //! For a small triangle (see kSmallColumns), the first sample column of its box; else -1.
    int smallFirstColumn;
    //! A small triangle's samples all lie within this many columns from smallFirstColumn.
    int smallColumnCount;
};

/** Triangles at most this many sample columns wide and kSmallRows tall are walked by edge
functions at all their columns at once (walkSmallTriangle): for the few rows of a small face,
cheaper than starting two EdgeWalkers, each with its divisions. 16 columns, not 8: 40% of the
demo knot's faces are 8 to 15 pixels wide. Within these extents every edge function value fits
in 32 bits (below 2^26). */
constexpr int kSmallColumns = 16;
constexpr int kSmallRows = 16;

//! ceil(v / 256), the first pixel row or column at or after fixed-point v, clamped to [0, limit].
inline int ceilToPixel(int64_t fixed, int limit)
{
    // ceil(v / 256) as a shift: >> of a negative value is arithmetic on every compiler we build
    // with (and defined so from C++20).
    const int64_t pixel = (fixed + kSubpixelOne - 1) >> kSubpixelBits;
    return int(std::min<int64_t>(std::max<int64_t>(pixel, 0), limit));
}

//! The first sample column at or right of fixed-point x, clamped to the target's columns.
inline int firstColumnAt(int64_t xMin, int width)
{
    return std::min(ceilToPixel(xMin, width), width - 1);
}

inline bool above(const FixedPoint& a, const FixedPoint& b)
{
    return a.y < b.y || (a.y == b.y && a.x < b.x);
}

/** The box of samples triangle p may cover on a target of `size` pixels, without the full setup
(for binning and occlusion tests): rows [rowBegin, rowEnd), columns [colFirst, colLast]. False
when it surely covers nothing there. */
struct SampleBox {
    int rowBegin, rowEnd;
    int colFirst, colLast;
};

inline bool triangleBox(const FixedPoint p[3], Size size, SampleBox& box)
{
    if (!isValid(p))
        return false;
    const int64_t xMax = std::max({p[0].x, p[1].x, p[2].x});
    const int64_t xMin = std::min({p[0].x, p[1].x, p[2].x});
    if (xMax < 0 || xMin > int64_t(size.width) * kSubpixelOne)
        return false;
    box.rowBegin = ceilToPixel(std::min({p[0].y, p[1].y, p[2].y}), size.height);
    box.rowEnd = ceilToPixel(std::max({p[0].y, p[1].y, p[2].y}), size.height);
    // Samples x with xMin <= 256 x <= xMax; clamping keeps a superset, which is all a box needs.
    box.colFirst = firstColumnAt(xMin, size.width);
    box.colLast = int(std::min<int64_t>(xMax >> kSubpixelBits, size.width - 1));
    return box.rowBegin < box.rowEnd && box.colFirst <= box.colLast;
}

/** The rest of the setup, shared by setupTriangle and setupBoxedTriangle: p holds the vertices
sorted top to bottom, xMin and xMax their extreme x. Rows are not set here. Returns false for
zero area. */
inline bool setupSorted(const FixedPoint p[3], int64_t xMin, int64_t xMax, bool narrow, Size size,
                        TriangleSetup& t)
{
    t.narrow = narrow;
    // Sign of the middle vertex against the long edge: < 0 puts it to the right.
    int sign;
    if (narrow) {
        const int64_t cross = (p[2].x - p[0].x) * (p[1].y - p[0].y) -
                              (p[2].y - p[0].y) * (p[1].x - p[0].x);
        sign = (cross > 0) - (cross < 0);
    } else {
        const Int128 cross = Int128(p[2].x - p[0].x) * (p[1].y - p[0].y) -
                             Int128(p[2].y - p[0].y) * (p[1].x - p[0].x);
        sign = (cross > 0) - (cross < 0);
    }
    if (sign == 0)
        return false;
    t.top = p[0];
    t.mid = p[1];
    t.bottom = p[2];
    t.longEdgeLeft = sign < 0;
    // Extents below kSmallColumns and kSmallRows pixels leave at most that many columns and rows.
    const bool small = xMax - xMin < kSmallColumns * kSubpixelOne &&
                       p[2].y - p[0].y < kSmallRows * kSubpixelOne;
    t.smallFirstColumn = small ? firstColumnAt(xMin, size.width) : -1;
    // A covered sample x has 256 x < xMax: a sample at the rightmost x lies on a right edge
    // (the interior is to its left), which the top-left rule leaves out. So x < ceil(xMax / 256).
    t.smallColumnCount =
        small ? int(std::min<int64_t>(((xMax + kSubpixelOne - 1) >> kSubpixelBits) -
                                          t.smallFirstColumn,
                                      kSmallColumns))
              : 0;
    return true;
}

/** Sets up the triangle with snapped vertices `in` for a target of `size` pixels. Returns false
when it covers no sample of the target: an invalid vertex, zero area, or no overlap. `order`
receives the input indices of top, middle and bottom vertex (sorted by y, then x): a canonical
order, so everything derived from it is independent of the order the vertices were given in. */
inline bool setupTriangle(const FixedPoint in[3], Size size, TriangleSetup& t, int order[3])
{
    if (!isValid(in))
        return false;
    FixedPoint p[3] = {in[0], in[1], in[2]};
    order[0] = 0, order[1] = 1, order[2] = 2;
    auto sortPair = [&](int i, int j) {
        if (above(p[j], p[i])) {
            std::swap(p[i], p[j]);
            std::swap(order[i], order[j]);
        }
    };
    sortPair(0, 1);
    sortPair(1, 2);
    sortPair(0, 1);
    const int64_t xMin = std::min({p[0].x, p[1].x, p[2].x});
    const int64_t xMax = std::max({p[0].x, p[1].x, p[2].x});
    if (xMax < 0 || xMin > int64_t(size.width) * kSubpixelOne)
        return false;
    const int64_t extent = std::max({xMax, -xMin, p[2].y, -p[0].y});
    const int64_t canvasExtent = int64_t(std::max(size.width, size.height)) * kSubpixelOne;
    if (!setupSorted(p, xMin, xMax, extent < kNarrowLimit && canvasExtent < kNarrowLimit, size, t))
        return false;
    t.rowBegin = ceilToPixel(p[0].y, size.height);
    t.rowMid = ceilToPixel(p[1].y, size.height);
    t.rowEnd = ceilToPixel(p[2].y, size.height);
    return t.rowBegin < t.rowEnd;
}

/** setupTriangle for a mesh's face whose box triangleBox() gave (so its vertices are valid and
it overlaps the target): the rows come from the box. Narrow faces (nearly all) are sorted
without branches, on one 64-bit key per vertex: y, then x, then the input index, so that equal
points keep their input order, as setupTriangle's stable sort does. */
__attribute__((always_inline)) inline bool setupBoxedTriangle(const FixedPoint in[3],
                                                              const SampleBox& box, Size size,
                                                              TriangleSetup& t, int order[3])
{
    const int64_t xMin = std::min({in[0].x, in[1].x, in[2].x});
    const int64_t xMax = std::max({in[0].x, in[1].x, in[2].x});
    const int64_t yMin = std::min({in[0].y, in[1].y, in[2].y});
    const int64_t yMax = std::max({in[0].y, in[1].y, in[2].y});
    const int64_t extent = std::max({xMax, -xMin, yMax, -yMin});
    const int64_t canvasExtent = int64_t(std::max(size.width, size.height)) * kSubpixelOne;
    if (!(extent < kNarrowLimit && canvasExtent < kNarrowLimit))
        return setupTriangle(in, size, t, order);
    // |x|, |y| < 2^28: y + 2^28 and x + 2^28 take 29 bits each.
    uint64_t key[3];
    for (int i = 0; i < 3; i++)
        key[i] = uint64_t(in[i].y + kNarrowLimit) << 33 | uint64_t(in[i].x + kNarrowLimit) << 2 |
                 uint64_t(i);
    const uint64_t a = std::min(key[0], key[1]), b = std::max(key[0], key[1]);
    const uint64_t c = std::min(b, key[2]), last = std::max(b, key[2]);
    const uint64_t first = std::min(a, c), middle = std::max(a, c);
    order[0] = int(first & 3), order[1] = int(middle & 3), order[2] = int(last & 3);
    const FixedPoint p[3] = {in[order[0]], in[order[1]], in[order[2]]};
    if (!setupSorted(p, xMin, xMax, true, size, t))
        return false;
    t.rowBegin = box.rowBegin;
    t.rowMid = ceilToPixel(p[1].y, size.height);
    t.rowEnd = box.rowEnd;
    return true;
}

/** The lanes that walkSmallTriangle tests a row's samples in: 8 columns a vector in the AVX2
build (isa_avx2.hpp), 4 in the baseline. */
#if CV_SIMD256
using SmallLanes = v_int32x8;
inline SmallLanes smallLanesAll(int32_t v) { return v256_setall_s32(v); }
//! Lane i: a + b * i.
inline SmallLanes smallLanesRamp(int32_t a, int32_t b)
{
    return v256_setall_s32(a) + v256_setall_s32(b) * v_int32x8(0, 1, 2, 3, 4, 5, 6, 7);
}
#else
using SmallLanes = v_int32x4;
inline SmallLanes smallLanesAll(int32_t v) { return v_setall_s32(v); }
inline SmallLanes smallLanesRamp(int32_t a, int32_t b)
{
    return SmallLanes(a, a + b, a + 2 * b, a + 3 * b);  // no 32-bit multiply in SSE2
}
#endif
constexpr int kSmallLanes = SmallLanes::nlanes;

/** walkSmallTriangle's rows with kGroups vectors of columns: G at the first column of each
edge's first row (at0), its steps per column and per row, for edges 0-2. */
template <int kGroups, typename SpanFn>
__attribute__((always_inline)) inline void walkSmallRows(int begin, int end, int firstColumn,
                                                         unsigned onCanvas, const int32_t at0[3],
                                                         const int32_t perColumn[3],
                                                         const int32_t perRow[3], SpanFn& spanFn)
{
    SmallLanes at[3][kGroups], step[3];
    for (int e = 0; e < 3; e++) {
        at[e][0] = smallLanesRamp(at0[e], perColumn[e]);
        for (int g = 1; g < kGroups; g++)
            at[e][g] = at[e][0] + smallLanesAll(perColumn[e] * kSmallLanes * g);
        step[e] = smallLanesAll(perRow[e]);
    }
    const SmallLanes zero = smallLanesAll(0);
    for (int row = begin; row < end; row++) {
        unsigned inside = 0;
        for (int g = 0; g < kGroups; g++) {
            inside |= unsigned(v_signmask((at[0][g] > zero) & (at[1][g] > zero) &
                                          (at[2][g] > zero)))
                      << (g * kSmallLanes);
            for (int e = 0; e < 3; e++)
                at[e][g] += step[e];
        }
        inside &= onCanvas;
        if (inside) {  // a convex shape: the covered samples are contiguous
            spanFn(row, firstColumn + __builtin_ctz(inside),
                   firstColumn + 32 - __builtin_clz(inside));
        }
    }
}

/** walkSmallRows for faces of `columns` columns that one vector does not hold, out of line:
inlined beside the one-vector loop, it cost a 4-pixel grid 9-20% (the enclosing band loop lost
registers, or the walk its inlining). The baseline's 4-lane vectors take two for up to 8 columns
(2-3% off the demo and sphere512 in that build), four beyond. */
template <typename SpanFn>
__attribute__((noinline)) void walkWiderSmallRows(int columns, int begin, int end,
                                                  int firstColumn, unsigned onCanvas,
                                                  const int32_t at0[3],
                                                  const int32_t perColumn[3],
                                                  const int32_t perRow[3], SpanFn& spanFn)
{
    if (kSmallColumns / kSmallLanes > 2 && columns <= 2 * kSmallLanes)
        walkSmallRows<2>(begin, end, firstColumn, onCanvas, at0, perColumn, perRow, spanFn);
    else
        walkSmallRows<kSmallColumns / kSmallLanes>(begin, end, firstColumn, onCanvas, at0,
                                                   perColumn, perRow, spanFn);
}

#if CV_SIMD256
/** walkSmallTriangle's edge functions of 8 faces at once, for the meshes of tiny faces: the same
three (at0, perColumn, perRow), bit for bit, in another order, without sorting the vertices.
x[j], y[j]: vertex j of each face (given order, narrow, so their low words); firstColumn and
firstRow: where its walk starts (t.smallFirstColumn and the walk's first row). Writes lane i to
at0[e][i] etc. Returns bit i set where face i has a nonzero area and is small enough for one
vector of columns (at most kSmallLanes): the others are set up as usual.

Why no sort: with A = (v2 - v0) x (v1 - v0), the edges u -> v in the cyclic order (v0 v1, v1 v2,
v2 v0) all have F(w) = A at their third vertex w. walkSmallTriangle's s F of edge a -> b (a above
b, s = 1 for a left edge, where F(w) > 0) is then sign(A) F_uv whichever of u, v is above (both
signs flip with the direction), and the edge is left where A > 0 unless v is above u. */
inline int smallEdgesEight(const v_int32x8 x[3], const v_int32x8 y[3],
                           const v_int32x8& firstColumn, const v_int32x8& firstRow,
                           int32_t* const at0[3], int32_t* const perColumn[3],
                           int32_t* const perRow[3])
{
    const v_int32x8 zero = v256_setzero_s32(), one = v256_setall_s32(1);
    const v_int32x8 xMin = v_min(v_min(x[0], x[1]), x[2]), xMax = v_max(v_max(x[0], x[1]), x[2]);
    const v_int32x8 yMin = v_min(v_min(y[0], y[1]), y[2]), yMax = v_max(v_max(y[0], y[1]), y[2]);
    const v_int32x8 limit = v256_setall_s32(int(kSmallColumns * kSubpixelOne));
    // setupSorted's small test and its column count (a sample x has x < ceil(xMax / 256)).
    const v_int32x8 columnsEnd =
        (xMax + v256_setall_s32(int(kSubpixelOne - 1))) >> kSubpixelBits;
    const v_int32x8 fits = (xMax - xMin < limit) & (yMax - yMin < limit) &
                           (columnsEnd - firstColumn <= v256_setall_s32(kSmallLanes));
    // Within these extents every product below is under 2^26 in magnitude; the lanes of faces
    // beyond them may wrap, and are not used.
    const v_int32x8 area = (x[2] - x[0]) * (y[1] - y[0]) - (y[2] - y[0]) * (x[1] - x[0]);
    const v_int32x8 negative = area < zero;  // all ones: v is negated as (v ^ m) - m
    const v_int32x8 positive = area > zero;
    const v_int32x8 ox = firstColumn << kSubpixelBits, oy = firstRow << kSubpixelBits;
    for (int e = 0; e < 3; e++) {
        const v_int32x8 &ux = x[e], &uy = y[e], &vx = x[(e + 1) % 3], &vy = y[(e + 1) % 3];
        const v_int32x8 dx = vx - ux, dy = vy - uy;
        const v_int32x8 f = (ox - ux) * dy - (oy - uy) * dx;
        const v_int32x8 left = positive ^ (uy > vy);
        const v_int32x8 horizontal = dy == zero;  // never active: always passes
        v_store(at0[e], v_select(horizontal, one, ((f ^ negative) - negative) + (left & one)));
        v_store(perColumn[e],
                v_select(horizontal, zero, ((dy ^ negative) - negative) << kSubpixelBits));
        const v_int32x8 notNegative = ~negative;  // -s dx = (dx ^ m) - m with m = ~negative
        v_store(perRow[e],
                v_select(horizontal, zero, ((dx ^ notNegative) - notNegative) << kSubpixelBits));
    }
    return v_signmask(v_reinterpret_as_f32(fits & (negative | positive)));
}

//! All ones in the lanes of faces whose samples, `rows` by `columns`, fit 4 x 4 (see below).
inline v_int32x8 tinyBlockFitsEight(const v_int32x8& rows, const v_int32x8& columns)
{
    const v_int32x8 zero = v256_setzero_s32(), five = v256_setall_s32(5);
    return (rows > zero) & (rows < five) & (columns > zero) & (columns < five);
}

/** The samples of 8 small faces (smallEdgesEight's lanes) that lie within 4 x 4 samples from
each one's first column and row: lane i's bit 4 r + c is sample (firstColumn + c, firstRow + r)
of face i, tested as walkSmallRows tests it (every G > 0), so the same samples. rows and columns:
how many of each the face's sample box holds where it may be drawn (within the band and the
canvas); fits: tinyBlockFitsEight's lanes. Lanes that do not fit get 0. About 20 instructions a
face, where a walk of its rows takes about 50. */
inline v_int32x8 tinyBlockSamplesEight(const int32_t* const at0[3], const int32_t* const perColumn[3],
                                       const int32_t* const perRow[3], const v_int32x8& rows,
                                       const v_int32x8& columns, const v_int32x8& fits)
{
    const v_int32x8 zero = v256_setzero_s32(), one = v256_setall_s32(1);
    // Bits 4 r + c for r < rows and c < columns (a shift of 32 or more gives 0).
    const v_int32x8 inRows =
        v_int32x8(_mm256_sllv_epi32(one.val, v_shl<2>(rows).val)) - one;
    const v_int32x8 inRow = v_int32x8(_mm256_sllv_epi32(one.val, columns.val)) - one;
    const v_int32x8 inBox =
        inRows & (inRow | v_shl<4>(inRow) | v_shl<8>(inRow) | v_shl<12>(inRow)) & fits;
    v_int32x8 rowAt[3], column[3], row[3];
    for (int e = 0; e < 3; e++) {
        rowAt[e] = v256_load(at0[e]);
        column[e] = v256_load(perColumn[e]);
        row[e] = v256_load(perRow[e]);
    }
    v_int32x8 covered = zero;
    for (int r = 0; r < 4; r++) {
        v_int32x8 at[3] = {rowAt[0], rowAt[1], rowAt[2]};
        for (int c = 0; c < 4; c++) {
            covered = covered | ((at[0] > zero) & (at[1] > zero) & (at[2] > zero) &
                                 v256_setall_s32(1 << (4 * r + c)));
            for (int e = 0; e < 3; e++)
                at[e] += column[e];
        }
        for (int e = 0; e < 3; e++)
            rowAt[e] += row[e];
    }
    return covered & inBox;
}

/** ExactWeights' integers for 8 small faces at once (those smallEdgesEight reports small, whose
extents keep every value below 2^26; the other lanes are not meaningful): the vertices in the
canonical order (top, mid, bottom, sorted as setupTriangle sorts them) as indices 0-2 into the
given order (vertex[i]); edge function i, opposite canonical vertex i, at the sample
(firstColumn, firstRow) and its steps per column and per row; and 1 / twice the signed area,
the same division of the same integer (invArea2, 8 doubles). */
inline void smallWeightsEight(const v_int32x8 x[3], const v_int32x8 y[3],
                              const v_int32x8& firstColumn, const v_int32x8& firstRow,
                              int32_t* const vertex[3], int32_t* const at0[3],
                              int32_t* const perColumn[3], int32_t* const perRow[3],
                              double* invArea2)
{
    v_int32x8 px[3] = {x[0], x[1], x[2]}, py[3] = {y[0], y[1], y[2]};
    v_int32x8 index[3] = {v256_setall_s32(0), v256_setall_s32(1), v256_setall_s32(2)};
    auto sortPair = [&](int i, int j) {  // setupTriangle's: j first where it is above i
        const v_int32x8 swap = (py[j] < py[i]) | ((py[j] == py[i]) & (px[j] < px[i]));
        const v_int32x8 xi = px[i], yi = py[i], vi = index[i];
        px[i] = v_select(swap, px[j], xi), px[j] = v_select(swap, xi, px[j]);
        py[i] = v_select(swap, py[j], yi), py[j] = v_select(swap, yi, py[j]);
        index[i] = v_select(swap, index[j], vi), index[j] = v_select(swap, vi, index[j]);
    };
    sortPair(0, 1);
    sortPair(1, 2);
    sortPair(0, 1);
    const v_int32x8 ox = firstColumn << kSubpixelBits, oy = firstRow << kSubpixelBits;
    for (int i = 0; i < 3; i++) {
        const v_int32x8 &ax = px[(i + 1) % 3], &ay = py[(i + 1) % 3];
        const v_int32x8 dx = px[(i + 2) % 3] - ax, dy = py[(i + 2) % 3] - ay;
        v_store(vertex[i], index[i]);
        v_store(at0[i], dx * (oy - ay) - dy * (ox - ax));
        v_store(perColumn[i], v256_setzero_s32() - (dy << kSubpixelBits));
        v_store(perRow[i], dx << kSubpixelBits);
    }
    const v_int32x8 area2 = (px[1] - px[0]) * (py[2] - py[0]) - (py[1] - py[0]) * (px[2] - px[0]);
    const v_float64x4 one = v256_setall_f64(1.0);
    v_store(invArea2, one / v_cvt_f64(area2));
    v_store(invArea2 + 4, one / v_cvt_f64_high(area2));
}
#endif

/** walkTriangle for a small triangle (t.smallFirstColumn >= 0) over rows [begin, end): the
same spans, found by testing the samples of each row from the box's first column against the
three edges, a vector of columns at a time (as many vectors as t.smallColumnCount needs: one
for a grid's 4-pixel cells).

Edge a -> b (a above b) covers, as the EdgeWalker does, the samples right of or on it when it is
a left edge (F >= 0, F(p) = (p - a) x (b - a) in subpixels) and those strictly left of it when
it is a right edge (F < 0); each test is G = s F + bias > 0. Testing all three edges on every row
equals walking the two active ones: within the rows between its ends an edge is active, and
outside them the triangle's samples lie strictly inside its half-plane. The one exception, a
horizontal edge, is never active and is left out (the row range bounds it). */
template <typename SpanFn>
inline void walkSmallTriangle(const TriangleSetup& t, int begin, int end, int width,
                              SpanFn&& spanFn)
{
    const int firstColumn = t.smallFirstColumn;
    const int64_t ox = int64_t(firstColumn) * kSubpixelOne, oy = int64_t(begin) * kSubpixelOne;
    // G at column 0 of the first row, and its steps per column and per row.
    int32_t at0[3], perColumn[3], perRow[3];
    auto edgeAt = [&](int e, const FixedPoint& a, const FixedPoint& b, bool left) {
        const int64_t dx = b.x - a.x, dy = b.y - a.y;
        at0[e] = 1, perColumn[e] = 0, perRow[e] = 0;  // horizontal: always passes
        if (dy != 0) {
            const int64_t s = left ? 1 : -1;
            at0[e] = int32_t(s * ((ox - a.x) * dy - (oy - a.y) * dx) + (left ? 1 : 0));
            perColumn[e] = int32_t(s * dy * kSubpixelOne);
            perRow[e] = int32_t(-s * dx * kSubpixelOne);
        }
    };
    const bool longLeft = t.longEdgeLeft;
    edgeAt(0, t.top, t.bottom, longLeft);
    edgeAt(1, t.top, t.mid, !longLeft);
    edgeAt(2, t.mid, t.bottom, !longLeft);
    // Columns at or past the canvas's right edge are not tested.
    const unsigned onCanvas = (1u << std::min(kSmallColumns, width - firstColumn)) - 1;
    static_assert(kSmallColumns <= 4 * kSmallLanes, "at most four vectors of columns");
    if (t.smallColumnCount <= kSmallLanes)
        walkSmallRows<1>(begin, end, firstColumn, onCanvas, at0, perColumn, perRow, spanFn);
    else
        walkWiderSmallRows(t.smallColumnCount, begin, end, firstColumn, onCanvas, at0, perColumn,
                           perRow, spanFn);
}

/** Calls spanFn(row, xBegin, xEnd) for every non-empty span of t within rows
[rowFirst, rowLast) and columns [0, width). One loop over both halves (the short edge restarts at
the middle vertex's row) keeps the walk inlined and its state in registers. */
template <typename SpanFn>
inline void walkTriangle(const TriangleSetup& t, int rowFirst, int rowLast, int width,
                         SpanFn&& spanFn)
{
    const int begin = std::max(t.rowBegin, rowFirst);
    const int end = std::min(t.rowEnd, rowLast);
    if (begin >= end)
        return;
    if (t.smallFirstColumn >= 0) {
        walkSmallTriangle(t, begin, end, width, spanFn);
        return;
    }
    EdgeWalker longEdge, shortEdge;
    longEdge.start(t.top, t.bottom, begin, t.narrow);
    int restartRow = end;  // where the lower short edge takes over, if within [begin, end)
    if (t.rowMid > begin) {
        shortEdge.start(t.top, t.mid, begin, t.narrow);
        restartRow = std::min(t.rowMid, end);
    } else {
        shortEdge.start(t.mid, t.bottom, begin, t.narrow);
    }
    const bool longLeft = t.longEdgeLeft;
#if OPENCV_SHADING_SIMD128 && CV_AVX2
    // Both edges stepped in one vector, lane 0 the left edge and lane 1 the right:
    // EdgeWalker::nextRow in 64-bit lanes. The two walkers held ten general registers in the
    // span callbacks' loops, which then kept their own values on the stack.
    const EdgeWalker& left = longLeft ? longEdge : shortEdge;
    const EdgeWalker& right = longLeft ? shortEdge : longEdge;
    __m128i x = _mm_set_epi64x(right.x, left.x), rem = _mm_set_epi64x(right.rem, left.rem);
    __m128i step = _mm_set_epi64x(right.step, left.step);
    __m128i stepRem = _mm_set_epi64x(right.stepRem, left.stepRem);
    __m128i den = _mm_set_epi64x(right.den, left.den);
    __m128i denLess1 = _mm_sub_epi64(den, _mm_set1_epi64x(1));
    for (int row = begin; row < end; row++) {
        if (row == restartRow) {
            shortEdge.start(t.mid, t.bottom, row, t.narrow);
            const __m128i shortLane = longLeft ? _mm_set_epi64x(-1, 0) : _mm_set_epi64x(0, -1);
            auto take = [&](__m128i& v, int64_t value) {
                v = _mm_blendv_epi8(v, _mm_set1_epi64x(value), shortLane);
            };
            take(x, shortEdge.x);
            take(rem, shortEdge.rem);
            take(step, shortEdge.step);
            take(stepRem, shortEdge.stepRem);
            take(den, shortEdge.den);
            take(denLess1, shortEdge.den - 1);
        }
        const int64_t xl = std::max<int64_t>(_mm_cvtsi128_si64(x), 0);
        const int64_t xr = std::min<int64_t>(_mm_extract_epi64(x, 1), width);
        if (xl < xr)
            spanFn(row, int(xl), int(xr));
        rem = _mm_add_epi64(rem, stepRem);
        const __m128i carry = _mm_cmpgt_epi64(rem, denLess1);  // rem >= den: all ones
        x = _mm_add_epi64(_mm_add_epi64(x, step), carry);
        rem = _mm_sub_epi64(rem, _mm_and_si128(carry, den));
    }
#else
    for (int row = begin; row < end; row++) {
        if (row == restartRow)
            shortEdge.start(t.mid, t.bottom, row, t.narrow);
        const int64_t xl = std::max<int64_t>(longLeft ? longEdge.x : shortEdge.x, 0);
        const int64_t xr = std::min<int64_t>(longLeft ? shortEdge.x : longEdge.x, width);
        if (xl < xr)
            spanFn(row, int(xl), int(xr));
        longEdge.nextRow();
        shortEdge.nextRow();
    }
#endif
}

OPENCV_SHADING_ISA_END
}  // namespace detail
}  // namespace shading
}  // namespace cv

#endif  // OPENCV_SHADING_RASTER_HPP
