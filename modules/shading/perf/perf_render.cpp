// This file is part of opencv_shading. License: Apache-2.0.
//
// opencv_shading_perf: cv::shading::render against its peers on the same scenes, in one run.
//
//   render          cv::shading::render (CV_32FC3, white background), 1 thread and all threads
//   plain           the plain single-threaded edge-function rasterizer (perf_baselines.hpp)
//   fillConvexPoly  cv::fillConvexPoly per triangle, flat only
//   clear           canvas.setTo(white) alone
//   clearRead       the clear plus one read of every value of the scene's arrays (cv::sum, one
//                   thread): the floor any renderer of the scene must at least pay
//   llvmpipe        Mesa's llvmpipe through OSMesa, when built with it (perf_llvmpipe.hpp)
//   machine         pure arithmetic, 1 thread and all threads: how much the extra cores gave
//
// on the scenes of perf_scenes.hpp (grid, sphere, random at 512 and 2048, demo at 512); every
// method clears the canvas and draws all faces in painter's order. Names and counters are
// described in perf_harness.hpp. The context also says whether the plain rasterizer paints the
// same image as render (it should: 0 pixels differ), checked on the 512 scenes.
//
// The 3D benchmarks (perf_render3d.hpp, perf_llvmpipe3d.hpp): cv::shading::drawMesh3d and
// llvmpipe with the same lighting in GLSL on lit 3D meshes (knot3d512, torus3d2048), flat,
// Gouraud and Phong, z-buffer and painter's; their scene names contain "3d". Textured:
// drawTexturedMesh3d and llvmpipeTextured on the same scenes with texture coordinates and a
// 512 x 512 texture (bilinear, wrapped), lit the same way; their method names contain "Textured".
//
// Run it through run_benchmarks.sh (medians of repetitions, JSON, report.py), or directly, e.g.
//   opencv_shading_perf --benchmark_filter='render/grid512' --benchmark_repetitions=5
//   opencv_shading_perf --benchmark_filter=3d            # the 3D cells only
//   opencv_shading_perf --benchmark_filter=Textured      # the textured 3D cells only

#include "perf_baselines.hpp"
#include "perf_harness.hpp"
#include "perf_line.hpp"
#include "perf_polygon.hpp"
#include "perf_render3d.hpp"
#ifdef OPENCV_SHADING_PERF_LLVMPIPE
#include "perf_llvmpipe.hpp"
#include "perf_llvmpipe3d.hpp"
#endif

#include <opencv2/core.hpp>
#include <opencv2/shading.hpp>

#include <benchmark/benchmark.h>

#include <memory>
#include <string>
#include <vector>

namespace {

using namespace shading_perf;

//! All benchmarks of one scene. `allThreads` is the thread count of the parallel runs.
void addScene(const Scene& sc, int allThreads)
{
    using cv::shading::SHADE_FLAT;
    using cv::shading::SHADE_GOURAUD;
    for (int shade : {SHADE_FLAT, SHADE_GOURAUD})
        for (int threads : {1, allThreads})
            if (threads == 1 || allThreads > 1)
                addBenchmark("render", sc, shadeName(shade), threads,
                             [&sc, shade](cv::Mat& img) { renderScene(sc, shade, img); });
    for (int shade : {SHADE_FLAT, SHADE_GOURAUD}) {
        auto plain = std::make_shared<PlainRasterizer>();  // scratch buffers kept across runs
        addBenchmark("plain", sc, shadeName(shade), 1, [&sc, shade, plain](cv::Mat& img) {
            plain->render(sc, shade == SHADE_GOURAUD, img);
        });
    }
    auto fill = std::make_shared<FillConvexPolyPainter>();
    addBenchmark("fillConvexPoly", sc, "flat", 1,
                 [&sc, fill](cv::Mat& img) { fill->render(sc, img); });
    addBenchmark("clear", sc, nullptr, 1, [&sc](cv::Mat& img) { clearCanvas(img, sc.size); });
    addBenchmark("clearRead", sc, nullptr, 1, [&sc](cv::Mat& img) {
        benchmark::DoNotOptimize(clearAndReadScene(img, sc));
    });
}

}  // namespace

int main(int argc, char** argv)
{
    benchmark::Initialize(&argc, argv);
    if (benchmark::ReportUnrecognizedArguments(argc, argv))
        return 1;

    const int allThreads = cv::getNumberOfCPUs();
    const std::vector<Scene> scenes = benchmarkScenes();  // outlives the benchmarks
    addMachineContext();
    benchmark::AddCustomContext("all_threads", std::to_string(allThreads));
    addArithmeticBenchmark(1);
    if (allThreads > 1)
        addArithmeticBenchmark(allThreads);
    for (const Scene& sc : scenes) {
        if (sc.size.width <= 512)  // the plain rasterizer does not depend on the size
            benchmark::AddCustomContext(
                "check_plain_vs_render/" + sc.name,
                compareWithRender(sc, [&sc](int shade, cv::Mat& img) {
                    PlainRasterizer().render(sc, shade == cv::shading::SHADE_GOURAUD, img);
                }));
        addScene(sc, allThreads);
    }
    const std::vector<Scene3d> scenes3d = benchmarkScenes3d();  // outlives the benchmarks
    for (const Scene3d& sc : scenes3d)
        addScene3d(sc, allThreads);
    const std::vector<TexturedScene3d> textured3d = benchmarkTexturedScenes3d();
    for (const TexturedScene3d& ts : textured3d)
        addTexturedScene3d(ts, allThreads);

    addLineBenchmarks(allThreads);     // lines vs cv::line, textures vs remap (perf_line.hpp)
    addPolygonBenchmarks(allThreads);  // fillPolygons vs cv::fillPoly (perf_polygon.hpp)

#ifdef OPENCV_SHADING_PERF_LLVMPIPE
    addLlvmpipeBenchmarks(scenes);
    addLlvmpipe3dBenchmarks(scenes3d);
    addLlvmpipeTextured3dBenchmarks(textured3d);
#endif

    benchmark::RunSpecifiedBenchmarks();
    benchmark::Shutdown();
    return 0;
}
