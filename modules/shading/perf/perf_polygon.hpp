// This file is part of opencv_shading. License: Apache-2.0.
//
// perf_polygon.hpp: cv::shading::fillPolygons against cv::fillPoly (LINE_8, 8 fractional bits,
// the same 1/256 px precision) on random star-shaped, concave polygons of 10, 1,000 and 100,000
// vertices on a 1024 x 1024 CV_8UC3 canvas. Names: fillPolygons/polyN/threads:T and
// fillPoly/polyN/threads:1 (fillPoly is single-threaded); triangulatePolygons/polyN/threads:1
// and, when built with GLU (libglu1-mesa-dev), gluTess/polyN/threads:1, the seed's GLU
// tessellator, up to 10,000 vertices. The canvas is not cleared between
// iterations: both draw the same pixels again. The context records how many pixels the two
// cover differently (fillPoly also paints boundary pixels; fillPolygons the top-left rule).
#ifndef OPENCV_SHADING_PERF_POLYGON_HPP
#define OPENCV_SHADING_PERF_POLYGON_HPP

#include "perf_harness.hpp"

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/shading.hpp>

#ifdef OPENCV_SHADING_PERF_GLU
#include <GL/glu.h>
#endif

#include <cmath>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace shading_perf {

/** A star-shaped polygon of n vertices around the canvas centre: jittered, evenly spaced
angles, radii uniform in [0.15, 0.48] x side, so deeply concave. Deterministic. */
inline std::vector<cv::Point2f> starPolygon(int n, int side)
{
    cv::RNG rng(uint64(1000 + n));
    std::vector<cv::Point2f> pts;
    const double c = side / 2.0;
    for (int i = 0; i < n; i++) {
        const double a = 2 * CV_PI * (i + rng.uniform(0.0, 0.9)) / n;
        const double r = side * rng.uniform(0.15, 0.48);
        pts.push_back(cv::Point2f(float(c + r * std::cos(a)), float(c + r * std::sin(a))));
    }
    return pts;
}

#ifdef OPENCV_SHADING_PERF_GLU
/** GLU's tessellator (the seed's gluTess* calls) on one contour, odd winding rule, triangles
only: the indices of their vertices in `out` (GLU adds no vertex to a simple contour). */
inline void gluTriangulate(const std::vector<cv::Point2f>& pts, std::vector<int>& out)
{
    struct Calls {
        static void vertex(void* data, void* user)
        {
            static_cast<std::vector<int>*>(user)->push_back(int(reinterpret_cast<intptr_t>(data)));
        }
        static void edgeFlag(GLboolean, void*) {}  // asks GLU for plain triangles
    };
    std::vector<GLdouble> coords(3 * pts.size());
    for (size_t i = 0; i < pts.size(); i++)
        coords[3 * i] = pts[i].x, coords[3 * i + 1] = pts[i].y, coords[3 * i + 2] = 0;
    out.clear();
    GLUtesselator* tess = gluNewTess();
    gluTessCallback(tess, GLU_TESS_VERTEX_DATA, reinterpret_cast<_GLUfuncptr>(&Calls::vertex));
    gluTessCallback(tess, GLU_TESS_EDGE_FLAG_DATA,
                    reinterpret_cast<_GLUfuncptr>(&Calls::edgeFlag));
    gluTessProperty(tess, GLU_TESS_WINDING_RULE, GLU_TESS_WINDING_ODD);
    gluTessNormal(tess, 0, 0, 1);
    gluTessBeginPolygon(tess, &out);
    gluTessBeginContour(tess);
    for (size_t i = 0; i < pts.size(); i++)
        gluTessVertex(tess, &coords[3 * i], reinterpret_cast<void*>(intptr_t(i)));
    gluTessEndContour(tess);
    gluTessEndPolygon(tess);
    gluDeleteTess(tess);
}
#endif

inline void addPolygonBenchmarks(int allThreads)
{
    const int side = 1024;
    const cv::Size size(side, side);
    for (int n : {10, 1000, 100000}) {
        const std::string scene = "poly" + std::to_string(n);
        auto poly = std::make_shared<std::vector<std::vector<cv::Point2f>>>(
            1, starPolygon(n, side));
        auto fixed = std::make_shared<std::vector<std::vector<cv::Point>>>(1);
        for (const cv::Point2f& p : (*poly)[0])
            (*fixed)[0].push_back(cv::Point(int(std::lround(p.x * 256.0)),
                                             int(std::lround(p.y * 256.0))));
        const cv::Scalar color(40, 160, 220);
        auto ours = [poly, size, color](cv::Mat& canvas) {
            if (canvas.empty())
                canvas.create(size, CV_8UC3), canvas.setTo(cv::Scalar::all(255));
            cv::shading::fillPolygons(canvas, *poly, color);
        };
        auto theirs = [fixed, size, color](cv::Mat& canvas) {
            if (canvas.empty())
                canvas.create(size, CV_8UC3), canvas.setTo(cv::Scalar::all(255));
            cv::fillPoly(canvas, *fixed, color, cv::LINE_8, 8);
        };
        for (int threads : {1, allThreads})
            if (threads == 1 || allThreads > 1)
                addNamedBenchmark("fillPolygons/" + scene + "/threads:" + std::to_string(threads),
                                  n, double(size.area()), threads, ours);
        addNamedBenchmark("fillPoly/" + scene + "/threads:1", n, double(size.area()), 1, theirs);
        if (n <= 10000) {  // ear clipping: superlinear, seconds at 100,000 points
            auto faces = std::make_shared<cv::Mat>();
            addNamedBenchmark("triangulatePolygons/" + scene + "/threads:1", n,
                              double(size.area()), 1, [poly, faces](cv::Mat&) {
                                  cv::shading::triangulatePolygons(*poly, *faces);
                              });
#ifdef OPENCV_SHADING_PERF_GLU
            auto indices = std::make_shared<std::vector<int>>();
            addNamedBenchmark("gluTess/" + scene + "/threads:1", n, double(size.area()), 1,
                              [poly, indices](cv::Mat&) { gluTriangulate((*poly)[0], *indices); });
#endif
        }
        // Coverage of the two, compared once.
        cv::Mat a, b, diff;
        ours(a);
        theirs(b);
        cv::compare(a.reshape(1), b.reshape(1), diff, cv::CMP_NE);
        const cv::Mat covered = a.reshape(1) != 255;
        benchmark::AddCustomContext(
            "check_fillPolygons_vs_fillPoly/" + scene,
            std::to_string(cv::countNonZero(diff) / 3) + " of " +
                std::to_string(cv::countNonZero(covered) / 3) + " covered pixels differ");
    }
}

}  // namespace shading_perf

#endif  // OPENCV_SHADING_PERF_POLYGON_HPP
