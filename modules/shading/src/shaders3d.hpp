// This file is part of opencv_shading. License: Apache-2.0.
//
// Span shaders of the 3D path: perspective-correct depth and attributes, the z-buffer test, the
// depth and face-id outputs, texturing, and the Phong lighting model (seed 004) they share.
#ifndef OPENCV_SHADING_SHADERS3D_HPP
#define OPENCV_SHADING_SHADERS3D_HPP

#include "shaders.hpp"
#include "texture_sampler.hpp"

#include <opencv2/core.hpp>

#include <cmath>
#include <tuple>
#include <type_traits>
#include <vector>

namespace cv {
namespace shading {
namespace detail {

/** The Phong lighting model with the material, lights and eye of one drawMesh3d call:
I = c (ka Ia + kd sum I_i max(N.L_i, 0)) + ks sum I_i [N.L_i > 0] max(R_i.V, 0)^shininess, per
channel, clamped to [0, 1]. */
struct Lighting {
    struct Light {
        Vec3d position, intensity;
    };
    std::vector<Light> lights;  //!< empty: unlit
    Vec3d eye;                  //!< camera centre, world coordinates
    Vec3d ambient;              //!< ka Ia
    double kd = 0, ks = 0, shininess = 0;
    double unit = 1;            //!< the canvas's colour units per lighting unit (1 or 255)

    bool lit() const { return !lights.empty(); }

    //! v^shininess for v in (0, 1]; whole exponents up to 256 by squaring (std::pow is several
    //! times slower, and the two differ by a few ulps).
    double power(double v) const
    {
        if (!(shininess == std::floor(shininess) && shininess <= 256))
            return std::pow(v, shininess);
        double result = 1;
        for (unsigned e = unsigned(shininess); e; e >>= 1, v *= v)
            if (e & 1)
                result *= v;
        return result;
    }

#if OPENCV_SHADING_SIMD128
    /** terms() for four points in float lanes: v holds position and normal (not normalized). */
    void termsQuad(const v_float32x4 v[6], v_float32x4 diffuse[3], v_float32x4 specular[3]) const
    {
        const v_float32x4 zero = v_setzero_f32(), one = v_setall_f32(1.f);
        auto inverseLength = [&](const v_float32x4& x, const v_float32x4& y,
                                 const v_float32x4& z) {
            const v_float32x4 length2 = x * x + y * y + z * z;
            return v_select(length2 > zero, one / v_sqrt(length2), zero);  // zero stays zero
        };
        const v_float32x4 px = v[0], py = v[1], pz = v[2];
        const v_float32x4 invN = inverseLength(v[3], v[4], v[5]);
        const v_float32x4 nx = v[3] * invN, ny = v[4] * invN, nz = v[5] * invN;
        v_float32x4 vx = v_setall_f32(float(eye[0])) - px, vy = v_setall_f32(float(eye[1])) - py,
                    vz = v_setall_f32(float(eye[2])) - pz;
        const v_float32x4 invV = inverseLength(vx, vy, vz);
        vx = vx * invV, vy = vy * invV, vz = vz * invV;
        for (int k = 0; k < 3; k++) {
            diffuse[k] = v_setall_f32(float(ambient[k]));
            specular[k] = zero;
        }
        const bool wholePower = shininess == std::floor(shininess) && shininess <= 256;
        for (const Light& light : lights) {
            v_float32x4 lx = v_setall_f32(float(light.position[0])) - px;
            v_float32x4 ly = v_setall_f32(float(light.position[1])) - py;
            v_float32x4 lz = v_setall_f32(float(light.position[2])) - pz;
            const v_float32x4 invL = inverseLength(lx, ly, lz);
            lx = lx * invL, ly = ly * invL, lz = lz * invL;
            const v_float32x4 nl = nx * lx + ny * ly + nz * lz;
            const v_float32x4 facing = nl > zero;
            if (!v_check_any(facing))
                continue;
            const v_float32x4 diffuseTerm = v_select(facing, nl * v_setall_f32(float(kd)), zero);
            const v_float32x4 twoNl = nl + nl;
            const v_float32x4 rv = (twoNl * nx - lx) * vx + (twoNl * ny - ly) * vy +
                                   (twoNl * nz - lz) * vz;
            const v_float32x4 shiny = facing & (rv > zero);
            v_float32x4 highlight = zero;
            if (v_check_any(shiny)) {
                v_float32x4 base = v_select(shiny, rv, zero);
                if (wholePower) {
                    v_float32x4 result = one;
                    for (unsigned e = unsigned(shininess); e; e >>= 1, base = base * base)
                        if (e & 1)
                            result = result * base;
                    highlight = result;
                } else {
                    float b[4];
                    v_store(b, base);
                    for (float& x : b)
                        x = x > 0 ? float(std::pow(double(x), shininess)) : 0.f;
                    highlight = v_load(b);
                }
                highlight = v_select(shiny, highlight * v_setall_f32(float(ks)), zero);
            }
            for (int k = 0; k < 3; k++) {
                const v_float32x4 intensity = v_setall_f32(float(light.intensity[k]));
                diffuse[k] = diffuse[k] + intensity * diffuseTerm;
                specular[k] = specular[k] + intensity * highlight;
            }
        }
    }

