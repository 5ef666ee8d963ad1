// This file is part of opencv_shading. License: Apache-2.0.
//
// The entry points of the band pass, which is built once per instruction set (see isa.hpp):
// bands_2d.cpp and bands_3d.cpp for the baseline and their _avx2 twins for AVX2, the same code.
// The functions outside the build namespaces (bands.cpp) call the AVX2 build where it is there
// and the CPU runs it (OpenCV's checkHardwareSupport, so OPENCV_CPU_DISABLE=AVX2 turns it off),
// else the baseline; both draw the same images bit for bit (no FMA contraction in either).
#ifndef OPENCV_SHADING_BANDS_HPP
#define OPENCV_SHADING_BANDS_HPP

#include "lighting_kernel.hpp"  // KernelBuild
#include "screen_mesh.hpp"

#include <opencv2/core.hpp>

namespace cv {
namespace shading {
namespace detail {

/** Draws a 2D mesh coloured from its vertex colours (flat or Gouraud, `shadeType`) in the
painter's order; with `background`, also sets every pixel no face covers (render()). */
void drawVertexColorMesh(Mat& canvas, const MeshData& mesh, int shadeType,
                         const Scalar* background);

/** Draws drawMesh3d's projected mesh, with the z-buffer (`zbuffer`) or in the painter's order,
into the canvas and the outputs of `targets`; with `background`, on a canvas cleared to it (each
band just before it is drawn). */
void drawScreenMesh(Mat& canvas, const ScreenMesh& screen, const DepthTargets& targets,
                    bool zbuffer, const Scalar* background);

/** Which build the functions above use from now on (for tests; the default is the best the
CPU runs): `build` where the library has it and the CPU runs it, else the baseline. Returns the
build chosen. */
CV_EXPORTS KernelBuild useBandBuild(KernelBuild build);

//! The builds themselves.
namespace bands_baseline {
void drawVertexColorMesh(Mat&, const MeshData&, int, const Scalar*);
void drawScreenMesh(Mat&, const ScreenMesh&, const DepthTargets&, bool, const Scalar*);
}  // namespace bands_baseline
namespace bands_avx2 {
void drawVertexColorMesh(Mat&, const MeshData&, int, const Scalar*);
void drawScreenMesh(Mat&, const ScreenMesh&, const DepthTargets&, bool, const Scalar*);
}  // namespace bands_avx2

}  // namespace detail
}  // namespace shading
}  // namespace cv

#endif  // OPENCV_SHADING_BANDS_HPP
