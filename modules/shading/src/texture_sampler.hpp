// This file is part of opencv_shading. License: Apache-2.0.
//
// Texture sampling as cv::remap does it with CV_32FC1 maps (OpenCV 4.x imgwarp.cpp:
// remapNearest, remapBilinear), shared by texturedTriangles and drawTexturedMesh3d, and the
// checks of their texture arguments.
#ifndef OPENCV_SHADING_TEXTURE_SAMPLER_HPP
#define OPENCV_SHADING_TEXTURE_SAMPLER_HPP

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <type_traits>

namespace cv {
namespace shading {
namespace detail {

//! remap's fixed point: coordinates in 1/32 px (INTER_TAB_SIZE), 8-bit weights out of 2^15.
constexpr int kTabBits = 5;
constexpr int kTabSize = 1 << kTabBits;
constexpr int kCoefBits = 15;

//! OpenCV's clip(x, a, b) in imgwarp.cpp: x clamped to [a, b - 1].
inline int clipTo(int x, int a, int b)
{
    return x >= a ? (x < b ? x : b - 1) : a;
}

/** The float value of each 8-bit texel value on a float canvas, t * (1/255) in float: what
`Mat::convertTo(dst, CV_32F, 1.0 / 255)` gives, so sampling bytes through it equals sampling
the converted texture. */
const float* byteTexelUnits();

/** Samples a texture as cv::remap does with float maps. Coordinates are clamped to +-1e6 first:
the same result for every |coordinate| below 2^31 (remap saturates indices to 16 bits anyway),
and defined beyond. T is the canvas's type; the texture is of the same type, or, for a float
canvas, 8-bit read through byteTexelUnits() (no float copy per call, a quarter of the memory to
fetch). */
template <typename T>
struct RemapSampler {
    using Acc = typename std::conditional<std::is_same<T, uchar>::value, int, float>::type;

    const uchar* data;
    size_t step;
    int cols, rows;
    int border;
    bool linear;
    double invCols, invRows;  //!< for BORDER_WRAP's remainders
    const float* byteUnits;   //!< set for an 8-bit texture on a float canvas

    RemapSampler(const Mat& tex, int interpolation, int borderMode)
        : data(tex.data), step(tex.step[0]), cols(tex.cols), rows(tex.rows), border(borderMode),
          linear(interpolation == INTER_LINEAR), invCols(1.0 / tex.cols), invRows(1.0 / tex.rows),
          byteUnits(std::is_same<T, float>::value && tex.depth() == CV_8U ? byteTexelUnits()
                                                                          : nullptr)
    {
        CV_Assert(tex.depth() == DataType<T>::depth || byteUnits != nullptr);
    }

    template <typename S>
    const S* texel(int x, int y) const
    {
        return reinterpret_cast<const S*>(data + size_t(y) * step) + 3 * x;
    }

    //! Channel k of texel p in the canvas's units.
    template <typename S>
    T value(const S* p, int k) const
    {
        if constexpr (std::is_same<S, T>::value)
            return p[k];
        else
            return byteUnits[p[k]];
    }

    static float clampCoordinate(float v)
    {
        return std::min(std::max(v, -1e6f), 1e6f);
    }

    //! The sample at map coordinate (u, v); taps outside the texture take the slower border path.
    void sample(float u, float v, T* out) const
    {
        if constexpr (std::is_same<T, float>::value) {
            if (byteUnits != nullptr) {
                sampleAs<uchar>(u, v, out);
                return;
            }
        }
        sampleAs<T>(u, v, out);
    }

private:
    template <typename S>
    void sampleAs(float u, float v, T* out) const
    {
        if (linear)
            sampleLinear<S>(clampCoordinate(u), clampCoordinate(v), out);
        else
            sampleNearest<S>(clampCoordinate(u), clampCoordinate(v), out);
    }

    template <typename S>
    void sampleNearest(float u, float v, T* out) const
    {
        const int sx = saturate_cast<short>(u), sy = saturate_cast<short>(v);  // cvRound, as remap
        if (unsigned(sx) >= unsigned(cols) || unsigned(sy) >= unsigned(rows))
            return sampleNearestOutside<S>(sx, sy, out);
        const S* s = texel<S>(sx, sy);
        out[0] = value(s, 0), out[1] = value(s, 1), out[2] = value(s, 2);
    }

    template <typename S>
    void sampleLinear(float u, float v, T* out) const
    {
        const int sx = cvRound(u * float(kTabSize)), sy = cvRound(v * float(kTabSize));
        const int fx = sx & (kTabSize - 1), fy = sy & (kTabSize - 1);
        const int ix = saturate_cast<short>(sx >> kTabBits);
        const int iy = saturate_cast<short>(sy >> kTabBits);
        if (unsigned(ix) < unsigned(std::max(cols - 1, 0)) &&
            unsigned(iy) < unsigned(std::max(rows - 1, 0))) {
            const S* v0 = texel<S>(ix, iy);
            const S* v2 = texel<S>(ix, iy + 1);
            blend(v0, v0 + 3, v2, v2 + 3, fx, fy, out);
        } else {
            sampleLinearOutside<S>(ix, iy, fx, fy, out);
        }
    }

