// This file is part of opencv_shading. License: Apache-2.0.
//
// The lighting kernels (lighting_kernel.hpp), written once in OpenCV's universal intrinsics at
// their widest (v_float32: 4 lanes with SSE2, 8 with AVX2) and compiled once per instruction set
// by lighting_kernel.cpp and lighting_kernel_avx2.cpp, each defining
// OPENCV_SHADING_KERNEL_NAMESPACE. Only the intrinsics and plain data are used here: inline
// library or standard functions compiled with AVX2 could be picked by the linker for baseline
// callers.
#include "lighting_kernel.hpp"

#include <math.h>

namespace cv {
namespace shading {
namespace detail {
namespace OPENCV_SHADING_KERNEL_NAMESPACE {
namespace {

#if CV_SIMD
constexpr int kLanes = v_float32::nlanes;

//! 1 / |(x, y, z)|, or 0 for a zero vector.
inline v_float32 inverseLength(const v_float32& x, const v_float32& y, const v_float32& z)
{
    const v_float32 length2 = x * x + y * y + z * z;
    return v_select(length2 > vx_setzero_f32(), vx_setall_f32(1.f) / v_sqrt(length2),
                    vx_setzero_f32());
}

/** D and S (see termsBatch) of kLanes points from `in` at lane offset i: position rows 0..2,
normal rows 3..5 (normalized here; zero stays zero). */
inline void terms(const LightingKernel& k, const float (*in)[kLightBatch], int i,
                  v_float32 diffuse[3], v_float32 specular[3])
{
    const v_float32 zero = vx_setzero_f32(), one = vx_setall_f32(1.f);
    const v_float32 px = vx_load(in[0] + i), py = vx_load(in[1] + i), pz = vx_load(in[2] + i);
    const v_float32 mx = vx_load(in[3] + i), my = vx_load(in[4] + i), mz = vx_load(in[5] + i);
    const v_float32 invN = inverseLength(mx, my, mz);
    const v_float32 nx = mx * invN, ny = my * invN, nz = mz * invN;
    v_float32 vx = vx_setall_f32(k.eye[0]) - px, vy = vx_setall_f32(k.eye[1]) - py,
              vz = vx_setall_f32(k.eye[2]) - pz;
    const v_float32 invV = inverseLength(vx, vy, vz);
    vx = vx * invV, vy = vy * invV, vz = vz * invV;
    for (int c = 0; c < 3; c++) {
        diffuse[c] = vx_setall_f32(k.ambient[c]);
        specular[c] = zero;
    }
    for (int light = 0; light < k.lightCount; light++) {
        const float* position = k.lightPositions + 3 * light;
        v_float32 lx = vx_setall_f32(position[0]) - px;
        v_float32 ly = vx_setall_f32(position[1]) - py;
        v_float32 lz = vx_setall_f32(position[2]) - pz;
        const v_float32 invL = inverseLength(lx, ly, lz);
        lx = lx * invL, ly = ly * invL, lz = lz * invL;
        const v_float32 nl = nx * lx + ny * ly + nz * lz;
        const v_float32 facing = nl > zero;
        if (!v_check_any(facing))
            continue;  // adding the zero terms would change nothing
        const v_float32 diffuseTerm = v_select(facing, nl * vx_setall_f32(k.kd), zero);
        const v_float32 twoNl = nl + nl;
        const v_float32 rv =
            (twoNl * nx - lx) * vx + (twoNl * ny - ly) * vy + (twoNl * nz - lz) * vz;
        const v_float32 shiny = facing & (rv > zero);
        v_float32 highlight = zero;
        if (v_check_any(shiny)) {
            v_float32 base = v_select(shiny, rv, zero);
            if (k.wholeShininess >= 0) {
                v_float32 result = one;
                for (unsigned e = unsigned(k.wholeShininess); e; e >>= 1, base = base * base)
                    if (e & 1)
                        result = result * base;
                highlight = result;
            } else {
                float b[kLanes];
                v_store(b, base);
                for (float& x : b)
                    x = x > 0 ? float(pow(double(x), k.shininess)) : 0.f;
                highlight = vx_load(b);
            }
            highlight = v_select(shiny, highlight * vx_setall_f32(k.ks), zero);
        }
        const float* intensity = k.lightIntensities + 3 * light;
        for (int c = 0; c < 3; c++) {
            const v_float32 gain = vx_setall_f32(intensity[c]);
            diffuse[c] = diffuse[c] + gain * diffuseTerm;
            specular[c] = specular[c] + gain * highlight;
        }
    }
}
#endif

}  // namespace

void shadeBatch(const LightingKernel& k, const float in[9][kLightBatch],
                float out[3][kLightBatch], int count)
{
#if CV_SIMD
    const v_float32 zero = vx_setzero_f32(), one = vx_setall_f32(1.f);
    const v_float32 toColor = vx_setall_f32(k.toColor), toUnit = vx_setall_f32(k.toUnit);
    for (int i = 0; i < count; i += kLanes) {
        v_float32 diffuse[3], specular[3];
        terms(k, in, i, diffuse, specular);
        for (int c = 0; c < 3; c++) {
            const v_float32 lit = vx_load(in[6 + c] + i) * toColor * diffuse[c] + specular[c];
            v_store(out[c] + i, v_min(v_max(lit, zero), one) * toUnit);
        }
    }
#else
    (void)k, (void)in, (void)out, (void)count;
#endif
}

void termsBatch(const LightingKernel& k, const float in[6][kLightBatch],
                float out[6][kLightBatch], int count)
{
#if CV_SIMD
    for (int i = 0; i < count; i += kLanes) {
        v_float32 diffuse[3], specular[3];
        terms(k, in, i, diffuse, specular);
        for (int c = 0; c < 3; c++) {
            v_store(out[c] + i, diffuse[c]);
            v_store(out[3 + c] + i, specular[c]);
        }
    }
#else
    (void)k, (void)in, (void)out, (void)count;
#endif
}

}  // namespace OPENCV_SHADING_KERNEL_NAMESPACE
}  // namespace detail
}  // namespace shading
}  // namespace cv
