// This file is part of opencv_shading. License: Apache-2.0.
//
// The Phong lighting model on batches of points, in float lanes: the hot loop of per-sample
// (Phong) shading and of lighting big meshes' vertices and faces. Built once per instruction set
// (lighting_kernel.simd.hpp: SSE2 baseline, and AVX2 where the compiler has it), chosen at run
// time with cv::checkHardwareSupport. Every instruction set does the same IEEE float operations
// in the same order, lane by lane (no FMA contraction), so the images do not depend on the CPU.
#ifndef OPENCV_SHADING_LIGHTING_KERNEL_HPP
#define OPENCV_SHADING_LIGHTING_KERNEL_HPP

#include <opencv2/core/cvdef.h>

namespace cv {
namespace shading {
namespace detail {

//! Points per batch: a multiple of every instruction set's lane count.
constexpr int kLightBatch = 64;

/** The lighting of one draw, as plain data (the kernels are compiled with other instruction sets
and so see no library types): I = c (ka Ia + kd sum I_i max(N.L_i, 0)) + ks sum I_i [N.L_i > 0]
max(R_i.V, 0)^shininess, per channel, clamped to [0, 1]. */
struct LightingKernel {
    const float* lightPositions = nullptr;    //!< 3 per light, world coordinates
    const float* lightIntensities = nullptr;  //!< 3 per light
    int lightCount = 0;
    float eye[3] = {0, 0, 0};      //!< camera centre
    float ambient[3] = {0, 0, 0};  //!< ka Ia
    float kd = 0, ks = 0;
    double shininess = 0;
    //! shininess when it is a whole number up to 256 (raised by squaring), else -1 (std::pow).
    int wholeShininess = -1;
    float toColor = 1, toUnit = 1;  //!< 1 / unit and unit: the canvas's colour units
};

/** Lights points 0 .. count - 1 of a batch: in[0..2] position, in[3..5] normal (unit or zero:
ambient only), in[6..8] colour in the canvas's units; out[0..2] the lit colour. Lanes from count
up to the next multiple of 8 are computed too and must hold finite values. */
void shadeBatch(const LightingKernel& k, const float in[9][kLightBatch],
                float out[3][kLightBatch], int count);

/** The model split as I = c D + S: in[0..5] position and normal, out[0..2] D (ambient and
diffuse factor), out[3..5] S (the highlight), per channel, unclamped. Lanes as shadeBatch's. */
void termsBatch(const LightingKernel& k, const float in[6][kLightBatch],
                float out[6][kLightBatch], int count);

//! The builds of the kernels.
enum class KernelBuild { kBaseline, kAvx2 };

/** shadeBatch or termsBatch (`terms`) of one build, for tests: false, computing nothing, when
that build is not in the library or the CPU cannot run it. */
CV_EXPORTS bool lightBatchWith(KernelBuild build, bool terms, const LightingKernel& k,
                               const float (*in)[kLightBatch], float (*out)[kLightBatch],
                               int count);

//! The instruction sets the kernels are built for; the dispatch above calls one of these.
namespace kernel_baseline {
void shadeBatch(const LightingKernel&, const float[9][kLightBatch], float[3][kLightBatch], int);
void termsBatch(const LightingKernel&, const float[6][kLightBatch], float[6][kLightBatch], int);
}  // namespace kernel_baseline
namespace kernel_avx2 {
void shadeBatch(const LightingKernel&, const float[9][kLightBatch], float[3][kLightBatch], int);
void termsBatch(const LightingKernel&, const float[6][kLightBatch], float[6][kLightBatch], int);
}  // namespace kernel_avx2

}  // namespace detail
}  // namespace shading
}  // namespace cv

#endif  // OPENCV_SHADING_LIGHTING_KERNEL_HPP
