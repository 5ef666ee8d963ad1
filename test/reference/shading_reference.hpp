// This file is part of opencv_shading. License: Apache-2.0.
//
// shading_ref: a brute-force reference rasterizer used by the tests.
//
// It is written independently of the library and on purpose does the simplest possible thing:
// for every canvas pixel in the triangle's bounding box it evaluates the three edge functions
// exactly (128-bit integers) at the pixel's sample point and applies the fill rule literally.
// Read it as an executable statement of the conventions in <opencv2/shading.hpp>:
//
//  - Pixel (x, y) is canvas.at(y, x); its sample point is the integer point (x, y).
//  - Vertices snap to a 1/256 px grid: X = llround(v * 256). A triangle with a NaN, infinite or
//    larger than 2^40 coordinate draws nothing.
//  - Top-left rule: a sample strictly inside is covered; a sample on an edge is covered only if
//    that edge is a top edge (horizontal, interior below it, y grows downward) or a left edge
//    (non-horizontal, interior to its right). Zero area (after snapping) covers nothing.
//  - Flat colour is the mean of the vertex colours; Gouraud colour is the affine (barycentric)
//    interpolation of the vertex colours at the sample point, using the snapped vertices.
//  - CV_32FC3 canvases get floats; CV_8UC3 canvases get saturate_cast<uchar> (round, saturate).
//  - Meshes are painted far to near: faces stably sorted by mean vertex depth, largest first.
#ifndef OPENCV_SHADING_TEST_SHADING_REFERENCE_HPP
#define OPENCV_SHADING_TEST_SHADING_REFERENCE_HPP

#include <opencv2/core.hpp>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <vector>

