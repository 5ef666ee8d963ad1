// This file is part of opencv_shading. License: Apache-2.0.
//
// Span shaders: given a row and a run of covered columns, write the colours. A shader is built
// once per triangle (all per-triangle math happens there) and then only fills runs.
#ifndef OPENCV_SHADING_SHADERS_HPP
#define OPENCV_SHADING_SHADERS_HPP

#include "raster.hpp"

#include <opencv2/core.hpp>
#include <opencv2/core/hal/intrin.hpp>

#include <algorithm>
#include <cstddef>
#include <cstring>
#include <limits>
#include <type_traits>

namespace cv {
namespace shading {
namespace detail {
OPENCV_SHADING_ISA_BEGIN

/** Samples per depth bound of the z-buffer's occlusion test, as a shift (8): the span shaders
keep the bounds, ZBufferBlocks (mesh.hpp) tests faces against them. */
constexpr int kDepthBoundShift = 3;

//! Converts a colour channel to the canvas's element type (8-bit: rounded and saturated).
template <typename T>
inline T toChannel(float v)
{
    return saturate_cast<T>(v);
}

#if OPENCV_SHADING_SIMD128
//! Stores the first three lanes of v at p: 8 + 4 bytes, nothing after them touched.
inline void storePixel(float* p, const v_float32x4& v)
{
    v_store_low(p, v);
    p[2] = v_extract_n<2>(v);
}

#if OPENCV_SHADING_SIMD128 && CV_SIMD128_64F
//! A vertex colour's channels 0 and 1 as doubles (a mesh's colours: Vec3d, or the caller's
//! Vec3f read where they are; float to double is exact).
inline v_float64x2 channelPair(const Vec3d& c)
{
    return v_load(c.val);
}
inline v_float64x2 channelPair(const Vec3f& c)
{
    return v_cvt_f64(v_load_low(c.val));
}
#endif

#if CV_AVX2
//! 8 RGB pixels of value v (lanes r, g, b), one after the other, as three 32-byte vectors: lanes
//! r g b r g b r g, b r g b r g b r and g b r g b r g b.
__attribute__((always_inline)) inline void eightPixelLanes(const v_float32x4& v, v_float32x8& l0,
                                                           v_float32x8& l1, v_float32x8& l2)
{
    const __m256 v8 = _mm256_castps128_ps256(v.val);
    l0 = v_float32x8(_mm256_permutevar8x32_ps(v8, _mm256_setr_epi32(0, 1, 2, 0, 1, 2, 0, 1)));
    l1 = v_float32x8(_mm256_permutevar8x32_ps(v8, _mm256_setr_epi32(2, 0, 1, 2, 0, 1, 2, 0)));
    l2 = v_float32x8(_mm256_permutevar8x32_ps(v8, _mm256_setr_epi32(1, 2, 0, 1, 2, 0, 1, 2)));
}
#endif

//! Runs from this many pixels on are written in groups: float claimed runs
//! (storeFloatPixelGroups) and every 8-bit Gouraud run (storeBytePixelGroups).
constexpr int kFloatGroupMinPixels = 8;

/** The values of a Gouraud run [xBegin, xEnd) of at least kGroupPixels, in groups of that many
pixels: fn(x, v0, v1, v2) for each group's first pixel x, its 3 kGroupPixels channels in three
vectors of lanes r g b r g b ... of pixels 0 0 0 1 1 1 ..., each base[k] + step[k] *
float(x + pixel - spanBegin) for its channel k, one product and one sum in float as the scalar
loop's. 8 pixels in 8-lane vectors (AVX2) or 4 in 4-lane ones; the last group ends at xEnd,
overlapping the one before with the same values. */
#if CV_AVX2
constexpr int kGroupPixels = 8;
#else
constexpr int kGroupPixels = 4;
#endif
template <typename GroupFn>
__attribute__((always_inline)) inline void forPixelGroups(int spanBegin, int xBegin, int xEnd,
                                                          v_float32x4 base, v_float32x4 step,
                                                          GroupFn&& fn)
{
#if CV_AVX2
    v_float32x8 b0, b1, b2, s0, s1, s2;
    eightPixelLanes(base, b0, b1, b2);
    eightPixelLanes(step, s0, s1, s2);
    const v_int32x8 o0(0, 0, 0, 1, 1, 1, 2, 2), o1(2, 3, 3, 3, 4, 4, 4, 5),
        o2(5, 5, 6, 6, 6, 7, 7, 7);
    auto group = [&](int x) {
        const v_int32x8 at = v256_setall_s32(x - spanBegin);
        fn(x, b0 + s0 * v_cvt_f32(at + o0), b1 + s1 * v_cvt_f32(at + o1),
           b2 + s2 * v_cvt_f32(at + o2));
    };
#else
    const float r = v_extract_n<0>(base), g = v_extract_n<1>(base), b = v_extract_n<2>(base);
    const float sr = v_extract_n<0>(step), sg = v_extract_n<1>(step), sb = v_extract_n<2>(step);
    const v_float32x4 b0(r, g, b, r), b1(g, b, r, g), b2(b, r, g, b);
    const v_float32x4 s0(sr, sg, sb, sr), s1(sg, sb, sr, sg), s2(sb, sr, sg, sb);
    const v_int32x4 o0(0, 0, 0, 1), o1(1, 1, 2, 2), o2(2, 3, 3, 3);
    auto group = [&](int x) {
        const v_int32x4 at = v_setall_s32(x - spanBegin);
        fn(x, b0 + s0 * v_cvt_f32(at + o0), b1 + s1 * v_cvt_f32(at + o1),
           b2 + s2 * v_cvt_f32(at + o2));
    };
#endif
    const int last = xEnd - kGroupPixels;
    for (int x = xBegin; x < last; x += kGroupPixels)
        group(x);
    group(last);
}

/** storeFloatPixels for runs of kFloatGroupMinPixels or more: forPixelGroups' groups in three
stores each (32 or 16 bytes) instead of a store per pixel. */
__attribute__((always_inline)) inline void storeFloatPixelGroups(float* row, int spanBegin,
                                                                 int xBegin, int xEnd,
                                                                 v_float32x4 base,
                                                                 v_float32x4 step)
{
    forPixelGroups(spanBegin, xBegin, xEnd, base, step, [row](int x, auto v0, auto v1, auto v2) {
        constexpr int n = decltype(v0)::nlanes;
        float* const q = row + 3 * x;
        v_store(q, v0);
        v_store(q + n, v1);
        v_store(q + 2 * n, v2);
    });
}

/** storeGouraudRun's 8-bit pixels of a run of kFloatGroupMinPixels or more: forPixelGroups'
values rounded to nearest even (cvRound's conversion) and saturated by two packs, as toChannel
gives them, 3 kGroupPixels bytes a group. (Shorter runs: grid512's spans of 1-5 pixels took
1.03x the time through groups of 4.) */
__attribute__((always_inline)) inline void storeBytePixelGroups(uchar* row, int spanBegin,
                                                                int xBegin, int xEnd,
                                                                v_float32x4 base,
                                                                v_float32x4 step)
{
    forPixelGroups(spanBegin, xBegin, xEnd, base, step, [row](int x, auto v0, auto v1, auto v2) {
        const auto bytes = v_pack_u(v_pack(v_round(v0), v_round(v1)),
                                    v_pack(v_round(v2), v_round(v2)));
        uchar* const q = row + 3 * x;
#if CV_AVX2
        v_store_low(q, bytes);  // channels 0-15, then 16-23
        _mm_storel_epi64(reinterpret_cast<__m128i*>(q + 16),
                         _mm256_extracti128_si256(bytes.val, 1));
#else
        v_store_low(q, bytes);  // channels 0-7, then 8-11
        const unsigned last = v_extract_n<2>(v_reinterpret_as_u32(bytes));
        std::memcpy(q + 8, &last, 4);
#endif
    });
}

/** Writes pixels [xBegin, xEnd) of a float RGB row: channel k of pixel x gets
base[k] + step[k] * float(x - spanBegin), one product and one sum in float: one 16-byte store
per pixel, whose fourth lane spills into the next pixel and is overwritten by that pixel's store,
the last pixel as 8 + 4 bytes; nothing outside the run is touched.

kClaimedRun: a run that a coverage claim left, of 1 to 30-odd pixels that vary from one run to
the next: up to 4 pixels without a loop, from kFloatGroupMinPixels on in groups; the same values.
(A grid's spans, whose lengths repeat, are faster through the plain loop: the grids took 3-19%
longer through this one.) */
template <bool kClaimedRun = false>
inline void storeFloatPixels(float* row, int spanBegin, int xBegin, int xEnd,
                             const v_float32x4& base, const v_float32x4& step)
{
    if constexpr (kClaimedRun) {
        if (xEnd - xBegin >= kFloatGroupMinPixels) {
            storeFloatPixelGroups(row, spanBegin, xBegin, xEnd, base, step);
            return;
        }
        if (xEnd - xBegin <= 4) {
            // As storeColorRun: pixels min(j, n - 1), j = 0 .. 3, no loop exit to mispredict.
            const int lastPixel = xEnd - xBegin - 1;
            for (int j = 0; j < 4; j++) {
                const int k = std::min(j, lastPixel);
                storePixel(row + 3 * (xBegin + k),
                           base + step * v_setall_f32(float(xBegin + k - spanBegin)));
            }
            return;
        }
    }
    const v_float32x4 one = v_setall_f32(1.f);
    v_float32x4 i = v_setall_f32(float(xBegin - spanBegin));  // exact: small integers
    float* p = row + 3 * xBegin;
    for (float* const last = row + 3 * (xEnd - 1); p < last; p += 3, i = i + one)
        v_store(p, base + step * i);
    storePixel(p, base + step * i);
}

/** Sets the float RGB pixels [p, end), at least four, to the first three lanes of `color`: four
pixels a step, then the last four again, ending at `end` (they start on a pixel, so the same
three vectors): no loop over what is left, whose exit the runs' lengths would mispredict. */
__attribute__((always_inline)) inline void storeColorGroups(float* p, float* const end,
                                                            const v_float32x4& color)
{
    const float r = v_extract_n<0>(color), g = v_extract_n<1>(color), b = v_extract_n<2>(color);
    const v_float32x4 c0(r, g, b, r), c1(g, b, r, g), c2(b, r, g, b);
    for (; end - p >= 12; p += 12) {
        v_store(p, c0);
        v_store(p + 4, c1);
        v_store(p + 8, c2);
    }
    if (p < end) {
        p = end - 12;
        v_store(p, c0);
        v_store(p + 4, c1);
        v_store(p + 8, c2);
    }
}

#if CV_AVX2
/** Sets the float RGB pixels [0, n) (n >= 8) at `first` to the first three lanes of `color`:
eight pixels in three 32-byte stores a step, then the last eight again. */
__attribute__((always_inline)) inline void storeColorOctets(float* first, int n,
                                                            const v_float32x4& color)
{
    v_float32x8 g0, g1, g2;
    eightPixelLanes(color, g0, g1, g2);
    float* p = first;
    float* const last = first + 3 * (n - 8);
    for (; p < last; p += 24) {
        v_store(p, g0);
        v_store(p + 8, g1);
        v_store(p + 16, g2);
    }
    v_store(last, g0);
    v_store(last + 8, g1);
    v_store(last + 16, g2);
}
#endif

/** Sets pixels [0, n) (n >= 1) of the float RGB run at `first` to `color` (its first three
lanes), touching nothing outside the run, with no branch for runs of up to four pixels: four
8 + 4-byte stores at pixels min(j, n - 1), j = 0 .. 3, the last pixel stored again where the run
is shorter; longer runs by storeColorGroups, or from 8 pixels on with AVX2 by 8 pixels in three
32-byte stores (random2048 1.5% faster). For the runs that coverage claims leave
(CoverageBits::claim), whose lengths (1 to 8 pixels on the demo mesh) vary from one run to the
next: a store loop's exit, mispredicted on many of them, cost the demo mesh 4% of its frame in
flat. Not for the spans of a regular mesh (a grid's), where the loop predicts well and stores
less. */
__attribute__((always_inline)) inline void storeColorRun(float* first, int n,
                                                         const v_float32x4& color)
{
#if CV_AVX2
    if (n >= 8) {
        storeColorOctets(first, n, color);
        return;
    }
#endif
    if (n > 4) {
        storeColorGroups(first, first + 3 * n, color);
        return;
    }
    const int lastPixel = n - 1;
    for (int j = 0; j < 4; j++)
        storePixel(first + 3 * std::min(j, lastPixel), color);
}
#else
inline void storeFloatPixels(float* row, int spanBegin, int xBegin, int xEnd, const float base[3],
                             const float step[3])
{
    for (int x = xBegin; x < xEnd; x++) {
        const float i = float(x - spanBegin);
        row[3 * x] = base[0] + step[0] * i;
        row[3 * x + 1] = base[1] + step[1] * i;
        row[3 * x + 2] = base[2] + step[2] * i;
    }
}
#endif

/** Sets pixels [xBegin, xEnd) of an RGB row to `color`, touching nothing outside them. Float
rows are written with 16-byte stores: four pixels per three stores in runs of four pixels or
more (with AVX2, eight per three 32-byte stores from eight pixels on), one per pixel (its fourth
lane overwritten by the next pixel's store) in shorter ones. */
template <typename T>
inline void fillPixels(T* row, int xBegin, int xEnd, const T color[3])
{
    T* p = row + 3 * xBegin;
    T* const end = row + 3 * xEnd;
#if OPENCV_SHADING_SIMD128
    if constexpr (std::is_same<T, float>::value) {
        const v_float32x4 c0(color[0], color[1], color[2], color[0]);
#if CV_AVX2
        if (xEnd - xBegin >= 8) {  // long runs of claims and spans, background rows
            storeColorOctets(p, xEnd - xBegin, c0);
            return;
        }
#endif
        if (xEnd - xBegin >= 4) {
            storeColorGroups(p, end, c0);
            return;
        }
        for (; end - p > 3; p += 3)
            v_store(p, c0);
    }
#endif
    if constexpr (std::is_same<T, uchar>::value) {
        // Long 8-bit runs (big polygons): 16 pixels, 48 bytes, per fixed-size copy.
        if (xEnd - xBegin >= 32) {
            uchar pattern[48];
            for (int i = 0; i < 48; i += 3)
                pattern[i] = color[0], pattern[i + 1] = color[1], pattern[i + 2] = color[2];
            for (; end - p >= 48; p += 48)
                std::memcpy(p, pattern, 48);
        }
    }
    for (; p < end; p += 3) {
        p[0] = color[0];
        p[1] = color[1];
        p[2] = color[2];
    }
}

/** Flat shading: the mean of the vertex colours, taken in the order the vertices were given. */
template <typename T>
struct FlatShader {
    using Small = FlatShader;  //!< small faces' form: the same, set up with no weights
    static constexpr bool kReadsWeights = false;
    T color[4];  //!< the colour; for float rows a copy of its first channel in the fourth lane