    /** shade() for four samples in float lanes: v holds position, normal (not normalized) and
    colour; out[channel][lane] the lit colours in the canvas's units. */
    void shadeQuad(const v_float32x4 v[9], float out[3][4]) const
    {
        v_float32x4 diffuse[3], specular[3];
        termsQuad(v, diffuse, specular);
        const v_float32x4 zero = v_setzero_f32(), one = v_setall_f32(1.f);
        const v_float32x4 toColor = v_setall_f32(float(1.0 / unit)),
                          toUnit = v_setall_f32(float(unit));
        for (int k = 0; k < 3; k++) {
            const v_float32x4 lit = v[6 + k] * toColor * diffuse[k] + specular[k];
            v_store(out[k], v_min(v_max(lit, zero), one) * toUnit);
        }
    }
#endif

    /** Lights `count` points: in[9 i ..] holds position, normal (unit or zero) and colour,
    out[3 i ..] receives the lit colour, both colours in the canvas's units. Four at a time in
    float lanes where SIMD is built (for per-face and per-vertex lighting of big meshes). */
    void shadeMany(const float* in, float* out, int count) const
    {
        forPoints<9, 3>(in, out, count,
#if OPENCV_SHADING_SIMD128
                        [&](const v_float32x4 v[9], float lit[][4]) { shadeQuad(v, lit); },
#endif
                        [&](const float* p, float* o) {
                            const Vec3d c = shade(Vec3d(p[0], p[1], p[2]),
                                                  Vec3d(p[3], p[4], p[5]),
                                                  Vec3d(p[6], p[7], p[8]));
                            for (int k = 0; k < 3; k++)
                                o[k] = float(c[k]);
                        });
    }

    /** terms() of `count` points: in[6 i ..] holds position and normal (unit or zero), out[6 i
    ..] receives D then S. */
    void termsMany(const float* in, float* out, int count) const
    {
        forPoints<6, 6>(in, out, count,
#if OPENCV_SHADING_SIMD128
                        [&](const v_float32x4 v[6], float ds[][4]) {
                            v_float32x4 d[3], s[3];
                            termsQuad(v, d, s);
                            for (int k = 0; k < 3; k++) {
                                v_store(ds[k], d[k]);
                                v_store(ds[3 + k], s[k]);
                            }
                        },
#endif
                        [&](const float* p, float* o) {
                            Vec3d d, s;
                            terms(Vec3d(p[0], p[1], p[2]), Vec3d(p[3], p[4], p[5]), d, s);
                            for (int k = 0; k < 3; k++) {
                                o[k] = float(d[k]);
                                o[3 + k] = float(s[k]);
                            }
                        });
    }

    /** The model split as I = c D + S (before clamping) at world point p with normal n (unit,
    or zero: ambient only): D the ambient and diffuse factor, S the highlight, per channel. */
    void terms(const Vec3d& p, const Vec3d& n, Vec3d& diffuse, Vec3d& specular) const
    {
        diffuse = ambient, specular = Vec3d(0, 0, 0);
        const Vec3d toEye = eye - p;
        const double eyeLength = std::sqrt(toEye.dot(toEye));
        const Vec3d v = eyeLength > 0 ? toEye * (1.0 / eyeLength) : Vec3d(0, 0, 0);
        for (const Light& light : lights) {
            const Vec3d toLight = light.position - p;
            const double length = std::sqrt(toLight.dot(toLight));
            if (!(length > 0))
                continue;  // a light at the point lights no direction
            const Vec3d l = toLight * (1.0 / length);
            const double nl = n.dot(l);
            if (nl <= 0)
                continue;  // both terms vanish
            diffuse += light.intensity * (kd * nl);
            const Vec3d r = n * (2 * nl) - l;
            const double rv = r.dot(v);
            if (rv > 0)
                specular += light.intensity * (ks * power(rv));
        }
    }