namespace shading_ref {

// Products of two 49-bit fixed-point differences need up to ~99 bits.
// (__extension__ keeps -Wpedantic quiet about the GCC/Clang type.)
__extension__ typedef __int128 Int128;

constexpr double kSubpixel = 256.0;              // fixed-point units per pixel
constexpr double kMaxCoord = 1099511627776.0;    // 2^40: largest accepted |coordinate|

// A point in fixed-point units (1/256 px).
struct Fixed {
    long long x = 0, y = 0;
};

// Snaps one vertex; false if it is NaN, infinite or beyond 2^40 (the triangle is then skipped).
inline bool snap(const cv::Point2d& p, Fixed& out)
{
    if (!std::isfinite(p.x) || !std::isfinite(p.y))
        return false;
    if (std::abs(p.x) > kMaxCoord || std::abs(p.y) > kMaxCoord)
        return false;
    out.x = std::llround(p.x * kSubpixel);
    out.y = std::llround(p.y * kSubpixel);
    return true;
}

// Sample point of pixel (x, y) in fixed-point units.
inline Fixed samplePoint(int x, int y)
{
    return Fixed{ (long long)x * 256, (long long)y * 256 };
}

// Edge function of the directed edge a->b at p: the cross product (b - a) x (p - a), i.e. twice
// the signed area of triangle (a, b, p). Exact. Its partial derivatives are
//   dE/dx = -(b.y - a.y)   and   dE/dy = (b.x - a.x).
inline Int128 edgeFunction(const Fixed& a, const Fixed& b, const Fixed& p)
{
    return Int128(b.x - a.x) * Int128(p.y - a.y) - Int128(b.y - a.y) * Int128(p.x - a.x);
}

// A triangle ready for sampling. Vertices are ordered so that the twice-area is positive; then
// every edge function v[i] -> v[i+1] is positive inside the triangle, whatever the input winding.
struct Triangle {
    bool drawable = false;  // false: invalid coordinates or zero area, nothing is drawn
    Fixed v[3];             // snapped vertices, positively oriented
    int src[3] = {0, 1, 2}; // v[i] is input vertex src[i] (to pick the matching colour)
    Int128 area2 = 0;       // twice the area, > 0 when drawable
};

inline Triangle setupTriangle(const cv::Point2d in[3])
{
    Triangle t;
    for (int i = 0; i < 3; i++)
        if (!snap(in[i], t.v[i]))
            return t;
    t.area2 = edgeFunction(t.v[0], t.v[1], t.v[2]);
    if (t.area2 == 0)
        return t;
    if (t.area2 < 0) {  // normalise the orientation: swap two vertices
        std::swap(t.v[1], t.v[2]);
        std::swap(t.src[1], t.src[2]);
        t.area2 = -t.area2;
    }
    t.drawable = true;
    return t;
}

// Top or left edge of a positively oriented triangle (interior where the edge function > 0).
//  - top:  horizontal (dy == 0) with the interior below it, i.e. E grows with y: dE/dy = dx > 0.
//  - left: not horizontal, with the interior to its right, i.e. E grows with x: dE/dx = -dy > 0.
// Equivalently, a sample on an edge counts iff moving it to (x + e, y + e*e), for a tiny e > 0,
// moves it inside. That one consistent nudge is why triangles sharing an edge or a vertex cover
// each sample of a closed mesh exactly once.
inline bool isTopLeft(const Fixed& a, const Fixed& b)
{
    const long long dx = b.x - a.x, dy = b.y - a.y;
    const bool top = (dy == 0 && dx > 0);
    const bool left = (dy < 0);
    return top || left;
}

// The fill rule at one point (fixed-point units).
inline bool coversPoint(const Triangle& t, const Fixed& p)
{
    if (!t.drawable)
        return false;
    for (int i = 0; i < 3; i++) {
        const Fixed& a = t.v[i];
        const Fixed& b = t.v[(i + 1) % 3];
        const Int128 e = edgeFunction(a, b, p);
        if (e < 0)
            return false;                // outside this edge
        if (e == 0 && !isTopLeft(a, b))
            return false;                // on a bottom or right edge
    }
    return true;                          // strictly inside, or only on top/left edges
}

// Does the triangle cover the sample point of pixel (x, y)?
inline bool covers(const cv::Point2d v[3], int x, int y)
{
    return coversPoint(setupTriangle(v), samplePoint(x, y));
}

// Flat colour: the mean of the vertex colours.
inline cv::Vec3d flatColor(const cv::Vec3d c[3])
{
    cv::Vec3d m;
    for (int k = 0; k < 3; k++)
        m[k] = (c[0][k] + c[1][k] + c[2][k]) / 3.0;
    return m;
}

// Gouraud colour at p: barycentric weights from the exact edge functions of the snapped
// triangle. The weight of vertex v[i] is E(v[i+1] -> v[i+2], p) / area2; the weights sum to 1.
inline cv::Vec3d gouraudColor(const Triangle& t, const cv::Vec3d c[3], const Fixed& p)
{
    cv::Vec3d out(0, 0, 0);
    for (int i = 0; i < 3; i++) {
        const Int128 e = edgeFunction(t.v[(i + 1) % 3], t.v[(i + 2) % 3], p);
        const double w = (double)e / (double)t.area2;
        const cv::Vec3d& ci = c[t.src[i]];
        for (int k = 0; k < 3; k++)
            out[k] += w * ci[k];
    }
    return out;
}

// Writes a colour into a CV_32FC3 or CV_8UC3 pixel.
inline void putPixel(cv::Mat& canvas, int x, int y, const cv::Vec3d& c)
{
    if (canvas.type() == CV_32FC3)
        canvas.at<cv::Vec3f>(y, x) = cv::Vec3f((float)c[0], (float)c[1], (float)c[2]);
    else
        canvas.at<cv::Vec3b>(y, x) = cv::Vec3b(cv::saturate_cast<uchar>(c[0]),
                                               cv::saturate_cast<uchar>(c[1]),
                                               cv::saturate_cast<uchar>(c[2]));
}

// Inclusive pixel range [lo, hi] that can hold samples between fixed-point coordinates
// fmin..fmax, clipped to [0, n - 1]. Empty when lo > hi. (fmin / 256 is exact in double.)
inline void clippedRange(long long fmin, long long fmax, int n, int& lo, int& hi)
{
    const double a = std::floor((double)fmin / kSubpixel);
    const double b = std::ceil((double)fmax / kSubpixel);
    if (a > n - 1 || b < 0) {  // wholly outside
        lo = 1;
        hi = 0;
        return;
    }
    lo = (int)std::max(a, 0.0);
    hi = (int)std::min(b, (double)(n - 1));
}

// Calls f(x, y, samplePoint) for every pixel of a width x height canvas that the triangle covers.
// Only the bounding box of the snapped vertices, clipped to the canvas, is visited.
template <typename F>
void forEachCoveredPixel(const Triangle& t, cv::Size size, F f)
{
    if (!t.drawable)
        return;
    long long minX = t.v[0].x, maxX = t.v[0].x, minY = t.v[0].y, maxY = t.v[0].y;
    for (int i = 1; i < 3; i++) {
        minX = std::min(minX, t.v[i].x);
        maxX = std::max(maxX, t.v[i].x);
        minY = std::min(minY, t.v[i].y);
        maxY = std::max(maxY, t.v[i].y);
    }
    int x0, x1, y0, y1;
    clippedRange(minX, maxX, size.width, x0, x1);
    clippedRange(minY, maxY, size.height, y0, y1);
    for (int y = y0; y <= y1; y++)
        for (int x = x0; x <= x1; x++) {
            const Fixed p = samplePoint(x, y);
            if (coversPoint(t, p))
                f(x, y, p);
        }
}

// Fills one triangle: flat (mean colour) or Gouraud. Only covered pixels are written.
// canvas: CV_32FC3 or CV_8UC3, possibly an ROI.
inline void fillTriangle(cv::Mat& canvas, const cv::Point2d v[3], const cv::Vec3d c[3],
                         bool gouraud)
{
    CV_Assert(canvas.type() == CV_32FC3 || canvas.type() == CV_8UC3);
    const Triangle t = setupTriangle(v);
    const cv::Vec3d flat = flatColor(c);
    forEachCoveredPixel(t, canvas.size(), [&](int x, int y, const Fixed& p) {
        putPixel(canvas, x, y, gouraud ? gouraudColor(t, c, p) : flat);
    });
}

// CV_8UC1 mask of the given size: 1 where the triangle covers the pixel's sample, else 0.
inline cv::Mat coverageMask(cv::Size size, const cv::Point2d v[3])
{
    cv::Mat mask(size, CV_8UC1, cv::Scalar(0));
    forEachCoveredPixel(setupTriangle(v), size,
                        [&](int x, int y, const Fixed&) { mask.at<uchar>(y, x) = 1; });
    return mask;
}

// Painter's order: face indices sorted by mean vertex depth, largest (farthest) first; equal
// means keep their order in faces. Empty depth: the order of faces.
inline std::vector<int> paintersOrder(const std::vector<cv::Vec3i>& faces,
                                      const std::vector<double>& depth)
{
    std::vector<int> order(faces.size());
    std::iota(order.begin(), order.end(), 0);
    if (depth.empty())
        return order;
    std::vector<double> mean(faces.size());
    for (size_t f = 0; f < faces.size(); f++) {
        const cv::Vec3i& t = faces[f];
        mean[f] = (depth[t[0]] + depth[t[1]] + depth[t[2]]) / 3.0;
    }
    std::stable_sort(order.begin(), order.end(),
                     [&](int a, int b) { return mean[a] > mean[b]; });
    return order;
}

// Draws a mesh in painter's order: each face simply overwrites what is below it.
inline void drawMesh(cv::Mat& canvas, const std::vector<cv::Point2d>& verts,
                     const std::vector<cv::Vec3i>& faces, const std::vector<cv::Vec3d>& colors,
                     const std::vector<double>& depth, bool gouraud)
{
    for (int f : paintersOrder(faces, depth)) {
        const cv::Vec3i& t = faces[f];
        const cv::Point2d v[3] = { verts[t[0]], verts[t[1]], verts[t[2]] };
        const cv::Vec3d c[3] = { colors[t[0]], colors[t[1]], colors[t[2]] };
        fillTriangle(canvas, v, c, gouraud);
    }
}

// render: a new CV_32FC3 image of the given size filled with background, then drawMesh.
inline cv::Mat render(const std::vector<cv::Point2d>& verts, const std::vector<cv::Vec3i>& faces,
                      const std::vector<cv::Vec3d>& colors, const std::vector<double>& depth,
                      bool gouraud, cv::Size size,
                      const cv::Scalar& background = cv::Scalar::all(1))
{
    cv::Mat img(size, CV_32FC3, background);
    drawMesh(img, verts, faces, colors, depth, gouraud);
    return img;
}

}  // namespace shading_ref

#endif  // OPENCV_SHADING_TEST_SHADING_REFERENCE_HPP
