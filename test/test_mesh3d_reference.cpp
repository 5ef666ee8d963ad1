// This file is part of opencv_shading. License: Apache-2.0.
//
// cv::shading::drawMesh3d / computeNormals / lookAt against the brute-force reference
// (test/reference/shading3d_reference.hpp) on random scenes and on hand-worked cases.
//
// What is compared, pixel by pixel (fixed seeds):
//  - Which face coloured the pixel (faceIds, -1 = none): EXACTLY, wherever the winner is
//    unambiguous. The spec leaves two things open that move depths by ~1e-5 (relative): the
//    library may make 1/Zc affine in the SNAPPED screen triangle (the reference intersects a ray
//    with the unsnapped plane), and it may split a near-clipped quad along either diagonal. So
//    every reference fragment carries the range of all these readings; a z-buffer pixel is
//    ambiguous when the winner's range comes within 1e-6 (relative) of another fragment's or of
//    the given buffer value, and a painter pixel when two of its faces' mean depths are within
//    1e-12. At ambiguous pixels the library's face must still be one covering the sample (or -1
//    when the background could win). Such pixels are rare (none in the current seeds).
//  - Depth (the CV_32F buffer) within that range, widened by its own width (room for an
//    implementation mixing the readings) and 1e-6 relative (float storage is 6e-8).
//  - Colour within the range of the readings widened by its width, plus 1e-5 on float canvases
//    (float storage 6e-8, float arithmetic ~1e-6) and 1 level on 8-bit ones (a value near .5
//    rounds either way when computed in another order). Colours next to a discontinuity of the
//    model (N.L ~ 0 switches the highlight on; a renormalized near-zero normal) are not compared.
//  - Untouched pixels: canvas and depth buffer bit-exactly as given.
// Scenes with every vertex in front of the near plane are not clipped, so there the faceIds must
// match the reference's exactly (painter: everywhere; z-buffer: outside near-ties).
// Each random suite prints its statistics (how wide the ranges were, the largest excess).

#include <gtest/gtest.h>

#include <opencv2/core.hpp>
#include <opencv2/shading.hpp>

#include "reference/shading3d_reference.hpp"
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
using shading_ref3d::Fragment;
using shading_ref3d::Light;
using shading_ref3d::Matx33d;
using shading_ref3d::Scene;
using shading_ref3d::Settings;
using shading_ref3d::Vec3d;
using Faces = std::vector<cv::Vec3i>;

const double kTieRel = 1e-6;     // z-buffer winner ambiguous within this relative depth gap
const double kPaintTie = 1e-12;  // painter: mean depths this close may sort either way
const double kDepthRel = 1e-6;   // depth slack (relative) beyond the readings
const double kColorTolF = 1e-5;  // float canvas colour slack beyond the readings
const double kColorTol8 = 1.0;   // 8-bit canvas: one level
const float kInf = std::numeric_limits<float>::infinity();

// ---------------------------------------------------------------------------------------------
// Calling the library

sh::RenderSettings toLib(const Settings& s)
{
    sh::RenderSettings r;
    r.shadeType = s.shadeType;
    r.visibility = s.visibility;
    r.cullMode = s.cullMode;
    r.zNear = s.zNear;
    for (const Light& l : s.lights)
        r.lights.push_back(sh::PointLight(cv::Point3d(l.position), l.intensity));
    r.ambient = s.ambient;
    r.ka = s.ka;
    r.kd = s.kd;
    r.ks = s.ks;
    r.shininess = s.shininess;
    return r;
}

// Rodrigues vector of a rotation, for handing poses to the library as rvec. Returns false near
// a half turn, where this simple formula is ill-conditioned (the caller passes R itself then).
bool rotationVector(const Matx33d& R, Vec3d& r)
{
    const double c = std::min(1.0, std::max(-1.0, (R(0, 0) + R(1, 1) + R(2, 2) - 1) / 2));
    const double th = std::acos(c);
    if (std::sin(th) < 1e-3)
        return false;
    const Vec3d axis(R(2, 1) - R(1, 2), R(0, 2) - R(2, 0), R(1, 0) - R(0, 1));
    r = axis * (th / (2 * std::sin(th)));
    return cv::norm(shading_ref3d::rodrigues(r) - R, cv::NORM_INF) < 1e-12;
}

// How the inputs are handed over; every form must give the same picture.
struct Forms {
    bool vertsMat = false;        // L x 3 CV_64F Mat instead of vector<Vec3d>
    bool vertsFloat = false;      // vector<Point3f> (the scene's vertices are float-representable)
    bool kFloat = false;          // camera matrix CV_32F
    bool rotationMatrix = false;  // 3 x 3 R instead of a Rodrigues vector
};

struct LibOut {
    cv::Mat canvas, depth, faceIds;
};

cv::Mat cameraMatrix(const shading_ref3d::Camera& cam)
{
    return cv::Mat(cv::Matx33d(cam.fx, cam.s, cam.cx, 0, cam.fy, cam.cy, 0, 0, 1));
}

LibOut runLib(const Scene& sc, const cv::Mat& canvas, const cv::Mat& depthIn, const Forms& fm)
{
    LibOut out;
    out.canvas = canvas.clone();
    out.depth = depthIn.empty() ? cv::Mat() : depthIn.clone();
    cv::Mat K = cameraMatrix(sc.cam);
    if (fm.kFloat)
        K.convertTo(K, CV_32F);
    Vec3d rvec;
    cv::Mat rot;
    if (fm.rotationMatrix || !rotationVector(sc.cam.R, rvec))
        rot = cv::Mat(sc.cam.R);
    else
        rot = cv::Mat(rvec).clone();
    const cv::Mat tvec = cv::Mat(sc.cam.t).clone();
    const sh::RenderSettings rs = toLib(sc.settings);
    if (fm.vertsFloat) {
        std::vector<cv::Point3f> vf;
        for (const Vec3d& v : sc.verts)
            vf.emplace_back((float)v[0], (float)v[1], (float)v[2]);
        sh::drawMesh3d(out.canvas, vf, sc.faces, sc.colors, K, rot, tvec, rs, sc.normals,
                       out.depth, out.faceIds);
    } else if (fm.vertsMat) {
        const cv::Mat verts =
            cv::Mat((int)sc.verts.size(), 3, CV_64F, (void*)sc.verts.data()).clone();
        sh::drawMesh3d(out.canvas, verts, sc.faces, sc.colors, K, rot, tvec, rs, sc.normals,
                       out.depth, out.faceIds);
    } else {
        sh::drawMesh3d(out.canvas, sc.verts, sc.faces, sc.colors, K, rot, tvec, rs, sc.normals,
                       out.depth, out.faceIds);
    }
    return out;
}

// ---------------------------------------------------------------------------------------------
// Comparison

