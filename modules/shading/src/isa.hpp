// This file is part of opencv_shading. License: Apache-2.0.
//
// The band pass (the rasterizer, its span shaders and the mesh engine) is compiled once per
// instruction set: bands_2d.cpp and bands_3d.cpp for the baseline, their _avx2 twins for AVX2,
// chosen at run time (bands.hpp). Its code lives in an inline namespace named after the set, so
// that the two builds never share a function: without it the linker would keep one copy of each
// inline function and template, and the AVX2 build would run baseline code (or the baseline AVX2
// code, on a CPU without it). The types the builds hand each other (MeshData, ScreenMesh,
// DepthTargets, Lighting, the texture samplers) stay outside it.
#ifndef OPENCV_SHADING_ISA_HPP
#define OPENCV_SHADING_ISA_HPP

#ifndef OPENCV_SHADING_ISA
#define OPENCV_SHADING_ISA isa_baseline
#endif
// Where the band pass's units put their entry points (bands.hpp): bands_baseline unless
// isa_avx2.hpp said otherwise.
#ifndef OPENCV_SHADING_BANDS_NAMESPACE
#define OPENCV_SHADING_BANDS_NAMESPACE bands_baseline
#endif

#define OPENCV_SHADING_ISA_BEGIN inline namespace OPENCV_SHADING_ISA {
#define OPENCV_SHADING_ISA_END }

#endif  // OPENCV_SHADING_ISA_HPP
