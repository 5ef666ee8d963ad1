// This file is part of opencv_shading. License: Apache-2.0.
//
// perf_render3d.hpp: the 3D benchmarks of opencv_shading_perf, cv::shading::drawMesh3d on the
// scenes of makeScene3d (perf_scenes.hpp), lit by three point lights:
//
//   drawMesh3d/SCENE/SHADE/VIS/threads:N  draw a frame: the CV_32FC3 canvas cleared to white
//                                         (and, for the z-buffer, the CV_32F depth buffer to
//                                         +inf) by the call itself (RenderSettings::clear, the
//                                         bands cleared as they are drawn), then the mesh
//   clear/SCENE/threads:1                 clearing both with setTo, alone: the floor
//
//   drawTexturedMesh3d/SCENE/SHADE/VIS/threads:N  the same with the scene's textured variant
//                                         (makeTexturedScene3d: a 512 x 512 texture, bilinear,
//                                         BORDER_WRAP) in place of the vertex colours
//
// SHADE is flat, gouraud or phong, VIS zbuffer or painter; SCENE names contain "3d", so
// --benchmark_filter=3d selects these and llvmpipe's 3D cells (perf_llvmpipe3d.hpp) only, and
// --benchmark_filter=Textured the textured cells and their llvmpipe peers only.
// Vertex normals come with the meshes (exact ones), as a static mesh's would, not per frame.
#ifndef OPENCV_SHADING_PERF_RENDER3D_HPP
#define OPENCV_SHADING_PERF_RENDER3D_HPP

#include "perf_baselines.hpp"
#include "perf_harness.hpp"
#include "perf_scenes.hpp"

#include <opencv2/core.hpp>
#include <opencv2/shading.hpp>

#include <limits>
#include <memory>
#include <string>
#include <vector>

