// This file is part of opencv_shading. License: Apache-2.0.
//
// The lighting kernels built for AVX2 (8 float lanes): CMake compiles this file with -mavx2 (no
// FMA, so that every lane rounds as the baseline's does) and defines
// OPENCV_SHADING_HAVE_AVX2 for lighting_kernel.cpp, which calls it on CPUs that have AVX2.
// OpenCV's headers enable their 256-bit intrinsics only inside OpenCV's own build: here they are
// asked for explicitly, in their own namespace (hal_AVX2), so nothing built for AVX2 can stand in
// for a baseline function.
#if OPENCV_SHADING_HAVE_AVX2
#include <immintrin.h>
#define CV_CPU_DISPATCH_MODE AVX2
#define CV_AVX 1
#define CV_AVX2 1
#include <opencv2/core/hal/intrin.hpp>

#define OPENCV_SHADING_KERNEL_NAMESPACE kernel_avx2
#include "lighting_kernel.simd.hpp"
#endif