    //! A face's own colour, its channels already as toChannel gives them (drawMesh3d's).
    explicit FlatShader(const T faceColor[3])
        : color{faceColor[0], faceColor[1], faceColor[2], faceColor[0]}
    {
    }

    //! Color: Vec3d, or Vec3f (the caller's colours, where they are).
    template <typename Color>
    FlatShader(const TriangleSetup&, const int*, const Color* const c[3], bool = false)
    {
#if OPENCV_SHADING_SIMD128 && CV_SIMD128_64F
        if constexpr (std::is_same<T, float>::value) {
            // The scalar loop's sums and divisions, two channels a vector: two divisions a
            // face instead of three, the fourth lane's copy of channel 0 divided with channel 2.
            const v_float64x2 sum01 = channelPair(*c[0]) + channelPair(*c[1]) + channelPair(*c[2]);
            const v_float64x2 sum2 = v_setall_f64(double((*c[0])[2])) +
                                     v_setall_f64(double((*c[1])[2])) +
                                     v_setall_f64(double((*c[2])[2]));
            const v_float64x2 three = v_setall_f64(3.0);
            v_store(color, v_cvt_f32(sum01 / three, v_combine_low(sum2, sum01) / three));
            return;
        }
#endif
        for (int k = 0; k < 3; k++)
            color[k] = toChannel<T>(float((double((*c[0])[k]) + double((*c[1])[k]) +
                                           double((*c[2])[k])) /
                                          3.0));
        color[3] = color[0];
    }

