// This file is part of opencv_shading. License: Apache-2.0.
//
// The band pass's 2D entry point (bands.hpp): the mesh engine (mesh.hpp) with the span shaders
// of the 2D functions. bands_2d_avx2.cpp compiles this file again for AVX2, in its own
// namespaces. The 2D and 3D shaders are separate translation units: GCC spends an inlining budget
// per unit, and in one unit the 3D instantiations took the 2D grids' share (2-5% slower).
#include <opencv2/shading.hpp>

#include "bands.hpp"
#include "mesh.hpp"
#include "shaders.hpp"

namespace cv {
namespace shading {
namespace detail {
OPENCV_SHADING_ISA_BEGIN
namespace {

//! Draws the mesh; with `background`, also sets every pixel no face covers (render()).
template <typename T>
void drawMeshAs(Mat& canvas, const MeshData& mesh, int shadeType, const Scalar* background)
{
    Vec<T, 3> bg;
    const Vec<T, 3>* fill = backgroundAs(background, bg);
    if (shadeType == SHADE_FLAT) {
        drawMeshInBands(canvas, mesh,
                        VertexColorShaders<FlatShader<T>>{mesh.colors.doubles(), false,
                                                          mesh.colors.floats()},
                        fill);
        return;
    }
    // Colours in double (readMesh converts them for Gouraud); with every one in range
    // (checked as they were read), no face checks its own.
    CV_DbgAssert(mesh.colors.empty() || mesh.colors.doubles());
    drawMeshInBands(
        canvas, mesh,
        VertexColorShaders<GouraudShader<T>>{mesh.colors.doubles(), mesh.colorsInGouraudRange},
        fill);
}

}  // namespace
OPENCV_SHADING_ISA_END

void OPENCV_SHADING_BANDS_NAMESPACE::drawVertexColorMesh(Mat& canvas, const MeshData& mesh,
                                                         int shadeType, const Scalar* background)
{
    if (canvas.depth() == CV_8U)
        drawMeshAs<uchar>(canvas, mesh, shadeType, background);
    else
        drawMeshAs<float>(canvas, mesh, shadeType, background);
}

}  // namespace detail
}  // namespace shading
}  // namespace cv
