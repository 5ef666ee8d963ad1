// This file is part of opencv_shading. License: Apache-2.0.
//
// Tests of the textured-3D reference itself (test/reference/texture3d_reference.hpp): hand-worked
// weights, its sampler against cv::remap (OpenCV's, not ours), its lighting split against the
// earlier 3D reference's Phong model, its fragments against shading3d_reference.hpp's. The
// library is not called: these straighten the yardstick before test_texture3d_reference.cpp
// measures the library with it.

#include <gtest/gtest.h>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "reference/texture3d_reference.hpp"

#include <cmath>
#include <cstdio>
#include <vector>

namespace {

namespace rt = shading_reftex3d;
using cv::Point2d;
using cv::Vec2d;
using cv::Vec3d;

// Right triangle (0, 0), (8, 0), (0, 8) with depths 1, 2, 2, sample (2, 2):
// screen weights w = (1 - 2/8 - 2/8, 2/8, 2/8) = (1/2, 1/4, 1/4); h = w / z = (1/2, 1/8, 1/8),
// sum 3/4, so q = (2/3, 1/6, 1/6) and depth 4/3. Check in 3D: P0 = (0, 0, 1), P1 = 2 (8, 0, 1) =
// (16, 0, 2), P2 = (0, 16, 2); 2/3 P0 + 1/6 P1 + 1/6 P2 = (8/3, 8/3, 4/3) = 4/3 (2, 2, 1), on
// the ray through (2, 2).
TEST(ReferenceTex3dSelf, HandWorkedPerspectiveWeights)
{
    const Point2d v[3] = { { 0, 0 }, { 8, 0 }, { 0, 8 } };
    const double z[3] = { 1, 2, 2 };
    for (bool snap : { false, true }) {
        Vec3d q;
        double depth;
        ASSERT_TRUE(rt::depthWeights(v, z, 2, 2, snap, q, depth));
        EXPECT_NEAR(q[0], 2.0 / 3, 1e-15);
        EXPECT_NEAR(q[1], 1.0 / 6, 1e-15);
        EXPECT_NEAR(q[2], 1.0 / 6, 1e-15);
        EXPECT_NEAR(depth, 4.0 / 3, 1e-15);
    }
    // At a vertex the weights are that vertex's alone, the depth its own.
    Vec3d q;
    double depth;
    ASSERT_TRUE(rt::depthWeights(v, z, 8, 0, false, q, depth));
    EXPECT_NEAR(q[1], 1, 1e-15);
    EXPECT_NEAR(depth, 2, 1e-15);
}

// The by-definition weights on snapped vertices are the documented formula
// q_i = (b_i / z_i) / sum_j (b_j / z_j) with b the exact screen barycentrics of the snapped
// triangle, and 1 / sum_j (b_j / z_j) is the ray depth.
TEST(ReferenceTex3dSelf, SnappedRayWeightsAreTheScreenFormula)
{
    cv::RNG rng(0x7e301);
    double worst = 0;
    int samples = 0;
    for (int i = 0; i < 300; i++) {
        const Point2d v[3] = { { rng.uniform(-20., 84.), rng.uniform(-20., 68.) },
                               { rng.uniform(-20., 84.), rng.uniform(-20., 68.) },
                               { rng.uniform(-20., 84.), rng.uniform(-20., 68.) } };
        const double z[3] = { rng.uniform(0.5, 50.), rng.uniform(0.5, 50.), rng.uniform(0.5, 50.) };
        const shading_ref::Triangle t = shading_ref::setupTriangle(v);
        shading_ref::forEachCoveredPixel(t, cv::Size(64, 48), [&](int x, int y,
                                                                  const shading_ref::Fixed& p) {
            Vec3d b, h;
            for (int k = 0; k < 3; k++)
                b[t.src[k]] = (double)shading_ref::edgeFunction(t.v[(k + 1) % 3],
                                                                t.v[(k + 2) % 3], p) /
                              (double)t.area2;
            double sum = 0;
            for (int k = 0; k < 3; k++)
                sum += h[k] = b[k] / z[k];
            Vec3d q;
            double depth;
            ASSERT_TRUE(rt::depthWeights(v, z, x, y, true, q, depth));
            for (int k = 0; k < 3; k++)
                worst = std::max(worst, std::abs(q[k] - h[k] / sum));
            worst = std::max(worst, std::abs(depth * sum - 1));
            samples++;
        });
    }
    EXPECT_GT(samples, 10000);
    EXPECT_LT(worst, 1e-11);
    std::printf("[ info ] %d samples: ray vs screen formula differ by %.2g at most\n", samples,
                worst);
}

TEST(ReferenceTex3dSelf, BorderIndexIsBorderInterpolate)
{
    for (int border : { cv::BORDER_CONSTANT, cv::BORDER_REPLICATE, cv::BORDER_REFLECT,
                        cv::BORDER_WRAP, cv::BORDER_REFLECT_101 })
        for (int n = 1; n <= 7; n++)
            for (int p = -40; p <= 40; p++)
                EXPECT_EQ(cv::borderInterpolate(p, n, border), rt::borderIndex(p, n, border))
                    << "border " << border << " n " << n << " p " << p;
    // By hand: n = 4 (abcd), p = -1 and 4.
    EXPECT_EQ(0, rt::borderIndex(-1, 4, cv::BORDER_REFLECT));     // a|abcd
    EXPECT_EQ(3, rt::borderIndex(4, 4, cv::BORDER_REFLECT));      // abcd|d
    EXPECT_EQ(1, rt::borderIndex(-1, 4, cv::BORDER_REFLECT_101)); // b|abcd
    EXPECT_EQ(2, rt::borderIndex(4, 4, cv::BORDER_REFLECT_101));  // abcd|c
    EXPECT_EQ(3, rt::borderIndex(-1, 4, cv::BORDER_WRAP));        // d|abcd
}

TEST(ReferenceTex3dSelf, QuantizedRange)
{
    long long a, b;
    rt::quantizedRange(2.4, 2.6, cv::INTER_NEAREST, a, b);  // 2.5 inside: either texel
    EXPECT_EQ(2, a);
    EXPECT_EQ(3, b);
    rt::quantizedRange(2.51, 3.49, cv::INTER_NEAREST, a, b);
    EXPECT_EQ(3, a);
    EXPECT_EQ(3, b);
    rt::quantizedRange(-0.7, -0.6, cv::INTER_NEAREST, a, b);
    EXPECT_EQ(-1, a);
    EXPECT_EQ(-1, b);
    // Bilinear: 1/32 steps; 1.01 * 32 = 32.32 -> 32; 1.02 * 32 = 32.64 -> 33.
    rt::quantizedRange(1.01, 1.011, cv::INTER_LINEAR, a, b);
    EXPECT_EQ(32, a);
    EXPECT_EQ(32, b);
    rt::quantizedRange(1.01, 1.02, cv::INTER_LINEAR, a, b);
    EXPECT_EQ(32, a);
    EXPECT_EQ(33, b);
}

// The sampler, at random coordinates and on remap's ties (exact halves for nearest, odd
// multiples of 1/64 for bilinear), against cv::remap with CV_32FC1 maps holding the same
// coordinates: float within 1e-6, 8-bit equal after rounding (a tie either way).
TEST(ReferenceTex3dSelf, SamplerIsRemap)
{
    cv::RNG rng(0x7e302);
    int compared = 0, ties8 = 0;
    double worstF = 0;
    for (int it = 0; it < 60; it++) {
        const cv::Size ts(rng.uniform(1, 9), rng.uniform(1, 9));
        for (int depth : { CV_8U, CV_32F }) {
            const cv::Mat tex = rt::randomTexture(rng, ts, depth, it % 3 == 0);
            const int n = 400;
            cv::Mat mx(n, 1, CV_32FC1), my(n, 1, CV_32FC1);
            for (int i = 0; i < n; i++) {
                double u = rng.uniform(-2.5 * ts.width, 3.5 * ts.width);
                double v = rng.uniform(-2.5 * ts.height, 3.5 * ts.height);
                if (i % 4 == 1) {  // ties
                    u = std::floor(u) + 0.5;
                    v = (std::floor(v * 32) + 0.5) / 32;
                }
                mx.at<float>(i) = (float)u;
                my.at<float>(i) = (float)v;
            }
            for (int interp : { cv::INTER_NEAREST, cv::INTER_LINEAR })
                for (int border : { cv::BORDER_CONSTANT, cv::BORDER_REPLICATE, cv::BORDER_REFLECT,
                                    cv::BORDER_WRAP, cv::BORDER_REFLECT_101 }) {
                    cv::Mat out;
                    cv::remap(tex, out, mx, my, interp, border, cv::Scalar::all(0));
                    for (int i = 0; i < n; i++) {
                        const Vec3d r = rt::sample(tex, mx.at<float>(i), my.at<float>(i), interp,
                                                   border);
                        for (int k = 0; k < 3; k++) {
                            compared++;
                            if (depth == CV_32F) {
                                const double d = std::abs(out.at<cv::Vec3f>(i)[k] - r[k]);
                                worstF = std::max(worstF, d);
                                EXPECT_LE(d, 1e-6) << i;
                            } else {
                                const double got = out.at<cv::Vec3b>(i)[k];
                                const double lo = std::floor(r[k] + 0.5 - 1e-7),
                                             hi = std::floor(r[k] + 0.5 + 1e-7);
                                ties8 += lo != hi;
                                EXPECT_TRUE(got == lo || got == hi)
                                    << "8-bit remap " << got << ", reference " << r[k]
                                    << " interp " << interp << " border " << border << " tex "
                                    << ts << " at " << mx.at<float>(i) << ", " << my.at<float>(i);
                            }
                        }
                    }
                }
        }
    }
    std::printf("[ info ] %d texel values compared with cv::remap: float within %.2g, 8-bit "
                "equal (%d on a .5 tie)\n", compared, worstF, ties8);
}

// clamp(c D + S) is the Phong model of the earlier reference, for any colour c.
TEST(ReferenceTex3dSelf, LightingSplitIsPhong)
{
    cv::RNG rng(0x7e303);
    for (int i = 0; i < 2000; i++) {
        shading_ref3d::Settings st;
        for (int l = rng.uniform(1, 4); l > 0; l--)
            st.lights.push_back({ rt::randomUnitVector(rng) * rng.uniform(0.5, 4.0),
                                  Vec3d(rng.uniform(0., 1.), rng.uniform(0., 1.),
                                        rng.uniform(0., 1.)) });
        st.ambient = Vec3d(rng.uniform(0., 1.), rng.uniform(0., 1.), rng.uniform(0., 1.));
        st.ka = rng.uniform(0., 0.5);
        st.kd = rng.uniform(0., 1.);
        st.ks = rng.uniform(0., 1.);
        st.shininess = rng.uniform(1., 40.);
        const Vec3d P = rt::randomUnitVector(rng) * rng.uniform(0., 1.);
        const Vec3d N = i % 10 == 0 ? Vec3d(0, 0, 0) : rt::randomUnitVector(rng);
        const Vec3d E = rt::randomUnitVector(rng) * rng.uniform(1., 5.);
        const Vec3d c(rng.uniform(0., 1.), rng.uniform(0., 1.), rng.uniform(0., 1.));
        Vec3d D, S;
        rt::phongSplit(P, N, E, st, D, S);
        const Vec3d expected = shading_ref3d::phong(P, N, c, E, st);
        for (int k = 0; k < 3; k++) {
            EXPECT_GE(D[k], 0);
            EXPECT_GE(S[k], 0);
            EXPECT_NEAR(std::min(std::max(c[k] * D[k] + S[k], 0.0), 1.0), expected[k], 1e-12);
        }
    }
}

shading_ref3d::Scene asScene(const rt::TexScene& t, const std::vector<Vec3d>& colors)
{
    shading_ref3d::Scene s;
    s.verts = t.verts;
    s.faces = t.faces;
    s.colors = colors;
    s.normals = t.normals;
    s.cam = t.cam;
    s.settings = t.settings;
    return s;
}

// Against the earlier, independent 3D reference: the same fragments (faces per pixel, in
// order, same depth); with vertex colours (u, v, 0), unlit Gouraud, its colour is the
// perspective-correct uv, which must be ours; with a uniform texture of colour c, our colour
// range must hold its lit colour for vertex colours c (FLAT, PHONG; GOURAUD where no vertex
// clamps).
TEST(ReferenceTex3dSelf, FragmentsAgreeWithTheMeshReference)
{
    cv::RNG rng(0x7e304);
    const cv::Size size(64, 48);
    long fragmentsSeen = 0, clippedFragments = 0, colourChecks = 0;
    double worstUv = 0, worstWidth = 0;
    for (int i = 0; i < 60; i++) {
        rt::TexScene sc = rt::randomTexScene(rng, size, i % 4 == 0 ? 0 : 1 + i % 3);
        sc.settings.shadeType = i % 3;
        const rt::TexFragments tf = rt::fragments(sc, size);
        // uv through the earlier reference (unlit Gouraud of colours (u, v, 0)).
        std::vector<Vec3d> uvColors;
        for (const Vec2d& uv : sc.uv)
            uvColors.push_back(Vec3d(uv[0], uv[1], 0));
        shading_ref3d::Scene uvScene = asScene(sc, uvColors);
        uvScene.settings.lights.clear();
        uvScene.settings.shadeType = cv::shading::SHADE_GOURAUD;
        const cv::Mat canvasF(size, CV_32FC3, cv::Scalar::all(0));
        const shading_ref3d::Result ru = shading_ref3d::render(uvScene, canvasF);
        // A uniform texture against vertex colours c.
        // float-representable, as the CV_32FC3 texture holds it
        const Vec3d c(rt::toFloat(rng.uniform(0.1, 0.9)), rt::toFloat(rng.uniform(0.1, 0.9)),
                      rt::toFloat(rng.uniform(0.1, 0.9)));
        rt::TexScene uni = sc;
        uni.texture = cv::Mat(3, 3, CV_32FC3, cv::Scalar(c[0], c[1], c[2]));
        const shading_ref3d::Result rc =
            shading_ref3d::render(asScene(sc, std::vector<Vec3d>(sc.verts.size(), c)), canvasF);
        bool gouraudClamps = false;  // any lit vertex colour beyond 1: Gouraud is not comparable
        if (!sc.settings.lights.empty()) {
            const auto normals = sc.normals.empty()
                                     ? shading_ref3d::computeNormals(sc.verts, sc.faces)
                                     : sc.normals;
            for (size_t v = 0; v < sc.verts.size(); v++) {
                Vec3d D, S;
                rt::phongSplit(sc.verts[v], shading_ref3d::normalizeOrZero(normals[v]),
                               sc.cam.eye(), sc.settings, D, S);
                for (int k = 0; k < 3; k++)
                    gouraudClamps |= c[k] * D[k] + S[k] > 1;
            }
        }
        for (int y = 0; y < size.height; y++)
            for (int x = 0; x < size.width; x++) {
                const auto& mine = tf.at[(size_t)y * size.width + x];
                const auto& theirs = ru.fragments[(size_t)y * size.width + x];
                ASSERT_EQ(mine.size(), theirs.size()) << "scene " << i << " at " << x << "," << y;
                for (size_t j = 0; j < mine.size(); j++) {
                    ASSERT_EQ(mine[j].face, theirs[j].face);
                    ASSERT_EQ(mine[j].valid, theirs[j].valid);
                    if (!mine[j].valid)
                        continue;
                    fragmentsSeen++;
                    clippedFragments += mine[j].clippedTo != 0;
                    EXPECT_NEAR(mine[j].depth, theirs[j].depth, 1e-12 * theirs[j].depth);
                    const double scale = 1 + std::abs(mine[j].uv[0]) + std::abs(mine[j].uv[1]);
                    for (int k = 0; k < 2; k++) {
                        const double d = std::max(std::abs(mine[j].uv[k] - theirs[j].color[k]),
                                                  std::max(std::abs(mine[j].uvLo[k] -
                                                                    theirs[j].colorLo[k]),
                                                           std::abs(mine[j].uvHi[k] -
                                                                    theirs[j].colorHi[k])));
                        worstUv = std::max(worstUv, d / scale);
                        EXPECT_LE(d, 1e-9 * scale) << "scene " << i << " at " << x << "," << y;
                    }
                    // Uniform texture.
                    const shading_ref3d::Fragment& fc = rc.fragments[(size_t)y * size.width + x][j];
                    if (!mine[j].stable || !fc.colorStable ||
                        (sc.settings.shadeType == cv::shading::SHADE_GOURAUD && gouraudClamps &&
                         !sc.settings.lights.empty()))
                        continue;
                    const rt::Expected ex = rt::expectedColor(mine[j], uni.texture, CV_32FC3, uni);
                    if (ex.wide)
                        continue;
                    colourChecks++;
                    for (int k = 0; k < 3; k++) {
                        EXPECT_LE(ex.lo[k], fc.color[k] + 1e-9) << "scene " << i;
                        EXPECT_GE(ex.hi[k], fc.color[k] - 1e-9) << "scene " << i;
                        worstWidth = std::max(worstWidth, ex.hi[k] - ex.lo[k]);
                    }
                }
            }
    }
    EXPECT_GT(fragmentsSeen, 20000);
    EXPECT_GT(clippedFragments, 2000);
    // The snapped and unsnapped readings differ by what the 1/256 px snap moves: a few 1e-4 of
    // a colour on these small triangles.
    EXPECT_LT(worstWidth, 2e-2);
    std::printf("[ info ] %ld fragments (%ld clipped), uv within %.2g (relative) of the mesh "
                "reference's; %ld uniform-texture colours checked, ranges %.2g wide at most\n",
                fragmentsSeen, clippedFragments, worstUv, colourChecks, worstWidth);
}

// Every mutant must change the expected colour at many pixels, or catching it proves nothing.
TEST(ReferenceTex3dSelf, MutantsChangeTheExpectedImage)
{
    cv::RNG rng(0x7e305);
    const cv::Size size(64, 48);
    for (rt::Mutant mutant : { rt::MUTANT_AFFINE_UV, rt::MUTANT_SWAPPED_UV, rt::MUTANT_HALF_TEXEL,
                               rt::MUTANT_WRONG_BORDER }) {
        long differ = 0, total = 0;
        for (int i = 0; i < 10; i++) {
            rt::TexScene sc = rt::randomTexScene(rng, size, 0);
            sc.interpolation = i % 2 ? cv::INTER_LINEAR : cv::INTER_NEAREST;
            sc.border = (i / 2) % 5;
            if (sc.border == 3)
                sc.border = cv::BORDER_WRAP;
            sc.texture = rt::randomTexture(rng, cv::Size(7 + i, 5 + i), CV_32F, false);
            const rt::TexFragments good = rt::fragments(sc, size);
            const rt::TexFragments bad = rt::fragments(sc, size, mutant);
            for (size_t p = 0; p < good.at.size(); p++)
                for (size_t j = 0; j < good.at[p].size(); j++) {
                    if (!good.at[p][j].valid)
                        continue;
                    const rt::Expected a = rt::expectedColor(good.at[p][j], sc.texture, CV_32FC3,
                                                             sc);
                    const rt::Expected b = rt::expectedColor(bad.at[p][j], sc.texture, CV_32FC3,
                                                             sc, mutant);
                    if (a.wide || b.wide)
                        continue;
                    total++;
                    bool disjoint = false;
                    for (int k = 0; k < 3; k++)
                        disjoint |= a.hi[k] + 1e-4 < b.lo[k] || b.hi[k] + 1e-4 < a.lo[k];
                    differ += disjoint;
                }
        }
        EXPECT_GT(differ, total / 10) << "mutant " << mutant;
        std::printf("[ info ] mutant %d changes %ld of %ld fragments\n", (int)mutant, differ,
                    total);
    }
}

}  // namespace
