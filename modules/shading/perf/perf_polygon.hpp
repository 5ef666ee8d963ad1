// This file is part of opencv_shading. License: Apache-2.0.
//
// perf_polygon.hpp: cv::shading::fillPolygons against cv::fillPoly (LINE_8, 8 fractional bits,
// the same 1/256 px precision) on random star-shaped, concave polygons of 10 to 100,000
// vertices (polyN) and on self-crossing ones (crossN: the angles jittered by up to three steps)
// on a 1024 x 1024 CV_8UC3 canvas. Names: fillPolygons/SCENE/threads:T and fillPoly/SCENE/threads:1
// (fillPoly is single-threaded); triangulatePolygons/SCENE/threads:1 and, when built with GLU
// (libglu1-mesa-dev), gluTess/SCENE/threads:1, the seed's GLU tessellator (odd winding, a combine
// callback for crossings), both up to 10,000 vertices and given the same snapped points. The
// canvas is not cleared between iterations: both draw the same pixels again. The context records
// how many pixels fillPolygons and fillPoly cover differently (fillPoly also paints boundary
// pixels; fillPolygons the top-left rule), and, untimed, how the two tessellations drawn with the
// library's rasterizer differ from fillPolygons' coverage (polygon_coverage/SCENE: samples
// covered, then per tessellation the samples whose coverage differs and those covered twice).
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
angles, radii uniform in [0.15, 0.48] x side, so deeply concave. With `crossing`, each angle is
jittered by up to three steps either way, so that edges cross. Deterministic. */
inline std::vector<cv::Point2f> starPolygon(int n, int side, bool crossing = false)
{
    cv::RNG rng(uint64(1000 + n));
    std::vector<cv::Point2f> pts;
    const double c = side / 2.0;
    for (int i = 0; i < n; i++) {
        const double jitter = crossing ? rng.uniform(-3.0, 3.0) : rng.uniform(0.0, 0.9);
        const double a = 2 * CV_PI * (i + jitter) / n;
        const double r = side * rng.uniform(0.15, 0.48);
        pts.push_back(cv::Point2f(float(c + r * std::cos(a)), float(c + r * std::sin(a))));
    }
    return pts;
}

//! Triangles as vertex indices, 3 per face, and the vertices they index.
struct Triangles {
    std::vector<int> indices;
    std::vector<cv::Point2d> vertices;
};

#ifdef OPENCV_SHADING_PERF_GLU
/** GLU's tessellator (the seed's gluTess* calls) on one contour, odd winding rule, triangles
only. `out.vertices` starts as the contour; the combine callback appends the crossings. */
inline void gluTriangulate(Triangles& out)
{
    struct Calls {
        static void vertex(void* data, void* user)
        {
            static_cast<Triangles*>(user)->indices.push_back(int(reinterpret_cast<intptr_t>(data)));
        }
        static void edgeFlag(GLboolean, void*) {}  // asks GLU for plain triangles
        static void combine(GLdouble coords[3], void*[4], GLfloat[4], void** made, void* user)
        {
            std::vector<cv::Point2d>& v = static_cast<Triangles*>(user)->vertices;
            *made = reinterpret_cast<void*>(intptr_t(v.size()));
            v.push_back(cv::Point2d(coords[0], coords[1]));
        }
    };
    const size_t n = out.vertices.size();
    std::vector<GLdouble> coords(3 * n);
    for (size_t i = 0; i < n; i++)
        coords[3 * i] = out.vertices[i].x, coords[3 * i + 1] = out.vertices[i].y, coords[3 * i + 2] = 0;
    out.indices.clear();
    GLUtesselator* tess = gluNewTess();
    gluTessCallback(tess, GLU_TESS_VERTEX_DATA, reinterpret_cast<_GLUfuncptr>(&Calls::vertex));
    gluTessCallback(tess, GLU_TESS_EDGE_FLAG_DATA,
                    reinterpret_cast<_GLUfuncptr>(&Calls::edgeFlag));
    gluTessCallback(tess, GLU_TESS_COMBINE_DATA, reinterpret_cast<_GLUfuncptr>(&Calls::combine));
    gluTessProperty(tess, GLU_TESS_WINDING_RULE, GLU_TESS_WINDING_ODD);
    gluTessNormal(tess, 0, 0, 1);
    gluTessBeginPolygon(tess, &out);
    gluTessBeginContour(tess);
    for (size_t i = 0; i < n; i++)
        gluTessVertex(tess, &coords[3 * i], reinterpret_cast<void*>(intptr_t(i)));
    gluTessEndContour(tess);
    gluTessEndPolygon(tess);
    gluDeleteTess(tess);
}
#endif

