// This file is part of opencv_shading. License: Apache-2.0.
//
// Span shaders of the 3D path: perspective-correct depth and attributes, the z-buffer test, the
// depth and face-id outputs, texturing, and the Phong lighting model (seed 004) they share.
#ifndef OPENCV_SHADING_SHADERS3D_HPP
#define OPENCV_SHADING_SHADERS3D_HPP

#include "input.hpp"
#include "shaders.hpp"
#include "lighting_kernel.hpp"
#include "texture_sampler.hpp"

#include <opencv2/core.hpp>

#include <cmath>
#include <cstring>
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

    Lighting() = default;
    Lighting(const Lighting&) = delete;  // `kernel` points into this object's lightData
    Lighting& operator=(const Lighting&) = delete;

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

    /** Call once the fields above are set: the float form the batch kernels read. */
    void prepare()
    {
        lightData.clear();
        for (const Light& light : lights)
            for (int k = 0; k < 3; k++)
                lightData.push_back(float(light.position[k]));
        const size_t intensities = lightData.size();
        for (const Light& light : lights)
            for (int k = 0; k < 3; k++)
                lightData.push_back(float(light.intensity[k]));
        kernel.lightPositions = lightData.data();
        kernel.lightIntensities = lightData.data() + intensities;
        kernel.lightCount = int(lights.size());
        for (int k = 0; k < 3; k++) {
            kernel.eye[k] = float(eye[k]);
            kernel.ambient[k] = float(ambient[k]);
        }
        kernel.kd = float(kd), kernel.ks = float(ks), kernel.shininess = shininess;
        kernel.wholeShininess =
            shininess == std::floor(shininess) && shininess <= 256 ? int(shininess) : -1;
        kernel.toColor = float(1.0 / unit), kernel.toUnit = float(unit);
    }

    /** Lights points 0 .. count - 1 (at most kLightBatch) given in the kernel's rows: in[k][j]
    is value k of point j (k: position 0-2, normal 3-5 (unit or zero), colour 6-8 in the canvas's
    units). With `terms`, only rows 0-5 are read and out[0..5] receive terms() (D, then S);
    without, out[0..2] receive the lit colour. In float lanes where SIMD is built (for per-face
    and per-vertex lighting of big meshes), else one point at a time in double. The kernel
    computes whole vectors: in's lanes from count to the next multiple of 8 are set to the last
    point, and out's lanes there are written too. */
    void lightRows(bool terms, float (*in)[kLightBatch], float (*out)[kLightBatch],
                   int count) const
    {
        if (count <= 0)
            return;
#if OPENCV_SHADING_SIMD128
        const int padded = (count + 7) & ~7;  // whole vectors: the last point repeated
        for (int k = 0; k < (terms ? 6 : 9); k++)
            for (int j = count; j < padded; j++)
                in[k][j] = in[k][count - 1];
        if (terms)
            termsBatch(kernel, in, out, count);
        else
            shadeBatch(kernel, in, out, count);
#else
        for (int j = 0; j < count; j++) {
            const Vec3d p(in[0][j], in[1][j], in[2][j]), n(in[3][j], in[4][j], in[5][j]);
            Vec3d d, s;
            if (terms)
                this->terms(p, n, d, s);
            else
                d = shade(p, n, Vec3d(in[6][j], in[7][j], in[8][j]));
            for (int k = 0; k < 3; k++) {
                out[k][j] = float(d[k]);
                if (terms)
                    out[3 + k][j] = float(s[k]);
            }
        }
#endif
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

    LightingKernel kernel;  //!< set by prepare()

private:
    std::vector<float> lightData;  //!< kernel's light positions, then intensities
};

//! Normalizes v; a zero (or non-finite-length) vector stays zero.
inline Vec3d unitOrZero(const Vec3d& v)
{
    const double length = std::sqrt(v.dot(v));
    return length > 0 && std::isfinite(length) ? v * (1.0 / length) : Vec3d(0, 0, 0);
}

//! The unit normal of face v0 v1 v2 by the right-hand rule; zero for a degenerate face.
inline Vec3d faceNormal(const Vec3d& v0, const Vec3d& v1, const Vec3d& v2)
{
    return unitOrZero((v1 - v0).cross(v2 - v0));
}

