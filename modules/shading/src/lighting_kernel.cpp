// This file is part of opencv_shading. License: Apache-2.0.
//
// The lighting kernels for the baseline instruction set, and the choice among the builds at run
// time (see lighting_kernel.hpp).
#include <opencv2/core.hpp>
#include <opencv2/core/hal/intrin.hpp>

#define OPENCV_SHADING_KERNEL_NAMESPACE kernel_baseline
#include "lighting_kernel.simd.hpp"

namespace cv {
namespace shading {
namespace detail {
#if OPENCV_SHADING_HAVE_AVX2
namespace {

//! Whether the CPU runs the AVX2 build (OPENCV_CPU_DISABLE=AVX2 turns it off).
bool useAvx2()
{
    static const bool avx2 = checkHardwareSupport(CPU_AVX2);
    return avx2;
}

}  // namespace
#endif

void shadeBatch(const LightingKernel& k, const float in[9][kLightBatch],
                float out[3][kLightBatch], int count)
{
#if OPENCV_SHADING_HAVE_AVX2
    if (useAvx2())
        return kernel_avx2::shadeBatch(k, in, out, count);
#endif
    kernel_baseline::shadeBatch(k, in, out, count);
}

void termsBatch(const LightingKernel& k, const float in[6][kLightBatch],
                float out[6][kLightBatch], int count)
{
#if OPENCV_SHADING_HAVE_AVX2
    if (useAvx2())
        return kernel_avx2::termsBatch(k, in, out, count);
#endif
    kernel_baseline::termsBatch(k, in, out, count);
}

bool lightBatchWith(KernelBuild build, bool terms, const LightingKernel& k,
                    const float (*in)[kLightBatch], float (*out)[kLightBatch], int count)
{
    if (build == KernelBuild::kBaseline) {
        if (terms)
            kernel_baseline::termsBatch(k, in, out, count);
        else
            kernel_baseline::shadeBatch(k, in, out, count);
        return true;
    }
#if OPENCV_SHADING_HAVE_AVX2
    if (useAvx2()) {
        if (terms)
            kernel_avx2::termsBatch(k, in, out, count);
        else
            kernel_avx2::shadeBatch(k, in, out, count);
        return true;
    }
#endif
    return false;
}

}  // namespace detail
}  // namespace shading
}  // namespace cv