    /** The lit colour at world point p with normal n (unit, or zero: ambient only) and colour c,
    both colours in the canvas's units. */
    Vec3d shade(const Vec3d& p, const Vec3d& n, const Vec3d& color) const
    {
        Vec3d diffuse, specular;
        terms(p, n, diffuse, specular);
        Vec3d out;
        for (int k = 0; k < 3; k++)
            out[k] = combine(color[k], diffuse[k], specular[k]);
        return out;
    }

    //! clamp(c D + S) in the canvas's units, for c in the canvas's units.
    double combine(double c, double diffuse, double specular) const
    {
        return std::min(std::max(c * (1.0 / unit) * diffuse + specular, 0.0), 1.0) * unit;
    }

private:
    /** Runs quad() on four points at a time (lanes transposed) where SIMD is built, one() on
    the rest: kIn floats in and kOut out per point. */
    template <int kIn, int kOut, class... Fns>
    static void forPoints(const float* in, float* out, int count, Fns&&... fns)
    {
        auto fnList = std::forward_as_tuple(fns...);
        int i = 0;
#if OPENCV_SHADING_SIMD128
        auto& quad = std::get<0>(fnList);
        for (; i + 4 <= count; i += 4) {
            float lanes[kIn][4];
            for (int j = 0; j < 4; j++)
                for (int k = 0; k < kIn; k++)
                    lanes[k][j] = in[kIn * (i + j) + k];
            v_float32x4 v[kIn];
            for (int k = 0; k < kIn; k++)
                v[k] = v_load(lanes[k]);
            float result[kOut][4];
            quad(v, result);
            for (int j = 0; j < 4; j++)
                for (int k = 0; k < kOut; k++)
                    out[kOut * (i + j) + k] = result[k][j];
        }
#endif
        auto& one = std::get<sizeof...(Fns) - 1>(fnList);
        for (; i < count; i++)
            one(in + kIn * i, out + kOut * i);
    }
};

//! Normalizes v; a zero (or non-finite-length) vector stays zero.
inline Vec3d unitOrZero(const Vec3d& v)
{
    const double length = std::sqrt(v.dot(v));
    return length > 0 && std::isfinite(length) ? v * (1.0 / length) : Vec3d(0, 0, 0);
}

/** Samples waiting to be lit together (Phong): their pixels and interpolated position, normal
and colour. Four at a time in float lanes where SIMD is built, else one by one in double. */
template <typename T>
struct LitQuad {
    T* pixels[4];
    float values[9][4];
    int count = 0;

    //! Queues a pixel; v: position, normal (not normalized), colour. Lights when four wait.
    void add(T* pixel, const float v[9], const Lighting& lighting)
    {
        for (int k = 0; k < 9; k++)
            values[k][count] = v[k];
        pixels[count++] = pixel;
        if (count == 4)
            flush(lighting);
    }

    void flush(const Lighting& lighting)
    {
        if (count == 0)
            return;
#if OPENCV_SHADING_SIMD128
        for (int i = count; i < 4; i++)
            for (int k = 0; k < 9; k++)
                values[k][i] = values[k][0];
        v_float32x4 v[9];
        for (int k = 0; k < 9; k++)
            v[k] = v_load(values[k]);
        float lit[3][4];
        lighting.shadeQuad(v, lit);
        for (int i = 0; i < count; i++)
            for (int k = 0; k < 3; k++)
                pixels[i][k] = toChannel<T>(lit[k][i]);
#else
        for (int i = 0; i < count; i++) {
            const Vec3d c = lighting.shade(
                Vec3d(values[0][i], values[1][i], values[2][i]),
                unitOrZero(Vec3d(values[3][i], values[4][i], values[5][i])),
                Vec3d(values[6][i], values[7][i], values[8][i]));
            for (int k = 0; k < 3; k++)
                pixels[i][k] = toChannel<T>(float(c[k]));
        }
#endif
        count = 0;
    }
};

/** What the 3D shaders write besides the canvas, and the lighting and texture they use. */
struct DepthTargets {
    uchar* depth = nullptr;  //!< CV_32FC1 rows, canvas-sized; null: not written
    size_t depthStep = 0;
    uchar* ids = nullptr;    //!< CV_32SC1 rows; null: not written
    size_t idsStep = 0;
    const Lighting* lighting = nullptr;
    //! Textured surfaces: the texture, in the canvas's units (the one of the canvas's type).
    const RemapSampler<uchar>* sampler8u = nullptr;
    const RemapSampler<float>* sampler32f = nullptr;