namespace shading_perf {

//! The 3D benchmark scenes: the knot at 512 x 512, the million-face torus at 2048 x 2048.
inline std::vector<Scene3d> benchmarkScenes3d()
{
    return {makeScene3d("knot3d", 512), makeScene3d("torus3d", 2048)};
}

inline const char* shadeName3d(int shade)
{
    return shade == cv::shading::SHADE_FLAT      ? "flat"
           : shade == cv::shading::SHADE_GOURAUD ? "gouraud"
                                                 : "phong";
}

inline const char* visibilityName(int visibility)
{
    return visibility == cv::shading::VISIBILITY_ZBUFFER ? "zbuffer" : "painter";
}

//! METHOD/SCENE/SHADE/VIS/threads:N.
inline std::string cellName3d(const std::string& method, const Scene3d& sc, int shade,
                              int visibility, int threads)
{
    return method + "/" + sc.name + "/" + shadeName3d(shade) + "/" + visibilityName(visibility) +
           "/threads:" + std::to_string(threads);
}

//! Makes `canvas` a CV_32FC3 image cleared to white and, when `depth` is given, `depth` a
//! CV_32F buffer of +inf: what drawMesh3d starts a frame from.
inline void clearCanvas3d(cv::Mat& canvas, cv::Mat* depth, cv::Size size)
{
    clearCanvas(canvas, size);
    if (depth != nullptr) {
        depth->create(size, CV_32F);
        depth->setTo(std::numeric_limits<float>::infinity());
    }
}

/** A frame's start: `canvas` (and for the z-buffer `depth`) allocated, and `settings` told to
clear them to white (and +inf) as the call draws (RenderSettings::clear). */
inline void startFrame3d(cv::Size size, bool zbuffer, cv::Mat& canvas, cv::Mat& depth,
                         cv::shading::RenderSettings& settings)
{
    canvas.create(size, CV_32FC3);
    if (zbuffer)
        depth.create(size, CV_32F);
    settings.clear = true;
    settings.background = cv::Scalar::all(1);
}

/** One frame of drawMesh3d: draws `sc` with `shade` and `visibility` on a canvas it clears
(startFrame3d). The z-buffer uses `depth` (cleared by the call); painter's needs none.
`faceIds`, if given, receives the face ids. */
inline void drawScene3d(const Scene3d& sc, int shade, int visibility, cv::Mat& canvas,
                        cv::Mat& depth, cv::OutputArray faceIds = cv::noArray())
{
    const bool zbuffer = visibility == cv::shading::VISIBILITY_ZBUFFER;
    cv::shading::RenderSettings settings = sc.settings;  // a few vectors: cheap next to a frame
    startFrame3d(sc.size, zbuffer, canvas, depth, settings);
    settings.shadeType = shade;
    settings.visibility = visibility;
    const Mesh3d& m = sc.mesh;
    cv::shading::drawMesh3d(canvas, m.verts3d, m.faces, m.vcolors, sc.cameraMatrix, sc.rvec,
                            sc.tvec, settings, m.normals,
                            zbuffer ? cv::_InputOutputArray(depth) : cv::noArray(), faceIds);
}

inline const int kShades3d[] = {cv::shading::SHADE_FLAT, cv::shading::SHADE_GOURAUD,
                                cv::shading::SHADE_PHONG};
inline const int kVisibilities[] = {cv::shading::VISIBILITY_ZBUFFER,
                                    cv::shading::VISIBILITY_PAINTER};

//! All drawMesh3d benchmarks of one 3D scene, and its clear. `allThreads` as in addScene.
inline void addScene3d(const Scene3d& sc, int allThreads)
{
    const double triangles = sc.mesh.faces.rows, pixels = double(sc.size.area());
    for (int shade : kShades3d)
        for (int visibility : kVisibilities)
            for (int threads : {1, allThreads}) {
                if (threads != 1 && allThreads == 1)
                    continue;
                auto depth = std::make_shared<cv::Mat>();  // kept across frames
                addNamedBenchmark(cellName3d("drawMesh3d", sc, shade, visibility, threads),
                                  triangles, pixels, threads,
                                  [&sc, shade, visibility, depth](cv::Mat& img) {
                                      drawScene3d(sc, shade, visibility, img, *depth);
                                  });
            }
    auto depth = std::make_shared<cv::Mat>();
    addNamedBenchmark("clear/" + sc.name + "/threads:1", triangles, pixels, 1,
                      [&sc, depth](cv::Mat& img) { clearCanvas3d(img, depth.get(), sc.size); });
}

//! The textured 3D benchmark scenes: benchmarkScenes3d's, textured (makeTexturedScene3d).
inline std::vector<TexturedScene3d> benchmarkTexturedScenes3d()
{
    return {makeTexturedScene3d("knot3d", 512), makeTexturedScene3d("torus3d", 2048)};
}

/** One frame of drawTexturedMesh3d: draws `ts` with `shade` and `visibility` on a canvas it
clears, sampling its CV_32FC3 texture (the canvas's units: no conversion per frame) bilinearly
with BORDER_WRAP. As drawScene3d otherwise. */
inline void drawTexturedScene3d(const TexturedScene3d& ts, int shade, int visibility,
                                cv::Mat& canvas, cv::Mat& depth,
                                cv::OutputArray faceIds = cv::noArray())
{
    const Scene3d& sc = ts.scene;
    const bool zbuffer = visibility == cv::shading::VISIBILITY_ZBUFFER;
    cv::shading::RenderSettings settings = sc.settings;
    startFrame3d(sc.size, zbuffer, canvas, depth, settings);
    settings.shadeType = shade;
    settings.visibility = visibility;
    settings.textureInterpolation = cv::INTER_LINEAR;
    settings.textureBorder = cv::BORDER_WRAP;
    const Mesh3d& m = sc.mesh;
    cv::shading::drawTexturedMesh3d(canvas, m.verts3d, m.faces, ts.texCoords, ts.texture32f,
                                    sc.cameraMatrix, sc.rvec, sc.tvec, settings, m.normals,
                                    zbuffer ? cv::_InputOutputArray(depth) : cv::noArray(),
                                    faceIds);
}

/** All drawTexturedMesh3d benchmarks of one textured scene:
drawTexturedMesh3d/SCENE/SHADE/VIS/threads:N, lit as addScene3d's cells (the scene's three
lights), bilinear, BORDER_WRAP. */
inline void addTexturedScene3d(const TexturedScene3d& ts, int allThreads)
{
    const Scene3d& sc = ts.scene;
    const double triangles = sc.mesh.faces.rows, pixels = double(sc.size.area());
    for (int shade : kShades3d)
        for (int visibility : kVisibilities)
            for (int threads : {1, allThreads}) {
                if (threads != 1 && allThreads == 1)
                    continue;
                auto depth = std::make_shared<cv::Mat>();
                addNamedBenchmark(
                    cellName3d("drawTexturedMesh3d", sc, shade, visibility, threads), triangles,
                    pixels, threads, [&ts, shade, visibility, depth](cv::Mat& img) {
                        drawTexturedScene3d(ts, shade, visibility, img, *depth);
                    });
            }
}

}  // namespace shading_perf

#endif  // OPENCV_SHADING_PERF_RENDER3D_HPP