bool sameFloatBits(float a, float b) { return std::memcmp(&a, &b, sizeof a) == 0; }

// a is clearly nearer than b: a < b with a relative gap above kTieRel.
bool clearlyBefore(double a, double b)
{
    if (std::isinf(b) && b > 0)
        return !std::isinf(a);
    return a < b && (b - a) > kTieRel * std::max(std::abs(a), std::abs(b));
}

struct Stats {
    long pixels = 0, drawn = 0, ambiguous = 0, colorChecked = 0, depthChecked = 0;
    double maxDepthRel = 0, maxColorF = 0, maxColor8 = 0;
    double maxDepthWidth = 0, sumDepthWidth = 0;  // relative width of the accepted interval
};

std::string describe(const Scene& sc, cv::Size size, int type)
{
    std::ostringstream s;
    s.precision(17);
    const Settings& st = sc.settings;
    s << "canvas " << size << (type == CV_8UC3 ? " 8UC3" : " 32FC3") << ", " << sc.faces.size()
      << " faces, " << sc.verts.size() << " verts, shade " << st.shadeType << ", visibility "
      << st.visibility << ", cull " << st.cullMode << ", zNear " << st.zNear << ", "
      << st.lights.size() << " lights, normals " << (sc.normals.empty() ? "computed" : "given")
      << ", K fx " << sc.cam.fx << " fy " << sc.cam.fy << " s " << sc.cam.s << " c ("
      << sc.cam.cx << ", " << sc.cam.cy << "), eye " << sc.cam.eye();
    return s.str();
}

// Compares one library run with the reference; returns the number of mismatching pixels
// (reports the first few).
int compare(const Scene& sc, const cv::Mat& canvasIn, const cv::Mat& depthIn,
            const shading_ref3d::Result& ref, const LibOut& lib, Stats& stats,
            const std::string& what)
{
    const int W = canvasIn.cols, H = canvasIn.rows;
    const bool eight = canvasIn.type() == CV_8UC3;
    const bool zbuf = sc.settings.visibility == sh::VISIBILITY_ZBUFFER;
    EXPECT_EQ(lib.canvas.size(), canvasIn.size());
    EXPECT_EQ(lib.canvas.type(), canvasIn.type());
    EXPECT_EQ(lib.depth.size(), canvasIn.size());
    EXPECT_EQ(lib.depth.type(), CV_32FC1);
    EXPECT_EQ(lib.faceIds.size(), canvasIn.size());
    EXPECT_EQ(lib.faceIds.type(), CV_32SC1);
    if (lib.canvas.size() != canvasIn.size() || lib.depth.size() != canvasIn.size() ||
        lib.faceIds.size() != canvasIn.size() || lib.depth.type() != CV_32FC1 ||
        lib.faceIds.type() != CV_32SC1 || lib.canvas.type() != canvasIn.type())
        return 1;
    int bad = 0;
    auto fail = [&](int x, int y, const std::string& msg) {
        if (++bad <= 3)
            ADD_FAILURE() << what << "\n  " << describe(sc, canvasIn.size(), canvasIn.type())
                          << "\n  pixel (" << x << ", " << y << "): " << msg;
    };
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            stats.pixels++;
            const std::vector<Fragment>& fr = ref.fragments[(size_t)y * W + x];
            const int win = ref.winner[(size_t)y * W + x];
            const float B = depthIn.empty() ? kInf : depthIn.at<float>(y, x);
            // Is the winner beyond doubt?
            bool ambiguous = false;
            for (const Fragment& f : fr)
                ambiguous |= !f.valid;
            if (!ambiguous && zbuf) {
                if (win >= 0) {
                    for (int i = 0; i < (int)fr.size(); i++)
                        if (i != win && !clearlyBefore(fr[win].hi(), fr[i].lo()))
                            ambiguous = true;
                    if (!clearlyBefore(fr[win].hi(), B))
                        ambiguous = true;
                } else {
                    for (const Fragment& f : fr)
                        if (!clearlyBefore(B, f.lo()))
                            ambiguous = true;
                }
            } else if (!ambiguous && win >= 0) {
                const double m = ref.meanDepth[fr[win].face];
                for (const Fragment& f : fr) {
                    const double o = ref.meanDepth[f.face];
                    if (f.face != fr[win].face &&
                        std::abs(o - m) <= kPaintTie * std::max(std::abs(o), std::abs(m)))
                        ambiguous = true;
                }
            }
            stats.ambiguous += ambiguous;

            const int id = lib.faceIds.at<int>(y, x);
            const int refId = ref.faceIds.at<int>(y, x);
            const Fragment* mine = nullptr;
            for (const Fragment& f : fr)
                if (f.face == id) {
                    mine = &f;
                    break;
                }
            if (!ambiguous && id != refId) {
                std::ostringstream m;
                m.precision(9);
                m << "faceId " << id << ", reference " << refId << "; fragments:";
                for (const Fragment& f : fr)
                    m << " [face " << f.face << " depth " << f.lo() << " .. " << f.hi()
                      << " mean " << ref.meanDepth[f.face] << "]";
                m << " buffer in " << B << ", library depth " << lib.depth.at<float>(y, x);
                fail(x, y, m.str());
                continue;
            }
            if (ambiguous && id >= 0 && !mine) {
                fail(x, y, cv::format("faceId %d covers no sample here (ambiguous pixel)", id));
                continue;
            }
            if (id < 0) {
                if (win >= 0 && (!zbuf || std::isinf(B))) {
                    fail(x, y, "nothing drawn where a face covers the sample");
                    continue;
                }
                const bool same =
                    eight ? lib.canvas.at<cv::Vec3b>(y, x) == canvasIn.at<cv::Vec3b>(y, x)
                          : std::memcmp(&lib.canvas.at<cv::Vec3f>(y, x),
                                        &canvasIn.at<cv::Vec3f>(y, x), 12) == 0;
                if (!same)
                    fail(x, y, "canvas changed where faceIds is -1");
                if (!sameFloatBits(lib.depth.at<float>(y, x), B))
                    fail(x, y, cv::format("depth changed to %.9g where nothing was drawn (was %g)",
                                          lib.depth.at<float>(y, x), B));
                continue;
            }
            stats.drawn++;
            if (!mine || !mine->valid)
                continue;
            // Depth.
            const double d = lib.depth.at<float>(y, x);
            const double lo = mine->lo(), hi = mine->hi();
            const double slack = kDepthRel * std::abs(hi) + (hi - lo);
            stats.depthChecked++;
            const double dErr = std::max(0.0, std::max(lo - d, d - hi)) / std::abs(hi);
            stats.maxDepthRel = std::max(stats.maxDepthRel, dErr);
            stats.maxDepthWidth = std::max(stats.maxDepthWidth, (hi - lo) / hi);
            stats.sumDepthWidth += (hi - lo) / hi;
            if (!(d >= lo - slack && d <= hi + slack))
                fail(x, y, cv::format("face %d depth %.9g, reference %.12g (%.12g .. %.12g), "
                                      "clipped to %d", id, d, mine->depth, lo, hi,
                                      mine->clippedTo));
            // Colour.
            if (!mine->colorStable)
                continue;
            stats.colorChecked++;
            for (int k = 0; k < 3; k++) {
                const double a = mine->colorLo[k], b = mine->colorHi[k];
                const double w = b - a;
                double v, tol, clo = a - w, chi = b + w;
                if (eight) {
                    v = lib.canvas.at<cv::Vec3b>(y, x)[k];
                    clo = std::min(std::max(clo, 0.0), 255.0);
                    chi = std::min(std::max(chi, 0.0), 255.0);
                    tol = kColorTol8;
                } else {
                    v = lib.canvas.at<cv::Vec3f>(y, x)[k];
                    tol = kColorTolF;
                }
                const double err = std::max(0.0, std::max(clo - v, v - chi));
                double& maxColor = eight ? stats.maxColor8 : stats.maxColorF;
                maxColor = std::max(maxColor, err);
                if (err > tol) {
                    fail(x, y, cv::format("face %d channel %d colour %.9g, reference %.9g (%.9g .. "
                                          "%.9g)", id, k, v, mine->color[k], a, b));
                    break;
                }
            }
        }
    return bad;
}