    void operator()(const TriangleSetup& t, T* row, int y, int spanBegin, int xBegin,
                    int xEnd) const
    {
        shadeRun(t, row, y, spanBegin, xBegin, xEnd);
    }

    /** operator(), always inlined. kClaimedRun: a run that a coverage claim left, stored by
    storeColorRun; the same pixels either way. */
    template <bool kClaimedRun = false>
    __attribute__((always_inline)) void shadeRun(const TriangleSetup&, T* row, int /*y*/,
                                                 int /*spanBegin*/, int xBegin, int xEnd) const
    {
#if OPENCV_SHADING_SIMD128
        if constexpr (std::is_same<T, float>::value) {
            if (xEnd - xBegin < 16) {
                // Spans of small faces are a few pixels: one store per pixel, no set-up.
                const v_float32x4 c = v_load(color);
                if constexpr (kClaimedRun) {
                    storeColorRun(row + 3 * xBegin, xEnd - xBegin, c);
                    return;
                }
                float* p = row + 3 * xBegin;
                for (float* const last = row + 3 * (xEnd - 1); p < last; p += 3)
                    v_store(p, c);
                storePixel(p, c);
                return;
            }
        }
#endif
        fillPixels(row, xBegin, xEnd, color);
    }

#if OPENCV_SHADING_SIMD128
    /** A span's pixels one at a time: put(pixel, x) stores at `pixel` what shadeRun stores at
    column x. For the spans of a pixel or few whose samples are each depth-tested, and the
    sample blocks: no run to find. Float rows: one 8 + 4-byte store. */
    struct FloatPen {
        v_float32x4 value;
        __attribute__((always_inline)) void put(float* pixel, int) const
        {
            storePixel(pixel, value);
        }
    };
    //! 8-bit rows: three byte stores (here too, so the scalar build keeps the row walk that
    //! these paths are checked against).
    struct BytePen {
        uchar value[3];
        __attribute__((always_inline)) void put(uchar* pixel, int) const
        {
            pixel[0] = value[0], pixel[1] = value[1], pixel[2] = value[2];
        }
    };
    using Pen = std::conditional_t<std::is_same<T, float>::value, FloatPen, BytePen>;
    //! Whether pen() serves this face: always.
    bool penFits() const { return true; }
    __attribute__((always_inline)) Pen pen(const TriangleSetup&, int, int) const
    {
        if constexpr (std::is_same<T, float>::value)
            return Pen{v_load(color)};
        else
            return Pen{{color[0], color[1], color[2]}};
    }
#endif
};

/** Exact barycentric weights of a set-up triangle's samples: integer edge functions at the
sample, each divided by the exact twice-area with one rounding, so they stay accurate even for
needles with vertices near the 2^40 limit. Weight i belongs to the setup's vertex i (top, mid,
bottom). */
struct ExactWeights {
    double invArea2;  //!< 1 / twice the signed area, in subpixel units
    //! Narrow triangles: edge function i (opposite vertex i) at pixel (x, y) is
    //! edgeAt0[i] + edgeDx[i] * x + edgeDy[i] * y, exactly, in 64 bits.
    int64_t edgeAt0[3], edgeDx[3], edgeDy[3];

