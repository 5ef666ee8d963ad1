// This file is part of opencv_shading. License: Apache-2.0.
//
// cv::shading::drawTexturedMesh3d and the perspective-correct forEachSample / forEachSpan
// (the overloads taking depths) against the brute-force reference
// test/reference/texture3d_reference.hpp, written from the documented conventions only.
//
// What is compared:
//  - forEachSample with depths: the samples of the 2D forEachSample, in its order; weights
//    summing to 1 (1e-12), between the unsnapped and snapped readings of the ray/plane
//    definition (1e-9), and equal to the snapped one, which interpolate.hpp documents (1e-9).
//    forEachSpan with depths: the same samples; h_i / sum(h) stepped along the span equals
//    forEachSample's weights (1e-9), 1 / sum(h) the ray depth.
//  - drawTexturedMesh3d: faceIds and the depth buffer exactly drawMesh3d's for the same scene
//    (same coverage, same visibility); untouched pixels bit-exact; at every drawn pixel the
//    colour within the reference's range: the texture coordinate's readings (unsnapped ray,
//    every snapped triangle of a clipped polygon) widened by their own width and 1e-6
//    (relative), every quantized texel position that interval reaches evaluated as remap does,
//    lit by the range of the D, S readings; plus 1e-5 on float canvases, 0 on 8-bit unlit ones
//    (remap's output is exact), 1 level on 8-bit lit ones. A pixel whose interval reaches more
//    than 3 quantized positions per axis (heavy minification) is not checked (counted).
//    The same comparison with the snapped readings only (the letter of mesh3d.hpp: 1/Zc affine
//    over the snapped triangle) is also asserted.
//  - The tolerances have teeth: MutantsAreCaught runs the comparison against deliberately wrong
//    references (affine uv, u/v swapped, half a texel off, a neighbouring border mode, the texel
//    scaling the highlight) and requires each to be flagged at many pixels. (Each was also planted by hand in the
//    reference while writing this, with the same outcome.)

#include <gtest/gtest.h>

#include <opencv2/core.hpp>
#include <opencv2/core/utility.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/shading.hpp>

#include "reference/texture3d_reference.hpp"
#include "test_common.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