// ---------------------------------------------------------------------------------------------
// Random scenes

double f32(double v) { return (double)(float)v; }  // float-representable, so every form agrees

Vec3d randomUnit(cv::RNG& rng)
{
    for (;;) {
        const Vec3d v(rng.uniform(-1.0, 1.0), rng.uniform(-1.0, 1.0), rng.uniform(-1.0, 1.0));
        const double n = cv::norm(v);
        if (n > 0.1 && n <= 1)
            return v * (1 / n);
    }
}

enum MeshKind { SOUP, HEIGHTFIELD, CLOSED };

void addSoup(cv::RNG& rng, Scene& sc, bool nonFinite)
{
    const int n = rng.uniform(5, 201);
    for (int f = 0; f < n; f++) {
        const Vec3d c(rng.uniform(-1.0, 1.0), rng.uniform(-1.0, 1.0), rng.uniform(-1.0, 1.0));
        const double scale = std::exp(rng.uniform(std::log(0.03), std::log(1.0)));
        cv::Vec3i face;
        for (int i = 0; i < 3; i++) {
            // Now and then share a vertex with an earlier face.
            if (f > 0 && rng.uniform(0, 10) == 0) {
                const int v = sc.faces[rng.uniform(0, f)][rng.uniform(0, 3)];
                bool repeated = false;
                for (int j = 0; j < i; j++)
                    repeated |= face[j] == v;
                if (!repeated) {
                    face[i] = v;
                    continue;
                }
            }
            face[i] = (int)sc.verts.size();
            sc.verts.push_back(c + scale * Vec3d(rng.uniform(-1.0, 1.0), rng.uniform(-1.0, 1.0),
                                                 rng.uniform(-1.0, 1.0)));
        }
        sc.faces.push_back(face);
    }
    if (nonFinite) {  // a face of its own gets a NaN or infinite coordinate
        const double bad[3] = { std::numeric_limits<double>::quiet_NaN(),
                                std::numeric_limits<double>::infinity(),
                                -std::numeric_limits<double>::infinity() };
        const int L = (int)sc.verts.size();
        sc.verts.push_back(Vec3d(0, 0, 0));
        sc.verts.push_back(Vec3d(0.5, 0, 0));
        sc.verts.push_back(Vec3d(0, 0.5, 0));
        sc.verts[L + rng.uniform(0, 3)][rng.uniform(0, 3)] = bad[rng.uniform(0, 3)];
        sc.faces.insert(sc.faces.begin() + rng.uniform(0, (int)sc.faces.size() + 1),
                        cv::Vec3i(L, L + 1, L + 2));
    }
}

void addHeightfield(cv::RNG& rng, Scene& sc)
{
    const int nx = rng.uniform(3, 12), ny = rng.uniform(3, 12);
    const double a1 = rng.uniform(0.0, 0.5), a2 = rng.uniform(0.0, 0.5);
    const double k1 = rng.uniform(0.5, 4.0), k2 = rng.uniform(0.5, 4.0), ph = rng.uniform(0., 6.);
    for (int j = 0; j < ny; j++)
        for (int i = 0; i < nx; i++) {
            const double x = -1 + 2.0 * i / (nx - 1), y = -1 + 2.0 * j / (ny - 1);
            sc.verts.push_back(Vec3d(x, y, a1 * std::sin(k1 * x + ph) + a2 * std::cos(k2 * y)));
        }
    for (int j = 0; j + 1 < ny; j++)
        for (int i = 0; i + 1 < nx; i++) {
            const int a = j * nx + i, b = a + 1, c = a + nx, d = c + 1;
            if (rng.uniform(0, 2)) {
                sc.faces.push_back(cv::Vec3i(a, b, d));
                sc.faces.push_back(cv::Vec3i(a, d, c));
            } else {
                sc.faces.push_back(cv::Vec3i(a, b, c));
                sc.faces.push_back(cv::Vec3i(b, d, c));
            }
        }
}

// A lumpy UV sphere, outward-wound: a closed surface for the culling modes.
void addClosed(cv::RNG& rng, Scene& sc)
{
    const int nu = rng.uniform(4, 11), nv = rng.uniform(3, 9);
    const int north = 0;
    sc.verts.push_back(Vec3d(0, 0, rng.uniform(0.7, 1.2)));
    for (int j = 1; j < nv; j++)
        for (int i = 0; i < nu; i++) {
            const double th = CV_PI * j / nv, ph = 2 * CV_PI * i / nu;
            const double r = rng.uniform(0.7, 1.2);
            sc.verts.push_back(r * Vec3d(std::sin(th) * std::cos(ph), std::sin(th) * std::sin(ph),
                                         std::cos(th)));
        }
    const int south = (int)sc.verts.size();
    sc.verts.push_back(Vec3d(0, 0, -rng.uniform(0.7, 1.2)));
    auto ring = [&](int j, int i) { return 1 + (j - 1) * nu + (i % nu); };
    for (int i = 0; i < nu; i++) {
        sc.faces.push_back(cv::Vec3i(north, ring(1, i), ring(1, i + 1)));
        sc.faces.push_back(cv::Vec3i(south, ring(nv - 1, i + 1), ring(nv - 1, i)));
        for (int j = 1; j + 1 < nv; j++) {
            sc.faces.push_back(cv::Vec3i(ring(j, i), ring(j + 1, i), ring(j + 1, i + 1)));
            sc.faces.push_back(cv::Vec3i(ring(j, i), ring(j + 1, i + 1), ring(j, i + 1)));
        }
    }
}