    explicit ExactWeights(const TriangleSetup& t)
    {
        const FixedPoint p[3] = {t.top, t.mid, t.bottom};
        if (t.narrow) {
            for (int i = 0; i < 3; i++) {
                const FixedPoint& a = p[(i + 1) % 3];
                const FixedPoint& b = p[(i + 2) % 3];
                edgeAt0[i] = -(b.x - a.x) * a.y + (b.y - a.y) * a.x;
                edgeDx[i] = -(b.y - a.y) * kSubpixelOne;
                edgeDy[i] = (b.x - a.x) * kSubpixelOne;
            }
        }
        invArea2 = 1.0 / edgeValue(p[0], p[1], p[2], t.narrow);
    }

    //! Edge function of a -> b at q, (b - a) x (q - a), exact until its one rounding to double.
    //! Narrow triangles stay in 64 bits: converting a 128-bit integer is a slow library call.
    static double edgeValue(const FixedPoint& a, const FixedPoint& b, const FixedPoint& q,
                            bool narrow)
    {
        if (narrow)
            return double((b.x - a.x) * (q.y - a.y) - (b.y - a.y) * (q.x - a.x));
        return double(Int128(b.x - a.x) * (q.y - a.y) - Int128(b.y - a.y) * (q.x - a.x));
    }

