// This file is part of opencv_shading. License: Apache-2.0.
//
// The band pass built for AVX2 (see isa.hpp and bands.hpp): CMake compiles this file with
// -mavx2 (no FMA, so that every operation rounds as the baseline's does) where
// OPENCV_SHADING_HAVE_AVX2 is set, and links it after the baseline objects, so that the inline
// functions of the standard library and OpenCV that both builds use resolve to the baseline's
// copies. OpenCV's intrinsics are asked for in their AVX2 namespace, as in
// lighting_kernel_avx2.cpp.
#if OPENCV_SHADING_HAVE_AVX2
#include <immintrin.h>
#define CV_CPU_DISPATCH_MODE AVX2
#define CV_AVX 1
#define CV_AVX2 1
#include <opencv2/core/hal/intrin.hpp>

#define OPENCV_SHADING_ISA isa_avx2
#define OPENCV_SHADING_BANDS_NAMESPACE bands_avx2
#define OPENCV_SHADING_BANDS_AVX2_BUILD 1
#include "bands.cpp"
#endif