struct Case {
    Scene scene;
    cv::Mat canvas, depthIn;
    Forms forms;
};

Case randomCase(cv::RNG& rng, MeshKind kind)
{
    Case c;
    Scene& sc = c.scene;
    if (kind == SOUP)
        addSoup(rng, sc, rng.uniform(0, 8) == 0);
    else if (kind == HEIGHTFIELD)
        addHeightfield(rng, sc);
    else
        addClosed(rng, sc);
    for (Vec3d& v : sc.verts)
        v = Vec3d(f32(v[0]), f32(v[1]), f32(v[2]));

    const cv::Size size(rng.uniform(24, 73), rng.uniform(20, 57));
    const int type = rng.uniform(0, 2) ? CV_8UC3 : CV_32FC3;
    const double unit = type == CV_8UC3 ? 255.0 : 1.0;
    for (size_t i = 0; i < sc.verts.size(); i++)
        sc.colors.push_back(Vec3d(f32(rng.uniform(0.0, unit)), f32(rng.uniform(0.0, unit)),
                                  f32(rng.uniform(0.0, unit))));

    // Camera: somewhere around the mesh, sometimes inside it (vertices behind the camera).
    shading_ref3d::Camera& cam = sc.cam;
    cam.fx = f32(size.width * rng.uniform(0.6, 1.5));
    cam.fy = f32(cam.fx * rng.uniform(0.8, 1.25));
    cam.s = rng.uniform(0, 2) ? 0.0 : f32(cam.fx * rng.uniform(-0.15, 0.15));
    cam.cx = f32(size.width * rng.uniform(0.35, 0.65));
    cam.cy = f32(size.height * rng.uniform(0.35, 0.65));
    for (;;) {
        const Vec3d eye = randomUnit(rng) * rng.uniform(0.2, 4.5);
        const Vec3d target(rng.uniform(-0.4, 0.4), rng.uniform(-0.4, 0.4),
                           rng.uniform(-0.4, 0.4));
        const Vec3d up = randomUnit(rng);
        if (cv::norm(target - eye) < 0.1 || std::abs(up.dot(cv::normalize(target - eye))) > 0.99)
            continue;
        shading_ref3d::lookAt(eye, target, up, cam.R, cam.t);
        break;
    }

    Settings& st = sc.settings;
    st.shadeType = rng.uniform(0, 3);
    st.visibility = rng.uniform(0, 2);
    st.cullMode = rng.uniform(0, 3);
    const double nears[4] = { 1e-3, 0.02, 0.3, 1.0 };
    st.zNear = nears[rng.uniform(0, 4)];
    const int nLights = rng.uniform(0, 4) == 0 ? 0 : rng.uniform(1, 5);
    for (int i = 0; i < nLights; i++)
        st.lights.push_back(Light{ randomUnit(rng) * rng.uniform(1.5, 4.0),
                                   Vec3d(rng.uniform(0.2, 1.0), rng.uniform(0.2, 1.0),
                                         rng.uniform(0.2, 1.0)) });
    st.ambient = Vec3d(rng.uniform(0.0, 1.0), rng.uniform(0.0, 1.0), rng.uniform(0.0, 1.0));
    st.ka = rng.uniform(0.0, 0.5);
    st.kd = rng.uniform(0.2, 1.0);
    st.ks = rng.uniform(0.0, 1.0);
    const double shin[4] = { 1, 5, 16, 40 };
    st.shininess = shin[rng.uniform(0, 4)];

    // Normals: computed by the library (empty), the reference's, or arbitrary (some zero).
    const int nm = rng.uniform(0, 3);
    if (nm == 1) {
        sc.normals = shading_ref3d::computeNormals(sc.verts, sc.faces);
    } else if (nm == 2) {
        for (size_t i = 0; i < sc.verts.size(); i++)
            sc.normals.push_back(rng.uniform(0, 10) == 0 ? Vec3d(0, 0, 0) : randomUnit(rng));
    }

    // Background noise, so an untouched pixel is told from a written one by value too.
    c.canvas.create(size, type);
    if (type == CV_8UC3)
        rng.fill(c.canvas, cv::RNG::UNIFORM, 0, 256);
    else
        rng.fill(c.canvas, cv::RNG::UNIFORM, -1.0, 2.0);
    if (rng.uniform(0, 2)) {
        c.depthIn.create(size, CV_32FC1);
        for (int y = 0; y < size.height; y++)
            for (int x = 0; x < size.width; x++)
                c.depthIn.at<float>(y, x) =
                    rng.uniform(0, 5) < 2 ? kInf : (float)rng.uniform(0.1, 5.0);
    }
    c.forms.vertsMat = rng.uniform(0, 3) == 0;
    c.forms.vertsFloat = !c.forms.vertsMat && rng.uniform(0, 3) == 0;
    c.forms.kFloat = rng.uniform(0, 2) == 0;  // K is float-representable, so this is lossless
    c.forms.rotationMatrix = rng.uniform(0, 4) == 0;
    return c;
}

bool anyClipped(const Scene& sc)
{
    for (const Vec3d& v : sc.verts)
        if (shading_ref3d::finite(v) && !(sc.cam.toCamera(v)[2] >= sc.settings.zNear))
            return true;
    return false;
}

void runRandom(MeshKind kind, int count, uint64 seed)
{
    cv::RNG rng(seed);
    Stats stats;
    int failures = 0, clippedScenes = 0;
    for (int i = 0; i < count && failures < 5; i++) {
        const Case c = randomCase(rng, kind);
        const shading_ref3d::Result ref = shading_ref3d::render(c.scene, c.canvas, c.depthIn);
        const LibOut lib = runLib(c.scene, c.canvas, c.depthIn, c.forms);
        clippedScenes += anyClipped(c.scene);
        const std::string what = cv::format("seed %llu, scene %d", (unsigned long long)seed, i);
        failures += compare(c.scene, c.canvas, c.depthIn, ref, lib, stats, what) > 0;
        // Without the optional outputs the picture is the same.
        if (i % 4 == 0 && c.depthIn.empty()) {
            cv::Mat canvas = c.canvas.clone();
            sh::drawMesh3d(canvas, c.scene.verts, c.scene.faces, c.scene.colors,
                           cameraMatrix(c.scene.cam), cv::Mat(c.scene.cam.R),
                           cv::Mat(c.scene.cam.t), toLib(c.scene.settings), c.scene.normals);
            EXPECT_EQ(0, cv::norm(canvas, lib.canvas, cv::NORM_INF)) << what << " (no outputs)";
        }
    }
    EXPECT_EQ(0, failures);
    // The comparison must have teeth: few pixels skipped, many drawn, many scenes clipped.
    EXPECT_LT(stats.ambiguous, stats.pixels / 50) << stats.ambiguous << " of " << stats.pixels;
    EXPECT_GT(stats.drawn, stats.pixels / 10);
    EXPECT_GT(clippedScenes, count / 5);
    std::printf("[ stats    ] %ld pixels, %ld drawn, %ld ambiguous; %ld depths: interval width "
                "mean %.2g max %.2g, error beyond it %.2g (relative); %ld colours: error beyond "
                "the interval %.2g (float), %.2g (8-bit); %d of %d scenes clipped\n",
                stats.pixels, stats.drawn, stats.ambiguous, stats.depthChecked,
                stats.sumDepthWidth / std::max(1L, stats.depthChecked), stats.maxDepthWidth,
                stats.maxDepthRel, stats.colorChecked, stats.maxColorF, stats.maxColor8,
                clippedScenes, count);
}

