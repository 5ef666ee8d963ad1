// This file is part of opencv_shading. License: Apache-2.0.
//
// Span shaders: given a row and a run of covered columns, write the colours. A shader is built
// once per triangle (all per-triangle math happens there) and then only fills runs.
#ifndef OPENCV_SHADING_SHADERS_HPP
#define OPENCV_SHADING_SHADERS_HPP

#include "raster.hpp"

#include <opencv2/core.hpp>

namespace cv {
namespace shading {
namespace detail {

//! Converts a colour channel to the canvas's element type (8-bit: rounded and saturated).
template <typename T>
inline T toChannel(float v)
{
    return saturate_cast<T>(v);
}

/** Flat shading: the mean of the vertex colours, taken in the order the vertices were given. */
template <typename T>
struct FlatShader {
    T color[3];

    FlatShader() = default;
    FlatShader(const TriangleSetup&, const int*, const Vec3d c[3])
    {
        for (int k = 0; k < 3; k++)
            color[k] = toChannel<T>(float((c[0][k] + c[1][k] + c[2][k]) / 3.0));
    }

    void operator()(T* row, int /*y*/, int /*spanBegin*/, int xBegin, int xEnd) const
    {
        const T c0 = color[0], c1 = color[1], c2 = color[2];
        for (int x = xBegin; x < xEnd; x++) {
            row[3 * x] = c0;
            row[3 * x + 1] = c1;
            row[3 * x + 2] = c2;
        }
    }
};

/** Gouraud shading: the affine function of (x, y) through the three (snapped) vertices and their
colours, which is what interpolating along the edges and then along the span gives.

The plane is set up in double from the canonical vertex order; each span evaluates it in double
at its first column, then steps in float. A pixel's value therefore depends only on the
triangle and the span's start, never on what was drawn before (so masked and unmasked drawing,
and any thread count, agree bit for bit). */
template <typename T>
struct GouraudShader {
    double x0, y0;
    double c0[3], gx[3], gy[3];

    GouraudShader() = default;
    GouraudShader(const TriangleSetup& t, const int* order, const Vec3d c[3])
    {
        const FixedPoint p[3] = {t.top, t.mid, t.bottom};
        const double s = 1.0 / double(kSubpixelOne);
        x0 = double(p[0].x) * s;
        y0 = double(p[0].y) * s;
        const double d1x = double(p[1].x - p[0].x) * s, d1y = double(p[1].y - p[0].y) * s;
        const double d2x = double(p[2].x - p[0].x) * s, d2y = double(p[2].y - p[0].y) * s;
        // Exact twice-area, rounded once: it is never zero here (setup rejected those).
        const Int128 area2 = Int128(p[1].x - p[0].x) * (p[2].y - p[0].y) -
                             Int128(p[2].x - p[0].x) * (p[1].y - p[0].y);
        const double invArea = double(kSubpixelOne * kSubpixelOne) / double(area2);
        for (int k = 0; k < 3; k++) {
            const double a = c[order[0]][k], b = c[order[1]][k], d = c[order[2]][k];
            c0[k] = a;
            gx[k] = ((b - a) * d2y - (d - a) * d1y) * invArea;
            gy[k] = ((d - a) * d1x - (b - a) * d2x) * invArea;
        }
    }

    void operator()(T* row, int y, int spanBegin, int xBegin, int xEnd) const
    {
        float base[3], step[3];
        for (int k = 0; k < 3; k++) {
            base[k] = float(c0[k] + gx[k] * (spanBegin - x0) + gy[k] * (y - y0));
            step[k] = float(gx[k]);
        }
        for (int x = xBegin; x < xEnd; x++) {
            const float i = float(x - spanBegin);
            row[3 * x] = toChannel<T>(base[0] + step[0] * i);
            row[3 * x + 1] = toChannel<T>(base[1] + step[1] * i);
            row[3 * x + 2] = toChannel<T>(base[2] + step[2] * i);
        }
    }
};

}  // namespace detail
}  // namespace shading
}  // namespace cv

#endif  // OPENCV_SHADING_SHADERS_HPP
