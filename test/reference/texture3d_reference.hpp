// This file is part of opencv_shading. License: Apache-2.0.
//
// shading_reftex3d: a brute-force reference for drawTexturedMesh3d and for the perspective-correct
// forEachSample / forEachSpan (the overloads taking depths), used by the tests. Written from the
// documented conventions only (mesh3d.hpp, interpolate.hpp, texture.hpp), not from the library's
// sources, one sample at a time in double precision. It reuses shading_reference.hpp (snapping,
// the exact top-left coverage rule) and shading3d_reference.hpp (camera, normals, Phong model).
//
//  - Perspective-correct weights, by definition: the ray from the camera centre through the image
//    point (x, y) meets the plane of the triangle's three camera-space points; the weights are the
//    3D barycentric coordinates of the hit and the depth is its Zc. For forEachSample(size,
//    vertices, depths) the camera is K = identity and the points are P_i = z_i (x_i, y_i, 1).
//    The spec makes 1/Zc affine over the SNAPPED (1/256 px) screen triangle; that is the same
//    definition applied to the snapped vertices. Both readings are computed (unsnapped and
//    snapped) and the tests accept the range between them.
//  - Every attribute of a mesh face (texture coordinate, position, normal, Gouraud's D and S) is
//    affine in 3D over the face, and the near clip lerps them in 3D along cut edges; so whichever
//    (sub-)triangle a reading comes from, its attributes are those of the original face at the
//    3D point it reads (its original-face barycentrics `lam`).
//  - Texture sampling, cv::remap's definition with CV_32FC1 maps: the coordinate is rounded to
//    float; INTER_NEAREST takes texel cvRound(u) (ties to even); INTER_LINEAR quantizes to 1/32 px,
//    X = cvRound(32 u), texel X >> 5, fraction (X & 31) / 32, bilinear weights. Texels outside the
//    texture come from the border: BORDER_CONSTANT black, REPLICATE, REFLECT (fedcba|abcdef),
//    REFLECT_101 (fedcb|abcdef), WRAP; each of the 2 x 2 bilinear texels on its own.
//    The texture is first converted to the canvas's depth (8-bit <-> float, x or / 255).
//  - Lighting with a texture (mesh3d.hpp): the Phong model split as I = c D + S per channel,
//    D = ka Ia + kd sum_i I_i max(N.L_i, 0), S = ks sum_i I_i [N.L_i > 0] max(R_i.V, 0)^shininess;
//    the sample gets clamp(t D + S) for its texel t (in [0, 1] units; 8-bit: t / 255, result
//    x 255 rounded). FLAT: D, S once per face at its 3D centroid with its face normal. GOURAUD:
//    D, S per vertex (own position and normal), interpolated perspective-correctly. PHONG:
//    position and normal interpolated, normal renormalized (zero: ambient only), D, S at the
//    sample. No lights: the texel as sampled.
//
// A fragment records the range of its readings (the ray through the unsnapped face, and every
// snapped triangle on the clipped polygon's vertices containing the sample: the spec leaves
// open along which diagonal a clipped quad is split). expectedColor() turns that range into the
// range of colours remap's rounding can give: every quantized texel position the widened
// uv-interval reaches (usually one) is evaluated.
//
// Mutants: deliberately wrong variants of the reference (affine uv, u/v swapped, half a texel
// off, another border mode, the texel scaling the highlight) used by the tests to prove that the
// comparison would catch them.
#ifndef OPENCV_SHADING_TEST_TEXTURE3D_REFERENCE_HPP
#define OPENCV_SHADING_TEST_TEXTURE3D_REFERENCE_HPP

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>  // the INTER_* and BORDER_* constants only
#include <opencv2/shading.hpp>  // the enums only

#include "shading3d_reference.hpp"
#include "shading_reference.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