    //! d(weight_i)/dx per pixel: exact integers until the one division.
    void stepX(const TriangleSetup& t, double dw[3]) const
    {
        dw[0] = -double(t.bottom.y - t.mid.y) * kSubpixelOne * invArea2;
        dw[1] = -double(t.top.y - t.bottom.y) * kSubpixelOne * invArea2;
        dw[2] = -double(t.mid.y - t.top.y) * kSubpixelOne * invArea2;
    }

    //! Barycentric weights of the sample (x, y): exact edge functions, one rounding each.
    __attribute__((always_inline)) void at(const TriangleSetup& t, int x, int y, double& w0,
                                           double& w1, double& w2) const
    {
        if (t.narrow) {  // the same integers as edgeValue's, from precomputed coefficients
            w0 = double(edgeAt0[0] + edgeDx[0] * x + edgeDy[0] * y) * invArea2;
            w1 = double(edgeAt0[1] + edgeDx[1] * x + edgeDy[1] * y) * invArea2;
            w2 = double(edgeAt0[2] + edgeDx[2] * x + edgeDy[2] * y) * invArea2;
        } else {
            wideAt(t, x, y, w0, w1, w2);
        }
    }

    //! at() for triangles beyond 64-bit edge functions (rare): out of line, so that the common
    //! path stays small enough to inline.
    __attribute__((noinline, cold)) void wideAt(const TriangleSetup& t, int x, int y, double& w0,
                                                double& w1, double& w2) const
    {
        const FixedPoint q = {int64_t(x) * kSubpixelOne, int64_t(y) * kSubpixelOne};
        w0 = edgeValue(t.mid, t.bottom, q, false) * invArea2;
        w1 = edgeValue(t.bottom, t.top, q, false) * invArea2;
        w2 = edgeValue(t.top, t.mid, q, false) * invArea2;
    }
};

/** ExactWeights of a small face (kSmallColumns) set up with others in SIMD lanes
(smallWeightsEight in raster.hpp), with no TriangleSetup: the same integers, hence the same
weights. Edge function i (opposite canonical vertex i) is kept at the face's origin sample and
stepped per column and per row in 32 bits, which a small face's samples never leave. */
struct SmallWeights {
    double invArea2;  //!< 1 / twice the signed area, canonical order
    int32_t edgeAt[3], edgePerColumn[3], edgePerRow[3];  //!< at (originColumn, originRow)
    int originColumn, originRow;

    //! ExactWeights::stepX: the step per column is the exact integer -dy * 256.
    void stepX(const TriangleSetup&, double dw[3]) const
    {
        for (int i = 0; i < 3; i++)
            dw[i] = double(edgePerColumn[i]) * invArea2;
    }