/** "D T": the samples where the triangles, drawn with the library's rasterizer, differ from
`filled` (D) and those they cover more than once (T). */
inline std::string coverageDifference(const Triangles& t, const cv::Mat& filled)
{
    cv::Mat counts(filled.size(), CV_16U, cv::Scalar(0));
    for (size_t f = 0; f + 2 < t.indices.size(); f += 3) {
        const std::vector<cv::Point2d> tri = {t.vertices[size_t(t.indices[f])],
                                              t.vertices[size_t(t.indices[f + 1])],
                                              t.vertices[size_t(t.indices[f + 2])]};
        cv::shading::forEachSpan(counts.size(), tri,
                                 [&](int y, int xb, int xe, const cv::Vec3d&, const cv::Vec3d&) {
                                     ushort* row = counts.ptr<ushort>(y);
                                     for (int x = xb; x < xe; x++)
                                         row[x]++;
                                 });
    }
    const cv::Mat differ = (counts > 0) != filled;
    return std::to_string(cv::countNonZero(differ)) + " " +
           std::to_string(cv::countNonZero(counts > 1));
}

inline void addPolygonBenchmarks(int allThreads)
{
    const int side = 1024;
    const cv::Size size(side, side);
    for (bool crossing : {false, true})
        for (int n : {10, 1000, 10000, 100000}) {
            const std::string scene = (crossing ? "cross" : "poly") + std::to_string(n);
            auto poly = std::make_shared<std::vector<std::vector<cv::Point2f>>>(
                1, starPolygon(n, side, crossing));
            auto fixed = std::make_shared<std::vector<std::vector<cv::Point>>>(1);
            auto snapped = std::make_shared<std::vector<cv::Point2d>>();
            for (const cv::Point2f& p : (*poly)[0]) {
                const cv::Point q(int(std::lround(p.x * 256.0)), int(std::lround(p.y * 256.0)));
                (*fixed)[0].push_back(q);
                snapped->push_back(cv::Point2d(q) / 256.0);
            }
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
                    addNamedBenchmark("fillPolygons/" + scene + "/threads:" +
                                          std::to_string(threads),
                                      n, double(size.area()), threads, ours);
            addNamedBenchmark("fillPoly/" + scene + "/threads:1", n, double(size.area()), 1,
                              theirs);
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
            if (n > 10000)
                continue;  // ear clipping: superlinear, seconds at 100,000 points
            auto faces = std::make_shared<cv::Mat>();
            addNamedBenchmark("triangulatePolygons/" + scene + "/threads:1", n,
                              double(size.area()), 1, [poly, faces](cv::Mat&) {
                                  cv::shading::triangulatePolygons(*poly, *faces);
                              });
            // The tessellations against fillPolygons' coverage, once, untimed.
            cv::Mat filled;
            cv::extractChannel(a, filled, 0);
            filled = filled != 255;
            Triangles mine;
            cv::Mat faceMat, vertexMat;
            cv::shading::triangulatePolygons(*poly, faceMat, cv::shading::FILL_EVEN_ODD,
                                             vertexMat);
            mine.indices.assign(faceMat.ptr<int>(), faceMat.ptr<int>() + faceMat.total());
            for (int i = 0; i < vertexMat.rows; i++)
                mine.vertices.push_back({vertexMat.at<double>(i, 0), vertexMat.at<double>(i, 1)});
            std::string record = "covered " + std::to_string(cv::countNonZero(filled)) +
                                 "; triangulatePolygons " + coverageDifference(mine, filled);
#ifdef OPENCV_SHADING_PERF_GLU
            auto glu = std::make_shared<Triangles>();
            addNamedBenchmark("gluTess/" + scene + "/threads:1", n, double(size.area()), 1,
                              [snapped, glu](cv::Mat&) {
                                  glu->vertices = *snapped;
                                  gluTriangulate(*glu);
                              });
            Triangles theirTriangles;
            theirTriangles.vertices = *snapped;
            gluTriangulate(theirTriangles);
            record += "; gluTess " + coverageDifference(theirTriangles, filled);
#endif
            benchmark::AddCustomContext("polygon_coverage/" + scene, record);
        }
}

}  // namespace shading_perf

#endif  // OPENCV_SHADING_PERF_POLYGON_HPP
