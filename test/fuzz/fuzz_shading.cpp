// libFuzzer target over the whole public API. The input bytes choose the function, the canvas
// (type, size, an ROI inside a larger image with a guard border), vertices (any float bit
// pattern, or values on the integer / half / 1/256 grids, or huge), colours, faces (indices in
// and out of range), depths and shadeType. Invariants checked on every input:
//  - no pixel outside the canvas (the guard border around the ROI) ever changes;
//  - a call that throws cv::Exception leaves the whole image untouched;
//  - no call takes longer than a bounded time;
//  - a single triangle with finite, moderate coordinates equals the brute-force reference.
// lines (5) and texturedTriangles (6) get the same vertices, colours and faces.
// drawMesh3d (function 4) gets fuzzed 3D vertices, camera, settings, normals and depth buffers;
// a rejected call also leaves the depth buffer untouched, and depths written are >= zNear.
#include "reference/shading_reference.hpp"

#include <fuzzer/FuzzedDataProvider.h>
#include <opencv2/core.hpp>
#include <opencv2/core/utility.hpp>
#include <opencv2/shading.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <vector>

namespace cv {
namespace shading {
namespace detail {
CV_EXPORTS uint64_t snapRoundingFallbacks();  // triangulatePolygons' fallbacks (polygon_arrangement.cpp)
}  // namespace detail
}  // namespace shading
}  // namespace cv

