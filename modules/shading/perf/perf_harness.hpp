// This file is part of opencv_shading. License: Apache-2.0.
//
// perf_harness.hpp: what the benchmark programs share: the scene list, registering one
// benchmark, OpenCV's thread count, image checks and the machine description in the context.
//
// Benchmarks are named METHOD/SCENE[/SHADE]/threads:N (Google Benchmark appends /real_time),
// timed in wall-clock time, with the counters `triangles` and `pixels`; report.py reads them.
#ifndef OPENCV_SHADING_PERF_HARNESS_HPP
#define OPENCV_SHADING_PERF_HARNESS_HPP

#include "perf_scenes.hpp"

#include <opencv2/core.hpp>
#include <opencv2/core/utility.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/shading.hpp>

#include <benchmark/benchmark.h>

#include <cstdint>
#include <fstream>
#include <functional>
#include <string>
#include <utility>
#include <vector>

namespace shading_perf {

//! Sets OpenCV's thread count for a scope, restoring the previous count afterwards.
class ThreadCount {
public:
    explicit ThreadCount(int n) : previous_(cv::getNumThreads()) { cv::setNumThreads(n); }
    ~ThreadCount() { cv::setNumThreads(previous_); }
    ThreadCount(const ThreadCount&) = delete;
    ThreadCount& operator=(const ThreadCount&) = delete;

private:
    int previous_;
};

//! The benchmark scenes: grid, sphere and random at 512 and 2048, and the demo mesh at 512.
inline std::vector<Scene> benchmarkScenes()
{
    std::vector<Scene> scenes;
    for (int side : {512, 2048})
        for (const char* kind : {"grid", "sphere", "random"})
            scenes.push_back(makeScene(kind, side));
    scenes.push_back(makeScene("demo", 512));
    // Big meshes of tiny triangles (about 4 pixels a face): a grid and a closed surface.
    scenes.push_back(makeScene("biggrid", 2048));
    scenes.push_back(makeScene("bigsphere", 2048));
    return scenes;
}

inline const char* shadeName(int shade)
{
    return shade == cv::shading::SHADE_FLAT ? "flat" : "gouraud";
}

//! cv::shading::render of a scene: CV_32FC3, white background.
inline void renderScene(const Scene& sc, int shade, cv::Mat& img)
{
    const MeshScene& m = sc.mesh;
    cv::shading::render(m.verts2d, m.faces, m.vcolors, m.depth, img, shade, sc.size,
                        cv::Scalar::all(1.0));
}

/** Registers the benchmark `name` (ending in /threads:N), which sets OpenCV's thread count to
`threads` and calls `draw(canvas)` once per iteration (the same canvas each time), with the
counters `triangles` and `pixels`. */
inline void addNamedBenchmark(const std::string& name, double triangles, double pixels,
                              int threads, std::function<void(cv::Mat&)> draw)
{
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

/** Registers METHOD/SCENE[/SHADE]/threads:N (addNamedBenchmark). `shade` may be null. */
inline void addBenchmark(const std::string& method, const Scene& sc, const char* shade,
                         int threads, std::function<void(cv::Mat&)> draw)
{
    std::string name = method + "/" + sc.name;
    if (shade != nullptr)
        name += std::string("/") + shade;
    name += "/threads:" + std::to_string(threads);
    addNamedBenchmark(name, sc.mesh.faces.rows, double(sc.size.area()), threads,
                      std::move(draw));
}

/** Registers machine/arithmetic/threads:N: a fixed amount of arithmetic (floating-point and
integer dependency chains, no memory traffic) in 16 parts over cv::parallel_for_, with `threads`
threads. Interleaved with the other benchmarks, its speed-up from 1 to N threads tells how much of
the extra cores the run got: on a shared machine a core can be slowed by other tenants for
seconds, which slows every multi-threaded method. */
inline void addArithmeticBenchmark(int threads)
{
    const std::string name = "machine/arithmetic/threads:" + std::to_string(threads);
    benchmark::RegisterBenchmark(name.c_str(), [threads](benchmark::State& state) {
        ThreadCount scope(threads);
        for (auto _ : state) {
            cv::parallel_for_(cv::Range(0, 16), [](const cv::Range& parts) {
                for (int part = parts.start; part < parts.end; part++) {
                    double a = 1, b = 2, c = 3, d = 4;
                    uint64_t x = uint64_t(part), y = 2;
                    for (int i = 0; i < 20000; i++) {
                        a = a * 1.0000001 + 0.1;
                        b = b * 0.9999 + 0.2;
                        c += a;
                        d += b;
                        x = x * 3 + uint64_t(i);
                        y ^= x >> 3;
                    }
                    benchmark::DoNotOptimize(a + b + c + d + double(x + y));
                }
            });
        }
    })->UseRealTime()->Unit(benchmark::kMillisecond);
}

/** Checks that `draw` paints what cv::shading::render paints (1 thread), flat and Gouraud:
"flat N/M pixels differ, gouraud ..." (a pixel differs when a channel is off by more than
1e-4). `draw(shade, canvas)` may give RGBA; the alpha channel is ignored. */
inline std::string compareWithRender(const Scene& sc,
                                     const std::function<void(int, cv::Mat&)>& draw)
{
    ThreadCount scope(1);
    std::string out;
    for (int shade : {cv::shading::SHADE_FLAT, cv::shading::SHADE_GOURAUD}) {
        cv::Mat expected, got, diff, worst;
        renderScene(sc, shade, expected);
        draw(shade, got);
        if (got.channels() == 4)
            cv::cvtColor(got, got, cv::COLOR_RGBA2RGB);
        cv::absdiff(expected, got, diff);
        cv::reduce(diff.reshape(1, sc.size.area()), worst, 1, cv::REDUCE_MAX);  // per pixel
        out += std::string(out.empty() ? "" : ", ") + shadeName(shade) + " " +
               std::to_string(cv::countNonZero(worst > 1e-4f)) + "/" +
               std::to_string(sc.size.area()) + " pixels differ";
    }
    return out;
}

//! The CPU's model name, from /proc/cpuinfo where there is one.
inline std::string cpuModel()
{
    std::ifstream in("/proc/cpuinfo");
    for (std::string line; std::getline(in, line);)
        if (line.rfind("model name", 0) == 0)
            return line.substr(line.find(':') + 2);
    return "unknown";
}

//! The "Parallel framework" line of OpenCV's build information.
inline std::string parallelFramework()
{
    const std::string info = cv::getBuildInformation();
    const std::string key = "Parallel framework:";
    const size_t at = info.find(key);
    if (at == std::string::npos)
        return "unknown";
    const size_t value = info.find_first_not_of(' ', at + key.size());
    return info.substr(value, info.find('\n', value) - value);
}

//! Adds the CPU model and OpenCV's version and parallel framework to the report's context.
inline void addMachineContext()
{
    benchmark::AddCustomContext("cpu_model", cpuModel());
    benchmark::AddCustomContext("opencv_version", CV_VERSION);
    benchmark::AddCustomContext("opencv_parallel_framework", parallelFramework());
}

}  // namespace shading_perf

#endif  // OPENCV_SHADING_PERF_HARNESS_HPP
