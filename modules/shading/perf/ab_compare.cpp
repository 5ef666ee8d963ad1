// This file is part of opencv_shading. License: Apache-2.0.
//
// opencv_shading_ab: two builds of the library, measured against each other in one process.
//
// A change's effect on this project's shared VMs is often a few percent, while the machine's speed
// drifts by 10-40% from minute to minute: two benchmark runs at different minutes cannot tell
// them apart. This program loads two builds of libopencv_shading (say main's and a change's),
// calls them in alternate frames on the same scene, and prints the medians and their ratio per
// round, plus the largest difference between the two builds' images (0: the change keeps every
// pixel). A build against a copy of itself gives 0.99-1.02 here.
//
//   usage: opencv_shading_ab OLD_LIB NEW_LIB SCENE [SHADE [VISIBILITY]]
//                            [--threads N] [--frames N] [--rounds N] [--block N] [--8u]
//
//   SCENE       a benchmark scene and its side: grid512, sphere512, random512, demo512,
//               biggrid2048, bigsphere2048 (render) or knot3d512, torus3d2048 (drawMesh3d)
//   SHADE       flat (default), gouraud, or for 3D phong
//   VISIBILITY  3D only: zbuffer (default) or painter
//   --threads   cv::setNumThreads (default 2); --frames per build and round (default 20);
//               --rounds (default 3); --block: frames in a row per build (default 1), the
//               first of each not timed. Blocks of frames find what the build's own last frame
//               left in each core's cache, as a benchmark (or a video) drawing the same scene
//               again does; alternate frames each find the other build's. --8u: a CV_8UC3
//               canvas (colours scaled to 255) instead of CV_32FC3: for the 2D scenes
//               drawMesh into a white canvas (set each frame) instead of render.
//
// e.g., with the libraries of main's build and of a change's copied aside first:
//   opencv_shading_ab /tmp/main.so /tmp/change.so torus3d2048 gouraud zbuffer --frames 15
#include "perf_scenes.hpp"

#include <opencv2/core.hpp>
#include <opencv2/core/utility.hpp>
#include <opencv2/shading.hpp>

#include <dlfcn.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <string>
#include <vector>

namespace {

using RenderFn = void (*)(const cv::_InputArray&, const cv::_InputArray&, const cv::_InputArray&,
                          const cv::_InputArray&, const cv::_OutputArray&, int, cv::Size,
                          const cv::Scalar&);
using DrawMeshFn = void (*)(const cv::_InputOutputArray&, const cv::_InputArray&,
                            const cv::_InputArray&, const cv::_InputArray&,
                            const cv::_InputArray&, int);
using DrawMesh3dFn = void (*)(const cv::_InputOutputArray&, const cv::_InputArray&,
                              const cv::_InputArray&, const cv::_InputArray&,
                              const cv::_InputArray&, const cv::_InputArray&,
                              const cv::_InputArray&, const cv::shading::RenderSettings&,
                              const cv::_InputArray&, const cv::_InputOutputArray&,
                              const cv::_OutputArray&);

// The mangled names of cv::shading::render, drawMesh and drawMesh3d (GCC and Clang on Linux).
const char* const kRenderSymbol =
    "_ZN2cv7shading6renderERKNS_11_InputArrayES3_S3_S3_RKNS_12_OutputArrayEiNS_5Size_IiEERKNS_"
    "7Scalar_IdEE";
const char* const kDrawMeshSymbol =
    "_ZN2cv7shading8drawMeshERKNS_17_InputOutputArrayERKNS_11_InputArrayES6_S6_S6_i";
const char* const kDrawMesh3dSymbol =
    "_ZN2cv7shading10drawMesh3dERKNS_17_InputOutputArrayERKNS_11_InputArrayES6_S6_S6_S6_S6_"
    "RKNS0_14RenderSettingsES6_S3_RKNS_12_OutputArrayE";

[[noreturn]] void fail(const std::string& message)
{
    std::fprintf(stderr, "opencv_shading_ab: %s\n", message.c_str());
    std::exit(2);
}

/** Loads one build. RTLD_DEEPBIND: each build's calls into itself stay in that build, though
both export the same names. */
void* loadBuild(std::string path)
{
    if (path.find('/') == std::string::npos)
        path = "./" + path;  // dlopen searches the library path for names without a slash
    void* handle = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL | RTLD_DEEPBIND);
    if (!handle)
        fail(dlerror());
    return handle;
}