    __attribute__((always_inline)) void at(const TriangleSetup&, int x, int y, double& w0,
                                           double& w1, double& w2) const
    {
        const int dx = x - originColumn, dy = y - originRow;
        w0 = double(edgeAt[0] + edgePerColumn[0] * dx + edgePerRow[0] * dy) * invArea2;
        w1 = double(edgeAt[1] + edgePerColumn[1] * dx + edgePerRow[1] * dy) * invArea2;
        w2 = double(edgeAt[2] + edgePerColumn[2] * dx + edgePerRow[2] * dy) * invArea2;
    }

#if CV_AVX2
    //! at()'s (w0, w1, w2) in lanes 0-2 (lane 3 not meaningful): the same integers, the same
    //! products.
    __attribute__((always_inline)) __m256d atLanes(int x, int y) const
    {
        // Each load's fourth lane is the next field's first: not meaningful, and never traps.
        auto lanes = [](const int32_t* v) {
            return _mm_loadu_si128(reinterpret_cast<const __m128i*>(v));
        };
        const __m128i edges = _mm_add_epi32(
            _mm_add_epi32(lanes(edgeAt),
                          _mm_mullo_epi32(lanes(edgePerColumn), _mm_set1_epi32(x - originColumn))),
            _mm_mullo_epi32(lanes(edgePerRow), _mm_set1_epi32(y - originRow)));
        return _mm256_mul_pd(_mm256_cvtepi32_pd(edges), _mm256_set1_pd(invArea2));
    }
#endif
};
static_assert(offsetof(SmallWeights, edgePerColumn) == offsetof(SmallWeights, edgeAt) + 12 &&
                  offsetof(SmallWeights, edgePerRow) ==
                      offsetof(SmallWeights, edgePerColumn) + 12 &&
                  offsetof(SmallWeights, originColumn) == offsetof(SmallWeights, edgePerRow) + 12,
              "SmallWeights::atLanes reads 4 lanes from each edge array");

/** Whether a colour value is within +-1e37 (so not NaN): Gouraud colours beyond that are
computed per pixel, where stepping in float could overflow. */
inline bool gouraudInRange(double v)
{
    return std::abs(v) <= kGouraudColorLimit;
}

#if CV_AVX2
//! A colour's channels 0, 1, 2, 2 in 4 lanes.
__attribute__((always_inline)) inline __m256d channelLanes(const double c[3])
{
    return _mm256_insertf128_pd(_mm256_castpd128_pd256(_mm_loadu_pd(c)), _mm_set1_pd(c[2]), 1);
}

/** w0 c0 + w1 c1 + w2 c2 lane by lane, in that order, the weights in lanes 0-2 of `w`. */
__attribute__((always_inline)) inline __m256d weightedSum(__m256d w, __m256d c0, __m256d c1,
                                                          __m256d c2)
{
    return _mm256_add_pd(_mm256_add_pd(_mm256_mul_pd(_mm256_permute4x64_pd(w, 0x00), c0),
                                       _mm256_mul_pd(_mm256_permute4x64_pd(w, 0x55), c1)),
                         _mm256_mul_pd(_mm256_permute4x64_pd(w, 0xaa), c2));
}
#endif

/** Writes Gouraud run [xBegin, xEnd) of the span that starts at spanBegin: channel k of pixel x
is base[k] + stepX[k] * float(x - spanBegin), base[k] = float(w0 * color[0][k] + w1 * color[1][k]
+ w2 * color[2][k]) from the exact weights (w0, w1, w2) of the span's first sample. (Float rows
with 64-bit SIMD: GouraudShader::spanBase and storeFloatPixels, the same values.) */
template <typename T, bool kClaimedRun, int kColorLanes>
__attribute__((always_inline)) inline void storeGouraudRun(const double (&color)[3][kColorLanes],
                                                           const float stepX[4], double w0,
                                                           double w1, double w2, T* row,
                                                           int spanBegin, int xBegin, int xEnd)
{
    float base[3];
    for (int k = 0; k < 3; k++)
        base[k] = float(w0 * color[0][k] + w1 * color[1][k] + w2 * color[2][k]);
    if constexpr (std::is_same<T, float>::value) {
#if OPENCV_SHADING_SIMD128
        const v_float32x4 baseV(base[0], base[1], base[2], base[0]);
        storeFloatPixels(row, spanBegin, xBegin, xEnd, baseV, v_load(stepX));
#else
        storeFloatPixels(row, spanBegin, xBegin, xEnd, base, stepX);
#endif
        return;
    }
#if OPENCV_SHADING_SIMD128
    if constexpr (std::is_same<T, uchar>::value) {
        if (xEnd - xBegin >= kFloatGroupMinPixels) {
            storeBytePixelGroups(row, spanBegin, xBegin, xEnd,
                                 v_float32x4(base[0], base[1], base[2], base[0]),
                                 v_load(stepX));
            return;
        }
    }
#endif
    for (int x = xBegin; x < xEnd; x++) {
        const float i = float(x - spanBegin);
        row[3 * x] = toChannel<T>(base[0] + stepX[0] * i);
        row[3 * x + 1] = toChannel<T>(base[1] + stepX[1] * i);
        row[3 * x + 2] = toChannel<T>(base[2] + stepX[2] * i);
    }
}

/** Gouraud shading: the affine function of (x, y) through the three (snapped) vertices and their
colours, which is what interpolating along the edges and then along the span gives.

Each span starts from exact barycentric weights (ExactWeights), so the value stays accurate for
any triangle; along the span it steps by the x-gradient in float. A pixel's value depends only
on the triangle and its span's start, never on what was drawn before: masked and unmasked
drawing, and any thread count, agree bit for bit.

Weights: ExactWeights, or SmallWeights for a small face set up with others (which must have its
colours in range: it is never drawn per pixel). */
template <typename T, class Weights = ExactWeights>
struct GouraudShader {
    //! The form of this shader for faces set up as SmallWeights.
    using Small = GouraudShader<T, SmallWeights>;
    static constexpr bool kReadsWeights = true;
    static constexpr bool kMayShadePerPixel = std::is_same<Weights, ExactWeights>::value;
    //! A small face's colours have a copy of channel 2 in a fourth lane, so that each of its
    //! rows' bases reads a vertex's channels in one 4-lane load (grid512 Gouraud 0.87-0.92x the
    //! time; with the fourth lane for every face, random512's big faces took 1.01x).
    static constexpr int kColorLanes = std::is_same<Weights, SmallWeights>::value ? 4 : 3;
    //! color[vertex][channel], vertices in the setup's canonical order.
    double color[3][kColorLanes];
    float stepX[4];      //!< d(colour)/dx per pixel; a copy of the first in the fourth lane
    Weights weights;
    //! A colour beyond +-1e37 (or not finite): values are computed per pixel, not stepped.
    bool perPixel;

