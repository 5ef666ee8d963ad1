// lines(): Bresenham and DDA against references written from their definitions, against
// cv::line LINE_8, clipping of far endpoints, colours, threads and every bad argument.
#include "test_common.hpp"

#include <opencv2/core/utility.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/shading.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <climits>
#include <cstdio>
#include <iomanip>
#include <set>
#include <string>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <utility>
#include <vector>

namespace {

using cv::Mat;
using cv::Point;
using cv::Point2d;
using cv::Size;
using cv::Vec3b;
using cv::Vec3d;
using cv::Vec3f;
namespace sh = cv::shading;
using Pixels = std::map<std::pair<int64_t, int64_t>, int>;  // (x, y) -> step index

__extension__ typedef __int128 I128;

/** Reference Bresenham by its definition in cv::line's iterator: start at the endpoint of
smaller x; at major step k the minor offset is k * |dminor| / |dmajor| rounded to nearest, an
exact half rounded toward the start. Pixels restricted to [x0, x1) x [y0, y1). */
Pixels referenceBresenham(Point2d a, Point2d b, cv::Rect window)
{
    int64_t ax = int64_t(std::nearbyint(a.x)), ay = int64_t(std::nearbyint(a.y));
    int64_t bx = int64_t(std::nearbyint(b.x)), by = int64_t(std::nearbyint(b.y));
    if (bx < ax) {
        std::swap(ax, bx);
        std::swap(ay, by);
    }
    const int64_t dx = bx - ax, dy = std::abs(by - ay), sy = by >= ay ? 1 : -1;
    const bool steep = dy > dx;
    const int64_t n = steep ? dy : dx, m = steep ? dx : dy;
    Pixels out;
    for (int64_t k = 0; k <= n; k++) {
        const I128 num = I128(k) * m;
        int64_t off = int64_t(num / (n ? n : 1));
        const I128 r = num - I128(off) * (n ? n : 1);
        if (2 * r > n)
            off++;
        const int64_t x = steep ? ax + off : ax + k, y = steep ? ay + sy * k : ay + sy * off;
        if (window.contains(Point(int(std::clamp<int64_t>(x, INT_MIN, INT_MAX)),
                                  int(std::clamp<int64_t>(y, INT_MIN, INT_MAX)))))
            out[{x, y}] = int(k);
    }
    return out;
}

/** Reference DDA by its definition: 1/256 endpoints, positions round(min) .. round(max) of the
major axis (round = floor(v + 1/2)), minor = the exact line's there, to nearest; a tie goes
toward the left end (smaller x), on axis-parallel lines toward the smaller coordinate. */
Pixels referenceDda(Point2d a, Point2d b, cv::Rect window)
{
    const int64_t ax = std::llround(a.x * 256), ay = std::llround(a.y * 256);
    const int64_t bx = std::llround(b.x * 256), by = std::llround(b.y * 256);
    const bool xMajor = std::abs(bx - ax) >= std::abs(by - ay);
    int64_t s0 = xMajor ? ax : ay, t0 = xMajor ? ay : ax, s1 = xMajor ? bx : by,
            t1 = xMajor ? by : bx;
    if (s1 < s0) {
        std::swap(s0, s1);
        std::swap(t0, t1);
    }
    auto roundHalfUp = [](int64_t v) {  // floor(v / 256 + 1/2)
        const int64_t n = v + 128;
        return n >= 0 ? n / 256 : -((-n + 255) / 256);
    };
    // Direction of a tie: toward the left end.
    int tieUp = 0;  // 1: a tie goes to the larger minor coordinate
    if (xMajor && t1 < t0)
        tieUp = 1;
    Pixels out;
    const int64_t first = roundHalfUp(s0), last = roundHalfUp(s1);
    const int64_t lo = std::max<int64_t>(first, xMajor ? window.x : window.y);
    const int64_t hi = std::min<int64_t>(last, xMajor ? window.x + window.width - 1
                                                     : window.y + window.height - 1);
    for (int64_t i = lo; i <= hi; i++) {
        // minor * 256 = t0 + (256 i - s0) (t1 - t0) / (s1 - s0): as num / den, den > 0
        const I128 den = s1 == s0 ? I128(256) : I128(s1 - s0) * 256;
        const I128 num =
            s1 == s0 ? I128(t0) : I128(t0) * (s1 - s0) + I128(256 * i - s0) * (t1 - t0);
        // value = num / den pixels; nearest integer with ties per tieUp.
        const I128 twice = 2 * num;  // compare 2 num with (2 k + 1) den
        I128 k = twice / (2 * den);
        if (twice - k * 2 * den < 0)
            k--;  // floor(num / den)
        const I128 r2 = twice - k * 2 * den;  // 2 (num - k den) in [0, 2 den)
        if (r2 > den || (r2 == den && tieUp))
            k++;
        const int64_t minor = int64_t(k);
        const int64_t x = xMajor ? i : minor, y = xMajor ? minor : i;
        if (x >= window.x && x < window.x + window.width && y >= window.y &&
            y < window.y + window.height)
            out[{x, y}] = int(i - first);
    }
    return out;
}

std::set<std::pair<int64_t, int64_t>> keys(const Pixels& p)
{
    std::set<std::pair<int64_t, int64_t>> s;
    for (const auto& kv : p)
        s.insert(kv.first);
    return s;
}

std::set<std::pair<int64_t, int64_t>> drawnSet(const Mat& canvas, const Mat& before,
                                              Point offset = Point())
{
    const Mat mask = shading_test::writtenMask(canvas, before);
    std::set<std::pair<int64_t, int64_t>> s;
    for (int y = 0; y < mask.rows; y++)
        for (int x = 0; x < mask.cols; x++)
            if (mask.at<uchar>(y, x))
                s.insert({x + offset.x, y + offset.y});
    return s;
}

std::set<std::pair<int64_t, int64_t>> drawOne(Size size, Point2d a, Point2d b, int algorithm,
                                             int type = CV_8UC3)
{
    Mat canvas = shading_test::sentinelCanvas(size, type), before = canvas.clone();
    const std::vector<Point2d> pts = {a, b};
    const std::vector<Vec3d> cols(2, Vec3d(200, 100, 50));
    sh::lines(canvas, pts, cols, algorithm);
    return drawnSet(canvas, before);
}

Point randomPoint(cv::RNG& rng, int w, int h, int margin)
{
    return Point(rng.uniform(-margin, w + margin), rng.uniform(-margin, h + margin));
}

TEST(Lines, BresenhamEqualsCvLineOnCanvas)
{
    cv::RNG rng(19);
    const Size size(64, 48);
    for (int iter = 0; iter < 4000; iter++) {
        Point a = randomPoint(rng, size.width, size.height, 0);
        Point b = randomPoint(rng, size.width, size.height, 0);
        a.x = std::min(a.x, size.width - 1), a.y = std::min(a.y, size.height - 1);
        b.x = std::min(b.x, size.width - 1), b.y = std::min(b.y, size.height - 1);
        switch (iter % 8) {  // horizontal, vertical, diagonal, a point, then general
        case 0: b.y = a.y; break;
        case 1: b.x = a.x; break;
        case 2: b = a + Point(1, 1) * std::min(size.width - 1 - a.x, size.height - 1 - a.y); break;
        case 3: b = a; break;
        default: break;
        }
        Mat ref(size, CV_8UC3, cv::Scalar::all(7));
        const Mat before = ref.clone();
        cv::line(ref, a, b, cv::Scalar(200, 100, 50), 1, cv::LINE_8);
        const auto expected = drawnSet(ref, before);
        for (int algorithm : {sh::LINE_BRESENHAM, sh::LINE_DDA}) {
            ASSERT_EQ(drawOne(size, a, b, algorithm), expected)
                << "segment " << a << " - " << b << " algorithm " << algorithm;
            ASSERT_EQ(drawOne(size, b, a, algorithm), expected) << "reversed " << a << b;
        }
    }
}

TEST(Lines, BresenhamEqualsCvLineOnAnyCanvasContainingTheSegment)
{
    // Off-canvas endpoints: ours on an ROI equals cv::line on the whole image, cropped.
    cv::RNG rng(7);
    const Size big(300, 260);
    const cv::Rect roi(100, 90, 80, 60);
    int differentClipped = 0, crossing = 0;
    for (int iter = 0; iter < 3000; iter++) {
        const Point a = randomPoint(rng, big.width - 1, big.height - 1, 0);
        const Point b = randomPoint(rng, big.width - 1, big.height - 1, 0);
        Mat ref(big, CV_8UC3, cv::Scalar::all(7));
        const Mat before = ref.clone();
        cv::line(ref, a, b, cv::Scalar(200, 100, 50), 1, cv::LINE_8);
        const auto expected = drawnSet(ref(roi), before(roi));
        Mat mine(big, CV_8UC3, cv::Scalar::all(7));
        Mat view = mine(roi);
        const std::vector<Point2d> pts = {Point2d(a - roi.tl()), Point2d(b - roi.tl())};
        sh::lines(view, pts, std::vector<Vec3d>(2, Vec3d(200, 100, 50)));
        ASSERT_EQ(drawnSet(view, before(roi)), expected) << a << " - " << b;
        // Outside the ROI nothing changed.
        Mat outside = mine.clone();
        before(roi).copyTo(outside(roi));
        ASSERT_EQ(cv::countNonZero(shading_test::writtenMask(outside, before)), 0);
        // cv::line on the small canvas clips with rounded intersections: it may differ.
        Mat small(roi.size(), CV_8UC3, cv::Scalar::all(7));
        cv::line(small, a - roi.tl(), b - roi.tl(), cv::Scalar(200, 100, 50), 1, cv::LINE_8);
        const bool cut = !expected.empty() && !(roi.contains(a) && roi.contains(b));
        crossing += cut;
        differentClipped += drawnSet(small, before(roi)) != expected;
    }
    std::printf("[ info ] cv::line on the ROI-sized canvas differs from its whole-image pixels "
                "on %d of the %d segments the ROI's border cuts\n",
                differentClipped, crossing);
}

TEST(Lines, BresenhamMatchesDefinition)
{
    cv::RNG rng(3);
    const Size size(90, 70);
    const cv::Rect window(0, 0, size.width, size.height);
    for (int iter = 0; iter < 3000; iter++) {
        const double s = iter % 3 == 0 ? 400 : 60;  // some far off the canvas
        const Point2d a(rng.uniform(-s, s + 90), rng.uniform(-s, s + 70));
        const Point2d b(rng.uniform(-s, s + 90), rng.uniform(-s, s + 70));
        ASSERT_EQ(drawOne(size, a, b, sh::LINE_BRESENHAM),
                  keys(referenceBresenham(a, b, window)))
            << a << " - " << b;
    }
}

TEST(Lines, DdaMatchesDefinition)
{
    cv::RNG rng(4);
    const Size size(90, 70);
    const cv::Rect window(0, 0, size.width, size.height);
    for (int iter = 0; iter < 5000; iter++) {
        const double s = iter % 3 == 0 ? 400 : 60;
        Point2d a(rng.uniform(-s, s + 90), rng.uniform(-s, s + 70));
        Point2d b(rng.uniform(-s, s + 90), rng.uniform(-s, s + 70));
        if (iter % 5 == 1) {  // halves and quarters: ties of both roundings
            a = Point2d(std::round(a.x * 4) / 4, std::round(a.y * 2) / 2);
            b = Point2d(std::round(b.x * 2) / 2, std::round(b.y * 4) / 4);
        }
        if (iter % 7 == 2)
            b.y = a.y;  // horizontal
        if (iter % 11 == 3)
            b = a + Point2d(rng.uniform(-1.0, 1.0), rng.uniform(-1.0, 1.0));  // short
        if (iter % 13 == 4)
            b = a;  // a point
        ASSERT_EQ(drawOne(size, a, b, sh::LINE_DDA), keys(referenceDda(a, b, window)))
            << std::setprecision(17) << a << " - " << b;
        ASSERT_EQ(drawOne(size, b, a, sh::LINE_DDA), keys(referenceDda(a, b, window)));
    }
}

TEST(Lines, HalfPixelTiesGoTowardTheLeftEnd)
{
    // (0,0)-(4,2): at x = 1 and 3 the line is at y = .5 and 1.5: ties go toward (0,0), up.
    const std::set<std::pair<int64_t, int64_t>> down = {{0, 0}, {1, 0}, {2, 1}, {3, 1}, {4, 2}};
    EXPECT_EQ(drawOne({8, 8}, {0, 0}, {4, 2}, sh::LINE_BRESENHAM), down);
    EXPECT_EQ(drawOne({8, 8}, {4, 2}, {0, 0}, sh::LINE_DDA), down);
    // (0,2)-(4,0) rises to the right: ties toward (0, 2), down the image.
    const std::set<std::pair<int64_t, int64_t>> up = {{0, 2}, {1, 2}, {2, 1}, {3, 1}, {4, 0}};
    EXPECT_EQ(drawOne({8, 8}, {0, 2}, {4, 0}, sh::LINE_BRESENHAM), up);
    // Steep: ties toward the smaller x.
    const std::set<std::pair<int64_t, int64_t>> steep = {{0, 0}, {0, 1}, {1, 2}, {1, 3}, {2, 4}};
    EXPECT_EQ(drawOne({8, 8}, {2, 4}, {0, 0}, sh::LINE_BRESENHAM), steep);
    // DDA, a horizontal line at y = 2.5: toward the smaller y; x from round(0.5) = 1.
    const std::set<std::pair<int64_t, int64_t>> half = {{1, 2}, {2, 2}, {3, 2}};
    EXPECT_EQ(drawOne({8, 8}, {0.5, 2.5}, {3.4, 2.5}, sh::LINE_DDA), half);
    // Bresenham rounds endpoints as cvRound: 2.5 -> 2, 3.5 -> 4.
    const std::set<std::pair<int64_t, int64_t>> rounded = {{2, 4}, {3, 4}, {4, 4}};
    EXPECT_EQ(drawOne({8, 8}, {2.5, 3.5}, {4.4, 3.6}, sh::LINE_BRESENHAM), rounded);
}

TEST(Lines, FarEndpointsAreClippedExactlyAndCheaply)
{
    const Size size(200, 150);
    const cv::Rect window(0, 0, size.width, size.height);
    const std::vector<std::pair<Point2d, Point2d>> cases = {
        {{-1e9, -1e9}, {1e9, 1e9}},         {{-1e9, 75}, {1e9, 75.3}},
        {{-1e9, -3e8}, {1e9, 4e8 + 0.5}},   {{100, -1e9}, {37.25, 1e9}},
        {{1e9, 1e9}, {-1e9 + 3, -1e9 + 7}}, {{-1099511627776.0, 5}, {1099511627776.0, 70}},
        {{-5e8, 1e9}, {5e8, -1e9}}};
    for (const auto& c : cases) {
        for (int algorithm : {sh::LINE_BRESENHAM, sh::LINE_DDA}) {
            const auto start = std::chrono::steady_clock::now();
            const auto drawn = drawOne(size, c.first, c.second, algorithm);
            const double ms = std::chrono::duration<double, std::milli>(
                                  std::chrono::steady_clock::now() - start).count();
            EXPECT_LT(ms, 50.0) << c.first << " - " << c.second;
            const Pixels ref = algorithm == sh::LINE_DDA
                                   ? referenceDda(c.first, c.second, window)
                                   : Pixels();
            if (algorithm == sh::LINE_DDA) {
                EXPECT_EQ(drawn, keys(ref)) << c.first << " - " << c.second;
            }
        }
    }
    // The diagonal through the canvas: exactly (i, i).
    const auto diag = drawOne(size, {-1e9, -1e9}, {1e9, 1e9}, sh::LINE_BRESENHAM);
    std::set<std::pair<int64_t, int64_t>> expected;
    for (int i = 0; i < 150; i++)
        expected.insert({i, i});
    EXPECT_EQ(diag, expected);
    // Beyond 2^40, NaN and infinity: skipped.
    for (double bad : {2e12, std::nan(""), std::numeric_limits<double>::infinity()}) {
        EXPECT_TRUE(drawOne(size, {bad, 0}, {10, 10}, sh::LINE_BRESENHAM).empty());
        EXPECT_TRUE(drawOne(size, {0, 0}, {10, bad}, sh::LINE_DDA).empty());
    }
}

TEST(Lines, ColoursInterpolateAlongTheMajorAxis)
{
    // 8-bit: 0 -> 255 over 10 steps, t = i / 10, rounded to nearest (cvRound).
    Mat canvas(4, 16, CV_8UC3, cv::Scalar::all(7));
    const std::vector<Point2d> pts = {{0, 1}, {10, 2}};
    const std::vector<Vec3d> cols = {{0, 255, 10}, {255, 0, 10}};
    sh::lines(canvas, pts, cols);
    for (int i = 0; i <= 10; i++) {
        const int y = i < 5 ? 1 : (i == 5 ? 1 : 2);  // tie at x = 5 goes toward (0, 1)
        const Vec3b px = canvas.at<Vec3b>(y, i);
        // Exact halves at odd i (0.5 ulp from a tie either way): within 1/2 there.
        EXPECT_NEAR(px[0], 25.5 * i, i % 2 ? 0.5 : 0.0) << i;
        EXPECT_NEAR(px[1], 255 - 25.5 * i, i % 2 ? 0.5 : 0.0) << i;
        EXPECT_EQ(px[2], 10);
    }
    EXPECT_EQ(canvas.at<Vec3b>(1, 1)[0], 26);  // 25.5 rounds to nearest, not truncated
    // Float, steep, given bottom to top: t runs from the first point.
    Mat f(12, 4, CV_32FC3, cv::Scalar::all(-1));
    sh::lines(f, std::vector<Point2d>{{1, 10}, {2, 0}},
              std::vector<Vec3f>{{1, 0, 0}, {0, 0, 1}});
    for (int y = 0; y <= 10; y++) {
        const int x = y > 5 ? 1 : (y == 5 ? 1 : 2);  // tie at y = 5 toward the smaller x
        const Vec3f px = f.at<Vec3f>(y, x);
        EXPECT_NEAR(px[0], (y) / 10.0, 1e-7) << y;
        EXPECT_NEAR(px[2], 1 - y / 10.0, 1e-7) << y;
    }
    // DDA: t from the 1/256 endpoints, clamped to [0, 1] at rounded ends.
    Mat d(4, 8, CV_32FC3, cv::Scalar::all(-1));
    sh::lines(d, std::vector<Point2d>{{0.75, 1}, {4.25, 1}},
              std::vector<Vec3d>{{0, 0, 0}, {1, 1, 1}}, sh::LINE_DDA);
    EXPECT_FLOAT_EQ(d.at<Vec3f>(1, 1)[0], float(0.25 / 3.5));
    EXPECT_FLOAT_EQ(d.at<Vec3f>(1, 4)[0], float(3.25 / 3.5));
    EXPECT_EQ(d.at<Vec3f>(1, 0)[0], -1.f);
    EXPECT_EQ(d.at<Vec3f>(1, 5)[0], -1.f);
    // A point: one pixel of the first colour. Saturation on 8-bit.
    Mat p(4, 4, CV_8UC3, cv::Scalar::all(7));
    sh::lines(p, std::vector<Point2d>{{2, 2}, {2.2, 1.9}},
              std::vector<Vec3d>{{300, -5, 127.5}, {0, 0, 0}});
    EXPECT_EQ(p.at<Vec3b>(2, 2), Vec3b(255, 0, 128));
    EXPECT_EQ(cv::countNonZero(shading_test::writtenMask(p, Mat(4, 4, CV_8UC3,
                                                             cv::Scalar::all(7)))), 1);
}

TEST(Lines, LaterSegmentsWinAndThreadsDoNotMatter)
{
    cv::RNG rng(11);
    std::vector<Point2d> pts;
    std::vector<Vec3f> cols;
    for (int i = 0; i < 40000; i++) {
        pts.emplace_back(rng.uniform(-100.0, 1100.0), rng.uniform(-100.0, 900.0));
        cols.emplace_back(rng.uniform(0.f, 1.f), rng.uniform(0.f, 1.f), rng.uniform(0.f, 1.f));
    }
    for (int algorithm : {sh::LINE_BRESENHAM, sh::LINE_DDA})
        for (int type : {CV_32FC3, CV_8UC3}) {
            std::vector<Vec3f> c = cols;
            if (type == CV_8UC3)
                for (Vec3f& v : c)
                    v *= 255.f;
            const int previous = cv::getNumThreads();
            Mat ref;
            for (int threads : {1, 2, 8}) {
                cv::setNumThreads(threads);
                Mat canvas(800, 1000, type, cv::Scalar::all(0));
                sh::lines(canvas, pts, c, algorithm);
                if (ref.empty()) {
                    ref = canvas;
                } else {
                    EXPECT_EQ(cv::norm(canvas, ref, cv::NORM_INF), 0) << threads;
                }
            }
            cv::setNumThreads(previous);
            // One by one, in order: the same image.
            Mat single(800, 1000, type, cv::Scalar::all(0));
            for (size_t i = 0; i < pts.size(); i += 2)
                sh::lines(single, std::vector<Point2d>{pts[i], pts[i + 1]},
                          std::vector<Vec3f>{c[i], c[i + 1]}, algorithm);
            EXPECT_EQ(cv::norm(single, ref, cv::NORM_INF), 0);
        }
}

TEST(Lines, InputFormsAndEmpty)
{
    Mat a(10, 10, CV_32FC3, cv::Scalar::all(0)), b = a.clone(), c = a.clone();
    sh::lines(a, std::vector<Point>{{1, 1}, {8, 5}}, std::vector<cv::Vec3i>{{1, 1, 1}, {0, 0, 0}});
    Mat m = (cv::Mat_<float>(2, 2) << 1, 1, 8, 5);
    Mat mc = (cv::Mat_<double>(2, 3) << 1, 1, 1, 0, 0, 0);
    sh::lines(b, m, mc);
    EXPECT_EQ(cv::norm(a, b, cv::NORM_INF), 0);
    sh::lines(c, cv::noArray(), cv::noArray());  // no segments: nothing drawn
    EXPECT_EQ(cv::countNonZero(c.reshape(1)), 0);
}

TEST(Lines, BadArgumentsRaiseAndLeaveTheCanvasUntouched)
{
    Mat canvas(10, 10, CV_8UC3, cv::Scalar::all(7));
    const Mat before = canvas.clone();
    const std::vector<Point2d> three = {{0, 0}, {5, 5}, {9, 0}};
    const std::vector<Point2d> two = {{0, 0}, {5, 5}};
    const std::vector<Vec3d> twoC(2, Vec3d(1, 2, 3)), threeC(3, Vec3d(1, 2, 3));
    auto expectError = [&](auto&& call, const char* word) {
        try {
            call();
            ADD_FAILURE() << "no exception; expected one naming " << word;
        } catch (const cv::Exception& e) {
            EXPECT_NE(std::string(e.what()).find(word), std::string::npos) << e.what();
        }
        EXPECT_EQ(cv::norm(canvas, before, cv::NORM_INF), 0);
    };
    expectError([&] { sh::lines(canvas, three, threeC); }, "points: expected an even number");
    expectError([&] { sh::lines(canvas, two, threeC); }, "colors: expected 2 items");
    expectError([&] { sh::lines(canvas, two, twoC, 2); }, "algorithm");
    expectError([&] { sh::lines(canvas, std::vector<cv::Point3f>(2), twoC); }, "points");
    Mat gray(10, 10, CV_8UC1);
    expectError([&] { sh::lines(gray, two, twoC); }, "canvas");
    Mat empty;
    expectError([&] { sh::lines(empty, two, twoC); }, "canvas");
}

}  // namespace
