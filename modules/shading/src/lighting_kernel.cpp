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
bool lightBatchWith(KernelBuild build, bool terms, const LightingKernel& k,
                    const float (*in)[kLightBatch], float (*out)[kLightBatch], int count)
{
    if (build == KernelBuild::kAvx2) {
#if OPENCV_SHADING_HAVE_AVX2
        // Asked once: OPENCV_CPU_DISABLE=AVX2 makes it false on any CPU.
        static const bool cpuHasAvx2 = checkHardwareSupport(CPU_AVX2);
        if (!cpuHasAvx2)
            return false;
        if (terms)
            kernel_avx2::termsBatch(k, in, out, count);
        else
            kernel_avx2::shadeBatch(k, in, out, count);
        return true;
#else
        return false;
#endif
    }
    if (terms)
        kernel_baseline::termsBatch(k, in, out, count);
    else
        kernel_baseline::shadeBatch(k, in, out, count);
    return true;
}

void shadeBatch(const LightingKernel& k, const float in[9][kLightBatch],
                float out[3][kLightBatch], int count)
{
    // The AVX2 build where it is there and the CPU runs it, else the baseline.
    if (!lightBatchWith(KernelBuild::kAvx2, false, k, in, out, count))
        lightBatchWith(KernelBuild::kBaseline, false, k, in, out, count);
}

void termsBatch(const LightingKernel& k, const float in[6][kLightBatch],
                float out[6][kLightBatch], int count)
{
    if (!lightBatchWith(KernelBuild::kAvx2, true, k, in, out, count))
        lightBatchWith(KernelBuild::kBaseline, true, k, in, out, count);
}

}  // namespace detail
}  // namespace shading
}  // namespace cv