    /** `colorsInRange`: the caller checked that every colour is within +-1e37 (a mesh's, once
    per draw), so this face need not. */
    GouraudShader(const TriangleSetup& t, const int* order, const Vec3d* const c[3],
                  bool colorsInRange = false)
        : weights(t)
    {
        setUp(t, order, c, colorsInRange);
    }

    //! A small face (SmallWeights) whose colours are all within +-1e37.
    GouraudShader(const Weights& w, const int* order, const Vec3d* const c[3]) : weights(w)
    {
#if CV_AVX2
        if constexpr (std::is_same<Weights, SmallWeights>::value) {
            // setUp's copies and sums, in 4 lanes (channels 0, 1, 2, 2): the same products,
            // sums, clamps and roundings.
            __m256d channels[3];
            for (int i = 0; i < 3; i++) {
                const double* const v = c[order[i]]->val;
                channels[i] = channelLanes(v);  // read before the stores, which may alias v
                _mm256_storeu_pd(color[i], channels[i]);
            }
            perPixel = false;
            // Element by element: the weights were just stored so, and a 16-byte load of
            // them would wait for the four stores to reach the cache.
            const int32_t* const perColumn = w.edgePerColumn;
            const __m256d dw = _mm256_mul_pd(
                _mm256_cvtepi32_pd(_mm_setr_epi32(perColumn[0], perColumn[1], perColumn[2], 0)),
                _mm256_set1_pd(w.invArea2));
            const __m256d sum = weightedSum(dw, channels[0], channels[1], channels[2]);
            // std::clamp's: the bound where beyond it, else the sum (NaN included).
            const double maxStep = std::numeric_limits<float>::max();
            const __m256d clamped = _mm256_min_pd(
                _mm256_set1_pd(maxStep), _mm256_max_pd(_mm256_set1_pd(-maxStep), sum));
            // Lanes 0, 1, 2 and a copy of 0.
            _mm_storeu_ps(stepX, _mm_permute_ps(_mm256_cvtpd_ps(clamped), 0x24));
            return;
        }
#endif
        const TriangleSetup unread{};  // SmallWeights read no setup
        setUp(unread, order, c, true);
    }

    //! The colours in canonical order, and their steps per column.
    __attribute__((always_inline)) void setUp(const TriangleSetup& t, const int* order,
                                              const Vec3d* const c[3], bool colorsInRange)
    {
        bool inRange = true;
        for (int i = 0; i < 3; i++)
            for (int k = 0; k < 3; k++) {
                color[i][k] = (*c[order[i]])[k];
                inRange &= colorsInRange || gouraudInRange(color[i][k]);
            }
        if constexpr (kColorLanes == 4)
            for (int i = 0; i < 3; i++)
                color[i][kColorLanes - 1] = color[i][2];
        perPixel = !inRange;
        double dw[3];
        weights.stepX(t, dw);
        // Clamped to float's range: an infinite step would turn the span's first pixel (step * 0)
        // into NaN for colours beyond float's range.
        const double maxStep = std::numeric_limits<float>::max();
        for (int k = 0; k < 3; k++)
            stepX[k] = float(std::clamp(dw[0] * color[0][k] + dw[1] * color[1][k] +
                                        dw[2] * color[2][k], -maxStep, maxStep));
        stepX[3] = stepX[0];
    }

    void weightsAt(const TriangleSetup& t, int x, int y, double& w0, double& w1, double& w2) const
    {
        weights.at(t, x, y, w0, w1, w2);
    }

    //! Huge colours: stepping in float could overflow where the values do not. Kept out of
    //! line so that the common path needs few registers and no stack frame.
    __attribute__((noinline, cold)) void shadePerPixel(const TriangleSetup& t, T* row, int y,
                                                       int xBegin, int xEnd) const
    {
        for (int x = xBegin; x < xEnd; x++) {
            double w0, w1, w2;
            weightsAt(t, x, y, w0, w1, w2);
            for (int k = 0; k < 3; k++)
                row[3 * x + k] =
                    toChannel<T>(float(w0 * color[0][k] + w1 * color[1][k] + w2 * color[2][k]));
        }
    }

    void operator()(const TriangleSetup& t, T* row, int y, int spanBegin, int xBegin,
                    int xEnd) const
    {
        shadeRun(t, row, y, spanBegin, xBegin, xEnd);
    }

