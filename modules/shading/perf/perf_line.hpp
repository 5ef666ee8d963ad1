// This file is part of opencv_shading. License: Apache-2.0.
//
// perf_line.hpp: cv::shading::lines against cv::line, and cv::shading::texturedTriangles against
// what an OpenCV user writes otherwise (per triangle: an affine map of its box, cv::remap, a
// cv::fillConvexPoly mask, copyTo).
//
//   lines/random100k/{bresenham,dda,bresenham-gradient}/threads:N   100,000 random segments
//   cvline/random100k/threads:1                                     cv::line, LINE_8, one each
//   texturedTriangles/grid1024/{nearest,linear}/threads:N           2,048 triangles, 256^2 texture
//   remapPerTriangle/grid1024/{nearest,linear}/threads:1
//
// Canvases are 1024 x 1024 CV_8UC3 (cv::line's usual target), cleared before each run.
#ifndef OPENCV_SHADING_PERF_LINE_HPP
#define OPENCV_SHADING_PERF_LINE_HPP

#include "perf_harness.hpp"

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/shading.hpp>

#include <cmath>
#include <memory>
#include <string>
#include <vector>

namespace shading_perf {

struct LineScene {
    std::vector<cv::Point> points;        //!< 2N integer endpoints (some off the canvas)
    std::vector<cv::Vec3b> colors;        //!< one colour per segment, for cv::line
    std::vector<cv::Vec3d> flat, ramp;    //!< 2N colours: constant per segment / two per segment
};

inline LineScene makeLineScene(int segments, int side)
{
    cv::RNG rng(0x11e5);
    LineScene s;
    for (int i = 0; i < segments; i++) {
        for (int k = 0; k < 2; k++)
            s.points.emplace_back(rng.uniform(-side / 8, side + side / 8),
                                  rng.uniform(-side / 8, side + side / 8));
        const cv::Vec3b c(uchar(rng.uniform(0, 256)), uchar(rng.uniform(0, 256)),
                          uchar(rng.uniform(0, 256)));
        s.colors.push_back(c);
        s.flat.push_back(cv::Vec3d(c)), s.flat.push_back(cv::Vec3d(c));
        s.ramp.push_back(cv::Vec3d(c)), s.ramp.push_back(cv::Vec3d(255, 255, 255) - cv::Vec3d(c));
    }
    return s;
}

struct TextureScene {
    std::vector<cv::Point2f> verts, uv;
    std::vector<cv::Vec3i> faces;
    cv::Mat texture;  //!< 256 x 256 CV_8UC3
};

inline TextureScene makeTextureScene(int side, int cells)
{
    TextureScene s;
    s.texture.create(256, 256, CV_8UC3);
    cv::RNG(5).fill(s.texture, cv::RNG::UNIFORM, 0, 256);
    cv::GaussianBlur(s.texture, s.texture, cv::Size(5, 5), 0);
    for (int j = 0; j <= cells; j++)
        for (int i = 0; i <= cells; i++) {
            const float x = float(side) * i / cells, y = float(side) * j / cells;
            s.verts.emplace_back(x + 5.f * std::sin(y / 40.f), y + 5.f * std::sin(x / 50.f));
            s.uv.emplace_back(255.f * i / cells, 255.f * j / cells);
        }
    for (int j = 0; j < cells; j++)
        for (int i = 0; i < cells; i++) {
            const int a = j * (cells + 1) + i, b = a + 1, c = a + cells + 1, d = c + 1;
            s.faces.emplace_back(a, b, d);
            s.faces.emplace_back(a, d, c);
        }
    return s;
}

//! The OpenCV way: per triangle, maps of its box by the screen-to-texture affine transform,
//! remap, and a fillConvexPoly mask to copy only the triangle.
inline void remapPerTriangle(const TextureScene& s, int interpolation, cv::Mat& canvas)
{
    cv::Mat mapX, mapY, patch, mask;
    for (const cv::Vec3i& f : s.faces) {
        const cv::Point2f src[3] = {s.verts[f[0]], s.verts[f[1]], s.verts[f[2]]};
        const cv::Point2f dst[3] = {s.uv[f[0]], s.uv[f[1]], s.uv[f[2]]};
        const cv::Rect box = cv::boundingRect(std::vector<cv::Point2f>(src, src + 3)) &
                             cv::Rect(0, 0, canvas.cols, canvas.rows);
        if (box.empty())
            continue;
        const cv::Mat a = cv::getAffineTransform(src, dst);  // screen -> texture
        mapX.create(box.size(), CV_32FC1);
        mapY.create(box.size(), CV_32FC1);
        for (int y = 0; y < box.height; y++)
            for (int x = 0; x < box.width; x++) {
                const double px = box.x + x, py = box.y + y;
                mapX.at<float>(y, x) = float(a.at<double>(0, 0) * px + a.at<double>(0, 1) * py +
                                             a.at<double>(0, 2));
                mapY.at<float>(y, x) = float(a.at<double>(1, 0) * px + a.at<double>(1, 1) * py +
                                             a.at<double>(1, 2));
            }
        cv::remap(s.texture, patch, mapX, mapY, interpolation, cv::BORDER_REPLICATE);
        mask = cv::Mat::zeros(box.size(), CV_8UC1);
        cv::Point pts[3];
        for (int k = 0; k < 3; k++)
            pts[k] = cv::Point(cvRound(src[k].x) - box.x, cvRound(src[k].y) - box.y);
        cv::fillConvexPoly(mask, pts, 3, cv::Scalar(255));
        patch.copyTo(canvas(box), mask);
    }
}

inline void clear8u(cv::Mat& canvas, int side)
{
    canvas.create(side, side, CV_8UC3);
    canvas.setTo(cv::Scalar::all(255));
}

inline void addLineBenchmarks(int allThreads)
{
    const int side = 1024;
    auto lines = std::make_shared<LineScene>(makeLineScene(100000, side));
    const double segments = double(lines->colors.size());
    for (int threads : {1, allThreads}) {
        if (threads != 1 && allThreads == 1)
            continue;
        const std::string t = "/threads:" + std::to_string(threads);
        addNamedBenchmark("lines/random100k/bresenham" + t, segments, side * side, threads,
                          [lines, side](cv::Mat& img) {
                              clear8u(img, side);
                              cv::shading::lines(img, lines->points, lines->flat);
                          });
        addNamedBenchmark("lines/random100k/dda" + t, segments, side * side, threads,
                          [lines, side](cv::Mat& img) {
                              clear8u(img, side);
                              cv::shading::lines(img, lines->points, lines->flat,
                                                 cv::shading::LINE_DDA);
                          });
        addNamedBenchmark("lines/random100k/bresenham-gradient" + t, segments, side * side,
                          threads, [lines, side](cv::Mat& img) {
                              clear8u(img, side);
                              cv::shading::lines(img, lines->points, lines->ramp);
                          });
    }
    addNamedBenchmark("cvline/random100k/threads:1", segments, side * side, 1,
                      [lines, side](cv::Mat& img) {
                          clear8u(img, side);
                          for (size_t i = 0; i < lines->colors.size(); i++)
                              cv::line(img, lines->points[2 * i], lines->points[2 * i + 1],
                                       cv::Scalar(lines->colors[i]), 1, cv::LINE_8);
                      });
    auto tex = std::make_shared<TextureScene>(makeTextureScene(side, 32));
    const double faces = double(tex->faces.size());
    for (int interpolation : {cv::INTER_NEAREST, cv::INTER_LINEAR}) {
        const std::string mode = interpolation == cv::INTER_NEAREST ? "nearest" : "linear";
        for (int threads : {1, allThreads}) {
            if (threads != 1 && allThreads == 1)
                continue;
            addNamedBenchmark("texturedTriangles/grid1024/" + mode + "/threads:" +
                                  std::to_string(threads),
                              faces, side * side, threads,
                              [tex, side, interpolation](cv::Mat& img) {
                                  clear8u(img, side);
                                  cv::shading::texturedTriangles(img, tex->verts, tex->faces,
                                                                 tex->uv, tex->texture,
                                                                 interpolation);
                              });
        }
        addNamedBenchmark("remapPerTriangle/grid1024/" + mode + "/threads:1", faces,
                          side * side, 1, [tex, side, interpolation](cv::Mat& img) {
                              clear8u(img, side);
                              remapPerTriangle(*tex, interpolation, img);
                          });
    }
}

}  // namespace shading_perf

#endif  // OPENCV_SHADING_PERF_LINE_HPP