/** Stages face f (flat shading) as point `slot` of Lighting::lightRows's rows: its centroid,
its face normal and, with `colors`, the mean of its vertex colours. */
inline void stageFace(const Rows3& verts, const Rows3* colors, const Vec3i& f,
                      float (*in)[kLightBatch], int slot)
{
    const Vec3d v0 = verts[f[0]], v1 = verts[f[1]], v2 = verts[f[2]];
    const Vec3d centroid = (v0 + v1 + v2) * (1.0 / 3.0), n = faceNormal(v0, v1, v2);
    Vec3d c0, c1, c2;
    if (colors)
        c0 = (*colors)[f[0]], c1 = (*colors)[f[1]], c2 = (*colors)[f[2]];
    for (int k = 0; k < 3; k++) {
        in[k][slot] = float(centroid[k]);
        in[3 + k][slot] = float(n[k]);
        if (colors)
            in[6 + k][slot] = float((c0[k] + c1[k] + c2[k]) / 3.0);
    }
}

OPENCV_SHADING_ISA_BEGIN

/** Samples waiting to be lit together (Phong): their pixels and interpolated position, normal
and colour, lit a batch at a time in float lanes where SIMD is built, else one by one in double.
Where SIMD is built the values are staged straight in the lighting kernel's rows (value k of
sample j in rows[k][j]), so that a full batch goes to the kernel as it is. */
template <typename T>
struct LitBatch {
    T* pixels[kLightBatch];
    alignas(32) float rows[9][kLightBatch];
    int count = 0;

    bool full() const { return count == kLightBatch; }

    //! Queues a pixel; v: position, normal (not normalized), colour. Lights when the batch is full.
    void add(T* pixel, const float v[9], const Lighting& lighting)
    {
        for (int k = 0; k < 9; k++)
            rows[k][count] = v[k];
        pixels[count++] = pixel;
        if (full())
            flush(lighting);
    }

#if OPENCV_SHADING_SIMD128
    /** add() without the flush (the caller flushes once full()), for values in lanes: a holds
    values 0-3, b values 4-7, c value 8 in its first lane. */
    __attribute__((always_inline)) void addLanes(T* pixel, const v_float32x4& a,
                                                 const v_float32x4& b, const v_float32x4& c)
    {
        const int j = count;
        storeLane<0>(&rows[0][j], a), storeLane<1>(&rows[1][j], a);
        storeLane<2>(&rows[2][j], a), storeLane<3>(&rows[3][j], a);
        storeLane<0>(&rows[4][j], b), storeLane<1>(&rows[5][j], b);
        storeLane<2>(&rows[6][j], b), storeLane<3>(&rows[7][j], b);
        storeLane<0>(&rows[8][j], c);
        pixels[count++] = pixel;
    }

    //! Writes lane kLane of v to *to: one instruction where SSE4.1 is built (the AVX2 build).
    template <int kLane>
    static void storeLane(float* to, const v_float32x4& v)
    {
#if defined(__SSE4_1__)
        const int bits = _mm_extract_ps(v.val, kLane);
        std::memcpy(to, &bits, sizeof(bits));
#else
        *to = v_extract_n<kLane>(v);
#endif
    }
#endif

    void flush(const Lighting& lighting)
    {
        if (count == 0)
            return;
#if OPENCV_SHADING_SIMD128
        // Whole vectors: the first sample repeated (kLightBatch is a multiple of 8).
        if (count % 8 != 0)
            for (int k = 0; k < 9; k++)
                for (int i = count; i % 8 != 0; i++)
                    rows[k][i] = rows[k][0];
        alignas(32) float lit[3][kLightBatch];
        shadeBatch(lighting.kernel, rows, lit, count);
        int i = 0;
        if constexpr (std::is_same<T, float>::value)
            for (; i + 4 <= count; i += 4) {  // four pixels' colours a transpose
                v_float32x4 p0, p1, p2, p3;
                v_transpose4x4(v_load_aligned(lit[0] + i), v_load_aligned(lit[1] + i),
                               v_load_aligned(lit[2] + i), v_load_aligned(lit[2] + i), p0, p1,
                               p2, p3);
                storePixel(pixels[i], p0);
                storePixel(pixels[i + 1], p1);
                storePixel(pixels[i + 2], p2);
                storePixel(pixels[i + 3], p3);
            }
        for (; i < count; i++)
            for (int k = 0; k < 3; k++)
                pixels[i][k] = toChannel<T>(lit[k][i]);
#else
        for (int i = 0; i < count; i++) {
            const Vec3d c = lighting.shade(Vec3d(rows[0][i], rows[1][i], rows[2][i]),
                                           unitOrZero(Vec3d(rows[3][i], rows[4][i], rows[5][i])),
                                           Vec3d(rows[6][i], rows[7][i], rows[8][i]));
            for (int k = 0; k < 3; k++)
                pixels[i][k] = toChannel<T>(float(c[k]));
        }
#endif
        count = 0;
    }
};

