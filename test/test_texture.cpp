// texturedTriangles: coverage of flats, pixels equal to cv::remap with maps of the same
// interpolated coordinates, face order, conversions and every bad argument.
#include "test_common.hpp"

#include <opencv2/core/utility.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/shading.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <set>
#include <utility>
#include <string>
#include <vector>

namespace {

using cv::Mat;
using cv::Point2d;
using cv::Size;
using cv::Vec3i;
namespace sh = cv::shading;

struct TexScene {
    std::vector<Point2d> verts, uv;
    std::vector<Vec3i> faces;
};

TexScene randomScene(cv::RNG& rng, int faces, Size canvas, Size tex)
{
    TexScene s;
    for (int f = 0; f < faces; f++) {
        for (int k = 0; k < 3; k++) {
            s.verts.emplace_back(rng.uniform(-10.0, canvas.width + 10.0),
                                 rng.uniform(-10.0, canvas.height + 10.0));
            // Beyond the texture on every side: all borders are exercised.
            s.uv.emplace_back(rng.uniform(-0.4 * tex.width, 1.4 * tex.width),
                              rng.uniform(-0.4 * tex.height, 1.4 * tex.height));
        }
        s.faces.emplace_back(3 * f, 3 * f + 1, 3 * f + 2);
    }
    return s;
}

//! Barycentric weights of sample (x, y) in the snapped triangle, in long double.
void weights(const Point2d* v[3], int x, int y, long double w[3])
{
    long double px[3], py[3];
    for (int i = 0; i < 3; i++) {
        px[i] = std::llround(v[i]->x * 256) / 256.0L;
        py[i] = std::llround(v[i]->y * 256) / 256.0L;
    }
    auto edge = [&](int a, int b, long double qx, long double qy) {
        return (px[b] - px[a]) * (qy - py[a]) - (py[b] - py[a]) * (qx - px[a]);
    };
    const long double area = edge(0, 1, px[2], py[2]);
    w[0] = edge(1, 2, x, y) / area;
    w[1] = edge(2, 0, x, y) / area;
    w[2] = edge(0, 1, x, y) / area;
}

//! Whether v lies within eps of where remap's rounding changes (a .5 for nearest, an odd
//! multiple of 1/64 for bilinear's 1/32 steps).
bool nearRoundingBoundary(long double v, int interpolation)
{
    const long double s = interpolation == cv::INTER_NEAREST ? v : v * 32;
    const long double frac = s - std::floor(s);
    return std::abs(frac - 0.5L) < 1e-4L * (interpolation == cv::INTER_NEAREST ? 1 : 32);
}

/** Draws the scene with texturedTriangles and with cv::remap of maps built from independent
weights (face by face, later faces over earlier ones). Returns the number of covered pixels
that differ, failing the test on any difference not at a rounding boundary. */
int compareWithRemap(const TexScene& s, const Mat& texture, int canvasType, int interpolation,
                     int border, Size size)
{
    Mat canvas = shading_test::sentinelCanvas(size, canvasType), before = canvas.clone();
    sh::texturedTriangles(canvas, s.verts, s.faces, s.uv, texture, interpolation, border);
    Mat mapX(size, CV_32FC1, cv::Scalar(-1e6)), mapY = mapX.clone();
    cv::Mat exactX(size, CV_64FC1, cv::Scalar(0)), exactY = exactX.clone();
    Mat covered(size, CV_8UC1, cv::Scalar(0));
    for (const Vec3i& f : s.faces) {
        const Point2d* v[3] = {&s.verts[f[0]], &s.verts[f[1]], &s.verts[f[2]]};
        const std::vector<Point2d> tri = {*v[0], *v[1], *v[2]};
        for (const auto& px : shading_test::flatCoverage(size, tri)) {
            long double w[3];
            weights(v, px.first, px.second, w);
            long double u = 0, t = 0;
            for (int k = 0; k < 3; k++) {
                u += w[k] * s.uv[f[k]].x;
                t += w[k] * s.uv[f[k]].y;
            }
            mapX.at<float>(px.second, px.first) = float(u);
            mapY.at<float>(px.second, px.first) = float(t);
            exactX.at<double>(px.second, px.first) = double(u);
            exactY.at<double>(px.second, px.first) = double(t);
            covered.at<uchar>(px.second, px.first) = 255;
        }
    }
    Mat tex = texture;
    if (texture.depth() != CV_MAT_DEPTH(canvasType))
        texture.convertTo(tex, CV_MAT_DEPTH(canvasType),
                          CV_MAT_DEPTH(canvasType) == CV_8U ? 255.0 : 1.0 / 255.0);
    Mat expected;
    cv::remap(tex, expected, mapX, mapY, interpolation, border, cv::Scalar::all(0));
    before.copyTo(expected, ~covered);  // uncovered pixels stay as they were
    Mat diff = shading_test::writtenMask(canvas, expected);
    int differing = 0;
    for (int y = 0; y < size.height; y++)
        for (int x = 0; x < size.width; x++)
            if (diff.at<uchar>(y, x)) {
                differing++;
                EXPECT_TRUE(covered.at<uchar>(y, x)) << "wrote an uncovered pixel " << x << ","
                                                     << y;
                EXPECT_TRUE(nearRoundingBoundary(exactX.at<double>(y, x), interpolation) ||
                            nearRoundingBoundary(exactY.at<double>(y, x), interpolation))
                    << "pixel " << x << "," << y << " u " << exactX.at<double>(y, x) << " v "
                    << exactY.at<double>(y, x);
            }
    return differing;
}

TEST(Texture, EqualsRemapWithTheSameCoordinates)
{
    cv::RNG rng(77);
    const Size size(72, 56);
    int total = 0, covered = 0;
    for (Size texSize : {Size(37, 29), Size(1, 1), Size(5, 1), Size(64, 64)}) {
        Mat tex8(texSize, CV_8UC3), tex32;
        rng.fill(tex8, cv::RNG::UNIFORM, 0, 256);
        tex8.convertTo(tex32, CV_32F, 1 / 255.0);
        for (int interpolation : {cv::INTER_NEAREST, cv::INTER_LINEAR})
            for (int border : {cv::BORDER_CONSTANT, cv::BORDER_REPLICATE, cv::BORDER_REFLECT,
                               cv::BORDER_WRAP, cv::BORDER_REFLECT_101})
                for (int kind = 0; kind < 3; kind++) {
                    // An 8-bit canvas; a float one with a float texture; a float one with the
                    // 8-bit texture, read as bytes without a float copy (compareWithRemap
                    // converts it first, as the documentation says).
                    const int canvasType = kind == 0 ? CV_8UC3 : CV_32FC3;
                    const TexScene s = randomScene(rng, 12, size, texSize);
                    const Mat& tex = kind == 1 ? tex32 : tex8;
                    const int differing =
                        compareWithRemap(s, tex, canvasType, interpolation, border, size);
                    EXPECT_LE(differing, 2) << "interp " << interpolation << " border " << border;
                    total += differing;
                    covered += 1;
                }
    }
    std::printf("[ info ] %d pixels differ from cv::remap over %d scenes (all at rounding "
                "boundaries)\n", total, covered);
}

TEST(Texture, FarWrappedAndReflectedCoordinatesEqualRemap)
{
    // Coordinates many texture widths away (up to remap's 16-bit index range): every tap wraps
    // or reflects independently, as in remap.
    cv::RNG rng(5);
    const Size size(64, 48);
    for (Size texSize : {Size(37, 29), Size(3, 7), Size(1, 1)}) {
        Mat tex(texSize, CV_8UC3);
        rng.fill(tex, cv::RNG::UNIFORM, 0, 256);
        for (int border : {cv::BORDER_WRAP, cv::BORDER_REFLECT_101, cv::BORDER_REFLECT})
            for (int interpolation : {cv::INTER_NEAREST, cv::INTER_LINEAR}) {
                TexScene s = randomScene(rng, 8, size, texSize);
                for (Point2d& uv : s.uv)
                    uv = Point2d(rng.uniform(-30000.0, 30000.0), rng.uniform(-30000.0, 30000.0));
                EXPECT_LE(compareWithRemap(s, tex, CV_8UC3, interpolation, border, size), 2)
                    << texSize << " border " << border << " interp " << interpolation;
            }
    }
}

TEST(Texture, HalfPixelCoordinatesRoundAsRemap)
{
    // Texture coordinates on exact halves (nearest: ties to even, as remap's cvRound) and on
    // exact 1/64 steps (bilinear's ties): still equal, since both sides get the same floats.
    const Size size(40, 40);
    Mat tex(8, 8, CV_8UC3);
    cv::RNG(1).fill(tex, cv::RNG::UNIFORM, 0, 256);
    TexScene s;
    s.verts = {{0, 0}, {32, 0}, {0, 32}, {32, 32}};
    s.uv = {{0.5, 0.5}, {4.5, 0.5}, {0.5, 4.5}, {4.5, 4.5}};  // u = 0.5 + x / 8: halves at x = 0, 8
    s.faces = {{0, 1, 2}, {1, 3, 2}};
    for (int interpolation : {cv::INTER_NEAREST, cv::INTER_LINEAR})
        EXPECT_EQ(compareWithRemap(s, tex, CV_8UC3, interpolation, cv::BORDER_REPLICATE, size), 0);
}

TEST(Texture, CoverageIsFlatsAndLaterFacesWin)
{
    const Size size(50, 40);
    Mat red(4, 4, CV_32FC3, cv::Scalar(1, 0, 0)), green(4, 4, CV_32FC3, cv::Scalar(0, 1, 0));
    const std::vector<Point2d> v = {{2.5, 3.25}, {45.7, 10}, {10, 37.9}};
    Mat canvas = shading_test::sentinelCanvas(size), before = canvas.clone();
    sh::texturedTriangles(canvas, v, std::vector<Vec3i>{{0, 1, 2}},
                          std::vector<Point2d>{{0, 0}, {3, 0}, {0, 3}}, red);
    Mat mask = shading_test::writtenMask(canvas, before);
    std::set<std::pair<int, int>> written;
    for (int y = 0; y < size.height; y++)
        for (int x = 0; x < size.width; x++)
            if (mask.at<uchar>(y, x))
                written.insert({x, y});
    EXPECT_EQ(written, shading_test::flatCoverage(size, v));
    // Two faces over each other: the second wins.
    Mat two = shading_test::sentinelCanvas(size);
    const std::vector<Point2d> verts = {{0, 0}, {40, 0}, {0, 40}};
    const std::vector<Point2d> uv = {{1, 1}, {2, 1}, {1, 2}};
    sh::texturedTriangles(two, verts, std::vector<Vec3i>{{0, 1, 2}}, uv, red);
    sh::texturedTriangles(two, verts, std::vector<Vec3i>{{0, 1, 2}, {2, 1, 0}}, uv, green);
    EXPECT_EQ(two.at<cv::Vec3f>(5, 5), cv::Vec3f(0, 1, 0));
    // An 8-bit texture on a float canvas is scaled to [0, 1]; float on 8-bit by 255.
    Mat tex8(2, 2, CV_8UC3, cv::Scalar(255, 51, 0)), f = shading_test::sentinelCanvas(size);
    sh::texturedTriangles(f, verts, std::vector<Vec3i>{{0, 1, 2}}, uv, tex8, cv::INTER_NEAREST);
    EXPECT_LE(cv::norm(cv::Vec3d(f.at<cv::Vec3f>(5, 5)) - cv::Vec3d(1, 0.2, 0), cv::NORM_INF),
              1e-7);
    Mat b = shading_test::sentinelCanvas(size, CV_8UC3);
    sh::texturedTriangles(b, verts, std::vector<Vec3i>{{0, 1, 2}}, uv,
                          Mat(2, 2, CV_32FC3, cv::Scalar(1, 0.2, 0.5)));
    EXPECT_EQ(b.at<cv::Vec3b>(5, 5), cv::Vec3b(255, 51, 128));
}

TEST(Texture, ThreadsDoNotChangeTheImage)
{
    cv::RNG rng(8);
    const Size size(400, 300);
    const TexScene s = randomScene(rng, 300, size, Size(50, 40));
    Mat tex(40, 50, CV_8UC3);
    rng.fill(tex, cv::RNG::UNIFORM, 0, 256);
    const int previous = cv::getNumThreads();
    Mat ref;
    for (int threads : {1, 2, 8}) {
        cv::setNumThreads(threads);
        Mat canvas(size, CV_8UC3, cv::Scalar::all(0));
        sh::texturedTriangles(canvas, s.verts, s.faces, s.uv, tex);
        if (ref.empty()) {
            ref = canvas;
        } else {
            EXPECT_EQ(cv::norm(canvas, ref, cv::NORM_INF), 0) << threads;
        }
    }
    cv::setNumThreads(previous);
}

TEST(Texture, InvalidFacesAreSkipped)
{
    const Size size(20, 20);
    Mat tex(2, 2, CV_32FC3, cv::Scalar(1, 1, 1));
    Mat canvas = shading_test::sentinelCanvas(size), before = canvas.clone();
    const std::vector<Point2d> verts = {{0, 0}, {19, 0}, {0, 19}, {std::nan(""), 3}};
    sh::texturedTriangles(canvas, verts, std::vector<Vec3i>{{0, 1, 3}}, std::vector<Point2d>(4),
                          tex);
    sh::texturedTriangles(canvas, verts, std::vector<Vec3i>{{0, 1, 2}},
                          std::vector<Point2d>{{0, 0}, {1, 0}, {std::nan(""), 0}, {0, 0}}, tex);
    EXPECT_EQ(cv::norm(canvas, before, cv::NORM_INF), 0);
}

TEST(Texture, BadArgumentsRaiseAndLeaveTheCanvasUntouched)
{
    Mat canvas(20, 20, CV_8UC3, cv::Scalar::all(7));
    const Mat before = canvas.clone();
    const std::vector<Point2d> verts = {{0, 0}, {19, 0}, {0, 19}};
    const std::vector<Point2d> uv = {{0, 0}, {1, 0}, {0, 1}};
    const std::vector<Vec3i> faces = {{0, 1, 2}};
    const Mat tex(2, 2, CV_8UC3, cv::Scalar::all(100));
    auto expectError = [&](auto&& call, const char* word) {
        try {
            call();
            ADD_FAILURE() << "no exception; expected one naming " << word;
        } catch (const cv::Exception& e) {
            EXPECT_NE(std::string(e.what()).find(word), std::string::npos) << e.what();
        }
        EXPECT_EQ(cv::norm(canvas, before, cv::NORM_INF), 0);
    };
    expectError([&] { sh::texturedTriangles(canvas, verts, faces, uv, Mat()); }, "texture");
    expectError([&] { sh::texturedTriangles(canvas, verts, faces, uv, Mat(2, 2, CV_8UC1)); },
                "texture");
    expectError([&] { sh::texturedTriangles(canvas, verts, faces, uv, Mat(2, 2, CV_16UC3)); },
                "texture");
    expectError([&] { sh::texturedTriangles(canvas, verts, faces, uv, tex, cv::INTER_CUBIC); },
                "interpolation");
    expectError(
        [&] {
            sh::texturedTriangles(canvas, verts, faces, uv, tex, cv::INTER_LINEAR,
                                  cv::BORDER_TRANSPARENT);
        },
        "borderMode");
    expectError([&] { sh::texturedTriangles(canvas, verts, faces, std::vector<Point2d>(2), tex); },
                "texCoords");
    expectError(
        [&] { sh::texturedTriangles(canvas, verts, std::vector<Vec3i>{{0, 1, 3}}, uv, tex); },
        "faces");
    Mat gray(20, 20, CV_8UC1);
    expectError([&] { sh::texturedTriangles(gray, verts, faces, uv, tex); }, "canvas");
}

}  // namespace