namespace shading_reftex3d {

using cv::Point2d;
using cv::Vec2d;
using cv::Vec3d;
using shading_ref3d::Camera;
using shading_ref3d::Light;
using shading_ref3d::Settings;

// ---------------------------------------------------------------------------------------------
// Perspective-correct weights

// Barycentrics q of the point where the ray through image point (x, y) meets the plane of the
// camera-space triangle T, and that point's Zc. False when the triangle is degenerate or the ray
// is parallel to its plane.
inline bool rayBarycentrics(const Camera& cam, const Vec3d T[3], double x, double y, Vec3d& q,
                            double& depth)
{
    const Vec3d n = (T[1] - T[0]).cross(T[2] - T[0]);
    const double nn = n.dot(n);
    const Vec3d d = cam.ray(x, y);
    const double den = n.dot(d);
    if (nn == 0 || den == 0)
        return false;
    const double t = n.dot(T[0]) / den;
    const Vec3d H = d * t;
    q[0] = (T[1] - H).cross(T[2] - H).dot(n) / nn;
    q[1] = (T[2] - H).cross(T[0] - H).dot(n) / nn;
    q[2] = (T[0] - H).cross(T[1] - H).dot(n) / nn;
    depth = t;
    return std::isfinite(t) && std::isfinite(q[0]) && std::isfinite(q[1]) && std::isfinite(q[2]);
}

// A vertex on the 1/256 px grid.
inline Point2d snapped(const Point2d& p)
{
    return Point2d(std::llround(p.x * 256) / 256.0, std::llround(p.y * 256) / 256.0);
}

// forEachSample(size, vertices, depths): the weights and depth of sample (x, y) by definition,
// K = identity and P_i = z_i (x_i, y_i, 1), on the given (snap = false) or snapped vertices.
inline bool depthWeights(const Point2d v[3], const double z[3], double x, double y, bool snap,
                         Vec3d& q, double& depth)
{
    Vec3d T[3];
    for (int i = 0; i < 3; i++) {
        const Point2d p = snap ? snapped(v[i]) : v[i];
        T[i] = Vec3d(p.x, p.y, 1) * z[i];
    }
    return rayBarycentrics(Camera(), T, x, y, q, depth);
}

// The range of both readings (unsnapped, snapped) of forEachSample-with-depths at one sample.
struct WeightRange {
    bool ok = false;
    Vec3d q, qSnapped;                 // the unsnapped and the snapped reading
    double depth = 0, depthSnapped = 0;
    Vec3d lo, hi;                      // per weight, min and max of the two
    double depthLo = 0, depthHi = 0;
};

inline WeightRange depthWeightRange(const Point2d v[3], const double z[3], int x, int y)
{
    WeightRange r;
    r.ok = depthWeights(v, z, x, y, false, r.q, r.depth) &&
           depthWeights(v, z, x, y, true, r.qSnapped, r.depthSnapped);
    for (int i = 0; i < 3; i++) {
        r.lo[i] = std::min(r.q[i], r.qSnapped[i]);
        r.hi[i] = std::max(r.q[i], r.qSnapped[i]);
    }
    r.depthLo = std::min(r.depth, r.depthSnapped);
    r.depthHi = std::max(r.depth, r.depthSnapped);
    return r;
}

// ---------------------------------------------------------------------------------------------
// Texture sampling (cv::remap's definition)

// Index of the texel that coordinate index p (of a row or column of n texels) reads under the
// border mode; -1 for BORDER_CONSTANT outside (the black border value).
inline int borderIndex(long long p, int n, int border)
{
    if (p >= 0 && p < n)
        return (int)p;
    auto mod = [](long long a, long long m) { return ((a % m) + m) % m; };
    switch (border) {
    case cv::BORDER_CONSTANT:
        return -1;
    case cv::BORDER_REPLICATE:
        return p < 0 ? 0 : n - 1;
    case cv::BORDER_WRAP:
        return (int)mod(p, n);
    case cv::BORDER_REFLECT: {  // fedcba|abcdef|fedcba: period 2n, the edge texel repeated
        const long long m = mod(p, 2LL * n);
        return (int)(m < n ? m : 2LL * n - 1 - m);
    }
    case cv::BORDER_REFLECT_101: {  // fedcb|abcdef|edcba: period 2n - 2, the edge texel once
        if (n == 1)
            return 0;
        const long long per = 2LL * n - 2, m = mod(p, per);
        return (int)(m < n ? m : per - m);
    }
    default:
        CV_Error(cv::Error::StsBadArg, "border mode");
    }
}

// Texel (ix, iy) after the border rule, in double (CV_8UC3 or CV_32FC3 texture).
inline Vec3d texel(const cv::Mat& tex, long long ix, long long iy, int border)
{
    const int x = borderIndex(ix, tex.cols, border), y = borderIndex(iy, tex.rows, border);
    if (x < 0 || y < 0)
        return Vec3d(0, 0, 0);
    if (tex.depth() == CV_8U) {
        const cv::Vec3b& t = tex.at<cv::Vec3b>(y, x);
        return Vec3d(t[0], t[1], t[2]);
    }
    const cv::Vec3f& t = tex.at<cv::Vec3f>(y, x);
    return Vec3d(t[0], t[1], t[2]);
}

// Bilinear value at the quantized position (X / 32, Y / 32), exact in double.
inline Vec3d bilinearAt(const cv::Mat& tex, long long X, long long Y, int border)
{
    const long long ix = X >> 5, iy = Y >> 5;  // floor (arithmetic shift)
    const double ax = (double)(X & 31) / 32, ay = (double)(Y & 31) / 32;
    return texel(tex, ix, iy, border) * ((1 - ax) * (1 - ay)) +
           texel(tex, ix + 1, iy, border) * (ax * (1 - ay)) +
           texel(tex, ix, iy + 1, border) * ((1 - ax) * ay) +
           texel(tex, ix + 1, iy + 1, border) * (ax * ay);
}

// v rounded to float. Through a volatile on purpose: GCC 12.2 at -O2 and -O3 was seen to drop
// (float) casts that its SLP vectorizer packs together (two or three casts of doubles built
// side by side into one Vec3d), leaving the doubles unrounded.
inline double toFloat(double v)
{
    volatile float f = (float)v;
    return f;
}

// Round half to even, as cvRound.
inline long long roundEven(double v) { return (long long)std::nearbyint(v); }

// The texel remap gives at the coordinate (u, v), in double (before remap rounds 8-bit output).
inline Vec3d sample(const cv::Mat& tex, double u, double v, int interpolation, int border)
{
    const double fu = toFloat(u), fv = toFloat(v);  // the float maps
    if (interpolation == cv::INTER_NEAREST)
        return texel(tex, roundEven(fu), roundEven(fv), border);
    return bilinearAt(tex, roundEven(fu * 32), roundEven(fv * 32), border);
}

// The quantized positions (texel index for nearest, 1/32 steps for bilinear) that some
// coordinate in [lo, hi] can round to: [first, last].
inline void quantizedRange(double lo, double hi, int interpolation, long long& first,
                           long long& last)
{
    const double s = interpolation == cv::INTER_NEAREST ? 1.0 : 32.0;
    first = (long long)std::ceil(lo * s - 0.5);
    last = (long long)std::floor(hi * s + 0.5);
}

// ---------------------------------------------------------------------------------------------
// Lighting split

// The Phong model at P with unit (or zero) normal N, eye E, as I = c D + S per channel.
inline void phongSplit(const Vec3d& P, const Vec3d& N, const Vec3d& E, const Settings& s, Vec3d& D,
                       Vec3d& S)
{
    const Vec3d V = shading_ref3d::normalizeOrZero(E - P);
    Vec3d diffuse(0, 0, 0), specular(0, 0, 0);
    for (const Light& l : s.lights) {
        const Vec3d L = shading_ref3d::normalizeOrZero(l.position - P);
        const double nl = N.dot(L);
        if (nl > 0) {
            diffuse += l.intensity * nl;
            const Vec3d R = 2 * nl * N - L;
            specular += l.intensity * std::pow(std::max(R.dot(V), 0.0), s.shininess);
        }
    }
    for (int k = 0; k < 3; k++) {
        D[k] = s.ka * s.ambient[k] + s.kd * diffuse[k];
        S[k] = s.ks * specular[k];
    }
}

// True where the lighting is near a step of the model (the highlight switches on at N.L = 0).
// A zero normal is no step: ambient only, exactly.
inline bool nearLightingStep(const Vec3d& P, const Vec3d& N, const Settings& s)
{
    if (N == Vec3d(0, 0, 0))
        return false;
    for (const Light& l : s.lights)
        if (std::abs(N.dot(shading_ref3d::normalizeOrZero(l.position - P))) < 1e-6)
            return true;
    return false;
}

// ---------------------------------------------------------------------------------------------
// Scenes and fragments

enum Mutant {
    NO_MUTANT = 0,
    MUTANT_AFFINE_UV,    // uv from screen-space (affine) weights
    MUTANT_SWAPPED_UV,   // (v, u)
    MUTANT_HALF_TEXEL,   // uv + (0.5, 0.5)
    MUTANT_WRONG_BORDER, // a neighbouring border mode
    MUTANT_TINTED_HIGHLIGHT  // clamp(t (D + S)): the texel scales the highlight too
};

struct TexScene {
    std::vector<Vec3d> verts;      // world
    std::vector<cv::Vec3i> faces;
    std::vector<Vec2d> uv;         // texture pixels, one per vertex
    std::vector<Vec3d> normals;    // empty: computeNormals
    Camera cam;
    Settings settings;
    cv::Mat texture;               // CV_8UC3 or CV_32FC3
    int interpolation = cv::INTER_LINEAR;
    int border = cv::BORDER_REPLICATE;
};

struct TexFragment {
    int face = -1;
    bool valid = false;    // the ray reading exists (the face is not seen edge-on)
    bool stable = true;    // lighting away from its steps (N.L ~ 0, a tiny renormalized normal)
    int clippedTo = 0;     // 0: not clipped; else the clipped polygon's size
    int readings = 0;      // how many readings the ranges hold
    double depth = 0;      // Zc of the ray reading
    Vec2d uv;              // the ray reading's texture coordinate
    Vec2d uvLo, uvHi;      // over the readings
    Vec3d D, S;            // the ray reading's lighting split (unlit: 1, 0)
    Vec3d Dlo, Dhi, Slo, Shi;
};

struct TexFragments {
    int width = 0, height = 0;
    std::vector<std::vector<TexFragment>> at;  // y * width + x, in face order
    const TexFragment* find(int x, int y, int face) const
    {
        for (const TexFragment& f : at[(size_t)y * width + x])
            if (f.face == face)
                return &f;
        return nullptr;
    }
};

inline bool finite2(const Vec2d& v) { return std::isfinite(v[0]) && std::isfinite(v[1]); }

// The border mode a MUTANT_WRONG_BORDER reference uses in place of b.
inline int wrongBorder(int b)
{
    switch (b) {
    case cv::BORDER_CONSTANT: return cv::BORDER_REPLICATE;
    case cv::BORDER_REPLICATE: return cv::BORDER_CONSTANT;
    case cv::BORDER_REFLECT: return cv::BORDER_REFLECT_101;
    case cv::BORDER_REFLECT_101: return cv::BORDER_REFLECT;
    default: return cv::BORDER_REFLECT;  // WRAP
    }
}

// Which readings a fragment's ranges hold: the ray through the unsnapped face and the snapped
// triangles (the default), or the snapped triangles only (the letter of the spec: 1/Zc affine
// over the snapped triangle).
enum Readings { ALL_READINGS, SNAPPED_ONLY };

// Every face's fragment at every sample it covers on a canvas of `size`.
inline TexFragments fragments(const TexScene& sc, cv::Size size, Mutant mutant = NO_MUTANT,
                              Readings readings = ALL_READINGS)
{
    const Settings& st = sc.settings;
    const Camera& cam = sc.cam;
    const bool lit = !st.lights.empty();
    const Vec3d E = cam.eye();
    const std::vector<Vec3d> normals =
        sc.normals.empty() ? shading_ref3d::computeNormals(sc.verts, sc.faces) : sc.normals;
    TexFragments out;
    out.width = size.width;
    out.height = size.height;
    out.at.assign((size_t)size.width * size.height, {});

    struct PV {
        Vec3d xc;   // camera space
        Vec3d lam;  // barycentrics in the original face
    };
    for (int f = 0; f < (int)sc.faces.size(); f++) {
        const cv::Vec3i& F = sc.faces[f];
        const Vec3d w[3] = { sc.verts[F[0]], sc.verts[F[1]], sc.verts[F[2]] };
        if (!shading_ref3d::finite(w[0]) || !shading_ref3d::finite(w[1]) ||
            !shading_ref3d::finite(w[2]))
            continue;
        bool uvOk = true;
        for (int i = 0; i < 3; i++)
            uvOk = uvOk && finite2(sc.uv[F[i]]) && std::abs(sc.uv[F[i]][0]) <= 1e30 &&
                   std::abs(sc.uv[F[i]][1]) <= 1e30;
        if (!uvOk)
            continue;
        const double side = (w[1] - w[0]).cross(w[2] - w[0]).dot(E - w[0]);
        if (st.cullMode == cv::shading::CULL_BACK && side <= 0)
            continue;
        if (st.cullMode == cv::shading::CULL_FRONT && side >= 0)
            continue;

        // Per original vertex: uv, lighting split (Gouraud), normal, position.
        Vec2d uv[3];
        Vec3d Dv[3], Sv[3], nv[3];
        bool vertsStable = true;
        for (int i = 0; i < 3; i++) {
            uv[i] = sc.uv[F[i]];
            if (mutant == MUTANT_SWAPPED_UV)
                uv[i] = Vec2d(uv[i][1], uv[i][0]);
            if (mutant == MUTANT_HALF_TEXEL)
                uv[i] += Vec2d(0.5, 0.5);
            nv[i] = normals[F[i]];
            Dv[i] = Vec3d(1, 1, 1);
            Sv[i] = Vec3d(0, 0, 0);
            if (lit) {
                const Vec3d N = shading_ref3d::normalizeOrZero(nv[i]);
                phongSplit(w[i], N, E, st, Dv[i], Sv[i]);
                vertsStable = vertsStable && !nearLightingStep(w[i], N, st);
            }
        }
        Vec3d Dflat(1, 1, 1), Sflat(0, 0, 0);
        bool flatStable = true;
        if (lit) {
            const Vec3d centroid = (w[0] + w[1] + w[2]) * (1.0 / 3);
            const Vec3d fn = shading_ref3d::faceNormal(w[0], w[1], w[2]);
            phongSplit(centroid, fn, E, st, Dflat, Sflat);
            flatStable = !nearLightingStep(centroid, fn, st);
        }
        // Attributes at original-face barycentrics lam.
        auto attributes = [&](const Vec3d& lam, Vec2d& uvOut, Vec3d& D, Vec3d& S, bool& stable) {
            uvOut = uv[0] * lam[0] + uv[1] * lam[1] + uv[2] * lam[2];
            if (!lit) {
                D = Vec3d(1, 1, 1);
                S = Vec3d(0, 0, 0);
            } else if (st.shadeType == cv::shading::SHADE_FLAT) {
                D = Dflat;
                S = Sflat;
                stable = stable && flatStable;
            } else if (st.shadeType == cv::shading::SHADE_GOURAUD) {
                D = Dv[0] * lam[0] + Dv[1] * lam[1] + Dv[2] * lam[2];
                S = Sv[0] * lam[0] + Sv[1] * lam[1] + Sv[2] * lam[2];
                stable = stable && vertsStable;
            } else {
                const Vec3d P = w[0] * lam[0] + w[1] * lam[1] + w[2] * lam[2];
                const Vec3d Nraw = nv[0] * lam[0] + nv[1] * lam[1] + nv[2] * lam[2];
                const double len = shading_ref3d::norm(Nraw);
                if (len != 0 && len < 1e-3)
                    stable = false;
                const Vec3d N = shading_ref3d::normalizeOrZero(Nraw);
                phongSplit(P, N, E, st, D, S);
                stable = stable && !nearLightingStep(P, N, st);
            }
        };

        std::vector<PV> poly(3);
        bool clipped = false;
        for (int i = 0; i < 3; i++) {
            poly[i].xc = cam.toCamera(w[i]);
            poly[i].lam = Vec3d(i == 0, i == 1, i == 2);
            clipped = clipped || !(poly[i].xc[2] >= st.zNear);
        }
        // Sutherland-Hodgman against Zc >= zNear; a cut point lies exactly on the plane.
        std::vector<PV> cl;
        for (size_t i = 0; i < 3; i++) {
            const PV& a = poly[i];
            const PV& b = poly[(i + 1) % 3];
            const bool ina = a.xc[2] >= st.zNear, inb = b.xc[2] >= st.zNear;
            if (ina)
                cl.push_back(a);
            if (ina != inb) {
                const double t = (st.zNear - a.xc[2]) / (b.xc[2] - a.xc[2]);
                PV m{ a.xc + (b.xc - a.xc) * t, a.lam + (b.lam - a.lam) * t };
                m.xc[2] = st.zNear;
                cl.push_back(m);
            }
        }
        const int m = (int)cl.size();
        std::vector<Point2d> proj(m);
        for (int i = 0; i < m; i++)
            proj[i] = cam.project(cl[i].xc);
        struct Split {
            int idx[3];
            shading_ref::Triangle t;
        };
        std::vector<Split> splits;  // every triangle on the polygon's vertices
        for (int a = 0; a < m; a++)
            for (int b = a + 1; b < m; b++)
                for (int c = b + 1; c < m; c++) {
                    const Point2d q[3] = { proj[a], proj[b], proj[c] };
                    Split sp{ { a, b, c }, shading_ref::setupTriangle(q) };
                    if (sp.t.drawable)
                        splits.push_back(sp);
                }

        for (int k = 1; k + 1 < m; k++) {  // the fan from the first vertex decides coverage
            const int fan[3] = { 0, k, k + 1 };
            const Point2d p2[3] = { proj[0], proj[k], proj[k + 1] };
            const shading_ref::Triangle t2 = shading_ref::setupTriangle(p2);
            const Vec3d T[3] = { cl[0].xc, cl[k].xc, cl[k + 1].xc };
            shading_ref::forEachCoveredPixel(t2, size, [&](int x, int y,
                                                           const shading_ref::Fixed& p) {
                TexFragment fr;
                fr.face = f;
                fr.clippedTo = clipped ? m : 0;
                Vec3d q;
                double depth;
                fr.valid = rayBarycentrics(cam, T, x, y, q, depth) && depth > 0;
                std::vector<TexFragment>& list = out.at[(size_t)y * size.width + x];
                if (!fr.valid) {
                    list.push_back(fr);
                    return;
                }
                fr.depth = depth;
                if (mutant == MUTANT_AFFINE_UV) {  // 2D barycentrics of the unsnapped triangle
                    const Point2d &A = p2[0], &B = p2[1], &C = p2[2];
                    const double ar = (B - A).cross(C - A);
                    q[0] = (B - Point2d(x, y)).cross(C - Point2d(x, y)) / ar;
                    q[1] = (C - Point2d(x, y)).cross(A - Point2d(x, y)) / ar;
                    q[2] = 1 - q[0] - q[1];
                }
                auto lamOf = [&](const int idx[3], const Vec3d& wts) {
                    return cl[idx[0]].lam * wts[0] + cl[idx[1]].lam * wts[1] +
                           cl[idx[2]].lam * wts[2];
                };
                auto add = [&](const Vec2d& uvr, const Vec3d& Dr, const Vec3d& Sr) {
                    if (fr.readings++ == 0) {
                        fr.uvLo = fr.uvHi = uvr;
                        fr.Dlo = fr.Dhi = Dr;
                        fr.Slo = fr.Shi = Sr;
                        return;
                    }
                    for (int c = 0; c < 3; c++) {
                        if (c < 2) {
                            fr.uvLo[c] = std::min(fr.uvLo[c], uvr[c]);
                            fr.uvHi[c] = std::max(fr.uvHi[c], uvr[c]);
                        }
                        fr.Dlo[c] = std::min(fr.Dlo[c], Dr[c]);
                        fr.Dhi[c] = std::max(fr.Dhi[c], Dr[c]);
                        fr.Slo[c] = std::min(fr.Slo[c], Sr[c]);
                        fr.Shi[c] = std::max(fr.Shi[c], Sr[c]);
                    }
                };
                attributes(lamOf(fan, q), fr.uv, fr.D, fr.S, fr.stable);
                if (readings != SNAPPED_ONLY)
                    add(fr.uv, fr.D, fr.S);
                // The snapped readings: exact 2D barycentrics b of the sample in a snapped
                // triangle, q_i = (b_i / Z_i) / sum_j (b_j / Z_j).
                for (const Split& sp : splits) {
                    Vec3d b, wq;
                    bool inside = true;
                    for (int i = 0; i < 3; i++) {
                        const shading_ref::Int128 e = shading_ref::edgeFunction(
                            sp.t.v[(i + 1) % 3], sp.t.v[(i + 2) % 3], p);
                        inside = inside && e >= 0;
                        b[sp.t.src[i]] = (double)e / (double)sp.t.area2;
                    }
                    if (!inside)
                        continue;
                    double sum = 0;
                    for (int i = 0; i < 3; i++)
                        sum += wq[i] = b[i] / cl[sp.idx[i]].xc[2];
                    wq *= 1.0 / sum;
                    Vec2d uvr;
                    Vec3d Dr, Sr;
                    attributes(lamOf(sp.idx, mutant == MUTANT_AFFINE_UV ? b : wq), uvr, Dr, Sr,
                               fr.stable);
                    add(uvr, Dr, Sr);
                }
                list.push_back(fr);
            });
        }
    }
    return out;
}

// The texture in the canvas's units: converted as texturedTriangles converts it.
inline cv::Mat textureForCanvas(const cv::Mat& texture, int canvasType)
{
    const int depth = CV_MAT_DEPTH(canvasType);
    if (texture.depth() == depth)
        return texture;
    cv::Mat out;
    texture.convertTo(out, depth, depth == CV_8U ? 255.0 : 1.0 / 255.0);
    return out;
}

// The colours the library may write for one fragment, per channel [lo, hi] in canvas units
// (before the tolerance of the caller). `texture` is in canvas units (textureForCanvas).
struct Expected {
    bool wide = false;   // the uv interval reaches too many quantized positions: not checked
    int positions = 0;   // quantized (u, v) positions considered (1: the uv is unambiguous)
    Vec3d lo, hi;
    Vec3d tLo, tHi;      // the texel's range
};

const double kUvRel = 1e-6;  // uv slack: float rounding (6e-8 relative) and double arithmetic

inline Expected expectedColor(const TexFragment& fr, const cv::Mat& texture, int canvasType,
                              const TexScene& sc, Mutant mutant = NO_MUTANT)
{
    Expected ex;
    const bool eight = CV_MAT_DEPTH(canvasType) == CV_8U;
    const int border = mutant == MUTANT_WRONG_BORDER ? wrongBorder(sc.border) : sc.border;
    long long first[2], last[2];
    for (int c = 0; c < 2; c++) {
        // Room for an implementation between (or mixing) the readings: the interval widened by
        // its own width, plus rounding slack.
        const double w = fr.uvHi[c] - fr.uvLo[c];
        const double eps = kUvRel * std::max(1.0, std::abs(fr.uv[c]));
        quantizedRange(fr.uvLo[c] - w - eps, fr.uvHi[c] + w + eps, sc.interpolation, first[c],
                       last[c]);
        if (last[c] - first[c] > 2) {
            ex.wide = true;
            return ex;
        }
    }
    ex.tLo = Vec3d::all(std::numeric_limits<double>::infinity());
    ex.tHi = -ex.tLo;
    for (long long X = first[0]; X <= last[0]; X++)
        for (long long Y = first[1]; Y <= last[1]; Y++) {
            ex.positions++;
            const Vec3d t = sc.interpolation == cv::INTER_NEAREST
                                ? texel(texture, X, Y, border)
                                : bilinearAt(texture, X, Y, border);
            for (int k = 0; k < 3; k++) {
                double a = t[k], b = t[k];
                if (eight) {  // remap writes 8-bit texels rounded; a tie may go either way
                    a = std::floor(t[k] + 0.5 - 1e-7);
                    b = std::floor(t[k] + 0.5 + 1e-7);
                }
                ex.tLo[k] = std::min(ex.tLo[k], a);
                ex.tHi[k] = std::max(ex.tHi[k], b);
            }
        }
    if (sc.settings.lights.empty()) {
        ex.lo = ex.tLo;
        ex.hi = ex.tHi;
        return ex;
    }
    const double unit = eight ? 255.0 : 1.0;
    for (int k = 0; k < 3; k++) {
        const double dw = fr.Dhi[k] - fr.Dlo[k], sw = fr.Shi[k] - fr.Slo[k];
        const double D[2] = { fr.Dlo[k] - dw, fr.Dhi[k] + dw };
        const double S[2] = { fr.Slo[k] - sw, fr.Shi[k] + sw };
        const double T[2] = { ex.tLo[k] / unit, ex.tHi[k] / unit };
        double lo = std::numeric_limits<double>::infinity(), hi = -lo;
        for (double t : T)
            for (double d : D)
                for (double s : S) {
                    const double lin = mutant == MUTANT_TINTED_HIGHLIGHT ? t * (d + s) : t * d + s;
                    const double v = std::min(std::max(lin, 0.0), 1.0);
                    lo = std::min(lo, v);
                    hi = std::max(hi, v);
                }
        ex.lo[k] = lo * unit;
        ex.hi[k] = hi * unit;
    }
    return ex;
}

// ---------------------------------------------------------------------------------------------
// Random scenes for the tests

// A texture of the given size and depth (CV_8U or CV_32F): noise, or smooth ramps and waves.
inline cv::Mat randomTexture(cv::RNG& rng, cv::Size size, int depth, bool smooth)
{
    cv::Mat t(size, CV_64FC3);
    const double k1 = rng.uniform(0.1, 1.0), k2 = rng.uniform(0.1, 1.0), ph = rng.uniform(0., 6.);
    for (int y = 0; y < size.height; y++)
        for (int x = 0; x < size.width; x++)
            for (int c = 0; c < 3; c++)
                t.at<Vec3d>(y, x)[c] =
                    smooth ? 0.5 + 0.45 * std::sin(k1 * x + k2 * y * (c + 1) + ph + c)
                           : rng.uniform(0.0, 1.0);
    cv::Mat out;
    t.convertTo(out, depth, depth == CV_8U ? 255.0 : 1.0);
    return out;
}

inline Vec3d randomUnitVector(cv::RNG& rng)
{
    for (;;) {
        const Vec3d v(rng.uniform(-1.0, 1.0), rng.uniform(-1.0, 1.0), rng.uniform(-1.0, 1.0));
        const double n = shading_ref3d::norm(v);
        if (n > 0.1 && n <= 1)
            return v * (1 / n);
    }
}

// A few random triangles (now and then sharing a vertex) seen by a random camera from nearby,
// so that some faces cross the near plane (half the scenes also raise zNear into the mesh).
// Texture coordinates reach beyond the texture on every side, so every border mode is used.
// The shading, visibility, interpolation and border are the caller's (left at the defaults).
inline TexScene randomTexScene(cv::RNG& rng, cv::Size canvas, int lights)
{
    TexScene sc;
    const int nFaces = rng.uniform(2, 9);
    const cv::Size tex(rng.uniform(1, 41), rng.uniform(1, 41));
    for (int f = 0; f < nFaces; f++) {
        const Vec3d c(rng.uniform(-0.8, 0.8), rng.uniform(-0.8, 0.8), rng.uniform(-0.8, 0.8));
        const double scale = rng.uniform(0.3, 1.5);
        cv::Vec3i face;
        for (int i = 0; i < 3; i++) {
            if (f > 0 && rng.uniform(0, 6) == 0) {
                const int v = sc.faces[rng.uniform(0, f)][rng.uniform(0, 3)];
                if ((i < 1 || face[0] != v) && (i < 2 || face[1] != v)) {
                    face[i] = v;
                    continue;
                }
            }
            face[i] = (int)sc.verts.size();
            sc.verts.push_back(c + scale * Vec3d(rng.uniform(-1.0, 1.0), rng.uniform(-1.0, 1.0),
                                                 rng.uniform(-1.0, 1.0)));
            sc.uv.push_back(Vec2d(rng.uniform(-0.6, 1.6) * tex.width,
                                  rng.uniform(-0.6, 1.6) * tex.height));
        }
        sc.faces.push_back(face);
    }
    // Camera: outside the cloud or just at its edge.
    Camera& cam = sc.cam;
    cam.fx = canvas.width * rng.uniform(0.6, 1.4);
    cam.fy = cam.fx * rng.uniform(0.8, 1.25);
    cam.s = rng.uniform(0, 2) ? 0.0 : cam.fx * rng.uniform(-0.1, 0.1);
    cam.cx = canvas.width * rng.uniform(0.4, 0.6);
    cam.cy = canvas.height * rng.uniform(0.4, 0.6);
    for (;;) {
        const Vec3d eye = randomUnitVector(rng) * rng.uniform(1.2, 4.0);
        const Vec3d target(rng.uniform(-0.3, 0.3), rng.uniform(-0.3, 0.3), rng.uniform(-0.3, 0.3));
        const Vec3d up = randomUnitVector(rng);
        const Vec3d view = target - eye;
        if (std::abs(up.dot(view)) > 0.95 * shading_ref3d::norm(view))
            continue;
        shading_ref3d::lookAt(eye, target, up, cam.R, cam.t);
        break;
    }
    Settings& st = sc.settings;
    st.zNear = 1e-3;
    if (rng.uniform(0, 2)) {  // a near plane through the mesh
        double lo = std::numeric_limits<double>::infinity(), hi = -lo;
        for (const Vec3d& v : sc.verts) {
            lo = std::min(lo, cam.toCamera(v)[2]);
            hi = std::max(hi, cam.toCamera(v)[2]);
        }
        if (hi > 0.05)
            st.zNear = std::max(0.05, lo + (hi - lo) * rng.uniform(0.1, 0.6));
    }
    for (int i = 0; i < lights; i++)
        st.lights.push_back(Light{ randomUnitVector(rng) * rng.uniform(1.5, 4.0),
                                   Vec3d(rng.uniform(0.2, 1.0), rng.uniform(0.2, 1.0),
                                         rng.uniform(0.2, 1.0)) });
    st.ambient = Vec3d(rng.uniform(0.0, 1.0), rng.uniform(0.0, 1.0), rng.uniform(0.0, 1.0));
    st.ka = rng.uniform(0.0, 0.5);
    st.kd = rng.uniform(0.2, 1.0);
    st.ks = rng.uniform(0.0, 1.0);
    const double shininess[4] = { 1, 5, 16, 40 };
    st.shininess = shininess[rng.uniform(0, 4)];
    if (rng.uniform(0, 3) == 0)  // given normals (some zero), else computed
        for (size_t i = 0; i < sc.verts.size(); i++)
            sc.normals.push_back(rng.uniform(0, 8) == 0 ? Vec3d(0, 0, 0) : randomUnitVector(rng));
    sc.texture = randomTexture(rng, tex, rng.uniform(0, 2) ? CV_8U : CV_32F, rng.uniform(0, 2));
    return sc;
}

}  // namespace shading_reftex3d

#endif  // OPENCV_SHADING_TEST_TEXTURE3D_REFERENCE_HPP