OPENCV_SHADING_ISA_END

/** What the 3D shaders write besides the canvas, and the lighting and texture they use. */
struct DepthTargets {
    uchar* depth = nullptr;  //!< CV_32FC1 rows, canvas-sized; null: not written
    size_t depthStep = 0;
    uchar* ids = nullptr;    //!< CV_32SC1 rows; null: not written
    size_t idsStep = 0;
    //! Outputs created by this call: each band first fills its rows (depth +inf, ids -1), in
    //! parallel and while they are about to be used, instead of a serial pass before.
    bool fillDepth = false, fillIds = false;
    int width = 0;  //!< of the outputs' rows
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

//! Surfaces lit per sample: their samples go through LitBatch, and through deferred shading.
constexpr bool litPerSample(Surface s)
{
    return s == Surface::kPhong || s == Surface::kTexturedSampleLit;
}

OPENCV_SHADING_ISA_BEGIN

/** Colours a sample from its interpolated attributes `a` (attributeCount(kSurface) values), or
queues it in `pending` to be lit (litPerSample; null for the other surfaces). Not for kFlat or
kTexturedFaceLit, whose colour or lighting belongs to the face. */
template <typename T, Surface kSurface>
inline void shadeAttributes(T* pixel, const float* a, const DepthTargets& targets,
                            LitBatch<T>* pending)
{
    if constexpr (kSurface == Surface::kGouraud) {
        for (int k = 0; k < 3; k++)
            pixel[k] = toChannel<T>(a[k]);
    } else if constexpr (kSurface == Surface::kPhong) {
        pending->add(pixel, a, *targets.lighting);
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
        pending->add(pixel, v, *targets.lighting);
    }
}

/** Shades a triangle of the projected mesh. Per sample: the screen-space weights w_i, their
perspective-correct form q_i = (w_i / z_i) / sum_j (w_j / z_j) and the depth
1 / sum_j (w_j / z_j); then the z-buffer test, and the colour (see Surface): the attributes
interpolated with q, then shadeAttributes. w_i / z_i is affine in screen space: each span starts
from the exact weights (ExactWeights) and steps by its x-gradient, so a sample's values depend
only on the face and its span. Weights: ExactWeights, or SmallWeights for a small face set up
with others (the same values). */
template <typename T, Surface kSurface, class Weights = ExactWeights>
struct SurfaceShader {
    //! The form of this shader for faces set up as SmallWeights.
    using Small = SurfaceShader<T, kSurface, SmallWeights>;
    static constexpr bool kReadsWeights = true;
    //! The attributes a span interpolates itself: none for surfaces lit per sample, which are
    //! always drawn deferred (BandOptions::deferred) from the ScreenMesh's vertices.
    static constexpr int kAttributes = litPerSample(kSurface) ? 0 : attributeCount(kSurface);
    Weights weights;
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

    SurfaceShader(const Weights& w, const DepthTargets* out, int id)
        : weights(w), targets(out), faceId(id)
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