template <typename Fn>
Fn entryPoint(void* handle, const char* symbol, const char* name)
{
    void* address = dlsym(handle, symbol);
    if (!address)
        fail(std::string("the library has no ") + name);
    return reinterpret_cast<Fn>(address);
}

int shadeOf(const std::string& name)
{
    if (name == "flat")
        return cv::shading::SHADE_FLAT;
    if (name == "gouraud")
        return cv::shading::SHADE_GOURAUD;
    if (name == "phong")
        return cv::shading::SHADE_PHONG;
    fail("SHADE: expected flat, gouraud or phong, got '" + name + "'");
}

double median(std::vector<double> v)
{
    std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
    return v[v.size() / 2];
}

}  // namespace

int main(int argc, char** argv)
{
    std::vector<std::string> positional;
    int threads = 2, frames = 20, rounds = 3, block = 1;
    bool help = false, eightBit = false;
    for (int i = 1; i < argc; i++) {
        const std::string arg = argv[i];
        auto count = [&](const char* flag) {
            if (i + 1 >= argc)
                fail(std::string(flag) + " needs a number");
            const int value = std::atoi(argv[++i]);
            if (value < 1)
                fail(std::string(flag) + ": expected a positive number, got " + argv[i]);
            return value;
        };
        if (arg == "--threads")
            threads = count("--threads");
        else if (arg == "--frames")
            frames = count("--frames");
        else if (arg == "--rounds")
            rounds = count("--rounds");
        else if (arg == "--block")
            block = count("--block");
        else if (arg == "--8u")
            eightBit = true;
        else if (arg == "-h" || arg == "--help")
            help = true;
        else
            positional.push_back(arg);
    }
    if (help || positional.size() < 3 || positional.size() > 5) {
        std::fprintf(stderr,
                     "usage: opencv_shading_ab OLD_LIB NEW_LIB SCENE [SHADE [VISIBILITY]] "
                     "[--threads N] [--frames N] [--rounds N] [--block N] [--8u]\n"
                     "  SCENE: grid512, demo512, biggrid2048, ... or knot3d512, torus3d2048\n");
        return help ? 0 : 2;
    }
    void* builds[2] = {loadBuild(positional[0]), loadBuild(positional[1])};

    // The scene: its kind and side from a benchmark name such as "demo512".
    const std::string& sceneName = positional[2];
    const size_t digits = sceneName.find_last_not_of("0123456789") + 1;
    if (digits == 0 || digits == sceneName.size())
        fail("SCENE: expected a kind and a side, such as demo512, got '" + sceneName + "'");
    const std::string kind = sceneName.substr(0, digits);
    const int side = std::atoi(sceneName.c_str() + digits);
    const bool is3d = kind.size() > 2 && kind.compare(kind.size() - 2, 2, "3d") == 0;
    const int shade = shadeOf(positional.size() > 3 ? positional[3] : "flat");
    const std::string visibilityName = positional.size() > 4 ? positional[4] : "zbuffer";
    if (visibilityName != "zbuffer" && visibilityName != "painter")
        fail("VISIBILITY: expected zbuffer or painter, got '" + visibilityName + "'");
    if (!is3d && (shade == cv::shading::SHADE_PHONG || positional.size() > 4))
        fail("phong and VISIBILITY are for the 3D scenes (knot3d, torus3d)");
    cv::setNumThreads(threads);

    // One frame of build k into images[k].
    cv::Mat images[2], depths[2];
    std::function<void(int)> frame;
    shading_perf::Scene scene2d;
    shading_perf::Scene3d scene3d;
    try {
        if (is3d) {
            scene3d = shading_perf::makeScene3d(kind, side);
            const double unit = eightBit ? 255.0 : 1.0;
            cv::Mat colors;
            scene3d.mesh.vcolors.convertTo(colors, -1, unit);
            const bool zbuffer = visibilityName == "zbuffer";
            DrawMesh3dFn draw[2];
            for (int k = 0; k < 2; k++)
                draw[k] = entryPoint<DrawMesh3dFn>(builds[k], kDrawMesh3dSymbol, "drawMesh3d");
            frame = [&, zbuffer, unit, colors, draw0 = draw[0], draw1 = draw[1]](int k) {
                cv::shading::RenderSettings settings = scene3d.settings;
                settings.shadeType = shade;
                settings.visibility =
                    zbuffer ? cv::shading::VISIBILITY_ZBUFFER : cv::shading::VISIBILITY_PAINTER;
                settings.clear = true;  // canvas to white, depth to +inf, as the benchmark does
                settings.background = cv::Scalar::all(unit);
                images[k].create(scene3d.size, eightBit ? CV_8UC3 : CV_32FC3);
                if (zbuffer)
                    depths[k].create(scene3d.size, CV_32F);
                const shading_perf::Mesh3d& m = scene3d.mesh;
                const cv::_InputOutputArray depth = zbuffer ? cv::_InputOutputArray(depths[k])
                                                            : cv::_InputOutputArray(cv::noArray());
                (k == 0 ? draw0 : draw1)(images[k], m.verts3d, m.faces, colors,
                                         scene3d.cameraMatrix, scene3d.rvec, scene3d.tvec,
                                         settings, m.normals, depth, cv::noArray());
            };
        } else {
            scene2d = shading_perf::makeScene(kind, side);
            if (eightBit) {  // render() draws CV_32FC3: drawMesh into an 8-bit canvas
                cv::Mat colors;
                scene2d.mesh.vcolors.convertTo(colors, -1, 255.0);
                DrawMeshFn draw[2];
                for (int k = 0; k < 2; k++)
                    draw[k] = entryPoint<DrawMeshFn>(builds[k], kDrawMeshSymbol, "drawMesh");
                frame = [&, colors, draw0 = draw[0], draw1 = draw[1]](int k) {
                    const shading_perf::MeshScene& m = scene2d.mesh;
                    images[k].create(scene2d.size, CV_8UC3);
                    images[k].setTo(cv::Scalar::all(255));
                    (k == 0 ? draw0 : draw1)(images[k], m.verts2d, m.faces, colors, m.depth,
                                             shade);
                };
            } else {
                RenderFn render[2];
                for (int k = 0; k < 2; k++)
                    render[k] = entryPoint<RenderFn>(builds[k], kRenderSymbol, "render");
                frame = [&, render0 = render[0], render1 = render[1]](int k) {
                    const shading_perf::MeshScene& m = scene2d.mesh;
                    (k == 0 ? render0 : render1)(m.verts2d, m.faces, m.vcolors, m.depth,
                                                 images[k], shade, scene2d.size,
                                                 cv::Scalar::all(1.0));
                };
            }
        }
    } catch (const std::exception& e) {
        fail(std::string("SCENE: ") + e.what());
    }

    std::printf("%s %s%s%s, %d threads, %d frames per build and round\n", sceneName.c_str(),
                positional.size() > 3 ? positional[3].c_str() : "flat", is3d ? " " : "",
                is3d ? visibilityName.c_str() : "", threads, frames);
    frame(0), frame(1);  // warm-up: first-call allocations and page faults
    std::vector<double> ratios;
    for (int round = 0; round < rounds; round++) {
        std::vector<double> times[2];
        for (int i = 0; i < 2 * frames; i++) {
            // Alternate frames or blocks: the machine's drift hits both builds.
            const int k = i / block & 1;
            const int64 start = cv::getTickCount();
            frame(k);
            if (block > 1 && i % block == 0)
                continue;  // a block's first frame finds the other build's caches: not timed
            times[k].push_back(double(cv::getTickCount() - start) * 1000.0 /
                               cv::getTickFrequency());
        }
        const double old = median(times[0]), now = median(times[1]);
        ratios.push_back(now / old);
        std::printf("round %d: old %.3f ms, new %.3f ms, new / old %.3f\n", round + 1, old, now,
                    now / old);
    }
    std::sort(ratios.begin(), ratios.end());
    const double difference = cv::norm(images[0], images[1], cv::NORM_INF);
    std::printf("new / old %.3f to %.3f; images: largest difference %g%s\n", ratios.front(),
                ratios.back(), difference, difference == 0 ? " (identical)" : "");
    return 0;
}
