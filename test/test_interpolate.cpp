// forEachSample / forEachSpan: the library's coverage and exact barycentric weights handed to
// user code; interpolate().
#include "test_common.hpp"

#include <opencv2/shading.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <set>
#include <utility>
#include <vector>

namespace {

using cv::Point2d;
using cv::Size;
using cv::Vec3d;
namespace sh = cv::shading;

//! Reference weights: areas of the snapped triangle in long double.
Vec3d referenceWeights(const std::vector<Point2d>& v, int x, int y)
{
    long double px[3], py[3];
    for (int i = 0; i < 3; i++) {
        px[i] = std::llround(v[i].x * 256) / 256.0L;
        py[i] = std::llround(v[i].y * 256) / 256.0L;
    }
    auto edge = [&](int a, int b, long double qx, long double qy) {
        return (px[b] - px[a]) * (qy - py[a]) - (py[b] - py[a]) * (qx - px[a]);
    };
    const long double area = edge(0, 1, px[2], py[2]);
    return Vec3d(double(edge(1, 2, x, y) / area), double(edge(2, 0, x, y) / area),
                 double(edge(0, 1, x, y) / area));
}

std::vector<Point2d> randomTriangle(cv::RNG& rng, double lo, double hi, bool subpixel)
{
    std::vector<Point2d> v(3);
    for (Point2d& p : v) {
        p = Point2d(rng.uniform(lo, hi), rng.uniform(lo, hi));
        if (!subpixel)
            p = Point2d(std::round(p.x), std::round(p.y));
    }
    return v;
}

TEST(Interpolate, SamplesAreFlatsCoverageWithExactWeights)
{
    cv::RNG rng(2024);
    const Size size(64, 48);
    for (int iter = 0; iter < 1500; iter++) {
        const bool far = iter % 5 == 0;
        const auto v = randomTriangle(rng, far ? -300 : -10, far ? 300 : 70, iter % 2 == 0);
        std::set<std::pair<int, int>> seen;
        int calls = 0;
        sh::forEachSample(size, v, [&](int x, int y, const Vec3d& w) {
            seen.insert({x, y});
            calls++;
            const Vec3d ref = referenceWeights(v, x, y);
            for (int k = 0; k < 3; k++)
                ASSERT_NEAR(w[k], ref[k], 1e-12 * (1 + std::abs(ref[k])));
            ASSERT_NEAR(w[0] + w[1] + w[2], 1.0, 1e-12);
        });
        ASSERT_EQ(calls, int(seen.size()));  // each sample once
        ASSERT_EQ(seen, shading_test::flatCoverage(size, v)) << iter;
    }
}

TEST(Interpolate, HugeTrianglesKeepExactWeights)
{
    // Beyond 2^20 px the core's 128-bit path: every canvas sample covered, weights still exact.
    const Size size(40, 30);
    const std::vector<Point2d> v = {{-1e7, -1e7}, {1e7 + 0.5, -5e6}, {3.25, 1e7}};
    int calls = 0;
    sh::forEachSample(size, v, [&](int x, int y, const Vec3d& w) {
        calls++;
        const Vec3d ref = referenceWeights(v, x, y);
        for (int k = 0; k < 3; k++)
            ASSERT_NEAR(w[k], ref[k], 1e-12);
    });
    EXPECT_EQ(calls, size.area());
}

TEST(Interpolate, SpansAgreeWithSamples)
{
    cv::RNG rng(5);
    const Size size(80, 60);
    for (int iter = 0; iter < 500; iter++) {
        const auto v = randomTriangle(rng, -20, 100, true);
        std::set<std::pair<int, int>> fromSpans;
        int lastRow = -1;
        sh::forEachSpan(size, v, [&](int y, int xBegin, int xEnd, const Vec3d& w,
                                     const Vec3d& dwdx) {
            ASSERT_GT(y, lastRow);  // one span per row, top to bottom
            lastRow = y;
            ASSERT_LT(xBegin, xEnd);
            for (int x = xBegin; x < xEnd; x++) {
                fromSpans.insert({x, y});
                const Vec3d stepped = w + dwdx * double(x - xBegin);
                const Vec3d ref = referenceWeights(v, x, y);
                for (int k = 0; k < 3; k++)
                    ASSERT_NEAR(stepped[k], ref[k], 1e-9);
            }
        });
        ASSERT_EQ(fromSpans, shading_test::flatCoverage(size, v));
    }
}

TEST(Interpolate, GouraudByCallbackEqualsGouraud)
{
    // The seed's use: interpolate 3 colour values per sample, write them.
    const std::vector<Point2d> v = {{3.3, 2.1}, {60.7, 20.2}, {15.5, 44.9}};
    const std::vector<cv::Vec3f> c = {{1, 0, 0}, {0, 1, 0}, {0.2f, 0.3f, 1}};
    cv::Mat mine(48, 64, CV_32FC3, cv::Scalar::all(-1)), ref = mine.clone();
    sh::gouraud(ref, v, c);
    sh::forEachSample(mine.size(), v, [&](int x, int y, const Vec3d& w) {
        mine.at<cv::Vec3f>(y, x) = sh::interpolate(c[0], c[1], c[2], w);
    });
    EXPECT_LE(cv::norm(mine, ref, cv::NORM_INF), 1e-6);
    EXPECT_EQ(cv::countNonZero(shading_test::writtenMask(mine, cv::Mat(48, 64, CV_32FC3,
                                                                     cv::Scalar::all(-1)))),
              cv::countNonZero(shading_test::writtenMask(ref, cv::Mat(48, 64, CV_32FC3,
                                                                    cv::Scalar::all(-1)))));
    EXPECT_DOUBLE_EQ(sh::interpolate(1.0, 2.0, 4.0, Vec3d(0.5, 0.25, 0.25)), 2.0);
    EXPECT_EQ(sh::interpolate(cv::Vec3b(0, 100, 255), cv::Vec3b(255, 100, 255),
                              cv::Vec3b(0, 100, 255), Vec3d(0.5, 0.25, 0.25)),
              cv::Vec3b(64, 100, 255));
}

TEST(Interpolate, DegenerateAndInvalidTrianglesCallNothing)
{
    int calls = 0;
    auto count = [&](int, int, const Vec3d&) { calls++; };
    const Size size(32, 32);
    sh::forEachSample(size, std::vector<Point2d>{{1, 1}, {5, 5}, {9, 9}}, count);
    sh::forEachSample(size, std::vector<Point2d>{{1, 1}, {std::nan(""), 5}, {9, 1}}, count);
    sh::forEachSample(size, std::vector<Point2d>{{-50, -50}, {-10, -50}, {-30, -10}}, count);
    EXPECT_EQ(calls, 0);
}

TEST(Interpolate, BadArgumentsRaise)
{
    const std::vector<Point2d> tri = {{1, 1}, {9, 1}, {1, 9}};
    auto fn = [](int, int, const Vec3d&) {};
    EXPECT_THROW(sh::forEachSample(Size(0, 10), tri, fn), cv::Exception);
    EXPECT_THROW(sh::forEachSample(Size(10, 10), std::vector<Point2d>(2), fn), cv::Exception);
    EXPECT_THROW(sh::forEachSample(Size(10, 10), tri, sh::SampleCallback()), cv::Exception);
    EXPECT_THROW(sh::forEachSpan(Size(10, 10), tri, sh::SpanCallback()), cv::Exception);
    try {
        sh::forEachSample(Size(10, -1), tri, fn);
    } catch (const cv::Exception& e) {
        EXPECT_NE(std::string(e.what()).find("canvasSize"), std::string::npos);
    }
    // A throwing callback stops the walk and propagates.
    int calls = 0;
    EXPECT_THROW(sh::forEachSample(Size(10, 10), tri,
                                   [&](int, int, const Vec3d&) {
                                       if (++calls == 3)
                                           throw std::runtime_error("stop");
                                   }),
                 std::runtime_error);
    EXPECT_EQ(calls, 3);
}

}  // namespace