TEST(Mesh3dReference, RandomSoups) { runRandom(SOUP, 120, 0x3d50u); }
TEST(Mesh3dReference, RandomHeightfields) { runRandom(HEIGHTFIELD, 80, 0x3d51u); }
TEST(Mesh3dReference, RandomClosedMeshes) { runRandom(CLOSED, 80, 0x3d52u); }

// Every vertex in front of the near plane: no clipping, so coverage is the 2D rule on the
// projected vertices and faceIds must be exactly the reference's (outside z-buffer near-ties).
TEST(Mesh3dReference, UnclippedScenesExactFaceIds)
{
    cv::RNG rng(0x3d53u);
    int done = 0;
    for (int i = 0; i < 400 && done < 60; i++) {
        Case c = randomCase(rng, MeshKind(i % 3));
        if (anyClipped(c.scene))
            continue;
        done++;
        const shading_ref3d::Result ref = shading_ref3d::render(c.scene, c.canvas, c.depthIn);
        const LibOut lib = runLib(c.scene, c.canvas, c.depthIn, c.forms);
        Stats stats;
        EXPECT_EQ(0, compare(c.scene, c.canvas, c.depthIn, ref, lib, stats,
                             cv::format("unclipped scene %d", i)));
        if (c.scene.settings.visibility == sh::VISIBILITY_PAINTER) {
            // Painter: no depth test at all, so every pixel must match.
            EXPECT_EQ(0, cv::norm(ref.faceIds, lib.faceIds, cv::NORM_INF)) << "scene " << i;
        }
    }
    EXPECT_GE(done, 30);
}

// Same pictures whatever the thread count, and with every band drawn in parts.
TEST(Mesh3dReference, ThreadCountIndependent)
{
    cv::RNG rng(0x3d54u);
    const int threads = cv::getNumThreads();
    for (int i = 0; i < 12; i++) {
        const Case c = randomCase(rng, MeshKind(i % 3));
        cv::setNumThreads(1);
        const LibOut a = runLib(c.scene, c.canvas, c.depthIn, c.forms);
        cv::setNumThreads(std::max(2, threads));
        const LibOut b = runLib(c.scene, c.canvas, c.depthIn, c.forms);
        LibOut parts;  // every band drawn in parts, as threads share bands
        {
            shading_test::SplitBands on(true);
            parts = runLib(c.scene, c.canvas, c.depthIn, c.forms);
        }
        cv::setNumThreads(threads);
        for (const LibOut* other : {&b, static_cast<const LibOut*>(&parts)}) {
            EXPECT_EQ(0, cv::norm(a.canvas, other->canvas, cv::NORM_INF)) << i;
            EXPECT_EQ(0, cv::norm(a.faceIds, other->faceIds, cv::NORM_INF)) << i;
            EXPECT_EQ(0, std::memcmp(a.depth.data, other->depth.data, a.depth.total() * 4)) << i;
        }
    }
}

// ---------------------------------------------------------------------------------------------
// computeNormals and lookAt

TEST(Mesh3dReference, ComputeNormalsMatchesReference)
{
    cv::RNG rng(0x3d55u);
    for (int i = 0; i < 30; i++) {
        Scene sc;
        if (i % 3 == 0)
            addSoup(rng, sc, false);
        else if (i % 3 == 1)
            addHeightfield(rng, sc);
        else
            addClosed(rng, sc);
        sc.verts.push_back(Vec3d(9, 9, 9));  // unused: zero normal
        std::vector<Vec3d> refFace;
        const std::vector<Vec3d> refVert =
            shading_ref3d::computeNormals(sc.verts, sc.faces, &refFace);
        cv::Mat vn, fn;
        sh::computeNormals(sc.verts, sc.faces, vn, fn);
        ASSERT_EQ(vn.type(), CV_32F);
        ASSERT_EQ(vn.rows, (int)sc.verts.size());
        ASSERT_EQ(vn.cols, 3);
        ASSERT_EQ(fn.type(), CV_32F);
        ASSERT_EQ(fn.rows, (int)sc.faces.size());
        ASSERT_EQ(fn.cols, 3);
        for (int v = 0; v < vn.rows; v++)
            for (int k = 0; k < 3; k++)
                EXPECT_NEAR(refVert[v][k], vn.at<float>(v, k), 1e-6) << "vertex " << v;
        for (int f = 0; f < fn.rows; f++)
            for (int k = 0; k < 3; k++)
                EXPECT_NEAR(refFace[f][k], fn.at<float>(f, k), 1e-6) << "face " << f;
    }
}

// Opposite faces on the same vertices: the unit normals cancel exactly, so the vertex normals
// are zero.
TEST(Mesh3dReference, ComputeNormalsCancelToZero)
{
    const std::vector<Vec3d> verts = { Vec3d(0, 0, 0), Vec3d(1, 0.25, 0), Vec3d(0.5, 1, 0.3) };
    const Faces faces = { cv::Vec3i(0, 1, 2), cv::Vec3i(0, 2, 1) };
    cv::Mat vn;
    sh::computeNormals(verts, faces, vn);
    EXPECT_EQ(0, cv::norm(vn, cv::NORM_INF));
}

TEST(Mesh3dReference, LookAtMatchesReference)
{
    cv::RNG rng(0x3d56u);
    for (int i = 0; i < 200; i++) {
        const Vec3d eye(rng.uniform(-5.0, 5.0), rng.uniform(-5.0, 5.0), rng.uniform(-5.0, 5.0));
        const Vec3d target(rng.uniform(-5.0, 5.0), rng.uniform(-5.0, 5.0),
                           rng.uniform(-5.0, 5.0));
        const Vec3d up = randomUnit(rng) * rng.uniform(0.1, 3.0);
        if (std::abs(cv::normalize(up).dot(cv::normalize(target - eye))) > 0.999)
            continue;
        Matx33d R;
        Vec3d t;
        shading_ref3d::lookAt(eye, target, up, R, t);
        cv::Mat rvec, tvec;
        sh::lookAt(cv::Point3d(eye), cv::Point3d(target), up, rvec, tvec);
        ASSERT_EQ(rvec.type(), CV_64F);
        ASSERT_EQ(rvec.total(), 3u);
        ASSERT_EQ(tvec.type(), CV_64F);
        ASSERT_EQ(tvec.total(), 3u);
        const Matx33d Rl = shading_ref3d::rodrigues(Vec3d(rvec.ptr<double>()));
        EXPECT_LT(cv::norm(Rl - R, cv::NORM_INF), 1e-12) << i;
        EXPECT_LT(cv::norm(Vec3d(tvec.ptr<double>()) - t, cv::NORM_INF), 1e-12) << i;
    }
}

