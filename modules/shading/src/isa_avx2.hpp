// This file is part of opencv_shading. License: Apache-2.0.
//
// What a band pass unit built for AVX2 defines first (bands_2d_avx2.cpp, bands_3d_avx2.cpp; see
// isa.hpp and bands.hpp). CMake compiles those files with -mavx2 (no FMA, so that every
// operation rounds as the baseline's does) where OPENCV_SHADING_HAVE_AVX2 is set, and links them
// after the baseline objects, so that the inline functions of the standard library and OpenCV
// that both builds use resolve to the baseline's copies. OpenCV's intrinsics are asked for in
// their AVX2 namespace, as in lighting_kernel_avx2.cpp.
#ifndef OPENCV_SHADING_ISA_AVX2_HPP
#define OPENCV_SHADING_ISA_AVX2_HPP

#include <immintrin.h>
#define CV_CPU_DISPATCH_MODE AVX2
#define CV_AVX 1
#define CV_AVX2 1
#include <opencv2/core/hal/intrin.hpp>

#define OPENCV_SHADING_ISA isa_avx2
#define OPENCV_SHADING_BANDS_NAMESPACE bands_avx2

#endif  // OPENCV_SHADING_ISA_AVX2_HPP
