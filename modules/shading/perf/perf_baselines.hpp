// This file is part of opencv_shading. License: Apache-2.0.
//
// perf_baselines.hpp: what the benchmark compares cv::shading::render with, each drawing a whole
// scene onto a CV_32FC3 canvas cleared to white, faces in painter's order (far to near):
//
//   PlainRasterizer     the "plain reference": a single-threaded bounding-box edge-function
//                       rasterizer (1/256 px fixed point, int64 edges stepped along each row,
//                       top-left rule as a bias, raw pointers, stable sort), flat or Gouraud:
//                       what a competent engineer writes in an hour
//   FillConvexPolyPainter  cv::fillConvexPoly per triangle with its mean colour (flat only)
//
// Both keep their scratch buffers between calls, as a renderer drawing frames would.
#ifndef OPENCV_SHADING_PERF_BASELINES_HPP
#define OPENCV_SHADING_PERF_BASELINES_HPP

#include "perf_scenes.hpp"

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <utility>
#include <vector>

namespace shading_perf {

//! Makes `canvas` a `size` CV_32FC3 image cleared to white, as cv::shading::render starts.
inline void clearCanvas(cv::Mat& canvas, cv::Size size)
{
    canvas.create(size, CV_32FC3);
    canvas.setTo(cv::Scalar::all(1.0));
}

/** Clears `canvas` as clearCanvas does, then reads every value of the scene's arrays once
(vertices, faces, colours, depths; cv::sum, one thread): the least any renderer of the scene
must do, the floor that issue 17's million-face target is measured against (render within 3x of
it). Returns the sums, for the caller to keep the reads. */
inline double clearAndReadScene(cv::Mat& canvas, const Scene& scene)
{
    clearCanvas(canvas, scene.size);
    const MeshScene& m = scene.mesh;
    double total = 0;
    for (const cv::Mat* a : {&m.verts2d, &m.faces, &m.vcolors, &m.depth}) {
        const cv::Scalar s = cv::sum(*a);
        total += s[0] + s[1] + s[2] + s[3];
    }
    return total;
}

//! Fixed-point units per pixel: vertices snap to a 1/256 px grid, as in the library.
constexpr int kSubpixelBits = 8;

/** Draws a scene's faces in painter's order. The order and the snapped vertices are recomputed
on every call (they would change every frame) into buffers kept between calls; the scene's
arrays are read through raw pointers, as a renderer written for speed would. */
class Painter {
public:
    /** Clears `canvas` to white, then calls `draw(face, v)` for every face in sort() order, `v`
    being the face's vertices in 1/256 px units. */
    template <class Draw>
    void paint(const Scene& scene, cv::Mat& canvas, Draw&& draw)
    {
        clearCanvas(canvas, scene.size);
        const MeshScene& s = scene.mesh;
        sort(s);
        const int vertexCount = s.verts2d.rows;
        const float* xy = s.verts2d.ptr<float>();
        snapped_.resize(static_cast<size_t>(vertexCount));
        for (int v = 0; v < vertexCount; ++v)  // the library's rounding: halves away from zero
            snapped_[v] = cv::Point(static_cast<int>(std::lround(xy[2 * v] * (1 << kSubpixelBits))),
                                    static_cast<int>(std::lround(xy[2 * v + 1] * (1 << kSubpixelBits))));
        const cv::Vec3i* faces = s.faces.ptr<cv::Vec3i>();
        for (int i : order_) {
            const cv::Vec3i& f = faces[i];
            const cv::Point v[3] = {snapped_[f[0]], snapped_[f[1]], snapped_[f[2]]};
            draw(f, v);
        }
    }

    /** Face indices far to near: stable sort by mean vertex depth, largest first (ties keep
    their order in `faces`), the order cv::shading::render uses. */
    const std::vector<int>& sort(const MeshScene& s)
    {
        const int faceCount = s.faces.rows;
        const cv::Vec3i* faces = s.faces.ptr<cv::Vec3i>();
        const float* depth = s.depth.ptr<float>();
        meanDepth_.resize(static_cast<size_t>(faceCount));
        order_.resize(static_cast<size_t>(faceCount));
        for (int i = 0; i < faceCount; ++i) {
            const cv::Vec3i& f = faces[i];
            meanDepth_[i] = (double(depth[f[0]]) + depth[f[1]] + depth[f[2]]) / 3.0;
            order_[i] = i;
        }
        std::stable_sort(order_.begin(), order_.end(),
                         [this](int a, int b) { return meanDepth_[a] > meanDepth_[b]; });
        return order_;
    }

private:
    std::vector<double> meanDepth_;
    std::vector<int> order_;
    std::vector<cv::Point> snapped_;
};

//! Mean of a face's three vertex colours.
inline cv::Vec3f meanColor(const MeshScene& s, const cv::Vec3i& f)
{
    return (s.vcolors.at<cv::Vec3f>(f[0]) + s.vcolors.at<cv::Vec3f>(f[1]) +
            s.vcolors.at<cv::Vec3f>(f[2])) * (1.f / 3.f);
}

/** The plain reference rasterizer, as a competent engineer writes it in an hour: for each
triangle, the rows of its bounding box (clipped to the canvas) step three int64 edge functions
(top-left rule as a bias) incrementally along the row; covered pixels get the flat colour or the
barycentric blend of the vertex colours, written through a raw row pointer. A row stops at the
end of its covered run (a triangle's samples on a row are contiguous). Single-threaded. */
class PlainRasterizer {
public:
    void render(const Scene& scene, bool gouraud, cv::Mat& canvas)
    {
        const MeshScene& s = scene.mesh;
        const cv::Vec3f* colors = s.vcolors.ptr<cv::Vec3f>();
        painter_.paint(scene, canvas, [&](const cv::Vec3i& f, const cv::Point(&v)[3]) {
            if (gouraud) {
                const cv::Vec3f c[3] = {colors[f[0]], colors[f[1]], colors[f[2]]};
                triangle<true>(canvas, v, c);
            } else {
                const cv::Vec3f c[3] = {(colors[f[0]] + colors[f[1]] + colors[f[2]]) * (1.f / 3.f),
                                        {}, {}};
                triangle<false>(canvas, v, c);
            }
        });
    }

private:
    // One edge a -> b: E(p) = (b - a) x (p - a) and its steps for one pixel in x and in y.
    struct Edge {
        int64_t value, stepX, stepY;
        Edge(cv::Point a, cv::Point b, int64_t px, int64_t py)
        {
            const int64_t dx = b.x - a.x, dy = b.y - a.y;
            value = dx * (py - a.y) - dy * (px - a.x);
            stepX = -dy * (1 << kSubpixelBits);
            stepY = dx * (1 << kSubpixelBits);
            // Top-left rule: a sample on the edge is covered only on a top edge (horizontal,
            // interior below) or a left edge (interior to its right); elsewhere require E > 0.
            if (!(dy < 0 || (dy == 0 && dx > 0)))
                value -= 1;
        }
    };