// The hand-worked frames (see the reference's self-test): a half turn about x, and a scene seen
// from +x with z up. The half turn is where a naive matrix-to-Rodrigues conversion fails.
TEST(Mesh3dReference, LookAtHandWorked)
{
    cv::Mat rvec, tvec;
    sh::lookAt(cv::Point3d(0, 0, 5), cv::Point3d(0, 0, 0), Vec3d(0, 1, 0), rvec, tvec);
    EXPECT_LT(cv::norm(shading_ref3d::rodrigues(Vec3d(rvec.ptr<double>())) -
                       Matx33d(1, 0, 0, 0, -1, 0, 0, 0, -1), cv::NORM_INF), 1e-12);
    EXPECT_LT(cv::norm(Vec3d(tvec.ptr<double>()) - Vec3d(0, 0, 5), cv::NORM_INF), 1e-12);

    sh::lookAt(cv::Point3d(5, 0, 0), cv::Point3d(0, 0, 0), Vec3d(0, 0, 1), rvec, tvec);
    EXPECT_LT(cv::norm(shading_ref3d::rodrigues(Vec3d(rvec.ptr<double>())) -
                       Matx33d(0, 1, 0, 0, 0, -1, -1, 0, 0), cv::NORM_INF), 1e-12);
    EXPECT_LT(cv::norm(Vec3d(tvec.ptr<double>()) - Vec3d(0, 0, 5), cv::NORM_INF), 1e-12);

    EXPECT_THROW(sh::lookAt(cv::Point3d(1, 2, 3), cv::Point3d(1, 2, 3), Vec3d(0, 1, 0), rvec,
                            tvec), cv::Exception);
    EXPECT_THROW(sh::lookAt(cv::Point3d(0, 0, 5), cv::Point3d(0, 0, 0), Vec3d(0, 0, 2), rvec,
                            tvec), cv::Exception);
    // Parallel but not along an axis: the residual is rounding noise, still parallel.
    EXPECT_THROW(sh::lookAt(cv::Point3d(0.1, 0.2, 0.3), cv::Point3d(1.3, -0.7, 2.9),
                            Vec3d(1.2, -0.9, 2.6) * 3, rvec, tvec), cv::Exception);
}

// ---------------------------------------------------------------------------------------------
// Hand-worked scenes: library and reference against values worked out on paper

// Identity pose, fx = fy = 10, c = (10, 10), no skew.
Scene handScene(const std::vector<Vec3d>& verts, const Faces& faces,
                const std::vector<Vec3d>& colors)
{
    Scene sc;
    sc.verts = verts;
    sc.faces = faces;
    sc.colors = colors;
    sc.cam.fx = sc.cam.fy = 10;
    sc.cam.cx = sc.cam.cy = 10;
    return sc;
}

const std::vector<Vec3d> kTriangleAt2 = { Vec3d(-1, -1, 2), Vec3d(1, -1, 2), Vec3d(-1, 1, 2) };

// A fronto-parallel triangle at Z = 2 projects to (5, 5), (15, 5), (5, 15): coverage is the 2D
// rule on those points, depth 2 everywhere, flat colour the mean.
TEST(Mesh3dReference, HandFrontoParallelTriangle)
{
    Scene sc = handScene(kTriangleAt2, Faces{ cv::Vec3i(0, 1, 2) },
                         { Vec3d(0.3, 0.6, 0.9), Vec3d(0.3, 0.0, 0.0), Vec3d(0.0, 0.0, 0.3) });
    sc.settings.shadeType = sh::SHADE_FLAT;
    const cv::Mat canvas(20, 20, CV_32FC3, cv::Scalar::all(-1));
    const LibOut lib = runLib(sc, canvas, cv::Mat(), Forms());
    const cv::Point2d p[3] = { { 5, 5 }, { 15, 5 }, { 5, 15 } };
    const cv::Mat mask = shading_ref::coverageMask(canvas.size(), p);
    ASSERT_EQ(lib.faceIds.type(), CV_32SC1);
    int covered = 0;
    for (int y = 0; y < 20; y++)
        for (int x = 0; x < 20; x++) {
            const bool in = mask.at<uchar>(y, x) != 0;
            covered += in;
            EXPECT_EQ(in ? 0 : -1, lib.faceIds.at<int>(y, x)) << x << ", " << y;
            if (in) {
                EXPECT_EQ(2.0f, lib.depth.at<float>(y, x));
                const cv::Vec3f c = lib.canvas.at<cv::Vec3f>(y, x);
                EXPECT_NEAR(0.2, c[0], 1e-6);
                EXPECT_NEAR(0.2, c[1], 1e-6);
                EXPECT_NEAR(0.4, c[2], 1e-6);
            } else {
                EXPECT_EQ(kInf, lib.depth.at<float>(y, x));
            }
        }
    EXPECT_EQ(55, covered);  // rows 5..14 hold 10, 9, ..., 1 samples
}

// A floor Y = 1 in front of the camera, X in [-1, 1], Z from zFrom to 8; fx = fy = 16,
// c = (12, 2): every vertex projects onto the 1/256 grid (the far edge to row 4), so snapping
// changes nothing. Row v sees the floor at Z = 16 / (v - 2) exactly: at v = 10, Z = 2. The
// colour ramps from 0 at Z = 1 to 1 at Z = 8, so perspective-correct Gouraud gives
// (Z - 1) / 7 = 1/7 there, where affine screen-space interpolation would give 4/7 (depth 5).
Scene floorScene(double zFrom)
{
    Scene sc;
    sc.verts = { Vec3d(-1, 1, zFrom), Vec3d(1, 1, zFrom), Vec3d(1, 1, 8), Vec3d(-1, 1, 8) };
    sc.faces = Faces{ cv::Vec3i(0, 1, 2), cv::Vec3i(0, 2, 3) };
    const double c0 = (zFrom - 1) / 7;
    sc.colors = { Vec3d::all(c0), Vec3d::all(c0), Vec3d::all(1), Vec3d::all(1) };
    sc.cam.fx = sc.cam.fy = 16;
    sc.cam.cx = 12;
    sc.cam.cy = 2;
    return sc;
}