    /** operator(), always inlined: for the front-to-back claims, a call per run of a few pixels.
    kClaimedRun: a run that a coverage claim left (storeFloatPixels); the same pixels either way.
    */
    template <bool kClaimedRun = false>
    __attribute__((always_inline)) void shadeRun(const TriangleSetup& t, T* row, int y,
                                                 int spanBegin, int xBegin, int xEnd) const
    {
        if (kMayShadePerPixel && perPixel) {
            shadePerPixel(t, row, y, xBegin, xEnd);
            return;
        }
#if OPENCV_SHADING_SIMD128 && CV_SIMD128_64F
        if constexpr (std::is_same<T, float>::value) {
            storeFloatPixels<kClaimedRun>(row, spanBegin, xBegin, xEnd, spanBase(t, y, spanBegin),
                                          v_load(stepX));
            return;
        }
#endif
        double w0, w1, w2;
        weightsAt(t, spanBegin, y, w0, w1, w2);
        storeGouraudRun<T, kClaimedRun>(color, stepX, w0, w1, w2, row, spanBegin, xBegin, xEnd);
    }

#if OPENCV_SHADING_SIMD128 && CV_SIMD128_64F
    /** storeGouraudRun's base for the span from spanBegin on row y, channels 0, 1, 2, 2 in
    float: the scalar sums in the same order, two channels per lane pair, or for a small face
    in the AVX2 build all in 4 lanes with its weights (a tiny face's spans are a pixel or two,
    so this is most of their cost). */
    __attribute__((always_inline)) v_float32x4 spanBase(const TriangleSetup& t, int y,
                                                        int spanBegin) const
    {
#if CV_AVX2
        if constexpr (std::is_same<Weights, SmallWeights>::value)
            return v_float32x4(_mm256_cvtpd_ps(weightedSum(
                weights.atLanes(spanBegin, y), _mm256_loadu_pd(color[0]),
                _mm256_loadu_pd(color[1]), _mm256_loadu_pd(color[2]))));
#endif
        double w0, w1, w2;
        weightsAt(t, spanBegin, y, w0, w1, w2);
        const v_float64x2 a = v_setall_f64(w0), b = v_setall_f64(w1), c = v_setall_f64(w2);
        const v_float64x2 lo = a * v_load(color[0]) + b * v_load(color[1]) + c * v_load(color[2]);
        const v_float64x2 hi = a * v_setall_f64(color[0][2]) + b * v_setall_f64(color[1][2]) +
                               c * v_setall_f64(color[2][2]);
        return v_cvt_f32(lo, hi);
    }
#endif

#if OPENCV_SHADING_SIMD128 && CV_SIMD128_64F
    /** FlatShader::Pen's counterpart: the values storeGouraudRun gives the span that starts at
    spanBegin, channel k of pixel x base[k] + stepX[k] * float(x - spanBegin), the same sums and
    the same products. Float rows: one 8 + 4-byte store. */
    struct FloatPen {
        v_float32x4 base, step;
        int spanBegin;
        __attribute__((always_inline)) void put(float* pixel, int x) const
        {
            storePixel(pixel, base + step * v_setall_f32(float(x - spanBegin)));
        }
    };
    /** 8-bit rows: those values as toChannel gives them, rounded to nearest even (cvRound's
    conversion, in 4 lanes) and saturated by the packs, then three byte stores. */
    struct BytePen {
        v_float32x4 base, step;
        int spanBegin;
        __attribute__((always_inline)) void put(uchar* pixel, int x) const
        {
            const v_int32x4 rounded = v_round(base + step * v_setall_f32(float(x - spanBegin)));
            const v_int16x8 shorts = v_pack(rounded, rounded);
            const unsigned bytes = v_reinterpret_as_u32(v_pack_u(shorts, shorts)).get0();
            pixel[0] = uchar(bytes), pixel[1] = uchar(bytes >> 8), pixel[2] = uchar(bytes >> 16);
        }
    };
    using Pen = std::conditional_t<std::is_same<T, float>::value, FloatPen, BytePen>;
    //! Whether pen() serves this face: not where its colours are computed per pixel.
    bool penFits() const { return !(kMayShadePerPixel && perPixel); }
    __attribute__((always_inline)) Pen pen(const TriangleSetup& t, int y, int spanBegin) const
    {
        return Pen{spanBase(t, y, spanBegin), v_load(stepX), spanBegin};
    }
#endif
};

//! Whether Shader has a Pen (FlatShader::Pen).
template <class Shader, class = void>
struct HasPen : std::false_type {};
template <class Shader>
struct HasPen<Shader, std::void_t<typename Shader::Pen>> : std::true_type {};

//! Whether Shader's pen draws rows of T: float and 8-bit rows, flat (FlatShader) or Gouraud
//! (GouraudShader), wherever the build has pens (128-bit SIMD with doubles).
template <class Shader, typename T>
constexpr bool penDraws()
{
    return HasPen<Shader>::value &&
           (std::is_same<T, float>::value || std::is_same<T, uchar>::value);
}

OPENCV_SHADING_ISA_END
}  // namespace detail
}  // namespace shading
}  // namespace cv

#endif  // OPENCV_SHADING_SHADERS_HPP
