// This file is part of opencv_shading. License: Apache-2.0.
#ifndef OPENCV_SHADING_INTERPOLATE_HPP
#define OPENCV_SHADING_INTERPOLATE_HPP

#include <opencv2/core.hpp>

#include <functional>

namespace cv {
namespace shading {

//! @addtogroup shading
//! @{

/** Called for each covered sample: pixel (x, y) and its barycentric weights w for the
triangle's vertices in the order given (`w[0] + w[1] + w[2] = 1`, up to rounding). */
using SampleCallback = std::function<void(int x, int y, const Vec3d& w)>;

/** Called for each span of covered samples: row y, columns [xBegin, xEnd), the weights at
(xBegin, y) and their change per pixel to the right (the weights at x are `w + (x - xBegin) *
dwdx`, which a caller may step in float for speed or recompute in double). */
using SpanCallback = std::function<void(int y, int xBegin, int xEnd, const Vec3d& w,
                                        const Vec3d& dwdx)>;

/** @brief Runs user code at every sample a triangle covers (the seed's LinearInterpolator with a
per-pixel delegate).

The covered samples are exactly those #flats and #gouraud write on a canvas of `canvasSize`
(same snapping, fill rule and clipping), visited row by row, top to bottom, left to right. The
weights are the exact barycentric coordinates of the sample point (x, y) in the snapped triangle
(integer edge functions, one rounding each), so `interpolate(a, b, c, w)` of per-vertex values
is what #gouraud computes for colours. A triangle with a NaN, infinite or too large coordinate
or zero area calls nothing. Exceptions thrown by `fn` propagate (the walk stops).

@param canvasSize Width and height of the target; samples outside it are not visited.
@param vertices The 3 vertices (x, y) in pixels, any accepted point form.
@param fn Called once per covered sample.
*/
CV_EXPORTS void forEachSample(Size canvasSize, InputArray vertices, const SampleCallback& fn);

/** @brief #forEachSample one span at a time: one call per row's run of covered samples, for
callers that step their values along the row themselves (much faster in tight loops). */
CV_EXPORTS void forEachSpan(Size canvasSize, InputArray vertices, const SpanCallback& fn);

/** @brief #forEachSample with perspective-correct weights, for a triangle seen in 3D.

`depths` are the camera depths `Zc` of the three vertices, whose projections are `vertices`.
Coverage is #forEachSample's; the weights are the barycentric coordinates of the 3D point seen
at the sample: `q_i = (w_i / z_i) / sum_j (w_j / z_j)` from the screen weights w, the weights
#drawMesh3d interpolates every attribute with (its depth is `1 / sum_j (w_j / z_j)`, which is
`interpolate(z0, z1, z2, q)` up to rounding).

@param depths 3 camera depths in [1e-30, 1e30], one per vertex.
*/
CV_EXPORTS void forEachSample(Size canvasSize, InputArray vertices, InputArray depths,
                              const SampleCallback& fn);

/** @brief #forEachSpan for a triangle seen in 3D: per span the affine quantities `h_i = w_i /
z_i` at `(xBegin, y)` (as `w`) and their change per pixel (as `dwdx`). At a sample,
`q_i = h_i / sum_j h_j` are #forEachSample's perspective-correct weights and `1 / sum_j h_j` its
depth. */
CV_EXPORTS void forEachSpan(Size canvasSize, InputArray vertices, InputArray depths,
                            const SpanCallback& fn);

/** @brief The values at three vertices interpolated with barycentric weights `w` (as given to a
#SampleCallback): `w[0] a + w[1] b + w[2] c` in double, then converted (saturated) to T. */
template <typename T, int n>
inline Vec<T, n> interpolate(const Vec<T, n>& a, const Vec<T, n>& b, const Vec<T, n>& c,
                             const Vec3d& w)
{
    Vec<T, n> out;
    for (int k = 0; k < n; k++)
        out[k] = saturate_cast<T>(w[0] * double(a[k]) + w[1] * double(b[k]) + w[2] * double(c[k]));
    return out;
}

//! @overload A single value per vertex.
inline double interpolate(double a, double b, double c, const Vec3d& w)
{
    return w[0] * a + w[1] * b + w[2] * c;
}

//! @}

}  // namespace shading
}  // namespace cv

#endif  // OPENCV_SHADING_INTERPOLATE_HPP