TEST(Mesh3dReference, HandSteepQuadIsPerspectiveCorrect)
{
    const Scene sc = floorScene(1);
    const cv::Mat canvas(20, 24, CV_32FC3, cv::Scalar::all(-1));
    const LibOut lib = runLib(sc, canvas, cv::Mat(), Forms());
    const shading_ref3d::Result ref = shading_ref3d::render(sc, canvas);
    ASSERT_EQ(lib.depth.type(), CV_32FC1);
    for (int y = 4; y < 18; y++) {
        const double z = 16.0 / (y - 2);
        EXPECT_GE(lib.faceIds.at<int>(y, 12), 0) << y;
        EXPECT_NEAR(z, lib.depth.at<float>(y, 12), 1e-5 * z) << y;
        EXPECT_NEAR((z - 1) / 7, lib.canvas.at<cv::Vec3f>(y, 12)[0], 1e-5) << y;
        EXPECT_NEAR(z, ref.depth.at<float>(y, 12), 1e-5 * z) << y;
        EXPECT_NEAR((z - 1) / 7, ref.canvas.at<cv::Vec3f>(y, 12)[0], 1e-5) << y;
    }
    EXPECT_NEAR(1.0 / 7, lib.canvas.at<cv::Vec3f>(10, 12)[1], 1e-5);  // not the affine 4/7
    EXPECT_NEAR(2.0, lib.depth.at<float>(10, 12), 1e-5);              // not the affine 5
    Stats stats;
    EXPECT_EQ(0, compare(sc, canvas, cv::Mat(), ref, lib, stats, "steep quad"));
}

// The same floor from Z = -5 (behind the camera) with zNear = 0.5: clipped at the near plane,
// which projects to row 2 + 16 / 0.5 = 34, below the canvas. Every row from the far edge down
// shows the floor at Z = 16 / (v - 2), and nothing from behind the camera is drawn (rows 0..3
// stay empty, where the part behind the camera would land without clipping).
TEST(Mesh3dReference, HandNearPlaneClipping)
{
    Scene sc = floorScene(-5);
    sc.settings.zNear = 0.5;
    const cv::Mat canvas(20, 24, CV_32FC3, cv::Scalar::all(-1));
    const LibOut lib = runLib(sc, canvas, cv::Mat(), Forms());
    const shading_ref3d::Result ref = shading_ref3d::render(sc, canvas);
    for (int y = 0; y <= 3; y++)
        for (int x = 0; x < 24; x++)
            EXPECT_EQ(-1, lib.faceIds.at<int>(y, x)) << x << ", " << y;
    for (int y = 4; y < 20; y++) {
        const double z = 16.0 / (y - 2);
        EXPECT_GE(lib.faceIds.at<int>(y, 12), 0) << y;
        EXPECT_NEAR(z, lib.depth.at<float>(y, 12), 1e-5 * z) << y;
        EXPECT_NEAR((z - 1) / 7, lib.canvas.at<cv::Vec3f>(y, 12)[0], 1e-5) << y;
    }
    Stats stats;
    EXPECT_EQ(0, compare(sc, canvas, cv::Mat(), ref, lib, stats, "clipped floor"));
}

// Faces with a vertex that projects millions of pixels off the canvas (in front of the near
// plane: no clipping) among small ones: the band pass's first pass, which boxes 8 faces at once
// in 32-bit lanes where every vertex allows (the AVX2 build), must box these in 64 bits. Each
// 3 x 3 block of small faces is followed by a far one, so that every step of 8 holds one.
TEST(Mesh3dReference, VerticesFarOffTheCanvas)
{
    std::vector<Vec3d> verts, colors;
    Faces faces;
    cv::RNG rng(0x3d60u);
    for (int i = 0; i < 48; i++) {
        const double x = -0.9 + 0.15 * (i % 12), y = -0.9 + 0.45 * (i / 12);
        const int v = (int)verts.size();
        verts.push_back(Vec3d(x, y, 2));
        verts.push_back(Vec3d(x + 0.3, y + 0.1, 2.5));
        verts.push_back(Vec3d(x + 0.05, y + 0.4, 1.5));
        faces.push_back(cv::Vec3i(v, v + 1, v + 2));
        if (i % 3 == 2) {
            // x = 10 * 11.7 / 1e-5 = 1.17e7 px, 3.0e9 subpixels, which wraps in 32 bits; or as
            // far to the left, or below.
            const double far[3][2] = { { 11.7, 0 }, { -11.7, 0.5 }, { 0.3, 11.7 } };
            const double* d = far[i % 9 / 3];
            verts.push_back(Vec3d(d[0], d[1], 1e-5));
            faces.push_back(cv::Vec3i(v, v + 3, v + 2));
        }
    }
    for (size_t i = 0; i < verts.size(); i++)
        colors.push_back(
            Vec3d(rng.uniform(0.0, 1.0), rng.uniform(0.0, 1.0), rng.uniform(0.0, 1.0)));
    Scene sc = handScene(verts, faces, colors);
    sc.settings.zNear = 1e-6;
    const cv::Mat canvas(20, 24, CV_32FC3, cv::Scalar::all(-1));
    for (int vis : { sh::VISIBILITY_ZBUFFER, sh::VISIBILITY_PAINTER })
        for (int shade : { sh::SHADE_FLAT, sh::SHADE_GOURAUD }) {
            sc.settings.visibility = vis;
            sc.settings.shadeType = shade;
            const LibOut lib = runLib(sc, canvas, cv::Mat(), Forms());
            const shading_ref3d::Result ref = shading_ref3d::render(sc, canvas);
            Stats stats;
            EXPECT_EQ(0, compare(sc, canvas, cv::Mat(), ref, lib, stats,
                                 cv::format("visibility %d shade %d", vis, shade)));
            EXPECT_GT(stats.drawn, stats.pixels / 4);
        }
}

// A triangle wholly between the camera and the near plane, and one behind the camera: nothing.
TEST(Mesh3dReference, HandBehindNearPlaneDrawsNothing)
{
    Scene sc = handScene({ Vec3d(-1, -1, 0.5), Vec3d(1, -1, 0.5), Vec3d(-1, 1, 0.5),
                           Vec3d(-1, -1, -2), Vec3d(1, -1, -2), Vec3d(-1, 1, -2) },
                         Faces{ cv::Vec3i(0, 1, 2), cv::Vec3i(3, 4, 5) },
                         std::vector<Vec3d>(6, Vec3d(1, 1, 1)));
    sc.settings.zNear = 0.75;
    const cv::Mat canvas(20, 20, CV_32FC3, cv::Scalar::all(-1));
    const LibOut lib = runLib(sc, canvas, cv::Mat(), Forms());
    EXPECT_EQ(0, cv::norm(lib.canvas, canvas, cv::NORM_INF));
    EXPECT_EQ(0, cv::norm(lib.faceIds, cv::Mat(20, 20, CV_32SC1, cv::Scalar(-1)), cv::NORM_INF));
}

