// This file is part of opencv_shading. License: Apache-2.0.
//
// perf_llvmpipe.hpp: Mesa's llvmpipe (OpenGL on the CPU, multi-threaded and SIMD) through OSMesa,
// on the benchmark scenes. opencv_shading_perf includes it when OSMesa is found (Debian:
// libosmesa6-dev), so llvmpipe runs in the same process and run as render, interleaved with it.
//
//   llvmpipe/SCENE/SHADE/threads:N  clear to white, then all triangles in painter's order (sorted
//                                   on the CPU every frame, as render does), glFinish
//
// The canvas is OSMesa's float RGBA buffer (GL_FLOAT; there is no float RGB one), in the user's
// memory. Flat shading sends every triangle's three vertices with its mean colour (GL_FLAT);
// Gouraud sends the shared vertices and colours with a sorted index list. Pixel (x, y) samples
// the point (x, y) and image rows map to GL's window rows (y up), where GL's fill rule is the
// library's: coverage matches but for a few pixels (GL rounds the vertices through a float
// transform) and Gouraud colours differ a little on thin triangles (GL interpolates in float).
// llvmpipe fixes its thread count when its first context starts: it uses LP_NUM_THREADS, which
// addLlvmpipeBenchmarks sets to the number of CPUs unless it is set already.
#ifndef OPENCV_SHADING_PERF_LLVMPIPE_HPP
#define OPENCV_SHADING_PERF_LLVMPIPE_HPP

#include "perf_baselines.hpp"
#include "perf_harness.hpp"

#include <GL/osmesa.h>

#include <opencv2/core.hpp>

#include <benchmark/benchmark.h>

#include <cstdlib>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace shading_perf {

//! One OSMesa context drawing scenes into float RGBA canvases.
class Llvmpipe {
public:
    Llvmpipe() : context_(OSMesaCreateContextExt(OSMESA_RGBA, 0, 0, 0, nullptr))
    {
        if (context_ == nullptr)
            throw std::runtime_error("OSMesaCreateContextExt failed");
    }
    ~Llvmpipe() { OSMesaDestroyContext(context_); }
    Llvmpipe(const Llvmpipe&) = delete;
    Llvmpipe& operator=(const Llvmpipe&) = delete;

    //! Draws `sc` into `canvas` (made `sc.size` CV_32FC4 and bound to the context if needed).
    void render(const Scene& sc, bool gouraud, cv::Mat& canvas)
    {
        if (canvas.size() != sc.size || canvas.type() != CV_32FC4 || canvas.data != bound_ ||
            OSMesaGetCurrentContext() != context_)  // the 3D benchmarks have their own contexts
            bind(canvas, sc.size);
        glClear(GL_COLOR_BUFFER_BIT);
        const MeshScene& m = sc.mesh;
        const std::vector<int>& order = painter_.sort(m);
        if (gouraud) {
            indices_.clear();
            for (int i : order)
                for (int k = 0; k < 3; ++k)
                    indices_.push_back(static_cast<GLuint>(m.faces.at<int>(i, k)));
            glShadeModel(GL_SMOOTH);
            glVertexPointer(2, GL_FLOAT, 0, m.verts2d.ptr<float>());
            glColorPointer(3, GL_FLOAT, 0, m.vcolors.ptr<float>());
            glDrawElements(GL_TRIANGLES, static_cast<GLsizei>(indices_.size()), GL_UNSIGNED_INT,
                           indices_.data());
        } else {
            positions_.clear();
            colors_.clear();
            for (int i : order) {
                const cv::Vec3i& f = m.faces.at<cv::Vec3i>(i);
                const cv::Vec3f c = meanColor(m, f);
                for (int k = 0; k < 3; ++k) {
                    positions_.push_back(m.verts2d.at<cv::Vec2f>(f[k]));
                    colors_.push_back(c);
                }
            }
            glShadeModel(GL_FLAT);
            glVertexPointer(2, GL_FLOAT, 0, positions_.data());
            glColorPointer(3, GL_FLOAT, 0, colors_.data());
            glDrawArrays(GL_TRIANGLES, 0, static_cast<GLsizei>(positions_.size()));
        }
        glFinish();  // the image is in `canvas` after this
    }

private:
    // Makes `canvas` the context's colour buffer; pixel (x, y) samples (x, y) and is in canvas
    // row y, which is GL's window row y (OSMESA_Y_UP: GL's y axis points along the rows).
    void bind(cv::Mat& canvas, cv::Size size)
    {
        canvas.create(size, CV_32FC4);
        if (!OSMesaMakeCurrent(context_, canvas.data, GL_FLOAT, size.width, size.height))
            throw std::runtime_error("OSMesaMakeCurrent failed");
        bound_ = canvas.data;
        OSMesaPixelStore(OSMESA_Y_UP, 1);
        glViewport(0, 0, size.width, size.height);
        glMatrixMode(GL_PROJECTION);
        glLoadIdentity();
        // GL samples pixel centres: shift by half a pixel.
        glOrtho(-0.5, size.width - 0.5, -0.5, size.height - 0.5, -1.0, 1.0);
        glMatrixMode(GL_MODELVIEW);
        glLoadIdentity();
        glDisable(GL_DEPTH_TEST);
        glDisable(GL_CULL_FACE);
        glDisable(GL_DITHER);
        glClearColor(1.f, 1.f, 1.f, 1.f);
        glEnableClientState(GL_VERTEX_ARRAY);
        glEnableClientState(GL_COLOR_ARRAY);
    }

    OSMesaContext context_;
    const uchar* bound_ = nullptr;  // the buffer the context draws into
    Painter painter_;
    std::vector<GLuint> indices_;
    std::vector<cv::Vec2f> positions_;
    std::vector<cv::Vec3f> colors_;
};

/** Registers llvmpipe on every scene, flat and Gouraud, with LP_NUM_THREADS threads (set to
the number of CPUs unless set already), and adds its pixel check against render to the context. */
inline void addLlvmpipeBenchmarks(const std::vector<Scene>& scenes)
{
    const std::string cpus = std::to_string(cv::getNumberOfCPUs());
    setenv("LP_NUM_THREADS", cpus.c_str(), 0);  // before the first context; kept if set
    const int threads = std::atoi(std::getenv("LP_NUM_THREADS"));
    auto gl = std::make_shared<Llvmpipe>();
    benchmark::AddCustomContext("llvmpipe_threads", std::to_string(threads));
    for (const Scene& sc : scenes) {
        if (sc.size.width <= 512)
            benchmark::AddCustomContext(
                "check_llvmpipe_vs_render/" + sc.name,
                compareWithRender(sc, [&sc, gl](int shade, cv::Mat& img) {
                    gl->render(sc, shade == cv::shading::SHADE_GOURAUD, img);
                }));
        for (int shade : {cv::shading::SHADE_FLAT, cv::shading::SHADE_GOURAUD})
            addBenchmark("llvmpipe", sc, shadeName(shade), threads,
                         [&sc, gl, shade](cv::Mat& img) {
                             gl->render(sc, shade == cv::shading::SHADE_GOURAUD, img);
                         });
    }
}

}  // namespace shading_perf

#endif  // OPENCV_SHADING_PERF_LLVMPIPE_HPP