namespace {

namespace sh = cv::shading;
namespace rt = shading_reftex3d;
using cv::Mat;
using cv::Point2d;
using cv::Size;
using cv::Vec2d;
using cv::Vec3d;

const double kColorTolF = 1e-5;  // float canvas, beyond the reference's range
const double kColorTol8Lit = 1;  // 8-bit lit: the result rounded after another order of work
const double kWeightTol = 1e-9;
const float kInf = std::numeric_limits<float>::infinity();

// ---------------------------------------------------------------------------------------------
// forEachSample / forEachSpan with depths

struct Visit {
    int x, y;
    Vec3d w;
};

std::vector<Visit> samples2d(Size size, const std::vector<Point2d>& v)
{
    std::vector<Visit> out;
    sh::forEachSample(size, v, [&](int x, int y, const Vec3d& w) { out.push_back({ x, y, w }); });
    return out;
}

std::vector<Visit> samples3d(Size size, const std::vector<Point2d>& v,
                             const std::vector<double>& z)
{
    std::vector<Visit> out;
    sh::forEachSample(size, v, z, [&](int x, int y, const Vec3d& w) {
        out.push_back({ x, y, w });
    });
    return out;
}

// Per sample of forEachSpan with depths: (x, y), q = h / sum(h), depth 1 / sum(h).
struct SpanVisit {
    int x, y;
    Vec3d q;
    double depth;
};

std::vector<SpanVisit> spans3d(Size size, const std::vector<Point2d>& v,
                               const std::vector<double>& z)
{
    std::vector<SpanVisit> out;
    sh::forEachSpan(size, v, z, [&](int y, int xBegin, int xEnd, const Vec3d& h0,
                                    const Vec3d& dhdx) {
        for (int x = xBegin; x < xEnd; x++) {
            const Vec3d h = h0 + dhdx * double(x - xBegin);
            const double sum = h[0] + h[1] + h[2];
            out.push_back({ x, y, h * (1.0 / sum), 1.0 / sum });
        }
    });
    return out;
}

TEST(Texture3dReference, ForEachSampleWithDepthsRandomTriangles)
{
    cv::RNG rng(0x7e3d1);
    const Size size(64, 48);
    long visited = 0;
    double worstRange = 0, worstSnapped = 0, worstSpan = 0, worstSpanDepth = 0, worstSum = 0;
    double widest = 0;
    for (int i = 0; i < 400; i++) {
        std::vector<Point2d> v(3);
        for (Point2d& p : v)
            p = Point2d(rng.uniform(-20.0, 84.0), rng.uniform(-20.0, 68.0));
        if (i % 5 == 0)  // small triangles, where the snap matters most
            for (int k = 1; k < 3; k++)
                v[k] = v[0] + Point2d(rng.uniform(-4.0, 4.0), rng.uniform(-4.0, 4.0));
        std::vector<double> z(3);
        for (double& d : z)
            d = std::exp(rng.uniform(std::log(0.5), std::log(50.0)));
        const std::vector<Visit> a = samples2d(size, v), b = samples3d(size, v, z);
        const std::vector<SpanVisit> s = spans3d(size, v, z);
        ASSERT_EQ(a.size(), b.size()) << "triangle " << i;
        ASSERT_EQ(a.size(), s.size()) << "triangle " << i;
        const Point2d tri[3] = { v[0], v[1], v[2] };
        for (size_t k = 0; k < a.size(); k++) {
            ASSERT_EQ(a[k].x, b[k].x);
            ASSERT_EQ(a[k].y, b[k].y);
            ASSERT_EQ(a[k].x, s[k].x);
            ASSERT_EQ(a[k].y, s[k].y);
            visited++;
            const Vec3d& q = b[k].w;
            worstSum = std::max(worstSum, std::abs(q[0] + q[1] + q[2] - 1));
            const rt::WeightRange r = rt::depthWeightRange(tri, z.data(), b[k].x, b[k].y);
            ASSERT_TRUE(r.ok);
            for (int j = 0; j < 3; j++) {
                EXPECT_GE(q[j], -1e-12) << "triangle " << i;
                widest = std::max(widest, r.hi[j] - r.lo[j]);
                worstRange = std::max(worstRange, std::max(r.lo[j] - q[j], q[j] - r.hi[j]));
                worstSnapped = std::max(worstSnapped, std::abs(q[j] - r.qSnapped[j]));
                worstSpan = std::max(worstSpan, std::abs(s[k].q[j] - q[j]));
            }
            worstSpanDepth =
                std::max(worstSpanDepth, std::abs(s[k].depth - r.depthSnapped) / r.depthSnapped);
            EXPECT_GE(s[k].depth, r.depthLo * (1 - kWeightTol));
            EXPECT_LE(s[k].depth, r.depthHi * (1 + kWeightTol));
        }
    }
    EXPECT_GT(visited, 100000);
    EXPECT_LE(worstSum, 1e-12);
    EXPECT_LE(worstRange, kWeightTol);    // within [unsnapped, snapped]
    EXPECT_LE(worstSnapped, kWeightTol);  // and, as documented, the snapped reading
    EXPECT_LE(worstSpan, kWeightTol);
    EXPECT_LE(worstSpanDepth, kWeightTol);
    std::printf("[ info ] %ld samples: weights beyond the [unsnapped, snapped] range %.2g, off "
                "the snapped reading %.2g (range up to %.2g wide), sum off 1 by %.2g; spans off "
                "by %.2g, depth %.2g (relative)\n",
                visited, std::max(0.0, worstRange), worstSnapped, widest, worstSum, worstSpan,
                worstSpanDepth);
}

// The right triangle (0, 0), (8, 0), (0, 8) with depths 1, 2, 2, sample (2, 2): screen weights
// (1/2, 1/4, 1/4), h = w / z = (1/2, 1/8, 1/8), sum 3/4, so q = (2/3, 1/6, 1/6) and depth 4/3
// (the 3D point 2/3 (0, 0, 1) + 1/6 (16, 0, 2) + 1/6 (0, 16, 2) = (8/3, 8/3, 4/3) lies on the
// ray through (2, 2)). Affine weights would give (1/2, 1/4, 1/4) and depth 1.5.
TEST(Texture3dReference, ForEachSampleWithDepthsHandWorked)
{
    const std::vector<Point2d> v = { { 0, 0 }, { 8, 0 }, { 0, 8 } };
    const std::vector<double> z = { 1, 2, 2 };
    int seen = 0;
    for (const Visit& s : samples3d(Size(16, 16), v, z))
        if (s.x == 2 && s.y == 2) {
            seen++;
            EXPECT_NEAR(s.w[0], 2.0 / 3, 1e-15);
            EXPECT_NEAR(s.w[1], 1.0 / 6, 1e-15);
            EXPECT_NEAR(s.w[2], 1.0 / 6, 1e-15);
        }
    EXPECT_EQ(1, seen);
    seen = 0;
    for (const SpanVisit& s : spans3d(Size(16, 16), v, z))
        if (s.x == 2 && s.y == 2) {
            seen++;
            EXPECT_NEAR(s.q[0], 2.0 / 3, 1e-15);
            EXPECT_NEAR(s.depth, 4.0 / 3, 1e-15);
        }
    EXPECT_EQ(1, seen);
    // Equal depths: the perspective weights are the screen weights.
    const std::vector<Visit> flat = samples2d(Size(16, 16), v),
                             same = samples3d(Size(16, 16), v, { 3, 3, 3 });
    ASSERT_EQ(flat.size(), same.size());
    for (size_t k = 0; k < flat.size(); k++)
        EXPECT_LE(cv::norm(flat[k].w - same[k].w, cv::NORM_INF), 1e-15);
}

TEST(Texture3dReference, ForEachSampleWithBadDepthsThrows)
{
    const std::vector<Point2d> v = { { 0, 0 }, { 8, 0 }, { 0, 8 } };
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const double inf = std::numeric_limits<double>::infinity();
    int calls = 0;
    auto sampleFn = [&](int, int, const Vec3d&) { calls++; };
    auto spanFn = [&](int, int, int, const Vec3d&, const Vec3d&) { calls++; };
    const std::vector<std::vector<double>> bad = {
        { 0, 1, 1 }, { 1, -2, 1 }, { 1, 1, nan }, { inf, 1, 1 }, { 1, 1 }, { 1, 1, 1, 1 }, {}
    };
    for (const std::vector<double>& z : bad) {
        std::ostringstream s;
        for (double d : z)
            s << d << " ";
        EXPECT_THROW(sh::forEachSample(Size(16, 16), v, z, sampleFn), cv::Exception) << s.str();
        EXPECT_THROW(sh::forEachSpan(Size(16, 16), v, z, spanFn), cv::Exception) << s.str();
    }
    EXPECT_EQ(0, calls);
}

// ---------------------------------------------------------------------------------------------
// drawTexturedMesh3d: calling the library

sh::RenderSettings toLib(const rt::TexScene& sc)
{
    const rt::Settings& s = sc.settings;
    sh::RenderSettings r;
    r.shadeType = s.shadeType;
    r.visibility = s.visibility;
    r.cullMode = s.cullMode;
    r.zNear = s.zNear;
    for (const rt::Light& l : s.lights)
        r.lights.push_back(sh::PointLight(cv::Point3d(l.position), l.intensity));
    r.ambient = s.ambient;
    r.ka = s.ka;
    r.kd = s.kd;
    r.ks = s.ks;
    r.shininess = s.shininess;
    r.textureInterpolation = sc.interpolation;
    r.textureBorder = sc.border;
    return r;
}

Mat cameraMatrix(const rt::Camera& cam)
{
    return Mat(cv::Matx33d(cam.fx, cam.s, cam.cx, 0, cam.fy, cam.cy, 0, 0, 1));
}

struct LibOut {
    Mat canvas, depth, faceIds;
};

std::vector<Point2d> texCoords(const rt::TexScene& sc)
{
    std::vector<Point2d> uv;
    for (const Vec2d& t : sc.uv)
        uv.emplace_back(t[0], t[1]);
    return uv;
}

LibOut drawTextured(const rt::TexScene& sc, const Mat& canvas, const Mat& depthIn)
{
    LibOut o;
    o.canvas = canvas.clone();
    o.depth = depthIn.empty() ? Mat() : depthIn.clone();
    sh::drawTexturedMesh3d(o.canvas, sc.verts, sc.faces, texCoords(sc), sc.texture,
                           cameraMatrix(sc.cam), Mat(sc.cam.R), Mat(sc.cam.t), toLib(sc),
                           sc.normals, o.depth, o.faceIds);
    return o;
}

// drawMesh3d of the same scene with the given vertex colours; faces listed in `skip` get a NaN
// vertex (drawTexturedMesh3d skips them for their texture coordinates).
LibOut drawPlain(const rt::TexScene& sc, const std::vector<Vec3d>& colors, const Mat& canvas,
                 const Mat& depthIn, const std::vector<int>& skip = {})
{
    std::vector<Vec3d> verts = sc.verts;
    for (int f : skip)
        verts[sc.faces[f][0]][0] = std::numeric_limits<double>::quiet_NaN();
    LibOut o;
    o.canvas = canvas.clone();
    o.depth = depthIn.empty() ? Mat() : depthIn.clone();
    sh::drawMesh3d(o.canvas, verts, sc.faces, colors, cameraMatrix(sc.cam), Mat(sc.cam.R),
                   Mat(sc.cam.t), toLib(sc), sc.normals, o.depth, o.faceIds);
    return o;
}

// ---------------------------------------------------------------------------------------------
// Comparison

struct Stats {
    long pixels = 0, drawn = 0, checked = 0, unambiguous = 0, multi = 0, wide = 0, unstable = 0;
    long strictChecked = 0, strictBad = 0;
    double maxErrF = 0, maxErr8 = 0;
    std::string firstStrict;
};

struct Report {
    long bad = 0;
    std::vector<std::string> messages;
    void fail(const std::string& m)
    {
        if (bad++ < 3)
            messages.push_back(m);
    }
};

std::string describe(const rt::TexScene& sc, const Mat& canvas)
{
    std::ostringstream s;
    s.precision(17);
    const rt::Settings& st = sc.settings;
    s << "canvas " << canvas.size() << (canvas.type() == CV_8UC3 ? " 8UC3" : " 32FC3")
      << ", texture " << sc.texture.size() << (sc.texture.depth() == CV_8U ? " 8U" : " 32F")
      << ", interpolation " << sc.interpolation << ", border " << sc.border << ", "
      << sc.faces.size() << " faces, shade " << st.shadeType << ", visibility " << st.visibility
      << ", cull " << st.cullMode << ", zNear " << st.zNear << ", " << st.lights.size()
      << " lights, normals " << (sc.normals.empty() ? "computed" : "given");
    return s.str();
}

Vec3d pixel(const Mat& m, int x, int y)
{
    if (m.type() == CV_8UC3) {
        const cv::Vec3b& p = m.at<cv::Vec3b>(y, x);
        return Vec3d(p[0], p[1], p[2]);
    }
    const cv::Vec3f& p = m.at<cv::Vec3f>(y, x);
    return Vec3d(p[0], p[1], p[2]);
}

// How far v is outside [lo - tol, hi + tol] (0 inside), worst channel.
double excess(const Vec3d& v, const rt::Expected& ex, double tol)
{
    double e = 0;
    for (int k = 0; k < 3; k++)
        e = std::max(e, std::max(ex.lo[k] - tol - v[k], v[k] - ex.hi[k] - tol));
    return e;
}

// Compares a library run with the reference (and with drawMesh3d's run `plain` for faceIds and
// depth). Failures go to `rep`, not to GoogleTest, so a mutant's can be counted.
void compare(const rt::TexScene& sc, const Mat& canvasIn, const LibOut& lib, const LibOut& plain,
             Stats& st, Report& rep, const std::string& what,
             rt::Mutant mutant = rt::NO_MUTANT)
{
    const Size size = canvasIn.size();
    const bool eight = canvasIn.type() == CV_8UC3;
    const bool lit = !sc.settings.lights.empty();
    auto fail = [&](int x, int y, const std::string& m) {
        rep.fail(what + "\n  " + describe(sc, canvasIn) + cv::format("\n  pixel (%d, %d): ", x, y) +
                 m);
    };
    if (lib.canvas.size() != size || lib.canvas.type() != canvasIn.type() ||
        lib.faceIds.size() != size || lib.faceIds.type() != CV_32SC1 ||
        lib.depth.size() != size || lib.depth.type() != CV_32FC1) {
        rep.fail(what + ": outputs of the wrong size or type");
        return;
    }
    const rt::TexFragments all = rt::fragments(sc, size, mutant, rt::ALL_READINGS);
    const rt::TexFragments snapped = rt::fragments(sc, size, mutant, rt::SNAPPED_ONLY);
    const Mat tex = rt::textureForCanvas(sc.texture, canvasIn.type());
    const double tol = eight ? (lit ? kColorTol8Lit : 0.0) : kColorTolF;
    for (int y = 0; y < size.height; y++)
        for (int x = 0; x < size.width; x++) {
            st.pixels++;
            const int id = lib.faceIds.at<int>(y, x);
            if (id != plain.faceIds.at<int>(y, x)) {
                fail(x, y, cv::format("faceId %d, drawMesh3d's %d", id,
                                      plain.faceIds.at<int>(y, x)));
                continue;
            }
            const float d = lib.depth.at<float>(y, x), dp = plain.depth.at<float>(y, x);
            if (std::memcmp(&d, &dp, sizeof d) != 0) {
                fail(x, y, cv::format("depth %.9g, drawMesh3d's %.9g", d, dp));
                continue;
            }
            if (id < 0) {
                if (std::memcmp(lib.canvas.ptr(y, x), canvasIn.ptr(y, x), canvasIn.elemSize()))
                    fail(x, y, "canvas changed where faceIds is -1");
                continue;
            }
            st.drawn++;
            const rt::TexFragment* fr = all.find(x, y, id);
            if (!fr) {
                fail(x, y, cv::format("face %d has no sample here in the reference", id));
                continue;
            }
            if (!fr->valid || !fr->stable) {
                st.unstable++;
                continue;
            }
            const rt::Expected ex = rt::expectedColor(*fr, tex, canvasIn.type(), sc, mutant);
            if (ex.wide) {
                st.wide++;
                continue;
            }
            st.checked++;
            (ex.positions == 1 ? st.unambiguous : st.multi)++;
            const Vec3d got = pixel(lib.canvas, x, y);
            double e = excess(got, ex, 0);
            double& maxErr = eight ? st.maxErr8 : st.maxErrF;
            maxErr = std::max(maxErr, e);
            if (e > tol) {
                std::ostringstream m;
                m.precision(9);
                m << "face " << id << " colour " << got << ", reference " << ex.lo << " .. "
                  << ex.hi << " (texel " << ex.tLo << " .. " << ex.tHi << ", " << ex.positions
                  << " positions); uv " << fr->uv << ", readings " << fr->uvLo << " .. "
                  << fr->uvHi << " (" << fr->readings << "), clipped to " << fr->clippedTo;
                if (lit)
                    m << "; D " << fr->Dlo << " .. " << fr->Dhi << ", S " << fr->Slo << " .. "
                      << fr->Shi;
                fail(x, y, m.str());
                continue;
            }
            // The letter of the spec: the snapped readings only.
            const rt::TexFragment* fs = snapped.find(x, y, id);
            const rt::Expected es = rt::expectedColor(*fs, tex, canvasIn.type(), sc, mutant);
            if (!es.wide) {
                st.strictChecked++;
                if (excess(got, es, tol) > 0 && st.strictBad++ == 0) {
                    std::ostringstream m;
                    m.precision(9);
                    m << what << " pixel (" << x << ", " << y << ") face " << id << " colour "
                      << got << ", snapped-only reference " << es.lo << " .. " << es.hi
                      << "; uv " << fs->uvLo << " .. " << fs->uvHi;
                    st.firstStrict = m.str();
                }
            }
        }
}

// ---------------------------------------------------------------------------------------------
// Random scenes

struct Case {
    rt::TexScene scene;
    Mat canvas, depthIn;
    std::vector<int> skipped;  // faces with unusable texture coordinates
};

const int kBorders[5] = { cv::BORDER_CONSTANT, cv::BORDER_REPLICATE, cv::BORDER_REFLECT,
                          cv::BORDER_WRAP, cv::BORDER_REFLECT_101 };

// Scene i of a suite: the canvas type, interpolation, border and shading cycle with i, the rest
// is random.
Case randomCase(cv::RNG& rng, int i)
{
    Case c;
    const Size size(64, 48);
    const int shading = (i / 20) % 4;  // unlit, FLAT, GOURAUD, PHONG
    c.scene = rt::randomTexScene(rng, size, shading == 0 ? 0 : rng.uniform(1, 4));
    rt::TexScene& sc = c.scene;
    sc.settings.shadeType = shading == 0 ? rng.uniform(0, 3) : shading - 1;
    sc.settings.visibility = rng.uniform(0, 2);
    sc.settings.cullMode = rng.uniform(0, 4) == 0 ? rng.uniform(1, 3) : 0;
    sc.interpolation = (i / 2) % 2 ? cv::INTER_LINEAR : cv::INTER_NEAREST;
    sc.border = kBorders[(i / 4) % 5];
    const int type = i % 2 ? CV_8UC3 : CV_32FC3;
    if (i % 7 == 3) {  // a face the textured draw must skip (NaN or > 1e30 texture coordinate)
        const int L = (int)sc.verts.size();
        for (int k = 0; k < 3; k++) {
            sc.verts.push_back(Vec3d(rng.uniform(-1.0, 1.0), rng.uniform(-1.0, 1.0),
                                     rng.uniform(-1.0, 1.0)));
            sc.uv.push_back(Vec2d(rng.uniform(0.0, 5.0), rng.uniform(0.0, 5.0)));
            if (!sc.normals.empty())
                sc.normals.push_back(rt::randomUnitVector(rng));
        }
        sc.uv[L + rng.uniform(0, 3)][rng.uniform(0, 2)] =
            rng.uniform(0, 2) ? std::numeric_limits<double>::quiet_NaN() : 2e30;
        const int at = rng.uniform(0, (int)sc.faces.size() + 1);
        sc.faces.insert(sc.faces.begin() + at, cv::Vec3i(L, L + 1, L + 2));
        c.skipped.push_back(at);
    }
    c.canvas.create(size, type);
    if (type == CV_8UC3)
        rng.fill(c.canvas, cv::RNG::UNIFORM, 0, 256);
    else
        rng.fill(c.canvas, cv::RNG::UNIFORM, -1.0, 2.0);
    if (rng.uniform(0, 3) == 0) {
        c.depthIn.create(size, CV_32FC1);
        for (int y = 0; y < size.height; y++)
            for (int x = 0; x < size.width; x++)
                c.depthIn.at<float>(y, x) =
                    rng.uniform(0, 3) == 0 ? kInf : (float)rng.uniform(0.5, 6.0);
    }
    return c;
}

std::vector<Vec3d> randomColors(cv::RNG& rng, size_t n, int type)
{
    const double unit = type == CV_8UC3 ? 255 : 1;
    std::vector<Vec3d> c;
    for (size_t i = 0; i < n; i++)
        c.push_back(Vec3d(rng.uniform(0.0, unit), rng.uniform(0.0, unit), rng.uniform(0.0, unit)));
    return c;
}

void printStats(const char* name, const Stats& st)
{
    std::printf("[ stats ] %s: %ld pixels, %ld drawn: %ld colours checked (%ld unambiguous, %ld "
                "near a rounding step), %ld skipped (uv interval too wide), %ld near a lighting "
                "step; beyond the range %.2g (float), %.2g (8-bit); snapped-only: %ld of %ld "
                "outside\n",
                name, st.pixels, st.drawn, st.checked, st.unambiguous, st.multi, st.wide,
                st.unstable, st.maxErrF, st.maxErr8, st.strictBad, st.strictChecked);
}

TEST(Texture3dReference, RandomScenes)
{
    cv::RNG rng(0x7e3d2);
    Stats st;
    Report rep;
    int clippedScenes = 0;
    const int count = 160;
    for (int i = 0; i < count; i++) {
        const Case c = randomCase(rng, i);
        const rt::TexScene& sc = c.scene;
        const std::string what = cv::format("scene %d", i);
        const LibOut lib = drawTextured(sc, c.canvas, c.depthIn);
        const LibOut plain = drawPlain(sc, randomColors(rng, sc.verts.size(), c.canvas.type()),
                                       c.canvas, c.depthIn, c.skipped);
        compare(sc, c.canvas, lib, plain, st, rep, what);
        for (const rt::Vec3d& v : sc.verts)
            if (!(sc.cam.toCamera(v)[2] >= sc.settings.zNear)) {
                clippedScenes++;
                break;
            }
        if (i % 5 == 0) {  // without the optional outputs the picture is the same
            Mat canvas = c.canvas.clone();
            sh::drawTexturedMesh3d(canvas, sc.verts, sc.faces, texCoords(sc), sc.texture,
                                   cameraMatrix(sc.cam), Mat(sc.cam.R), Mat(sc.cam.t), toLib(sc),
                                   sc.normals);
            if (c.depthIn.empty()) {
                EXPECT_EQ(0, cv::norm(canvas, lib.canvas, cv::NORM_INF)) << what;
            }
        }
    }
    for (const std::string& m : rep.messages)
        ADD_FAILURE() << m;
    EXPECT_EQ(0, rep.bad);
    // The comparison must have teeth: many pixels drawn and checked, few skipped.
    EXPECT_GT(st.drawn, st.pixels / 8);
    EXPECT_GT(st.checked, st.drawn * 8 / 10);
    EXPECT_GT(st.unambiguous, st.checked * 7 / 10);
    EXPECT_GT(clippedScenes, count / 5);
    EXPECT_EQ(0, st.strictBad) << st.firstStrict;
    printStats("random scenes", st);
    std::printf("[ stats ] %d of %d scenes clipped by the near plane\n", clippedScenes, count);
}

// The comparison catches each planted bug: against a deliberately wrong reference the library
// must fail at many pixels.
TEST(Texture3dReference, MutantsAreCaught)
{
    struct Trial {
        rt::Mutant mutant;
        int first;  // scenes first .. first + 39 of randomCase's cycle (20..: lit)
    };
    for (const Trial& tr : { Trial{ rt::MUTANT_AFFINE_UV, 0 }, Trial{ rt::MUTANT_SWAPPED_UV, 0 },
                             Trial{ rt::MUTANT_HALF_TEXEL, 0 }, Trial{ rt::MUTANT_WRONG_BORDER, 0 },
                             Trial{ rt::MUTANT_TINTED_HIGHLIGHT, 20 } }) {
        cv::RNG rng(0x7e3d3);
        Stats st;
        Report rep;
        for (int i = tr.first; i < tr.first + 40; i++) {
            Case c = randomCase(rng, i);
            if (tr.mutant == rt::MUTANT_WRONG_BORDER)  // coordinates well outside the texture
                for (Vec2d& uv : c.scene.uv)
                    uv = uv * 2.0 - Vec2d(c.scene.texture.cols, c.scene.texture.rows) * 0.5;
            if (tr.mutant == rt::MUTANT_TINTED_HIGHLIGHT) {  // bright highlights
                c.scene.settings.ks = 1;
                c.scene.settings.shininess = 2;
            }
            const LibOut lib = drawTextured(c.scene, c.canvas, c.depthIn);
            const LibOut plain = drawPlain(c.scene, std::vector<Vec3d>(c.scene.verts.size()),
                                           c.canvas, c.depthIn, c.skipped);
            compare(c.scene, c.canvas, lib, plain, st, rep, "mutant", tr.mutant);
        }
        EXPECT_GT(rep.bad, st.checked / 5) << "mutant " << tr.mutant << " not caught";
        std::printf("[ info ] mutant %d: flagged at %ld of %ld checked pixels\n", (int)tr.mutant,
                    rep.bad, st.checked);
    }
}

// ---------------------------------------------------------------------------------------------
// A receding floor: the textbook case where affine texture mapping is visibly wrong

TEST(Texture3dReference, RecedingCheckerboardFloorIsPerspective)
{
    // Camera at the origin looking along +z (R = I, t = 0); the floor is the plane Yc = 0.6
    // (below the eye: y points down) from Zc = 1 to 40, Xc in [-4, 4]. The texture is a 64 x 64
    // checkerboard of 8 px squares spread over the whole floor.
    rt::TexScene sc;
    sc.cam.fx = sc.cam.fy = 50;
    sc.cam.cx = 32;
    sc.cam.cy = 8;
    sc.verts = { Vec3d(-4, 0.6, 1), Vec3d(4, 0.6, 1), Vec3d(4, 0.6, 40), Vec3d(-4, 0.6, 40) };
    sc.uv = { Vec2d(-0.5, 63.5), Vec2d(63.5, 63.5), Vec2d(63.5, -0.5), Vec2d(-0.5, -0.5) };
    sc.faces = { cv::Vec3i(0, 1, 2), cv::Vec3i(0, 2, 3) };
    sc.interpolation = cv::INTER_NEAREST;
    sc.border = cv::BORDER_REPLICATE;
    sc.texture.create(64, 64, CV_8UC3);
    for (int y = 0; y < 64; y++)
        for (int x = 0; x < 64; x++)
            sc.texture.at<cv::Vec3b>(y, x) =
                ((x / 8 + y / 8) % 2) ? cv::Vec3b(230, 230, 230) : cv::Vec3b(20, 40, 60);
    const Size size(64, 48);
    const Mat canvas(size, CV_8UC3, cv::Scalar(255, 0, 255));
    const LibOut lib = drawTextured(sc, canvas, Mat());
    const LibOut plain = drawPlain(sc, std::vector<Vec3d>(4), canvas, Mat());
    Stats st;
    Report rep;
    compare(sc, canvas, lib, plain, st, rep, "floor");
    for (const std::string& m : rep.messages)
        ADD_FAILURE() << m;
    EXPECT_EQ(0, rep.bad);
    EXPECT_GT(st.drawn, 1000);
    // Affine mapping of the same projected triangles (texturedTriangles, the 2D function).
    std::vector<Point2d> proj;
    for (const Vec3d& v : sc.verts)
        proj.push_back(sc.cam.project(v));
    Mat affine = canvas.clone();
    sh::texturedTriangles(affine, proj, sc.faces, texCoords(sc), sc.texture, sc.interpolation,
                          sc.border);
    int covered = 0, differ = 0, coverageDiffers = 0;
    for (int y = 0; y < size.height; y++)
        for (int x = 0; x < size.width; x++) {
            const bool mine = lib.faceIds.at<int>(y, x) >= 0;
            // No checker colour is the magenta background.
            coverageDiffers += mine != (affine.at<cv::Vec3b>(y, x) != canvas.at<cv::Vec3b>(y, x));
            if (mine) {
                covered++;
                differ += lib.canvas.at<cv::Vec3b>(y, x) != affine.at<cv::Vec3b>(y, x);
            }
        }
    // The same coverage (the 2D rule on the projected vertices), different texels at many.
    EXPECT_EQ(0, coverageDiffers);
    EXPECT_GT(differ, covered / 4) << differ << " of " << covered;
    std::printf("[ info ] floor: %d covered pixels, %d differ from the affine mapping; %ld "
                "colours checked\n", covered, differ, st.checked);
}

// ---------------------------------------------------------------------------------------------
// A uniform texture is drawMesh3d with uniform vertex colours

TEST(Texture3dReference, UniformTextureIsDrawMesh3d)
{
    cv::RNG rng(0x7e3d4);
    int compared = 0, gouraudSkipped = 0;
    for (int i = 0; i < 80; i++) {
        Case c = randomCase(rng, i);
        rt::TexScene& sc = c.scene;
        if (sc.border == cv::BORDER_CONSTANT)  // black would mix in at the edges
            sc.border = cv::BORDER_REFLECT_101;
        const int type = c.canvas.type();
        const bool eight = type == CV_8UC3;
        // c in the canvas's units, exactly representable in the texture.
        const Vec3d col = eight ? Vec3d(rng.uniform(0, 256), rng.uniform(0, 256),
                                        rng.uniform(0, 256))
                                : Vec3d(rng.uniform(0, 256) / 256.0, rng.uniform(0, 256) / 256.0,
                                        rng.uniform(0, 256) / 256.0);
        sc.texture = Mat(rng.uniform(1, 9), rng.uniform(1, 9), eight ? CV_8UC3 : CV_32FC3,
                         cv::Scalar(col[0], col[1], col[2]));
        const bool lit = !sc.settings.lights.empty();
        if (lit && sc.settings.shadeType == sh::SHADE_GOURAUD) {
            // drawMesh3d clamps each lit vertex colour, the textured draw only the sample: the
            // same only where no vertex clamps.
            const std::vector<Vec3d> normals =
                sc.normals.empty() ? shading_ref3d::computeNormals(sc.verts, sc.faces)
                                   : sc.normals;
            bool clamps = false;
            for (size_t v = 0; v < sc.verts.size(); v++) {
                Vec3d D, S;
                rt::phongSplit(sc.verts[v], shading_ref3d::normalizeOrZero(normals[v]),
                               sc.cam.eye(), sc.settings, D, S);
                for (int k = 0; k < 3; k++)
                    clamps |= col[k] / (eight ? 255 : 1) * D[k] + S[k] > 1 - 1e-9;
            }
            if (clamps) {
                gouraudSkipped++;
                continue;
            }
        }
        const LibOut lib = drawTextured(sc, c.canvas, c.depthIn);
        const LibOut plain = drawPlain(sc, std::vector<Vec3d>(sc.verts.size(), col), c.canvas,
                                       c.depthIn, c.skipped);
        EXPECT_EQ(0, cv::norm(lib.faceIds, plain.faceIds, cv::NORM_INF)) << "scene " << i;
        EXPECT_EQ(0, std::memcmp(lib.depth.data, plain.depth.data, lib.depth.total() * 4))
            << "scene " << i;
        const double tol = eight ? (lit ? 1 : 0) : (lit ? 1e-5 : 1e-6);
        EXPECT_LE(cv::norm(lib.canvas, plain.canvas, cv::NORM_INF), tol)
            << "scene " << i << ": " << describe(sc, c.canvas);
        compared++;
    }
    EXPECT_GT(compared, 60);
    std::printf("[ info ] %d scenes compared (%d lit Gouraud scenes skipped: a vertex clamps)\n",
                compared, gouraudSkipped);
}

// ---------------------------------------------------------------------------------------------
// Bad input raises and leaves the canvas and the depth buffer as they were

TEST(Texture3dReference, BadInputThrowsAndTouchesNothing)
{
    const std::vector<Vec3d> verts = { Vec3d(-1, -1, 3), Vec3d(1, -1, 3), Vec3d(0, 1, 3) };
    const std::vector<cv::Vec3i> faces = { cv::Vec3i(0, 1, 2) };
    const std::vector<Point2d> uv = { { 0, 0 }, { 3, 0 }, { 0, 3 } };
    const Mat tex(4, 4, CV_8UC3, cv::Scalar(10, 20, 30));
    const Mat K(cv::Matx33d(20, 0, 16, 0, 20, 16, 0, 0, 1));
    const Mat R = Mat::eye(3, 3, CV_64F), t = Mat::zeros(3, 1, CV_64F);
    Mat canvas(32, 32, CV_8UC3, cv::Scalar(1, 2, 3)), depth(32, 32, CV_32FC1, cv::Scalar(7));
    const Mat canvas0 = canvas.clone(), depth0 = depth.clone();
    auto expectThrow = [&](const char* what, const std::vector<Point2d>& coords,
                           const Mat& texture, const sh::RenderSettings& rs) {
        EXPECT_THROW(sh::drawTexturedMesh3d(canvas, verts, faces, coords, texture, K, R, t, rs,
                                            cv::noArray(), depth),
                     cv::Exception)
            << what;
        EXPECT_EQ(0, cv::norm(canvas, canvas0, cv::NORM_INF)) << what;
        EXPECT_EQ(0, cv::norm(depth, depth0, cv::NORM_INF)) << what;
    };
    const sh::RenderSettings ok;
    expectThrow("empty texture", uv, Mat(), ok);
    expectThrow("CV_8UC1 texture", uv, Mat(4, 4, CV_8UC1, cv::Scalar(1)), ok);
    expectThrow("CV_16UC3 texture", uv, Mat(4, 4, CV_16UC3, cv::Scalar::all(1)), ok);
    expectThrow("CV_32FC1 texture", uv, Mat(4, 4, CV_32FC1, cv::Scalar(1)), ok);
    expectThrow("2 texCoords for 3 vertices", std::vector<Point2d>(2), tex, ok);
    expectThrow("4 texCoords for 3 vertices", std::vector<Point2d>(4), tex, ok);
    expectThrow("no texCoords", std::vector<Point2d>(), tex, ok);
    for (int bad : { (int)cv::INTER_CUBIC, (int)cv::INTER_AREA, -1, 99 }) {
        sh::RenderSettings rs;
        rs.textureInterpolation = bad;
        expectThrow(cv::format("textureInterpolation %d", bad).c_str(), uv, tex, rs);
    }
    for (int bad : { (int)cv::BORDER_TRANSPARENT, -1, 99 }) {
        sh::RenderSettings rs;
        rs.textureBorder = bad;
        expectThrow(cv::format("textureBorder %d", bad).c_str(), uv, tex, rs);
    }
    // The defaults are bilinear and replicated, and a good call does draw.
    EXPECT_EQ(cv::INTER_LINEAR, ok.textureInterpolation);
    EXPECT_EQ(cv::BORDER_REPLICATE, ok.textureBorder);
    sh::drawTexturedMesh3d(canvas, verts, faces, uv, tex, K, R, t, ok, cv::noArray(), depth);
    EXPECT_GT(cv::norm(canvas, canvas0, cv::NORM_INF), 0);
}

// Same picture whatever the thread count, and with every band drawn in parts.
TEST(Texture3dReference, ThreadCountIndependent)
{
    cv::RNG rng(0x7e3d5);
    const int threads = cv::getNumThreads();
    for (int i = 0; i < 16; i++) {
        const Case c = randomCase(rng, i * 7);
        cv::setNumThreads(1);
        const LibOut a = drawTextured(c.scene, c.canvas, c.depthIn);
        cv::setNumThreads(std::max(2, threads));
        const LibOut b = drawTextured(c.scene, c.canvas, c.depthIn);
        LibOut parts;  // every band drawn in parts, as threads share bands
        {
            shading_test::SplitBands on(true);
            parts = drawTextured(c.scene, c.canvas, c.depthIn);
        }
        cv::setNumThreads(threads);
        for (const LibOut* other : {&b, static_cast<const LibOut*>(&parts)}) {
            EXPECT_EQ(0, cv::norm(a.canvas, other->canvas, cv::NORM_INF)) << i;
            EXPECT_EQ(0, cv::norm(a.faceIds, other->faceIds, cv::NORM_INF)) << i;
        }
    }
}

}  // namespace