    template <typename T>
    const RemapSampler<T>& sampler() const
    {
        if constexpr (std::is_same<T, uchar>::value)
            return *sampler8u;
        else
            return *sampler32f;
    }
};

/** How a face colours its samples, and the per-vertex attributes it interpolates for that. */
enum class Surface {
    kFlat,               //!< one colour per face (no attributes)
    kGouraud,            //!< colour (3): vertex colours, lit or as given
    kPhong,              //!< position, normal, colour (9), lit at the sample
    kTextured,           //!< texture coordinate (2), the texel as sampled (unlit)
    kTexturedFaceLit,    //!< texture coordinate (2), lit by the face's D and S (flat)
    kTexturedVertexLit,  //!< texture coordinate, D, S (8): lit by interpolated D, S (Gouraud)
    kTexturedSampleLit   //!< texture coordinate, position, normal (8), lit at the sample (Phong)
};

constexpr int attributeCount(Surface s)
{
    return s == Surface::kFlat ? 0
         : s == Surface::kGouraud ? 3
         : s == Surface::kPhong ? 9
         : s == Surface::kTextured || s == Surface::kTexturedFaceLit ? 2
         : 8;
}

//! Surfaces lit per sample: their samples go through LitQuad, and through deferred shading.
constexpr bool litPerSample(Surface s)
{
    return s == Surface::kPhong || s == Surface::kTexturedSampleLit;
}

/** Colours a sample from its interpolated attributes `a` (attributeCount(kSurface) values), or
queues it in `quad` to be lit (litPerSample). Not for kFlat or kTexturedFaceLit, whose colour
or lighting belongs to the face. */
template <typename T, Surface kSurface>
inline void shadeAttributes(T* pixel, const float* a, const DepthTargets& targets,
                            LitQuad<T>& quad)
{
    if constexpr (kSurface == Surface::kGouraud) {
        for (int k = 0; k < 3; k++)
            pixel[k] = toChannel<T>(a[k]);
    } else if constexpr (kSurface == Surface::kPhong) {
        quad.add(pixel, a, *targets.lighting);
    } else if constexpr (kSurface == Surface::kTextured) {
        targets.sampler<T>().sample(a[0], a[1], pixel);
    } else if constexpr (kSurface == Surface::kTexturedVertexLit) {
        T texel[3];
        targets.sampler<T>().sample(a[0], a[1], texel);
        for (int k = 0; k < 3; k++)
            pixel[k] = toChannel<T>(float(targets.lighting->combine(texel[k], a[2 + k], a[5 + k])));
    } else if constexpr (kSurface == Surface::kTexturedSampleLit) {
        T texel[3];
        targets.sampler<T>().sample(a[0], a[1], texel);
        const float v[9] = {a[2], a[3], a[4], a[5], a[6], a[7],
                            float(texel[0]), float(texel[1]), float(texel[2])};
        quad.add(pixel, v, *targets.lighting);
    }
}

/** Shades a triangle of the projected mesh. Per sample: the screen-space weights w_i, their
perspective-correct form q_i = (w_i / z_i) / sum_j (w_j / z_j) and the depth
1 / sum_j (w_j / z_j); then the z-buffer test, and the colour (see Surface): the attributes
interpolated with q, then shadeAttributes. w_i / z_i is affine in screen space: each span starts
from the exact weights (ExactWeights) and steps by its x-gradient, so a sample's values depend
only on the face and its span. */
template <typename T, Surface kSurface>
struct SurfaceShader {
    static constexpr int kAttributes = attributeCount(kSurface);
    ExactWeights weights;
    double invZ[3];                                  //!< 1 / Zc per vertex, canonical order
    double stepX[3];                                 //!< d(w_i / z_i) / dx
    double attributes[3][kAttributes ? kAttributes : 1];
    T color[3];                                      //!< kFlat: the face's colour
    float faceLight[6];                              //!< kTexturedFaceLit: the face's D, S
    const DepthTargets* targets;
    int faceId;                                      //!< in the caller's faces
    int slotOf1 = 1, slotOf2 = 2;  //!< canonical slots of the face's own vertices 1 and 2

    SurfaceShader(const TriangleSetup& t, const DepthTargets* out, int id)
        : weights(t), targets(out), faceId(id)
    {
    }

    //! Call once invZ is set: the per-pixel steps.
    void finishSetup(const TriangleSetup& t)
    {
        double dw[3];
        weights.stepX(t, dw);
        for (int i = 0; i < 3; i++)
            stepX[i] = dw[i] * invZ[i];
    }