    // Draws one triangle; for flat shading only c[0] is used.
    template <bool Gouraud>
    static void triangle(cv::Mat& canvas, const cv::Point (&vin)[3], const cv::Vec3f (&cin)[3])
    {
        cv::Point v[3] = {vin[0], vin[1], vin[2]};
        cv::Vec3f c[3] = {cin[0], cin[1], cin[2]};
        int64_t area = int64_t(v[1].x - v[0].x) * (v[2].y - v[0].y) -
                       int64_t(v[1].y - v[0].y) * (v[2].x - v[0].x);
        if (area == 0)
            return;
        if (area < 0) {  // make the winding positive so the interior has E >= 0 on all edges
            std::swap(v[1], v[2]);
            std::swap(c[1], c[2]);
            area = -area;
        }
        // Bounding box in whole pixels (sample points are integer points), clipped.
        constexpr int one = 1 << kSubpixelBits;
        const int x0 = std::max(0, (std::min({v[0].x, v[1].x, v[2].x}) + one - 1) >> kSubpixelBits);
        const int y0 = std::max(0, (std::min({v[0].y, v[1].y, v[2].y}) + one - 1) >> kSubpixelBits);
        const int x1 = std::min(canvas.cols - 1, std::max({v[0].x, v[1].x, v[2].x}) >> kSubpixelBits);
        const int y1 = std::min(canvas.rows - 1, std::max({v[0].y, v[1].y, v[2].y}) >> kSubpixelBits);
        if (x0 > x1 || y0 > y1)
            return;

        // e[k] is the edge opposite vertex k: its value is area * (barycentric weight of k).
        const int64_t px = int64_t(x0) << kSubpixelBits, py = int64_t(y0) << kSubpixelBits;
        Edge e[3] = {Edge(v[1], v[2], px, py), Edge(v[2], v[0], px, py), Edge(v[0], v[1], px, py)};
        const float invArea = 1.f / static_cast<float>(area);
        float base[3], d1[3], d2[3];
        for (int k = 0; k < 3; ++k) {
            base[k] = c[0][k];
            d1[k] = (c[1][k] - c[0][k]) * invArea;
            d2[k] = (c[2][k] - c[0][k]) * invArea;
        }

        for (int y = y0; y <= y1; ++y) {
            int64_t w0 = e[0].value, w1 = e[1].value, w2 = e[2].value;
            float* row = canvas.ptr<float>(y);
            bool inside = false;
            for (int x = x0; x <= x1; ++x) {
                if ((w0 | w1 | w2) >= 0) {  // all three signs non-negative
                    inside = true;
                    float* p = row + 3 * x;
                    if (Gouraud) {
                        const float f1 = static_cast<float>(w1), f2 = static_cast<float>(w2);
                        p[0] = base[0] + d1[0] * f1 + d2[0] * f2;
                        p[1] = base[1] + d1[1] * f1 + d2[1] * f2;
                        p[2] = base[2] + d1[2] * f1 + d2[2] * f2;
                    } else {
                        p[0] = base[0], p[1] = base[1], p[2] = base[2];
                    }
                } else if (inside) {
                    break;  // past the row's covered run
                }
                w0 += e[0].stepX;
                w1 += e[1].stepX;
                w2 += e[2].stepX;
            }
            for (Edge& edge : e)
                edge.value += edge.stepY;
        }
    }

    Painter painter_;
};

/** cv::fillConvexPoly per triangle, far to near, each with its mean colour (flat shading), with
the vertices passed in the same 1/256 px fixed point (shift = 8). */
class FillConvexPolyPainter {
public:
    void render(const Scene& scene, cv::Mat& canvas)
    {
        painter_.paint(scene, canvas, [&](const cv::Vec3i& f, const cv::Point(&v)[3]) {
            const cv::Vec3f c = meanColor(scene.mesh, f);
            cv::fillConvexPoly(canvas, v, 3, cv::Scalar(c[0], c[1], c[2]), cv::LINE_8,
                               kSubpixelBits);
        });
    }

private:
    Painter painter_;
};

}  // namespace shading_perf

#endif  // OPENCV_SHADING_PERF_BASELINES_HPP
