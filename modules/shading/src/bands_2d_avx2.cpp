// This file is part of opencv_shading. License: Apache-2.0.
//
// bands_2d.cpp built for AVX2 (see isa_avx2.hpp).
#if OPENCV_SHADING_HAVE_AVX2
#include "isa_avx2.hpp"

#include "bands_2d.cpp"
#endif