// The same triangle twice at the same depth: the z-buffer keeps the earlier face (strict test),
// the painter draws the later one last.
TEST(Mesh3dReference, HandTies)
{
    Scene sc = handScene(kTriangleAt2, Faces{ cv::Vec3i(0, 1, 2), cv::Vec3i(1, 2, 0) },
                         std::vector<Vec3d>(3, Vec3d(1, 0, 0)));
    const cv::Mat canvas(20, 20, CV_32FC3, cv::Scalar::all(-1));
    for (int vis : { sh::VISIBILITY_ZBUFFER, sh::VISIBILITY_PAINTER }) {
        sc.settings.visibility = vis;
        const LibOut lib = runLib(sc, canvas, cv::Mat(), Forms());
        const shading_ref3d::Result ref = shading_ref3d::render(sc, canvas);
        const int want = vis == sh::VISIBILITY_ZBUFFER ? 0 : 1;
        EXPECT_EQ(want, lib.faceIds.at<int>(7, 7)) << vis;
        EXPECT_EQ(want, ref.faceIds.at<int>(7, 7)) << vis;
        EXPECT_EQ(0, cv::norm(lib.faceIds, ref.faceIds, cv::NORM_INF)) << vis;
    }
}

// A given depth buffer: the z-test is strict against it, in float.
TEST(Mesh3dReference, HandGivenDepthBuffer)
{
    Scene sc = handScene(kTriangleAt2, Faces{ cv::Vec3i(0, 1, 2) },
                         std::vector<Vec3d>(3, Vec3d(1, 0, 0)));
    const cv::Mat canvas(20, 20, CV_32FC3, cv::Scalar::all(-1));
    cv::Mat depth(20, 20, CV_32FC1, cv::Scalar(kInf));
    depth.at<float>(6, 6) = 1.5f;
    depth.at<float>(6, 7) = 2.0f;  // equal: not drawn
    depth.at<float>(6, 8) = std::nextafter(2.0f, 3.0f);
    depth.at<float>(6, 9) = 2.5f;
    const LibOut lib = runLib(sc, canvas, depth, Forms());
    EXPECT_EQ(-1, lib.faceIds.at<int>(6, 6));
    EXPECT_EQ(-1, lib.faceIds.at<int>(6, 7));
    EXPECT_EQ(0, lib.faceIds.at<int>(6, 8));
    EXPECT_EQ(0, lib.faceIds.at<int>(6, 9));
    EXPECT_EQ(1.5f, lib.depth.at<float>(6, 6));
    EXPECT_EQ(2.0f, lib.depth.at<float>(6, 7));
    EXPECT_EQ(2.0f, lib.depth.at<float>(6, 8));
    EXPECT_EQ(2.0f, lib.depth.at<float>(6, 9));
    EXPECT_EQ(cv::Vec3f(-1, -1, -1), lib.canvas.at<cv::Vec3f>(6, 6));
    EXPECT_EQ(cv::Vec3f(1, 0, 0), lib.canvas.at<cv::Vec3f>(6, 9));
    // Painter ignores the buffer's values but still records the drawn depth.
    sc.settings.visibility = sh::VISIBILITY_PAINTER;
    const LibOut p = runLib(sc, canvas, depth, Forms());
    EXPECT_EQ(0, p.faceIds.at<int>(6, 6));
    EXPECT_EQ(2.0f, p.depth.at<float>(6, 6));
}

// Culling: as given, the triangle's normal (0, 0, 4) points away from the camera at the origin
// (n.(E - v0) = -8): a back face; face 1 is the same triangle wound the other way.
TEST(Mesh3dReference, HandCulling)
{
    Scene sc = handScene(kTriangleAt2, Faces{ cv::Vec3i(0, 1, 2), cv::Vec3i(0, 2, 1) },
                         std::vector<Vec3d>(3, Vec3d(1, 0, 0)));
    const cv::Mat canvas(20, 20, CV_32FC3, cv::Scalar::all(-1));
    sc.settings.cullMode = sh::CULL_BACK;
    EXPECT_EQ(1, runLib(sc, canvas, cv::Mat(), Forms()).faceIds.at<int>(7, 7));
    sc.settings.cullMode = sh::CULL_FRONT;
    EXPECT_EQ(0, runLib(sc, canvas, cv::Mat(), Forms()).faceIds.at<int>(7, 7));
    sc.settings.cullMode = sh::CULL_NONE;
    EXPECT_EQ(0, runLib(sc, canvas, cv::Mat(), Forms()).faceIds.at<int>(7, 7));
}

// One white light at the eye, the face's centroid on the optical axis: N = L = V and R = V, so
// the flat colour is c (ka + kd) + ks = 0.5 * 0.9 + 0.5 = 0.95 with the default material. Wound
// the other way the normal faces away (normals are one-sided): ambient only, 0.5 * 0.2 = 0.1.
// On 8-bit, c = 102 is 0.4: 0.4 * 0.9 + 0.5 = 0.86, 219.3 -> 219.
TEST(Mesh3dReference, HandFlatLighting)
{
    Scene sc = handScene({ Vec3d(-1, -1, 2), Vec3d(2, -1, 2), Vec3d(-1, 2, 2) },
                         Faces{ cv::Vec3i(0, 2, 1) }, std::vector<Vec3d>(3, Vec3d::all(0.5)));
    sc.settings.shadeType = sh::SHADE_FLAT;
    sc.settings.lights.push_back(Light{ Vec3d(0, 0, 0), Vec3d(1, 1, 1) });
    const cv::Mat canvas(20, 20, CV_32FC3, cv::Scalar::all(-1));
    LibOut lib = runLib(sc, canvas, cv::Mat(), Forms());
    EXPECT_NEAR(0.95, lib.canvas.at<cv::Vec3f>(10, 10)[0], 1e-6);
    EXPECT_NEAR(0.95, shading_ref3d::render(sc, canvas).canvas.at<cv::Vec3f>(10, 10)[0], 1e-7);
    sc.faces = Faces{ cv::Vec3i(0, 1, 2) };
    lib = runLib(sc, canvas, cv::Mat(), Forms());
    EXPECT_NEAR(0.1, lib.canvas.at<cv::Vec3f>(10, 10)[0], 1e-6);
    sc.faces = Faces{ cv::Vec3i(0, 2, 1) };
    sc.colors.assign(3, Vec3d::all(102));
    const cv::Mat canvas8(20, 20, CV_8UC3, cv::Scalar::all(7));
    lib = runLib(sc, canvas8, cv::Mat(), Forms());
    EXPECT_EQ(cv::Vec3b(219, 219, 219), lib.canvas.at<cv::Vec3b>(10, 10));
}

}  // namespace