    //! remap's bilinear sum of four taps with weights at 1/32 steps, in its order and type.
    template <typename S>
    void blend(const S* v0, const S* v1, const S* v2, const S* v3, int fx, int fy, T* out) const
    {
        // remap's BilinearTab: (1 - fy)(1 - fx), (1 - fy) fx, fy (1 - fx), fy fx at 1/32 steps,
        // exact in float; the 8-bit table is the same times 2^15, exact integers.
        const int gx = kTabSize - fx, gy = kTabSize - fy;
        Acc w[4];
        if constexpr (std::is_same<T, uchar>::value) {
            const int scale = (1 << kCoefBits) / (kTabSize * kTabSize);
            w[0] = Acc(gy * gx * scale), w[1] = Acc(gy * fx * scale);
            w[2] = Acc(fy * gx * scale), w[3] = Acc(fy * fx * scale);
        } else {
            const float scale = 1.f / float(kTabSize * kTabSize);
            w[0] = Acc(float(gy * gx) * scale), w[1] = Acc(float(gy * fx) * scale);
            w[2] = Acc(float(fy * gx) * scale), w[3] = Acc(float(fy * fx) * scale);
        }
        for (int k = 0; k < 3; k++) {
            const Acc t = Acc(value(v0, k) * w[0] + value(v1, k) * w[1] + value(v2, k) * w[2] +
                              value(v3, k) * w[3]);
            if constexpr (std::is_same<T, uchar>::value)
                out[k] = saturate_cast<uchar>((t + (1 << (kCoefBits - 1))) >> kCoefBits);
            else
                out[k] = t;
        }
    }

    /** p mod length in [0, length) for |p| <= 2^15 (remap's indices are shorts): the quotient
    from the reciprocal is off by at most one, which the two corrections undo; no division. */
    static int wrapIndex(int p, int length, double invLength)
    {
        int r = p - int(p * invLength) * length;
        if (r < 0)
            r += length;
        if (r >= length)
            r -= length;
        return r;
    }

    //! cv::borderInterpolate, with the wrap (textures' usual border) computed inline.
    int borderIndex(int p, int length, double invLength) const
    {
        return border == BORDER_WRAP ? wrapIndex(p, length, invLength)
                                     : borderInterpolate(p, length, border);
    }

    //! Taps outside the texture: its border, as remap's.
    template <typename S>
    void sampleNearestOutside(int sx, int sy, T* out) const
    {
        if (border == BORDER_CONSTANT) {
            out[0] = out[1] = out[2] = T(0);
            return;
        }
        if (border == BORDER_REPLICATE) {
            sx = clipTo(sx, 0, cols);
            sy = clipTo(sy, 0, rows);
        } else {
            sx = borderIndex(sx, cols, invCols);
            sy = borderIndex(sy, rows, invRows);
        }
        const S* s = texel<S>(sx, sy);
        out[0] = value(s, 0), out[1] = value(s, 1), out[2] = value(s, 2);
    }

    template <typename S>
    void sampleLinearOutside(int ix, int iy, int fx, int fy, T* out) const
    {
        static const S zero[3] = {S(0), S(0), S(0)};
        const S *v0, *v1, *v2, *v3;
        if (border == BORDER_CONSTANT &&
            (ix >= cols || ix + 1 < 0 || iy >= rows || iy + 1 < 0)) {
            out[0] = out[1] = out[2] = T(0);
            return;
        } else if (border == BORDER_REPLICATE) {
            const int x0 = clipTo(ix, 0, cols), x1 = clipTo(ix + 1, 0, cols);
            const int y0 = clipTo(iy, 0, rows), y1 = clipTo(iy + 1, 0, rows);
            v0 = texel<S>(x0, y0), v1 = texel<S>(x1, y0);
            v2 = texel<S>(x0, y1), v3 = texel<S>(x1, y1);
        } else if (border == BORDER_WRAP) {  // each tap wrapped: the next one wraps to 0
            const int x0 = wrapIndex(ix, cols, invCols), x1 = x0 + 1 == cols ? 0 : x0 + 1;
            const int y0 = wrapIndex(iy, rows, invRows), y1 = y0 + 1 == rows ? 0 : y0 + 1;
            v0 = texel<S>(x0, y0), v1 = texel<S>(x1, y0);
            v2 = texel<S>(x0, y1), v3 = texel<S>(x1, y1);
        } else {
            const int x0 = borderIndex(ix, cols, invCols), x1 = borderIndex(ix + 1, cols, invCols);
            const int y0 = borderIndex(iy, rows, invRows), y1 = borderIndex(iy + 1, rows, invRows);
            v0 = x0 >= 0 && y0 >= 0 ? texel<S>(x0, y0) : zero;
            v1 = x1 >= 0 && y0 >= 0 ? texel<S>(x1, y0) : zero;
            v2 = x0 >= 0 && y1 >= 0 ? texel<S>(x0, y1) : zero;
            v3 = x1 >= 0 && y1 >= 0 ? texel<S>(x1, y1) : zero;
        }
        blend(v0, v1, v2, v3, fx, fy, out);
    }
};

//! Largest accepted |texture coordinate|; larger (or non-finite) ones skip their face.
constexpr double kMaxTexCoord = 1e30;

inline bool usableTexCoord(const Point2d& uv)
{
    return std::abs(uv.x) <= kMaxTexCoord && std::abs(uv.y) <= kMaxTexCoord;  // false for NaN
}

//! Checks a texture argument: a non-empty 2D CV_8UC3 or CV_32FC3 image.
void checkTexture(const Mat& texture, const char* argName);
//! Checks remap's interpolation (INTER_NEAREST, INTER_LINEAR) and border mode arguments.
void checkSampling(int interpolation, const char* interpolationName, int borderMode,
                   const char* borderName);
/** The texture as a RemapSampler for a canvas of this depth reads it: a float texture for an
8-bit canvas converted to 0..255, else the texture itself (no copy). */
Mat textureInUnitsOf(const Mat& texture, int canvasDepth);

}  // namespace detail
}  // namespace shading
}  // namespace cv

#endif  // OPENCV_SHADING_TEXTURE_SAMPLER_HPP