    //! q_i (unnormalized) at the span's first sample.
    void startSpan(const TriangleSetup& t, int x, int y, double q[3]) const
    {
        weights.at(t, x, y, q[0], q[1], q[2]);
        for (int i = 0; i < 3; i++)
            q[i] *= invZ[i];
    }

    //! The sample's colour from its q (unnormalized, `inv` = 1 / sum), or queued in `quad`.
    void shadeSample(T* pixel, const double q[3], double inv, LitQuad<T>& quad) const
    {
        if constexpr (kSurface == Surface::kFlat) {
            pixel[0] = color[0], pixel[1] = color[1], pixel[2] = color[2];
        } else {
            float a[kAttributes];
            for (int k = 0; k < kAttributes; k++)
                a[k] = float((q[0] * attributes[0][k] + q[1] * attributes[1][k] +
                              q[2] * attributes[2][k]) * inv);
            if constexpr (kSurface == Surface::kTexturedFaceLit) {
                T texel[3];
                targets->sampler<T>().sample(a[0], a[1], texel);
                for (int k = 0; k < 3; k++)
                    pixel[k] = toChannel<T>(float(
                        targets->lighting->combine(texel[k], faceLight[k], faceLight[3 + k])));
            } else {
                shadeAttributes<T, kSurface>(pixel, a, *targets, quad);
            }
        }
    }

    //! Draws the span without a depth test (painter's order): depth, face id and colour.
    void operator()(const TriangleSetup& t, T* row, int y, int /*spanBegin*/, int xBegin,
                    int xEnd) const
    {
        const DepthTargets& out = *targets;
        float* const depthRow =
            out.depth ? reinterpret_cast<float*>(out.depth + size_t(y) * out.depthStep) : nullptr;
        int* const idRow =
            out.ids ? reinterpret_cast<int*>(out.ids + size_t(y) * out.idsStep) : nullptr;
        double q[3];
        startSpan(t, xBegin, y, q);
        LitQuad<T> quad;
        for (int x = xBegin; x < xEnd;
             x++, q[0] += stepX[0], q[1] += stepX[1], q[2] += stepX[2]) {
            const double inv = 1.0 / (q[0] + q[1] + q[2]);
            if (depthRow)
                depthRow[x] = float(inv);
            if (idRow)
                idRow[x] = faceId;
            shadeSample(row + 3 * x, q, inv, quad);
        }
        if constexpr (litPerSample(kSurface))
            quad.flush(*out.lighting);
    }

    /** Z-buffer (BandOptions::depthTested): takes the span's samples where (depth, face) is
    smaller than what the sample keeps (kept face -1: the buffer's own value, depth only), so the
    faces may come in any order. A taken sample gets its depth, its face in `kept`, the block
    bookkeeping of ZBufferBlocks, and its colour and id, or with `keptWeights` (deferred) the
    perspective-correct weights of the face's own vertices 1 and 2 for shading later. */
    void depthTest(const TriangleSetup& t, T* row, int y, int xBegin, int xEnd, int face,
                   int* kept, float* keptWeights, uint64_t* covered, float* bound) const
    {
        const DepthTargets& out = *targets;
        float* const depthRow = reinterpret_cast<float*>(out.depth + size_t(y) * out.depthStep);
        int* const idRow =
            out.ids ? reinterpret_cast<int*>(out.ids + size_t(y) * out.idsStep) : nullptr;
        double q[3];
        startSpan(t, xBegin, y, q);
        LitQuad<T> quad;  // unused: surfaces lit per sample are deferred
        for (int x = xBegin; x < xEnd;
             x++, q[0] += stepX[0], q[1] += stepX[1], q[2] += stepX[2]) {
            const double inv = 1.0 / (q[0] + q[1] + q[2]);
            const float depth = float(inv);
            const float current = depthRow[x];
            if (!(depth < current || (depth == current && kept[x] > face)))
                continue;  // (kept -1 never loses a tie: the buffer's value was first)
            depthRow[x] = depth;
            kept[x] = face;
            covered[x >> 6] |= uint64_t(1) << (x & 63);
            bound[x >> kDepthBoundShift] = std::max(bound[x >> kDepthBoundShift], depth);
            if (keptWeights) {
                keptWeights[2 * x] = float(q[slotOf1] * inv);
                keptWeights[2 * x + 1] = float(q[slotOf2] * inv);
                continue;
            }
            if (idRow)
                idRow[x] = faceId;
            if constexpr (!litPerSample(kSurface))
                shadeSample(row + 3 * x, q, inv, quad);
        }
    }
};

}  // namespace detail
}  // namespace shading
}  // namespace cv

#endif  // OPENCV_SHADING_SHADERS3D_HPP
