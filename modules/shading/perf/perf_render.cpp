// This file is part of opencv_shading. License: Apache-2.0.
//
// opencv_shading_perf: cv::shading::render against its peers on the same scenes, in one run.
//
// Benchmarks are named METHOD/SCENE[/SHADE]/threads:N, all timed in wall-clock time:
//   render          cv::shading::render (CV_32FC3, white background), 1 thread and all threads
//   plain           the plain single-threaded edge-function rasterizer (perf_baselines.hpp)
//   fillConvexPoly  cv::fillConvexPoly per triangle, flat only
//   clear           canvas.setTo(white) alone: the floor
// on the scenes of perf_scenes.hpp (grid, sphere, random at 512 and 2048, demo at 512). Every
// method clears the canvas and draws all faces in painter's order. Each benchmark reports the
// counters `triangles` and `pixels`; the context records the CPU, OpenCV and a check that the
// plain rasterizer draws the same image as render (pixels that differ by more than 1e-4).
//
// Run it through run_benchmarks.sh (medians of repetitions, JSON, report.py), or directly, e.g.
//   opencv_shading_perf --benchmark_filter='render/grid512' --benchmark_repetitions=5

#include "perf_baselines.hpp"
#include "perf_scenes.hpp"

#include <opencv2/core.hpp>
#include <opencv2/core/utility.hpp>
#include <opencv2/shading.hpp>

#include <benchmark/benchmark.h>

#include <fstream>
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace {

using shading_perf::Scene;

//! Sets OpenCV's thread count for one benchmark, restoring the previous count afterwards.
class ThreadCount {
public:
    explicit ThreadCount(int n) : previous_(cv::getNumThreads()) { cv::setNumThreads(n); }
    ~ThreadCount() { cv::setNumThreads(previous_); }
    ThreadCount(const ThreadCount&) = delete;
    ThreadCount& operator=(const ThreadCount&) = delete;

private:
    int previous_;
};

const char* shadeName(int shade) { return shade == cv::shading::SHADE_FLAT ? "flat" : "gouraud"; }

void renderScene(const Scene& sc, int shade, cv::Mat& img)
{
    const shading_samples::MeshScene& m = sc.mesh;
    cv::shading::render(m.verts2d, m.faces, m.vcolors, m.depth, img, shade, sc.size,
                        cv::Scalar::all(1.0));
}

/** Registers `METHOD/SCENE[/SHADE]/threads:N`: `threads` OpenCV threads, `draw(canvas)` called
once per iteration. */
void add(const std::string& method, const Scene& sc, const char* shade, int threads,
         std::function<void(cv::Mat&)> draw)
{
    std::string name = method + "/" + sc.name;
    if (shade != nullptr)
        name += std::string("/") + shade;
    name += "/threads:" + std::to_string(threads);
    const double triangles = sc.mesh.faces.rows, pixels = double(sc.size.area());
    benchmark::RegisterBenchmark(name.c_str(), [=](benchmark::State& state) {
        ThreadCount scope(threads);
        cv::Mat canvas;
        for (auto _ : state) {
            draw(canvas);
            benchmark::DoNotOptimize(canvas.data);
            benchmark::ClobberMemory();
        }
        state.counters["triangles"] = triangles;
        state.counters["pixels"] = pixels;
    })->UseRealTime()->Unit(benchmark::kMillisecond);
}

//! All benchmarks of one scene. `allThreads` is the thread count of the parallel runs.
void addScene(const Scene& sc, int allThreads)
{
    using namespace cv::shading;
    for (int shade : {SHADE_FLAT, SHADE_GOURAUD})
        for (int threads : {1, allThreads})
            if (threads == 1 || allThreads > 1)
                add("render", sc, shadeName(shade), threads,
                    [&sc, shade](cv::Mat& img) { renderScene(sc, shade, img); });
    for (int shade : {SHADE_FLAT, SHADE_GOURAUD}) {
        auto plain = std::make_shared<shading_perf::PlainRasterizer>();
        add("plain", sc, shadeName(shade), 1, [&sc, shade, plain](cv::Mat& img) {
            plain->render(sc, shade == SHADE_GOURAUD, img);
        });
    }
    auto fill = std::make_shared<shading_perf::FillConvexPolyPainter>();
    add("fillConvexPoly", sc, "flat", 1, [&sc, fill](cv::Mat& img) { fill->render(sc, img); });
    add("clear", sc, nullptr, 1, [&sc](cv::Mat& img) { shading_perf::clearCanvas(img, sc.size); });
}

/** "N/M pixels differ": the plain rasterizer against render, each shading, at one thread. A
difference means the baseline does not do the same work; it should be 0. */
std::string checkPlain(const Scene& sc)
{
    ThreadCount scope(1);
    std::string out;
    for (int shade : {cv::shading::SHADE_FLAT, cv::shading::SHADE_GOURAUD}) {
        cv::Mat expected, got, diff, worst;
        renderScene(sc, shade, expected);
        shading_perf::PlainRasterizer().render(sc, shade == cv::shading::SHADE_GOURAUD, got);
        cv::absdiff(expected, got, diff);
        cv::reduce(diff.reshape(1, sc.size.area()), worst, 1, cv::REDUCE_MAX);  // per pixel
        out += std::string(out.empty() ? "" : ", ") + shadeName(shade) + " " +
               std::to_string(cv::countNonZero(worst > 1e-4f)) + "/" +
               std::to_string(sc.size.area()) + " pixels differ";
    }
    return out;
}

//! The CPU's model name, from /proc/cpuinfo where there is one.
std::string cpuModel()
{
    std::ifstream in("/proc/cpuinfo");
    for (std::string line; std::getline(in, line);)
        if (line.rfind("model name", 0) == 0)
            return line.substr(line.find(':') + 2);
    return "unknown";
}

//! The "Parallel framework" line of OpenCV's build information.
std::string parallelFramework()
{
    const std::string info = cv::getBuildInformation();
    const size_t at = info.find("Parallel framework:");
    if (at == std::string::npos)
        return "unknown";
    const size_t value = info.find_first_not_of(' ', at + 19);
    return info.substr(value, info.find('\n', value) - value);
}

}  // namespace

int main(int argc, char** argv)
{
    benchmark::Initialize(&argc, argv);
    if (benchmark::ReportUnrecognizedArguments(argc, argv))
        return 1;

    const int allThreads = cv::getNumberOfCPUs();
    std::vector<Scene> scenes;
    for (int side : {512, 2048})
        for (const char* kind : {"grid", "sphere", "random"})
            scenes.push_back(shading_perf::makeScene(kind, side));
    scenes.push_back(shading_perf::makeScene("demo", 512));

    benchmark::AddCustomContext("cpu_model", cpuModel());
    benchmark::AddCustomContext("opencv_version", CV_VERSION);
    benchmark::AddCustomContext("opencv_parallel_framework", parallelFramework());
    benchmark::AddCustomContext("all_threads", std::to_string(allThreads));
    for (const Scene& sc : scenes) {
        if (sc.size.width <= 512)  // the rasterizer does not depend on the size
            benchmark::AddCustomContext("check_plain_vs_render/" + sc.name, checkPlain(sc));
        addScene(sc, allThreads);
    }

    benchmark::RunSpecifiedBenchmarks();
    benchmark::Shutdown();
    return 0;
}
