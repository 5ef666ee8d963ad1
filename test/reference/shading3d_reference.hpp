// This file is part of opencv_shading. License: Apache-2.0.
//
// shading_ref3d: a brute-force reference for drawMesh3d, computeNormals and lookAt, used by the
// tests. It is written from the documented conventions only (not from the library's sources) and
// does the simplest possible thing, one face and one pixel at a time, in double precision:
//
//  - Camera (as cv::projectPoints, no distortion): Xc = R Xw + t, R from a Rodrigues vector;
//    +z looks forward, x right, y down. A camera-space point projects to
//    u = fx X/Z + s Y/Z + cx, v = fy Y/Z + cy.
//  - Culling in world space: n = (v1 - v0) x (v2 - v0), eye E = -R^T t. CULL_BACK drops a face
//    with n.(E - v0) <= 0, CULL_FRONT one with n.(E - v0) >= 0. A face with a non-finite vertex
//    is dropped.
//  - Near plane: each face is clipped in camera space to Zc >= zNear (Sutherland-Hodgman on the
//    triangle; a cut point's attributes are the linear 3D interpolation along its edge). The
//    polygon left is fanned from its first vertex; nothing behind the plane is drawn.
//  - Coverage: the projected (sub-)triangles are snapped to 1/256 px and sampled at the integer
//    points by the exact 2D top-left rule of shading_reference.hpp (reused, not re-derived).
//  - Depth of a covered sample: the ray from the camera centre through the image point (x, y),
//    direction ((x - cx - s (y - cy)/fy)/fx, (y - cy)/fy, 1), meets the (clipped) triangle's
//    plane; the hit's Zc is the depth. Attributes come from the hit's 3D barycentrics: that is
//    what perspective-correct interpolation means. (The spec leaves open whether 1/Zc is affine
//    in the snapped or the unsnapped screen triangle, and along which diagonal a clipped quad is
//    split; with snapping these readings differ by ~1e-5. So every fragment also carries the
//    range of the snapped readings over every triangle on the clipped polygon's vertices that
//    contains the sample, and the tests accept anything in that range.)
//  - Lighting (colours in [0, 1]), at P with unit normal N, colour c, eye E, lights (p_i, I_i):
//    V = normalize(E - P), L_i = normalize(p_i - P), R_i = 2 (N.L_i) N - L_i,
//    I = c (ka Ia + kd sum I_i max(N.L_i, 0)) + ks sum I_i [N.L_i > 0] max(R_i.V, 0)^shininess,
//    per channel, clamped to [0, 1]. No lights: unlit, the colours as given, not clamped.
//    8-bit canvases: lit on c / 255, written as 255 I rounded and saturated.
//  - FLAT: one colour per face, lit at the centroid of the original face with its face normal
//    and its mean vertex colour. GOURAUD: every original vertex lit, the lit colours interpolated
//    (cut vertices get the linear interpolation). PHONG: position, normal and colour interpolated,
//    the normal renormalized (zero: ambient only), lit at the sample.
//  - Normals: face normal normalize((v1 - v0) x (v2 - v0)), zero if degenerate; vertex normal the
//    normalized sum of the unit normals of its faces, zero where the sum is zero.
//  - Visibility. ZBUFFER: faces in order, a sample is drawn where float(depth) < buffer (the
//    buffer is CV_32F; strict, so the earlier face wins ties). PAINTER: faces by decreasing mean
//    of the original three vertices' Zc (stable), each overwriting, no depth test. The depth
//    buffer (given, or +inf) ends with float(depth) of every drawn sample; faceIds is the index of
//    the face that coloured the pixel, -1 elsewhere.
//  - lookAt: zc = normalize(target - eye), yc = normalize(-(up - (up.zc) zc)), xc = yc x zc,
//    R rows xc, yc, zc, t = -R eye; eye == target or up parallel to the view throws.
#ifndef OPENCV_SHADING_TEST_SHADING3D_REFERENCE_HPP
#define OPENCV_SHADING_TEST_SHADING3D_REFERENCE_HPP

