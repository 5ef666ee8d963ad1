// The band pass is built for the baseline instruction set and for AVX2 (bands.hpp): both builds
// draw the same images, depth and id maps bit for bit, on the benchmark scenes (2D and 3D, every
// shading and visibility, textured or not, float and 8-bit canvases).
#include "../modules/shading/perf/perf_scenes.hpp"
#include "../modules/shading/src/bands.hpp"

#include <gtest/gtest.h>
#include <opencv2/core.hpp>
#include <opencv2/shading.hpp>

#include <algorithm>
#include <functional>
#include <limits>
#include <string>

using namespace cv;
using cv::shading::detail::KernelBuild;
using cv::shading::detail::useBandBuild;

namespace {

//! Bytes of `a` and `b` that differ (0 when equal; sizes and types must match).
size_t differingBytes(const Mat& a, const Mat& b)
{
    if (a.size() != b.size() || a.type() != b.type())
        return size_t(-1);
    size_t n = 0;
    for (int y = 0; y < a.rows; y++)
        for (size_t i = 0; i < a.cols * a.elemSize(); i++)
            n += a.ptr<uchar>(y)[i] != b.ptr<uchar>(y)[i];
    return n;
}

//! Draws with each build (outputs: canvas, then any depth or ids maps) and compares them.
void expectBuildsAgree(const std::function<std::vector<Mat>()>& draw, const std::string& what)
{
    ASSERT_EQ(useBandBuild(KernelBuild::kBaseline), KernelBuild::kBaseline);
    const std::vector<Mat> base = draw();
    const bool avx2 = useBandBuild(KernelBuild::kAvx2) == KernelBuild::kAvx2;
    if (!avx2)
        GTEST_SKIP() << "no AVX2 build, or a CPU without AVX2";
    const std::vector<Mat> other = draw();
    ASSERT_EQ(base.size(), other.size());
    // Something was drawn: the canvas started uniform.
    Mat gray;
    base[0].reshape(1).convertTo(gray, CV_64F);
    double lo, hi;
    minMaxLoc(gray, &lo, &hi);
    EXPECT_LT(lo, hi) << what;
    for (size_t i = 0; i < base.size(); i++)
        EXPECT_EQ(differingBytes(base[i], other[i]), 0u) << what << ", output " << i;
}

class BandBuilds : public testing::Test {
protected:
    void TearDown() override { useBandBuild(KernelBuild::kAvx2); }  // the best the CPU runs
};

TEST_F(BandBuilds, Scenes2dAgreeBitForBit)
{
    for (const char* kind : {"grid", "sphere", "random", "demo"}) {
        const shading_perf::Scene scene = shading_perf::makeScene(kind, 256);
        const auto& m = scene.mesh;
        for (int shade : {shading::SHADE_FLAT, shading::SHADE_GOURAUD}) {
            expectBuildsAgree(
                [&] {
                    Mat img;
                    shading::render(m.verts2d, m.faces, m.vcolors, m.depth, img, shade,
                                    Size(256, 256), Scalar(0.1, 0.2, 0.3));
                    return std::vector<Mat>{img};
                },
                std::string(kind) + " render, shade " + std::to_string(shade));
            expectBuildsAgree(
                [&] {
                    Mat colors, img(256, 256, CV_8UC3, Scalar(1, 2, 3));
                    m.vcolors.convertTo(colors, CV_32F, 255.0);
                    shading::drawMesh(img, m.verts2d, m.faces, colors, m.depth, shade);
                    return std::vector<Mat>{img};
                },
                std::string(kind) + " 8-bit drawMesh, shade " + std::to_string(shade));
        }
    }
}

// Faces across the canvas's edges, on sample rows and columns, far off it, beyond the 2^40 limit
// or NaN (skipped), and degenerate: where the builds' small-face walks (8 columns in one vector,
// or two of 4) meet the canvas's last columns and clipped rows.
TEST_F(BandBuilds, FacesAcrossTheEdgesAgreeBitForBit)
{
    const Size size(97, 61);
    RNG rng(20261125);
    // Coordinates on and near the edges' samples, far away, and anywhere around the canvas.
    auto coordinate = [&](int extent) {
        const double special[] = {std::numeric_limits<double>::quiet_NaN(), -1e13, -1e12, -1e6, -1.0, -0.5, -1.0 / 256, 0.0, 1.0 / 256, 0.5,
                                  extent - 1.0, extent - 1.0 + 1.0 / 256, extent - 0.5,
                                  extent - 1.0 / 256, double(extent), extent + 1.0 / 256,
                                  extent + 1.0, 1e6, 1e12, 1e13};
        const int pick = rng.uniform(0, 4);
        if (pick == 0)
            return special[rng.uniform(0, int(sizeof(special) / sizeof(special[0])))];
        if (pick == 1)  // on the subpixel grid, near the canvas
            return rng.uniform(-3 * 256, (extent + 3) * 256) / 256.0;
        return rng.uniform(-0.5 * extent, 1.5 * extent);
    };
    const int vertexCount = 3001;  // faces: not a multiple of four
    Mat verts(vertexCount, 2, CV_64F), colors(vertexCount, 3, CV_32F), depth(vertexCount, 1, CV_64F);
    for (int i = 0; i < vertexCount; i++) {
        verts.at<double>(i, 0) = coordinate(size.width);
        verts.at<double>(i, 1) = coordinate(size.height);
        depth.at<double>(i) = rng.uniform(0.0, 10.0);
        for (int k = 0; k < 3; k++)
            colors.at<float>(i, k) = float(rng.uniform(0.0, 1.0));
    }
    Mat faces(4001, 3, CV_32S);
    for (int i = 0; i < faces.rows; i++) {
        // Mostly small faces: neighbouring vertices, with repeats (degenerate faces).
        const int first = rng.uniform(0, vertexCount);
        for (int k = 0; k < 3; k++)
            faces.at<int>(i, k) = k == 0 || rng.uniform(0, 8) == 0
                                      ? first
                                      : std::min(vertexCount - 1, first + rng.uniform(0, 40));
    }
    for (int shade : {shading::SHADE_FLAT, shading::SHADE_GOURAUD})
        for (bool byDepth : {false, true})
            expectBuildsAgree(
                [&] {
                    Mat img;
                    shading::render(verts, faces, colors, byDepth ? depth : Mat(), img, shade,
                                    size, Scalar(0.1, 0.2, 0.3));
                    return std::vector<Mat>{img};
                },
                "shade " + std::to_string(shade) + (byDepth ? ", by depth" : ", in face order"));
}

TEST_F(BandBuilds, Scenes3dAgreeBitForBit)
{
    const shading_perf::Scene3d sc = shading_perf::makeScene3d("knot3d", 256);
    const shading_perf::TexturedScene3d ts = shading_perf::makeTexturedScene3d("knot3d", 256);
    for (int shade : {shading::SHADE_FLAT, shading::SHADE_GOURAUD, shading::SHADE_PHONG})
        for (int vis : {shading::VISIBILITY_ZBUFFER, shading::VISIBILITY_PAINTER})
            for (int type : {CV_32FC3, CV_8UC3}) {
                shading::RenderSettings s = sc.settings;
                s.shadeType = shade;
                s.visibility = vis;
                const double unit = type == CV_8UC3 ? 255.0 : 1.0;
                const std::string what = "knot, shade " + std::to_string(shade) + ", visibility " +
                                         std::to_string(vis) + ", type " + std::to_string(type);
                expectBuildsAgree(
                    [&] {
                        Mat canvas(sc.size, type, Scalar::all(0.5 * unit)), depth, ids, colors;
                        sc.mesh.vcolors.convertTo(colors, CV_32F, unit);
                        shading::drawMesh3d(canvas, sc.mesh.verts3d, sc.mesh.faces, colors,
                                            sc.cameraMatrix, sc.rvec, sc.tvec, s,
                                            sc.mesh.normals, depth, ids);
                        return std::vector<Mat>{canvas, depth, ids};
                    },
                    what);
                if (shade == shading::SHADE_FLAT && vis == shading::VISIBILITY_PAINTER)
                    expectBuildsAgree(  // no outputs: the faces take render()'s flat shader
                        [&] {
                            Mat canvas(sc.size, type, Scalar::all(0.5 * unit)), colors;
                            sc.mesh.vcolors.convertTo(colors, CV_32F, unit);
                            shading::drawMesh3d(canvas, sc.mesh.verts3d, sc.mesh.faces, colors,
                                                sc.cameraMatrix, sc.rvec, sc.tvec, s,
                                                sc.mesh.normals);
                            return std::vector<Mat>{canvas};
                        },
                        what + ", colour only");
                s.textureBorder = BORDER_WRAP;  // the coordinates run past the texture
                expectBuildsAgree(
                    [&] {
                        Mat canvas(sc.size, type, Scalar::all(0.5 * unit)), depth, ids;
                        const auto& m = ts.scene.mesh;
                        shading::drawTexturedMesh3d(
                            canvas, m.verts3d, m.faces, ts.texCoords,
                            type == CV_8UC3 ? ts.texture8u : ts.texture32f,
                            ts.scene.cameraMatrix, ts.scene.rvec, ts.scene.tvec, s, m.normals,
                            depth, ids);
                        return std::vector<Mat>{canvas, depth, ids};
                    },
                    "textured " + what);
            }
}

// The 3D surfaces the lit knot leaves out, unlit (Gouraud and textured colours as given, flat
// faces' mean colours), and faces cut by the near plane (new vertices, and faces that are not
// the caller's): tiny faces take the AVX2 build's 8-face setup, the baseline the one-face one.
TEST_F(BandBuilds, Scenes3dUnlitAndClippedAgreeBitForBit)
{
    const shading_perf::Scene3d sc = shading_perf::makeScene3d("knot3d", 256);
    const shading_perf::TexturedScene3d ts = shading_perf::makeTexturedScene3d("knot3d", 256);
    // The eye is 9.1 from the knot's centre, and the knot 3.4 across: 8.5 cuts through it.
    for (double zNear : {1.0, 8.5})
        for (bool lit : {false, true})
            for (int shade : {shading::SHADE_FLAT, shading::SHADE_GOURAUD, shading::SHADE_PHONG})
                for (int vis : {shading::VISIBILITY_ZBUFFER, shading::VISIBILITY_PAINTER}) {
                    if (lit && zNear == 1.0)
                        continue;  // Scenes3dAgreeBitForBit
                    shading::RenderSettings s = sc.settings;
                    s.shadeType = shade;
                    s.visibility = vis;
                    s.zNear = zNear;
                    s.textureBorder = BORDER_WRAP;
                    if (!lit)
                        s.lights.clear();
                    const std::string what = "knot, zNear " + std::to_string(zNear) +
                                             (lit ? ", lit" : ", unlit") + ", shade " +
                                             std::to_string(shade) + ", visibility " +
                                             std::to_string(vis);
                    expectBuildsAgree(
                        [&] {
                            Mat canvas(sc.size, CV_32FC3, Scalar::all(0.5)), depth, ids;
                            shading::drawMesh3d(canvas, sc.mesh.verts3d, sc.mesh.faces,
                                                sc.mesh.vcolors, sc.cameraMatrix, sc.rvec,
                                                sc.tvec, s, sc.mesh.normals, depth, ids);
                            return std::vector<Mat>{canvas, depth, ids};
                        },
                        what);
                    expectBuildsAgree(
                        [&] {
                            Mat canvas(sc.size, CV_8UC3, Scalar::all(128)), depth, ids;
                            const auto& m = ts.scene.mesh;
                            shading::drawTexturedMesh3d(canvas, m.verts3d, m.faces, ts.texCoords,
                                                        ts.texture8u, ts.scene.cameraMatrix,
                                                        ts.scene.rvec, ts.scene.tvec, s,
                                                        m.normals, depth, ids);
                            return std::vector<Mat>{canvas, depth, ids};
                        },
                        "textured " + what);
                }
}

}  // namespace