namespace {

constexpr int kGuard = 3;              // guard pixels around the ROI
constexpr double kMaxSeconds = 2.0;    // per call; a small canvas must never take longer

[[noreturn]] void fail(const char* what)
{
    std::fprintf(stderr, "invariant violated: %s\n", what);
    std::abort();
}

double pickCoordinate(FuzzedDataProvider& in, int extent)
{
    switch (in.ConsumeIntegralInRange(0, 5)) {
    case 0: return in.ConsumeIntegralInRange(-4, extent + 4);                    // integer
    case 1: return in.ConsumeIntegralInRange(-8, 2 * extent + 8) * 0.5;          // halves
    case 2: return in.ConsumeIntegralInRange(-1024, 256 * extent + 1024) / 256.0;  // grid
    case 3: return in.ConsumeFloatingPointInRange(-1e10, 1e10);                  // huge
    case 4: {                                                                     // any float
        const uint32_t bits = in.ConsumeIntegral<uint32_t>();
        float f;
        std::memcpy(&f, &bits, sizeof f);
        return f;
    }
    default: {                                                                    // any double
        const uint64_t bits = in.ConsumeIntegral<uint64_t>();
        double d;
        std::memcpy(&d, &bits, sizeof d);
        return d;
    }
    }
}

bool moderate(const std::vector<cv::Point2d>& v)
{
    for (const cv::Point2d& p : v)
        if (!(std::abs(p.x) < 1e6 && std::abs(p.y) < 1e6))
            return false;
    return true;
}

void compareWithReference(const cv::Mat& got, const cv::Mat& before,
                          const std::vector<cv::Point2d>& v, const std::vector<cv::Vec3d>& c,
                          bool gouraud)
{
    cv::Mat expected = before.clone();
    shading_ref::fillTriangle(expected, v.data(), c.data(), gouraud);
    const bool bytes = got.depth() == CV_8U;
    for (int y = 0; y < got.rows; y++)
        for (int x = 0; x < got.cols; x++) {
            const bool refWrote = shading_ref::covers(v.data(), x, y);
            for (int k = 0; k < 3; k++) {
                const double g = bytes ? got.at<cv::Vec3b>(y, x)[k] : got.at<cv::Vec3f>(y, x)[k];
                const double e = bytes ? expected.at<cv::Vec3b>(y, x)[k]
                                       : expected.at<cv::Vec3f>(y, x)[k];
                const double b = bytes ? before.at<cv::Vec3b>(y, x)[k] : before.at<cv::Vec3f>(y, x)[k];
                if (!refWrote) {
                    if (g != b && !(std::isnan(g) && std::isnan(b)))
                        fail("a pixel outside the reference coverage changed");
                    continue;
                }
                if (std::isnan(e) || std::isinf(e))
                    continue;  // non-finite colours: coverage is what matters
                // Floats: relative to the colours' magnitude; bytes: one step of rounding.
                double scale = 1;
                for (const cv::Vec3d& ci : c)
                    scale = std::max(scale, std::abs(ci[k]));
                const double tol = bytes ? 1.0 : 1e-4 * scale;
                if (!(std::abs(g - e) <= tol)) {
                    std::fprintf(stderr, "pixel (%d, %d) channel %d: got %.9g, reference %.9g\n", x, y, k, g, e);
                    for (int i = 0; i < 3; i++)
                        std::fprintf(stderr, "  vertex %.17g %.17g colour %.17g %.17g %.17g\n", v[i].x,
                                     v[i].y, c[i][0], c[i][1], c[i][2]);
                    fail("colour differs from the reference");
                }
            }
        }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
    static const bool quiet = [] { cv::setNumThreads(1); return true; }();
    (void)quiet;
    FuzzedDataProvider in(data, size);
    // flats, gouraud, drawMesh, render, drawMesh3d, lines, texturedTriangles, fillPolygons,
    // triangulatePolygons, drawTexturedMesh3d, forEachSample with depths
    const int function = in.ConsumeIntegralInRange(0, 10);
    static const int kTypes[] = {CV_32FC3, CV_8UC3, CV_32FC3, CV_8UC3, CV_8UC1, CV_64FC3, CV_32FC4};
    const int type = kTypes[in.ConsumeIntegralInRange(0, 6)];
    const int width = in.ConsumeIntegralInRange(0, 40), height = in.ConsumeIntegralInRange(0, 40);

    // The canvas is an ROI of a larger image whose guard border is a known pattern.
    cv::Mat whole(height + 2 * kGuard, width + 2 * kGuard, type);
    cv::randu(whole, cv::Scalar::all(0), cv::Scalar::all(200));
    cv::Mat canvas = whole(cv::Rect(kGuard, kGuard, width, height));
    const cv::Mat wholeBefore = whole.clone();

    const int vertexCount = function < 2 ? (in.ConsumeBool() ? 3 : in.ConsumeIntegralInRange(0, 5))
                                         : in.ConsumeIntegralInRange(0, 24);
    std::vector<cv::Point2d> verts(vertexCount);
    for (cv::Point2d& p : verts)
        p = cv::Point2d(pickCoordinate(in, width), pickCoordinate(in, height));
    const int colorCount = in.ConsumeIntegralInRange(0, 8) == 0 ? in.ConsumeIntegralInRange(0, 5)
                                                                 : vertexCount;
    const double colorScale = type == CV_8UC3 ? 255.0 : 1.0;
    std::vector<cv::Vec3d> colors(colorCount);
    for (cv::Vec3d& c : colors)
        for (int k = 0; k < 3; k++)
            c[k] = in.ConsumeIntegralInRange(0, 20) == 0 ? pickCoordinate(in, 1)
                                                         : in.ConsumeProbability<double>() * colorScale;
    std::vector<cv::Vec3i> faces(function >= 2 ? in.ConsumeIntegralInRange(0, 32) : 0);
    for (cv::Vec3i& f : faces)
        for (int k = 0; k < 3; k++)
            f[k] = in.ConsumeIntegralInRange(0, 40) == 0 ? in.ConsumeIntegral<int>()
                                                         : in.ConsumeIntegralInRange(0, std::max(0, vertexCount - 1));
    std::vector<double> depth;
    if (in.ConsumeIntegralInRange(0, 4) != 0)
        depth.resize(in.ConsumeIntegralInRange(0, 10) == 0 ? in.ConsumeIntegralInRange(0, 30) : vertexCount);
    for (double& d : depth)
        d = in.ConsumeIntegralInRange(0, 10) == 0 ? pickCoordinate(in, 4) : in.ConsumeIntegralInRange(0, 6);
    const int shadeType = in.ConsumeIntegralInRange(0, 30) == 0 ? in.ConsumeIntegral<int>()
                                                                : in.ConsumeIntegralInRange(0, 1);
    const cv::Size renderSize(in.ConsumeIntegralInRange(-2, 40), in.ConsumeIntegralInRange(-2, 40));

    // drawMesh3d's own arguments: z from the vertex list's x values shifted forward, a camera
    // that is usually valid, settings that sometimes are not.
    std::vector<cv::Vec3d> verts3d;
    cv::Matx33d K(20, 0, width / 2.0, 0, 20, height / 2.0, 0, 0, 1);
    cv::Vec3d rvec(0, 0, 0), tvec(0, 0, 0);
    cv::shading::RenderSettings settings;
    cv::Mat normals, depthBuffer, faceIds;
    const bool in3d = function == 4 || function == 9;
    if (in3d) {
        for (const cv::Point2d& p : verts)
            verts3d.emplace_back(p.x - width / 2.0, p.y - height / 2.0,
                                 in.ConsumeBool() ? in.ConsumeIntegralInRange(-5, 40) * 0.5
                                                  : pickCoordinate(in, 8));
        if (in.ConsumeIntegralInRange(0, 10) == 0)
            K(in.ConsumeIntegralInRange(0, 2), in.ConsumeIntegralInRange(0, 2)) = pickCoordinate(in, 50);
        for (int k = 0; k < 3; k++) {
            rvec[k] = in.ConsumeIntegralInRange(0, 3) == 0 ? pickCoordinate(in, 1) * 0.01 : 0;
            tvec[k] = in.ConsumeIntegralInRange(0, 3) == 0 ? pickCoordinate(in, 4) : 0;
        }
        settings.shadeType = in.ConsumeIntegralInRange(0, 40) == 0 ? in.ConsumeIntegral<int>()
                                                                   : in.ConsumeIntegralInRange(0, 2);
        settings.visibility = in.ConsumeIntegralInRange(0, 40) == 0 ? 2 : in.ConsumeIntegralInRange(0, 1);
        settings.cullMode = in.ConsumeIntegralInRange(0, 40) == 0 ? 3 : in.ConsumeIntegralInRange(0, 2);
        settings.zNear = in.ConsumeIntegralInRange(0, 20) == 0 ? pickCoordinate(in, 1)
                                                               : in.ConsumeIntegralInRange(1, 8) * 0.25;
        settings.ks = in.ConsumeIntegralInRange(0, 40) == 0 ? pickCoordinate(in, 1) : 0.5;
        settings.shininess = in.ConsumeIntegralInRange(0, 40) == 0 ? pickCoordinate(in, 64)
                                                                   : in.ConsumeIntegralInRange(0, 64) * 0.5;
        const int lights = in.ConsumeIntegralInRange(0, 3);
        for (int i = 0; i < lights; i++)
            settings.lights.emplace_back(
                cv::Point3d(pickCoordinate(in, 20), pickCoordinate(in, 20), pickCoordinate(in, 20)),
                cv::Vec3d(in.ConsumeProbability<double>(), in.ConsumeProbability<double>(), 1));
        if (in.ConsumeIntegralInRange(0, 3) == 0) {  // a cleared frame, rarely a bad background
            settings.clear = true;
            settings.background = cv::Scalar(in.ConsumeProbability<double>() * 255,
                                             in.ConsumeIntegralInRange(0, 20) == 0
                                                 ? pickCoordinate(in, 1000)
                                                 : in.ConsumeProbability<double>(),
                                             1);
        }
        if (in.ConsumeBool()) {
            normals.create(in.ConsumeIntegralInRange(0, 10) == 0 ? 2 : int(verts3d.size()), 3, CV_64F);
            for (int i = 0; i < int(normals.total()); i++)
                normals.at<double>(i) = in.ConsumeIntegralInRange(0, 30) == 0 ? pickCoordinate(in, 1)
                                                                              : in.ConsumeProbability<double>() - 0.5;
        }
        if (in.ConsumeBool()) {
            const bool wrong = in.ConsumeIntegralInRange(0, 10) == 0;
            depthBuffer = cv::Mat(height + (wrong ? 1 : 0), width, CV_32FC1);
            if (!depthBuffer.empty())
                cv::randu(depthBuffer, 0, 20);
        }
    }
    const cv::Mat depthBefore = depthBuffer.clone();

    // texturedTriangles: the vertex list doubles as texture coordinates (in and around a small
    // texture: every border), shadeType as the interpolation, a border mode that may be bad.
    cv::Mat texture;
    int borderMode = cv::BORDER_REPLICATE;
    if (function == 6 || function == 9) {
        texture.create(in.ConsumeIntegralInRange(0, 6), in.ConsumeIntegralInRange(0, 6),
                       in.ConsumeBool() ? CV_8UC3 : CV_32FC3);
        if (!texture.empty())
            cv::randu(texture, cv::Scalar::all(0),
                      cv::Scalar::all(texture.depth() == CV_8U ? 255 : 1));
        borderMode = in.ConsumeIntegralInRange(0, 5);
        settings.textureInterpolation = shadeType;
        settings.textureBorder = borderMode;
    }

    // Polygons: the vertex list cut into up to three contours; shadeType as the fill rule.
    std::vector<std::vector<cv::Point2d>> contours;
    if (function >= 7) {
        const int cuts = in.ConsumeIntegralInRange(0, 2);
        size_t begin = 0;
        for (int c = 0; c <= cuts && begin <= verts.size(); c++) {
            const size_t end = c == cuts ? verts.size()
                                         : std::min(verts.size(), begin + in.ConsumeIntegralInRange<size_t>(0, 12));
            contours.emplace_back(verts.begin() + begin, verts.begin() + end);
            begin = end;
        }
    }
    const cv::Scalar polygonColor = colors.empty() ? cv::Scalar(0.5, 0.25, 0.75)
                                                   : cv::Scalar(colors[0][0], colors[0][1], colors[0][2]);
    cv::Mat triangles;

    const auto start = std::chrono::steady_clock::now();
    bool threw = false;
    cv::Mat rendered;
    try {
        switch (function) {
        case 0: cv::shading::flats(canvas, verts, colors); break;
        case 1: cv::shading::gouraud(canvas, verts, colors); break;
        case 2: cv::shading::drawMesh(canvas, verts, faces, colors, depth, shadeType); break;
        case 4:
            cv::shading::drawMesh3d(canvas, verts3d, faces, colors, K, rvec, tvec, settings,
                                    normals, depthBuffer, faceIds);
            break;
        case 5: cv::shading::lines(canvas, verts, colors, shadeType); break;
        case 7: cv::shading::fillPolygons(canvas, contours, polygonColor, shadeType); break;
        case 8: {
            cv::Mat vertices;
            const uint64_t fallbacksBefore = cv::shading::detail::snapRoundingFallbacks();
            cv::shading::triangulatePolygons(contours, triangles, shadeType, vertices);
            // Indices into the vertices: the contours' points, concatenated, then crossings.
            if (vertices.rows < int(verts.size()) || vertices.cols != 2)
                fail("triangulatePolygons returned fewer vertices than points");
            for (int i = 0; i < int(triangles.total() * triangles.channels()); i++)
                if (triangles.ptr<int>()[i] < 0 || triangles.ptr<int>()[i] >= vertices.rows)
                    fail("triangulatePolygons produced an index outside the vertices");
            // Drawn on a canvas of this size, the triangles cover each sample at most once.
            cv::Mat count(std::max(height, 1), std::max(width, 1), CV_32FC3, cv::Scalar::all(0));
            for (int f = 0; f < triangles.rows; f++) {
                std::vector<cv::Point2d> tri;
                for (int k = 0; k < 3; k++) {
                    const int v = triangles.ptr<int>(f)[k];
                    tri.push_back({vertices.at<double>(v, 0), vertices.at<double>(v, 1)});
                }
                cv::Mat one(count.size(), CV_32FC3, cv::Scalar::all(0));
                cv::shading::flats(one, tri, std::vector<cv::Vec3f>(3, cv::Vec3f(1, 1, 1)));
                count += one;
            }
            double most = 0;
            cv::minMaxLoc(count.reshape(1), nullptr, &most);
            if (most > 1)
                fail("triangulatePolygons covered a sample twice");
            // Unless it fell back to snap rounding (counted), exactly fillPolygons' samples.
            if (cv::shading::detail::snapRoundingFallbacks() == fallbacksBefore) {
                cv::Mat filled(count.size(), CV_8UC3, cv::Scalar::all(0));
                cv::shading::fillPolygons(filled, contours, cv::Scalar::all(255), shadeType);
                cv::Mat a, b;
                cv::extractChannel(count, a, 0);
                cv::extractChannel(filled, b, 0);
                if (cv::countNonZero((a > 0) != (b > 0)) != 0)
                    fail("triangulatePolygons' coverage differs from fillPolygons'");
            }
            break;
        }
        case 6:
            cv::shading::texturedTriangles(canvas, verts, faces, verts, texture, shadeType,
                                           borderMode);
            break;
        case 9:
            cv::shading::drawTexturedMesh3d(canvas, verts3d, faces, verts, texture, K, rvec, tvec,
                                            settings, normals, depthBuffer, faceIds);
            break;
        case 10: {
            // The first three points with depths (possibly bad); every visited sample must lie
            // on the canvas with finite weights summing to 1.
            const std::vector<cv::Point2d> tri(verts.begin(), verts.begin() + std::min<size_t>(3, verts.size()));
            cv::shading::forEachSample(canvas.size(), tri, depth, [&](int x, int y, const cv::Vec3d& w) {
                if (x < 0 || y < 0 || x >= width || y >= height)
                    fail("forEachSample visited a sample outside the canvas");
                if (!(std::abs(w[0] + w[1] + w[2] - 1) < 1e-6))
                    fail("forEachSample's perspective weights do not sum to 1");
            });
            break;
        }
        default:
            cv::shading::render(verts, faces, colors, depth, rendered, shadeType, renderSize);
            if (rendered.size() != renderSize || rendered.type() != CV_32FC3)
                fail("render produced the wrong size or type");
        }
    } catch (const cv::Exception&) {
        threw = true;
    }
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (seconds > kMaxSeconds)
        fail("a call took too long");

    cv::Mat diff;
    cv::compare(whole.reshape(1), wholeBefore.reshape(1), diff, cv::CMP_NE);
    if (threw) {
        if (cv::countNonZero(diff) != 0)
            fail("a rejected call changed the image");
        if (!rendered.empty())
            fail("a rejected render produced an image");
        if (!depthBefore.empty() && cv::norm(depthBuffer, depthBefore, cv::NORM_INF) != 0)
            fail("a rejected drawMesh3d changed the depth buffer");
        if (!faceIds.empty())
            fail("a rejected drawMesh3d produced face ids");
        return 0;
    }
    if (in3d && !faceIds.empty()) {
        // Every pixel a face coloured has a depth at or beyond the near plane (in float).
        for (int y = 0; y < faceIds.rows; y++)
            for (int x = 0; x < faceIds.cols; x++)
                if (faceIds.at<int>(y, x) >= 0 && !depthBuffer.empty() &&
                    !(depthBuffer.at<float>(y, x) >= float(settings.zNear) * (1 - 1e-5f)))
                    fail("a drawn sample lies in front of the near plane");
    }
    const cv::Mat inner = diff(cv::Rect(kGuard * whole.channels(), kGuard, width * whole.channels(), height));
    if (cv::countNonZero(diff) != cv::countNonZero(inner))
        fail("a pixel outside the canvas changed");
    if (function < 2 && verts.size() == 3 && colors.size() == 3 && moderate(verts))
        compareWithReference(canvas, wholeBefore(cv::Rect(kGuard, kGuard, width, height)), verts,
                             colors, function == 1);
    return 0;
}