#include <opencv2/core.hpp>
#include <opencv2/shading.hpp>  // the enums only

#include "shading_reference.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <vector>

namespace shading_ref3d {

using cv::Matx33d;
using cv::Vec3d;

// ---------------------------------------------------------------------------------------------
// Geometry helpers

inline double norm(const Vec3d& v) { return std::sqrt(v.dot(v)); }

// Unit vector, or zero for a zero vector.
inline Vec3d normalizeOrZero(const Vec3d& v)
{
    const double n = norm(v);
    return n > 0 ? v * (1.0 / n) : Vec3d(0, 0, 0);
}

inline bool finite(const Vec3d& v)
{
    return std::isfinite(v[0]) && std::isfinite(v[1]) && std::isfinite(v[2]);
}

// Rotation matrix of a Rodrigues vector: cos(th) I + (1 - cos(th)) k k^T + sin(th) [k]x.
inline Matx33d rodrigues(const Vec3d& r)
{
    const double th = norm(r);
    if (th == 0)
        return Matx33d::eye();
    const Vec3d k = r * (1.0 / th);
    const double c = std::cos(th), s = std::sin(th), C = 1 - c;
    return Matx33d(c + C * k[0] * k[0], C * k[0] * k[1] - s * k[2], C * k[0] * k[2] + s * k[1],
                   C * k[1] * k[0] + s * k[2], c + C * k[1] * k[1], C * k[1] * k[2] - s * k[0],
                   C * k[2] * k[0] - s * k[1], C * k[2] * k[1] + s * k[0], c + C * k[2] * k[2]);
}

// lookAt straight from the formula. Throws cv::Exception when the frame is undefined.
inline void lookAt(const Vec3d& eye, const Vec3d& target, const Vec3d& up, Matx33d& R, Vec3d& t)
{
    const Vec3d f = target - eye;
    if (norm(f) == 0)
        CV_Error(cv::Error::StsBadArg, "eye == target");
    const Vec3d zc = f * (1.0 / norm(f));
    const Vec3d down = -(up - up.dot(zc) * zc);
    // "parallel" with a relative tolerance: the residual of a parallel up is rounding noise
    if (!(norm(down) > 1e-12 * norm(up)))
        CV_Error(cv::Error::StsBadArg, "up parallel to the view");
    const Vec3d yc = down * (1.0 / norm(down));
    const Vec3d xc = yc.cross(zc);
    R = Matx33d(xc[0], xc[1], xc[2], yc[0], yc[1], yc[2], zc[0], zc[1], zc[2]);
    t = -(R * eye);
}

inline Vec3d faceNormal(const Vec3d& a, const Vec3d& b, const Vec3d& c)
{
    return normalizeOrZero((b - a).cross(c - a));
}

// Vertex normals (and optionally face normals) straight from the definition.
inline std::vector<Vec3d> computeNormals(const std::vector<Vec3d>& verts,
                                         const std::vector<cv::Vec3i>& faces,
                                         std::vector<Vec3d>* faceNormals = nullptr)
{
    std::vector<Vec3d> sum(verts.size(), Vec3d(0, 0, 0));
    if (faceNormals)
        faceNormals->clear();
    for (const cv::Vec3i& f : faces) {
        const Vec3d n = faceNormal(verts[f[0]], verts[f[1]], verts[f[2]]);
        if (faceNormals)
            faceNormals->push_back(n);
        for (int i = 0; i < 3; i++)
            sum[f[i]] += n;
    }
    for (Vec3d& s : sum)
        s = normalizeOrZero(s);
    return sum;
}

// ---------------------------------------------------------------------------------------------
// Scene description (mirrors cv::shading::RenderSettings, defaults included)

struct Light {
    Vec3d position, intensity;
};

struct Settings {
    int shadeType = cv::shading::SHADE_GOURAUD;
    int visibility = cv::shading::VISIBILITY_ZBUFFER;
    int cullMode = cv::shading::CULL_NONE;
    double zNear = 1e-3;
    std::vector<Light> lights;
    Vec3d ambient = Vec3d(1, 1, 1);
    double ka = 0.2, kd = 0.7, ks = 0.5, shininess = 16;
};

struct Camera {
    double fx = 1, fy = 1, s = 0, cx = 0, cy = 0;
    Matx33d R = Matx33d::eye();
    Vec3d t = Vec3d(0, 0, 0);
    Vec3d eye() const { return -(R.t() * t); }
    Vec3d toCamera(const Vec3d& X) const { return R * X + t; }
    cv::Point2d project(const Vec3d& Xc) const
    {
        const double a = Xc[0] / Xc[2], b = Xc[1] / Xc[2];
        return cv::Point2d(fx * a + s * b + cx, fy * b + cy);
    }
    // Direction (z = 1) of the ray through image point (x, y).
    Vec3d ray(double x, double y) const
    {
        const double b = (y - cy) / fy;
        return Vec3d((x - cx - s * b) / fx, b, 1.0);
    }
};

struct Scene {
    std::vector<Vec3d> verts;      // world
    std::vector<cv::Vec3i> faces;
    std::vector<Vec3d> colors;     // canvas units
    std::vector<Vec3d> normals;    // empty: computeNormals
    Camera cam;
    Settings settings;
};

// The Phong formula of the spec, colours in [0, 1]. N unit, or zero (then only the ambient
// term survives: N.L = 0 kills diffuse and specular).
inline Vec3d phong(const Vec3d& P, const Vec3d& N, const Vec3d& c, const Vec3d& E,
                   const Settings& s)
{
    const Vec3d V = normalizeOrZero(E - P);
    Vec3d diffuse(0, 0, 0), specular(0, 0, 0);
    for (const Light& l : s.lights) {
        const Vec3d L = normalizeOrZero(l.position - P);
        const double nl = N.dot(L);
        diffuse += l.intensity * std::max(nl, 0.0);
        if (nl > 0) {
            const Vec3d Rr = 2 * nl * N - L;
            specular += l.intensity * std::pow(std::max(Rr.dot(V), 0.0), s.shininess);
        }
    }
    Vec3d out;
    for (int k = 0; k < 3; k++) {
        const double v = c[k] * (s.ka * s.ambient[k] + s.kd * diffuse[k]) + s.ks * specular[k];
        out[k] = std::min(std::max(v, 0.0), 1.0);
    }
    return out;
}

// ---------------------------------------------------------------------------------------------
// Rendering

// One face's sample at one pixel.
struct Fragment {
    int face = -1;
    double depth = 0;         // Zc of the ray/plane hit (the reference value)
    Vec3d color;              // its colour, canvas units, before rounding/saturation
    // Range over this reading and every snapped screen-space reading (1/Zc affine in a snapped
    // triangle on the clipped polygon's vertices that contains the sample).
    double depthLo = 0, depthHi = 0;
    Vec3d colorLo, colorHi;
    bool valid = true;        // false: the depth could not be evaluated (edge-on)
    bool colorStable = true;  // false: colour near a discontinuity (N.L ~ 0, normal ~ 0)
    int clippedTo = 0;        // 0: the face was not clipped; else its clipped polygon's size
    double lo() const { return depthLo; }
    double hi() const { return depthHi; }
};

struct Result {
    cv::Mat canvas;     // reference image
    cv::Mat depth;      // CV_32FC1 as the buffer ends
    cv::Mat faceIds;    // CV_32SC1
    // Per pixel (y * width + x): every fragment, in face order, and the index of the winner in
    // that list (-1: none).
    std::vector<std::vector<Fragment>> fragments;
    std::vector<int> winner;
    std::vector<double> meanDepth;  // per face, mean of the original vertices' Zc (NaN: skipped)
    std::vector<int> paintRank;     // per face, position in the painter's order
};

namespace detail {

// A clip-space vertex and everything that is interpolated with it.
struct CVert {
    Vec3d xc;   // camera coordinates
    Vec3d pw;   // world position (for lighting)
    Vec3d n;    // world normal (not normalized)
    Vec3d c;    // colour, lighting units ([0, 1] when lit)
    Vec3d lit;  // Gouraud: the vertex's lit colour
};

inline CVert lerp(const CVert& a, const CVert& b, double t)
{
    CVert r;
    r.xc = a.xc + (b.xc - a.xc) * t;
    r.pw = a.pw + (b.pw - a.pw) * t;
    r.n = a.n + (b.n - a.n) * t;
    r.c = a.c + (b.c - a.c) * t;
    r.lit = a.lit + (b.lit - a.lit) * t;
    return r;
}

// Sutherland-Hodgman against Zc >= zNear. A cut point lies exactly on the plane.
inline std::vector<CVert> clipNear(const std::vector<CVert>& poly, double zNear)
{
    std::vector<CVert> out;
    const size_t n = poly.size();
    for (size_t i = 0; i < n; i++) {
        const CVert& a = poly[i];
        const CVert& b = poly[(i + 1) % n];
        const bool ina = a.xc[2] >= zNear, inb = b.xc[2] >= zNear;
        if (ina)
            out.push_back(a);
        if (ina != inb) {
            const double t = (zNear - a.xc[2]) / (b.xc[2] - a.xc[2]);
            CVert m = lerp(a, b, t);
            m.xc[2] = zNear;
            out.push_back(m);
        }
    }
    return out;
}

}  // namespace detail

// Renders the scene over `canvas` (CV_32FC3 or CV_8UC3) with the initial depth buffer
// `depthIn` (empty: +inf everywhere).
inline Result render(const Scene& sc, const cv::Mat& canvas, const cv::Mat& depthIn = cv::Mat())
{
    using detail::CVert;
    const Settings& st = sc.settings;
    const Camera& cam = sc.cam;
    const bool eightBit = canvas.type() == CV_8UC3;
    CV_Assert(eightBit || canvas.type() == CV_32FC3);
    const bool lit = !st.lights.empty();
    const double toUnit = (lit && eightBit) ? 1.0 / 255 : 1.0;    // canvas units -> lighting
    const double fromUnit = (lit && eightBit) ? 255.0 : 1.0;
    const int W = canvas.cols, H = canvas.rows;
    const Vec3d E = cam.eye();
    const std::vector<Vec3d> normals =
        sc.normals.empty() ? computeNormals(sc.verts, sc.faces) : sc.normals;

    Result res;
    res.fragments.assign((size_t)W * H, {});
    res.winner.assign((size_t)W * H, -1);
    res.meanDepth.assign(sc.faces.size(), std::numeric_limits<double>::quiet_NaN());

    for (int f = 0; f < (int)sc.faces.size(); f++) {
        const cv::Vec3i& F = sc.faces[f];
        const Vec3d v0 = sc.verts[F[0]], v1 = sc.verts[F[1]], v2 = sc.verts[F[2]];
        if (!finite(v0) || !finite(v1) || !finite(v2))
            continue;
        const double side = (v1 - v0).cross(v2 - v0).dot(E - v0);
        if (st.cullMode == cv::shading::CULL_BACK && side <= 0)
            continue;
        if (st.cullMode == cv::shading::CULL_FRONT && side >= 0)
            continue;

        std::vector<CVert> poly(3);
        bool vertsStable = true;  // Gouraud: no vertex on the specular step N.L = 0
        for (int i = 0; i < 3; i++) {
            CVert& cv_ = poly[i];
            cv_.pw = sc.verts[F[i]];
            cv_.xc = cam.toCamera(cv_.pw);
            cv_.n = normals[F[i]];
            cv_.c = sc.colors[F[i]] * toUnit;
            cv_.lit = lit ? phong(cv_.pw, normalizeOrZero(cv_.n), cv_.c, E, st) : cv_.c;
            for (const Light& l : st.lights)
                if (std::abs(normalizeOrZero(cv_.n).dot(normalizeOrZero(l.position - cv_.pw))) <
                    1e-6)
                    vertsStable = false;
        }
        res.meanDepth[f] = (poly[0].xc[2] + poly[1].xc[2] + poly[2].xc[2]) / 3.0;

        // Flat: one colour, from the original face.
        Vec3d flat = (poly[0].c + poly[1].c + poly[2].c) * (1.0 / 3);
        bool flatStable = true;
        if (lit) {
            const Vec3d centroid = (v0 + v1 + v2) * (1.0 / 3);
            const Vec3d fn = faceNormal(v0, v1, v2);
            for (const Light& l : st.lights)
                if (std::abs(fn.dot(normalizeOrZero(l.position - centroid))) < 1e-9)
                    flatStable = false;
            flat = phong(centroid, fn, flat, E, st);
        }

        const std::vector<CVert> clipped = detail::clipNear(poly, st.zNear);
        const int m = (int)clipped.size();
        std::vector<cv::Point2d> proj(m);
        for (int i = 0; i < m; i++)
            proj[i] = cam.project(clipped[i].xc);
        // Every triangle on the polygon's vertices: the spec leaves the split of a clipped quad
        // open, and after snapping the two diagonals read slightly different depths.
        struct Split {
            int idx[3];
            shading_ref::Triangle t;
        };
        std::vector<Split> splits;
        for (int a = 0; a < m; a++)
            for (int b = a + 1; b < m; b++)
                for (int c = b + 1; c < m; c++) {
                    const cv::Point2d q[3] = { proj[a], proj[b], proj[c] };
                    Split sp{ { a, b, c }, shading_ref::setupTriangle(q) };
                    if (sp.t.drawable)
                        splits.push_back(sp);
                }

        // Colour at a point given by weights on three polygon vertices.
        auto shade = [&](const CVert* const tv[3], const double* l, bool& stable) {
            auto mix = [&](Vec3d CVert::*mem) {
                return tv[0]->*mem * l[0] + tv[1]->*mem * l[1] + tv[2]->*mem * l[2];
            };
            if (st.shadeType == cv::shading::SHADE_FLAT) {
                stable = stable && flatStable;
                return flat;
            }
            if (st.shadeType == cv::shading::SHADE_GOURAUD) {
                stable = stable && vertsStable;
                return mix(&CVert::lit);
            }
            if (!lit)
                return mix(&CVert::c);
            const Vec3d P = mix(&CVert::pw), Nraw = mix(&CVert::n), c = mix(&CVert::c);
            const double len = norm(Nraw);
            if (len != 0 && len < 1e-3)
                stable = false;  // renormalizing a tiny normal: its direction is noise
            const Vec3d N = normalizeOrZero(Nraw);
            for (const Light& li : st.lights)
                if (std::abs(N.dot(normalizeOrZero(li.position - P))) < 1e-6)
                    stable = false;  // the specular switch [N.L > 0] is a step
            return phong(P, N, c, E, st);
        };

        for (int k = 1; k + 1 < m; k++) {  // the fan from the first vertex
            const CVert* tri[3] = { &clipped[0], &clipped[k], &clipped[k + 1] };
            const cv::Point2d p2[3] = { proj[0], proj[k], proj[k + 1] };
            const shading_ref::Triangle t2 = shading_ref::setupTriangle(p2);
            const Vec3d A = tri[0]->xc, B = tri[1]->xc, C = tri[2]->xc;
            const Vec3d n = (B - A).cross(C - A);
            const double nn = n.dot(n);

            shading_ref::forEachCoveredPixel(t2, canvas.size(), [&](int x, int y,
                                                                    const shading_ref::Fixed& p) {
                Fragment fr;
                fr.face = f;
                if (poly[0].xc[2] < st.zNear || poly[1].xc[2] < st.zNear ||
                    poly[2].xc[2] < st.zNear)
                    fr.clippedTo = m;
                // Ray / plane, then 3D barycentrics of the hit.
                const Vec3d d = cam.ray(x, y);
                const double den = n.dot(d);
                double lam[3] = { 0, 0, 0 };
                fr.depth = std::numeric_limits<double>::quiet_NaN();
                if (den != 0 && nn != 0) {
                    const double th = n.dot(A) / den;
                    const Vec3d hit = d * th;
                    fr.depth = th;
                    lam[0] = (B - hit).cross(C - hit).dot(n) / nn;
                    lam[1] = (C - hit).cross(A - hit).dot(n) / nn;
                    lam[2] = 1 - lam[0] - lam[1];
                }
                fr.valid = std::isfinite(fr.depth) && fr.depth > 0;  // edge-on: no depth
                if (!fr.valid) {
                    res.fragments[(size_t)y * W + x].push_back(fr);
                    return;
                }
                fr.color = shade(tri, lam, fr.colorStable) * fromUnit;
                fr.depthLo = fr.depthHi = fr.depth;
                fr.colorLo = fr.colorHi = fr.color;
                // The snapped screen-space readings: 2D barycentrics b_i, weights b_i / Z_i
                // normalized, 1/Zc = sum b_i / Z_i.
                for (const Split& sp : splits) {
                    double w[3];
                    bool inside = true;
                    for (int i = 0; i < 3; i++) {
                        const shading_ref::Int128 e = shading_ref::edgeFunction(
                            sp.t.v[(i + 1) % 3], sp.t.v[(i + 2) % 3], p);
                        inside = inside && e >= 0;
                        const int src = sp.t.src[i];
                        w[src] = ((double)e / (double)sp.t.area2) / clipped[sp.idx[src]].xc[2];
                    }
                    if (!inside)
                        continue;
                    const double sum = w[0] + w[1] + w[2];
                    for (double& wi : w)
                        wi /= sum;
                    const CVert* tv[3] = { &clipped[sp.idx[0]], &clipped[sp.idx[1]],
                                           &clipped[sp.idx[2]] };
                    const double dAlt = 1.0 / sum;
                    const Vec3d cAlt = shade(tv, w, fr.colorStable) * fromUnit;
                    fr.depthLo = std::min(fr.depthLo, dAlt);
                    fr.depthHi = std::max(fr.depthHi, dAlt);
                    for (int ch = 0; ch < 3; ch++) {
                        fr.colorLo[ch] = std::min(fr.colorLo[ch], cAlt[ch]);
                        fr.colorHi[ch] = std::max(fr.colorHi[ch], cAlt[ch]);
                    }
                }
                res.fragments[(size_t)y * W + x].push_back(fr);
            });
        }
    }

    // Painter's order: stable sort by decreasing mean depth.
    std::vector<int> order;
    for (int f = 0; f < (int)sc.faces.size(); f++)
        if (!std::isnan(res.meanDepth[f]))
            order.push_back(f);
    std::stable_sort(order.begin(), order.end(), [&](int a, int b) {
        return res.meanDepth[a] > res.meanDepth[b];
    });
    res.paintRank.assign(sc.faces.size(), -1);
    for (int i = 0; i < (int)order.size(); i++)
        res.paintRank[order[i]] = i;

    // Resolve every pixel.
    res.canvas = canvas.clone();
    if (depthIn.empty())
        res.depth = cv::Mat(canvas.size(), CV_32FC1, cv::Scalar(
            std::numeric_limits<float>::infinity()));
    else
        res.depth = depthIn.clone();
    res.faceIds = cv::Mat(canvas.size(), CV_32SC1, cv::Scalar(-1));
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            const std::vector<Fragment>& fr = res.fragments[(size_t)y * W + x];
            float& buf = res.depth.at<float>(y, x);
            int win = -1;
            for (int i = 0; i < (int)fr.size(); i++) {
                if (st.visibility == cv::shading::VISIBILITY_ZBUFFER) {
                    if ((float)fr[i].depth < buf) {
                        buf = (float)fr[i].depth;
                        win = i;
                    }
                } else if (win < 0 || res.paintRank[fr[i].face] > res.paintRank[fr[win].face]) {
                    win = i;
                }
            }
            res.winner[(size_t)y * W + x] = win;
            if (win < 0)
                continue;
            buf = (float)fr[win].depth;
            res.faceIds.at<int>(y, x) = fr[win].face;
            shading_ref::putPixel(res.canvas, x, y, fr[win].color);
        }
    return res;
}

}  // namespace shading_ref3d

#endif  // OPENCV_SHADING_TEST_SHADING3D_REFERENCE_HPP
