// This file is part of opencv_shading. License: Apache-2.0.
//
// The choice between the band pass's builds (bands.hpp): the baseline's (bands_2d.cpp,
// bands_3d.cpp) and AVX2's (bands_2d_avx2.cpp, bands_3d_avx2.cpp).
#include <opencv2/shading.hpp>

#include "bands.hpp"

#include <opencv2/core/utility.hpp>

#include <atomic>

namespace cv {
namespace shading {
namespace detail {
namespace {

//! Whether the AVX2 build is there and the CPU runs it (asked once).
bool avx2Available()
{
#if OPENCV_SHADING_HAVE_AVX2
    static const bool available = checkHardwareSupport(CPU_AVX2);
    return available;
#else
    return false;
#endif
}

std::atomic<bool> useAvx2{avx2Available()};

}  // namespace

KernelBuild useBandBuild(KernelBuild build)
{
    useAvx2 = build == KernelBuild::kAvx2 && avx2Available();
    return useAvx2 ? KernelBuild::kAvx2 : KernelBuild::kBaseline;
}

void drawVertexColorMesh(Mat& canvas, const MeshData& mesh, int shadeType,
                         const Scalar* background)
{
#if OPENCV_SHADING_HAVE_AVX2
    if (useAvx2.load(std::memory_order_relaxed))
        return bands_avx2::drawVertexColorMesh(canvas, mesh, shadeType, background);
#endif
    bands_baseline::drawVertexColorMesh(canvas, mesh, shadeType, background);
}

void drawScreenMesh(Mat& canvas, const ScreenMesh& screen, const DepthTargets& targets,
                    bool zbuffer, const Scalar* background)
{
#if OPENCV_SHADING_HAVE_AVX2
    if (useAvx2.load(std::memory_order_relaxed))
        return bands_avx2::drawScreenMesh(canvas, screen, targets, zbuffer, background);
#endif
    bands_baseline::drawScreenMesh(canvas, screen, targets, zbuffer, background);
}

}  // namespace detail
}  // namespace shading
}  // namespace cv