    //! The sample's colour from its q (unnormalized, `inv` = 1 / sum).
    void shadeSample(T* pixel, const double q[3], double inv) const
    {
        static_assert(!litPerSample(kSurface), "surfaces lit per sample are drawn deferred");
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
                shadeAttributes<T, kSurface>(pixel, a, *targets, nullptr);
            }
        }
    }

    /** Calls fn(x, q, inv) for each sample x of the span: q its unnormalized perspective
    weights, stepped from the span's exact start, and inv = 1 / sum q its depth. */
    template <typename Fn>
    __attribute__((always_inline)) void forSpanSamples(const TriangleSetup& t, int y, int xBegin,
                                                       int xEnd, Fn&& fn) const
    {
        double q[3];
        startSpan(t, xBegin, y, q);
        for (int x = xBegin; x < xEnd;
             x++, q[0] += stepX[0], q[1] += stepX[1], q[2] += stepX[2])
            fn(x, q, 1.0 / (q[0] + q[1] + q[2]));
    }

    //! Deferred shading's record of sample x: the perspective-correct weights of the face's own
    //! vertices 1 and 2 (vertex 0's is one less their sum).
    void keepWeights(int x, const double q[3], double inv, float* keptWeights) const
    {
        keptWeights[2 * x] = float(q[slotOf1] * inv);
        keptWeights[2 * x + 1] = float(q[slotOf2] * inv);
    }

    //! Row y of a canvas-sized output (depth or ids), or null when that output is not drawn.
    template <typename P>
    static P* outputRow(uchar* data, size_t step, int y)
    {
        return data ? reinterpret_cast<P*>(data + size_t(y) * step) : nullptr;
    }

    //! Draws the span without a depth test (painter's order): depth, face id and colour.
    void operator()(const TriangleSetup& t, T* row, int y, int /*spanBegin*/, int xBegin,
                    int xEnd) const
    {
        float* const depthRow = outputRow<float>(targets->depth, targets->depthStep, y);
        int* const idRow = outputRow<int>(targets->ids, targets->idsStep, y);
        forSpanSamples(t, y, xBegin, xEnd, [&](int x, const double q[3], double inv) {
            if (depthRow)
                depthRow[x] = float(inv);
            if (idRow)
                idRow[x] = faceId;
            if constexpr (!litPerSample(kSurface))
                shadeSample(row + 3 * x, q, inv);
        });
    }

    /** Deferred painter's order (BandOptions::deferred without depthTested): the span's samples
    are this face's; each gets its depth, and in `kept` the face and in `keptWeights` the
    perspective-correct weights of the face's own vertices 1 and 2, for shading later. */
    void keep(const TriangleSetup& t, int y, int xBegin, int xEnd, int face, int* kept,
              float* keptWeights) const
    {
        float* const depthRow = outputRow<float>(targets->depth, targets->depthStep, y);
        forSpanSamples(t, y, xBegin, xEnd, [&](int x, const double q[3], double inv) {
            if (depthRow)
                depthRow[x] = float(inv);
            kept[x] = face;
            keepWeights(x, q, inv, keptWeights);
        });
    }

    /** Z-buffer (BandOptions::depthTested): takes the span's samples where (depth, face) is
    smaller than what the sample keeps (its bit in `covered` clear: the buffer's own value,
    depth only), so the faces may come in any order. A taken sample gets its depth, its face in
    `kept`, the block bookkeeping of ZBufferBlocks, and its colour and id, or for surfaces lit
    per sample (always drawn deferred, into `keptWeights`) the perspective-correct weights of the
    face's own vertices 1 and 2 for shading later. */
    void depthTest(const TriangleSetup& t, T* row, int y, int xBegin, int xEnd, int face,
                   int* kept, float* keptWeights, uint64_t* covered, float* bound) const
    {
        float* const depthRow = outputRow<float>(targets->depth, targets->depthStep, y);
        int* const idRow = outputRow<int>(targets->ids, targets->idsStep, y);
        forSpanSamples(t, y, xBegin, xEnd, [&](int x, const double q[3], double inv) {
            const float depth = float(inv);
            const float current = depthRow[x];
            if (!(depth < current ||
                  (depth == current && (covered[x >> 6] >> (x & 63) & 1) && kept[x] > face)))
                return;  // (the buffer's own value never loses a tie: it was first)
            depthRow[x] = depth;
            kept[x] = face;
            covered[x >> 6] |= uint64_t(1) << (x & 63);
            bound[x >> kDepthBoundShift] = std::max(bound[x >> kDepthBoundShift], depth);
            if constexpr (litPerSample(kSurface)) {  // always deferred
                keepWeights(x, q, inv, keptWeights);
            } else {
                if (idRow)
                    idRow[x] = faceId;
                shadeSample(row + 3 * x, q, inv);
            }
        });
    }
};

OPENCV_SHADING_ISA_END
}  // namespace detail
}  // namespace shading
}  // namespace cv

#endif  // OPENCV_SHADING_SHADERS3D_HPP
