// This file is part of opencv_shading. License: Apache-2.0.
//
// The user-facing interpolator: the core's spans (raster.hpp) and exact weights (shaders.hpp)
// handed to a callback, for code that shades samples its own way.
#include <opencv2/shading.hpp>

#include "input.hpp"
#include "raster.hpp"
#include "shaders.hpp"

#include <cmath>
#include <vector>

namespace cv {
namespace shading {

using namespace detail;

namespace {

/** Sets up the triangle `vertices` for a canvasSize target and calls spanFn(y, xBegin, xEnd,
w(xBegin), dwdx) per span, the weights in the order the vertices were given. */
template <typename Fn>
void walkWithWeights(Size canvasSize, InputArray vertices, bool callbackEmpty, Fn&& spanFn)
{
    if (canvasSize.width <= 0 || canvasSize.height <= 0)
        CV_Error(Error::StsBadSize,
                 format("canvasSize: expected positive width and height, got %dx%d",
                        canvasSize.width, canvasSize.height));
    if (callbackEmpty)
        CV_Error(Error::StsNullPtr, "fn: the callback is empty");
    std::vector<Point2d> v;
    readPoints(vertices, "vertices", 3, v);
    const FixedPoint p[3] = {snapToGrid(v[0]), snapToGrid(v[1]), snapToGrid(v[2])};
    TriangleSetup t;
    int order[3];
    if (!setupTriangle(p, canvasSize, t, order))
        return;
    const ExactWeights weights(t);
    double dw[3];
    weights.stepX(t, dw);
    Vec3d dwdx;
    for (int k = 0; k < 3; k++)
        dwdx[order[k]] = dw[k];
    walkTriangle(t, 0, canvasSize.height, canvasSize.width, [&](int y, int xBegin, int xEnd) {
        spanFn(t, weights, order, y, xBegin, xEnd, dwdx);
    });
}

/** 1 / Zc of a triangle's three vertices, checked: `depths` holds 3 values in [1e-30, 1e30],
so that w_i / z_i and their sum neither overflow nor vanish (weights are at least ~1e-25 where
nonzero). */
Vec3d inverseDepths(InputArray depths)
{
    if (depths.empty())
        CV_Error(Error::StsBadArg, "depths: expected 3 camera depths, got none");
    std::vector<double> z;
    readDepths(depths, "depths", 3, z);
    Vec3d inv;
    for (int i = 0; i < 3; i++) {
        if (!(z[i] >= 1e-30 && z[i] <= 1e30))
            CV_Error(Error::StsOutOfRange,
                     format("depths: expected values in [1e-30, 1e30] (camera depths > 0), got "
                            "%g at %d", z[i], i));
        inv[i] = 1.0 / z[i];
    }
    return inv;
}

}  // namespace

void forEachSpan(Size canvasSize, InputArray vertices, InputArray depths, const SpanCallback& fn)
{
    const Vec3d invZ = inverseDepths(depths);
    forEachSpan(canvasSize, vertices, [&](int y, int xBegin, int xEnd, const Vec3d& w,
                                          const Vec3d& dwdx) {
        fn(y, xBegin, xEnd, w.mul(invZ), dwdx.mul(invZ));
    });
}

void forEachSample(Size canvasSize, InputArray vertices, InputArray depths,
                   const SampleCallback& fn)
{
    const Vec3d invZ = inverseDepths(depths);
    forEachSample(canvasSize, vertices, [&](int x, int y, const Vec3d& w) {
        const Vec3d h = w.mul(invZ);
        fn(x, y, h * (1.0 / (h[0] + h[1] + h[2])));
    });
}

void forEachSpan(Size canvasSize, InputArray vertices, const SpanCallback& fn)
{
    walkWithWeights(canvasSize, vertices, !fn,
                    [&](const TriangleSetup& t, const ExactWeights& weights, const int* order,
                        int y, int xBegin, int xEnd, const Vec3d& dwdx) {
                        double w[3];
                        weights.at(t, xBegin, y, w[0], w[1], w[2]);
                        Vec3d wIn;
                        for (int k = 0; k < 3; k++)
                            wIn[order[k]] = w[k];
                        fn(y, xBegin, xEnd, wIn, dwdx);
                    });
}

void forEachSample(Size canvasSize, InputArray vertices, const SampleCallback& fn)
{
    walkWithWeights(canvasSize, vertices, !fn,
                    [&](const TriangleSetup& t, const ExactWeights& weights, const int* order,
                        int y, int xBegin, int xEnd, const Vec3d&) {
                        for (int x = xBegin; x < xEnd; x++) {
                            double w[3];
                            weights.at(t, x, y, w[0], w[1], w[2]);  // exact per sample
                            Vec3d wIn;
                            for (int k = 0; k < 3; k++)
                                wIn[order[k]] = w[k];
                            fn(x, y, wIn);
                        }
                    });
}

}  // namespace shading
}  // namespace cv
