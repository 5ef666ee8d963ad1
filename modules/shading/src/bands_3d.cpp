// This file is part of opencv_shading. License: Apache-2.0.
//
// The band pass's 3D entry point (bands.hpp): the mesh engine (mesh.hpp) with the span shaders
// of drawMesh3d. bands_3d_avx2.cpp compiles this file again for AVX2, in its own namespaces
// (see bands_2d.cpp for why 2D and 3D are separate units).
#include <opencv2/shading.hpp>

#include "bands.hpp"
#include "mesh.hpp"
#include "screen_mesh.hpp"
#include "shaders.hpp"
#include "shaders3d.hpp"

#include <limits>

namespace cv {
namespace shading {
namespace detail {
OPENCV_SHADING_ISA_BEGIN
namespace {

template <typename T, Surface kSurface>
void shadeKeptSamples(const ScreenMesh& screen, const DepthTargets& targets, T* row, int y,
                      const int* kept, const float* weights, const uint64_t* written, int width);

/** Lit flat faces (ScreenMesh::flatLit): the colours of `count` set-up faces (at most
kLightBatch), lit together. Without lights, nothing: the shaders read ScreenMesh::faceValues. */
inline void lightFlatFaces(const ScreenMesh& screen, const DepthTargets& targets,
                           const int* faces, int count, float (*colors)[3])
{
    const ScreenMesh::FlatLit& lit = screen.flatLit;
    if (!lit.faces || count == 0)
        return;
    alignas(32) float in[9][kLightBatch];
    alignas(32) float out[6][kLightBatch];
    for (int j = 0; j < count; j++)
        stageFace(lit.verts, &lit.colors, lit.faces[screen.sourceOf(faces[j])], in, j);
    targets.lighting->lightRows(false, in, out, count);
    for (int j = 0; j < count; j++)
        for (int k = 0; k < 3; k++)
            colors[j][k] = out[k][j];
}

/** A flat face's colour in canvas units: lit (`litColor`, from lightFlatFaces) or as given. */
template <typename T>
inline void flatFaceColor(const ScreenMesh& screen, int face, const float* litColor, T color[3])
{
    const float* values = screen.faceValues.data() + size_t(face) * screen.faceStride;
    for (int k = 0; k < 3; k++)
        color[k] = toChannel<T>(screen.flatLit.faces ? litColor[k] : values[k]);
}

/** The span shaders of the 3D path, built per face from the ScreenMesh. */
template <typename T, Surface kSurface>
struct SurfaceShaders {
    using Shader = SurfaceShader<T, kSurface>;
    using SmallShader = typename Shader::Small;
    static constexpr int kAttributes = attributeCount(kSurface);  //!< per ScreenMesh vertex
    static constexpr bool kZBuffer = true;  //!< SurfaceShader::depthTest
    //! kFlat: lightFaces() gives make() the colours of lit faces (ScreenMesh::flatLit).
    static constexpr bool kLightsFaces = kSurface == Surface::kFlat;
    const ScreenMesh* screen;
    const DepthTargets* targets;

    /** Lit flat faces (ScreenMesh::flatLit): the colours of `count` set-up faces (at most
    kLightBatch), lit together. Without lights, nothing: make() reads ScreenMesh::faceValues. */
    void lightFaces(const int* faces, int count, float (*colors)[3]) const
    {
        lightFlatFaces(*screen, *targets, faces, count, colors);
    }

    void prefetchVertex(int vertex) const
    {
        __builtin_prefetch(&screen->invZ[vertex]);
        if constexpr (Shader::kAttributes > 0)  // read by make()
            __builtin_prefetch(&screen->attributes[size_t(vertex) * kAttributes]);
    }

    //! Fills the band's rows of the outputs this call created (DepthTargets::fillDepth).
    void beginBand(int y0, int y1) const
    {
        const DepthTargets& out = *targets;
        for (int y = y0; y < y1; y++) {
            if (out.fillDepth)
                std::fill_n(Shader::template outputRow<float>(out.depth, out.depthStep, y),
                            out.width, std::numeric_limits<float>::infinity());
            if (out.fillIds)
                std::fill_n(Shader::template outputRow<int>(out.ids, out.idsStep, y), out.width, -1);
        }
    }

    //! Deferred Phong (BandOptions::deferred): lights a row's kept (written) samples.
    void shadeKeptRow(T* row, int y, const int* kept, const float* weights,
                      const uint64_t* written, int width) const
    {
        if constexpr (litPerSample(kSurface))
            shadeKeptSamples<T, kSurface>(*screen, *targets, row, y, kept, weights, written,
                                          width);
    }

    //! Small faces' shaders give Shader's values for every face.
    bool smallShadersFit() const { return true; }

    //! The face's shader; `litColor`: its colour from lightFaces(), if it lit it.
    Shader make(const TriangleSetup& t, const int* order, const Vec3i& f, int face,
                const float* litColor = nullptr) const
    {
        Shader s(t, targets, screen->sourceOf(face));
        finish(s, t, order, f, face, litColor);
        return s;
    }

    //! make() for a small face set up with others (setUpSmallFaces in mesh.hpp).
    SmallShader makeSmall(const SmallWeights& w, const int* order, const Vec3i& f, int face,
                          const float* litColor = nullptr) const
    {
        SmallShader s(w, targets, screen->sourceOf(face));
        const TriangleSetup unread{};  // SmallWeights read no setup
        finish(s, unread, order, f, face, litColor);
        return s;
    }

    //! The shader's values past its weights: per vertex in canonical `order`, and per face.
    template <class S>
    __attribute__((always_inline)) void finish(S& s, const TriangleSetup& t, const int* order,
                                               const Vec3i& f, int face,
                                               const float* litColor) const
    {
        for (int i = 0; i < 3; i++) {
            const int v = f[order[i]];
            s.invZ[i] = screen->invZ[v];
            for (int k = 0; k < Shader::kAttributes; k++)  // none when lit per sample
                s.attributes[i][k] = screen->attributes[size_t(v) * kAttributes + k];
        }
        s.finishSetup(t);
        for (int i = 0; i < 3; i++) {
            if (order[i] == 1)
                s.slotOf1 = i;
            if (order[i] == 2)
                s.slotOf2 = i;
        }
        if constexpr (kSurface == Surface::kFlat)
            flatFaceColor(*screen, face, litColor, s.color);
        if constexpr (kSurface == Surface::kTexturedFaceLit)
            for (int k = 0; k < 6; k++)
                s.faceLight[k] = screen->faceValues[size_t(face) * screen->faceStride + k];
    }
};

/** Flat faces in painter's order with no depth or face-id output: only the colour is drawn, so
the faces take render()'s flat shader (FlatShader, set to each face's colour). It has a pen and
reads no weights, so the engine's sample blocks serve these faces as they serve render()'s
(SurfaceShaders<T, kFlat> computes each sample's depth, for the outputs it may write). The same
pixels. */
template <typename T>
struct FaceColorShaders {
    using Shader = FlatShader<T>;
    using SmallShader = FlatShader<T>;
    static constexpr bool kZBuffer = false;     //!< painter's order only
    static constexpr bool kLightsFaces = true;  //!< as SurfaceShaders<T, kFlat>
    const ScreenMesh* screen;
    const DepthTargets* targets;

    void lightFaces(const int* faces, int count, float (*colors)[3]) const
    {
        lightFlatFaces(*screen, *targets, faces, count, colors);
    }

    void prefetchVertex(int /*vertex*/) const {}  // nothing read per vertex
    void beginBand(int /*y0*/, int /*y1*/) const {}  // no outputs to fill
    bool smallShadersFit() const { return true; }

    Shader make(const TriangleSetup&, const int*, const Vec3i&, int face,
                const float* litColor = nullptr) const
    {
        T color[3];
        flatFaceColor(*screen, face, litColor, color);
        return Shader(color);
    }
};

/** Deferred lighting: lights the kept samples of a row (see BandOptions::deferred), those whose
bit is set in `written`: the kept face's vertex attributes weighted by the kept weights, lit a
batch at a time. Neighbouring samples mostly keep the same face: they are taken in runs of one
face, whose attributes are read once. */
template <typename T, Surface kSurface>
void shadeKeptSamples(const ScreenMesh& screen, const DepthTargets& targets, T* row, int y,
                      const int* kept, const float* weights, const uint64_t* written, int width)
{
    int* const idRow =
        targets.ids ? reinterpret_cast<int*>(targets.ids + size_t(y) * targets.idsStep) : nullptr;
    constexpr int n = attributeCount(kSurface);
    LitBatch<T> pending;
    // Samples x .. end - 1, all kept by `face`.
    auto shadeRun = [&](int x, int end, int face) {
        if (idRow)
            std::fill(idRow + x, idRow + end, screen.sourceOf(face));
        const Vec3i& f = screen.mesh.faces[face];
#if OPENCV_SHADING_SIMD128
        // The scalar loop's operations (below), four attributes at a time: the face's attributes
        // (each as float(double) gives it; past n, zeros) in `lanes`.
        constexpr int kPadded = (n + 3) & ~3;
        using Lanes = v_float32x4[3][kPadded / 4];
        auto loadLanes = [&](Lanes& lanes) {
            for (int i = 0; i < 3; i++) {
                const double* source = screen.attributes.data() + size_t(f[i]) * n;
                auto pair = [&](int k) {
                    return k + 2 <= n ? v_load(source + k)
                                      : v_float64x2(k < n ? source[k] : 0.0, 0.0);
                };
                for (int j = 0; j < kPadded / 4; j++)
                    lanes[i][j] = v_cvt_f32(pair(4 * j), pair(4 * j + 2));
            }
        };
        // Sample `at`'s attributes.
        auto interpolate = [&](const Lanes& lanes, int at, v_float32x4 (&v)[kPadded / 4]) {
            const float w1 = weights[2 * at], w2 = weights[2 * at + 1], w0 = 1.f - w1 - w2;
            const v_float32x4 l0 = v_setall_f32(w0), l1 = v_setall_f32(w1), l2 = v_setall_f32(w2);
            for (int j = 0; j < kPadded / 4; j++)
                v[j] = l0 * lanes[0][j] + l1 * lanes[1][j] + l2 * lanes[2][j];
        };
        if constexpr (kSurface == Surface::kPhong) {
            while (x < end) {
                Lanes lanes;  // read again after a flush: no vector lives across the kernel's call
                loadLanes(lanes);
                const int batchEnd = std::min(end, x + kLightBatch - pending.count);
                for (; x < batchEnd; x++) {
                    v_float32x4 v[kPadded / 4];
                    interpolate(lanes, x, v);
                    pending.addLanes(row + 3 * x, v[0], v[1], v[2]);
                }
                if (pending.full())
                    pending.flush(*targets.lighting);
            }
        } else {
            Lanes lanes;
            loadLanes(lanes);
            for (; x < end; x++) {
                v_float32x4 v[kPadded / 4];
                interpolate(lanes, x, v);
                alignas(16) float values[kPadded];
                for (int j = 0; j < kPadded / 4; j++)
                    v_store_aligned(values + 4 * j, v[j]);
                shadeAttributes<T, kSurface>(row + 3 * x, values, targets, &pending);
            }
        }
#else
        float a[3][n];  // the face's vertex attributes, each as float(double) gives it
        for (int i = 0; i < 3; i++)
            for (int k = 0; k < n; k++)
                a[i][k] = float(screen.attributes[size_t(f[i]) * n + k]);
        for (; x < end; x++) {
            const float w1 = weights[2 * x], w2 = weights[2 * x + 1], w0 = 1.f - w1 - w2;
            float v[n];
            for (int k = 0; k < n; k++)
                v[k] = w0 * a[0][k] + w1 * a[1][k] + w2 * a[2][k];
            shadeAttributes<T, kSurface>(row + 3 * x, v, targets, &pending);
        }
#endif
    };
    const int words = (width + 63) / 64;
    for (int word = 0; word < words; word++)
        for (uint64_t bits = written[word]; bits;) {
            // A run of kept samples in the word, cut where the kept face changes.
            const int first = __builtin_ctzll(bits);
            const uint64_t from = bits >> first;
            const int length = ~from == 0 ? 64 - first : __builtin_ctzll(~from);
            bits &= ~(rowsBelow(length) << first);
            const int end = word * 64 + first + length;
            for (int x = word * 64 + first; x < end;) {
                const int face = kept[x];
                int runEnd = x + 1;
                while (runEnd < end && kept[runEnd] == face)
                    runEnd++;
                shadeRun(x, runEnd, face);
                x = runEnd;
            }
        }
    pending.flush(*targets.lighting);
}

template <typename T, Surface kSurface>
void drawSurface(Mat& canvas, const ScreenMesh& screen, const DepthTargets& targets, bool zbuffer,
                 const Vec<T, 3>* background)
{
    BandOptions options;
    options.depthTested = zbuffer;
    // Per-sample lighting costs more than the bookkeeping: shade each sample once.
    options.deferred = options.frontToBack = litPerSample(kSurface);
    drawMeshInBands(canvas, screen.mesh, SurfaceShaders<T, kSurface>{&screen, &targets},
                    background, options);
}

template <typename T>
void drawScreenMeshAs(Mat& canvas, const ScreenMesh& screen, const DepthTargets& targets,
                      bool zbuffer, const Scalar* background)
{
    Vec<T, 3> bg;
    const Vec<T, 3>* fill = backgroundAs(background, bg);
    switch (screen.surface) {
    case Surface::kFlat:
        if (!zbuffer && !targets.depth && !targets.ids) {
            drawMeshInBands(canvas, screen.mesh, FaceColorShaders<T>{&screen, &targets}, fill,
                            BandOptions());
            return;
        }
        return drawSurface<T, Surface::kFlat>(canvas, screen, targets, zbuffer, fill);
    case Surface::kGouraud:
        return drawSurface<T, Surface::kGouraud>(canvas, screen, targets, zbuffer, fill);
    case Surface::kPhong:
        return drawSurface<T, Surface::kPhong>(canvas, screen, targets, zbuffer, fill);
    case Surface::kTextured:
        return drawSurface<T, Surface::kTextured>(canvas, screen, targets, zbuffer, fill);
    case Surface::kTexturedFaceLit:
        return drawSurface<T, Surface::kTexturedFaceLit>(canvas, screen, targets, zbuffer, fill);
    case Surface::kTexturedVertexLit:
        return drawSurface<T, Surface::kTexturedVertexLit>(canvas, screen, targets, zbuffer,
                                                           fill);
    case Surface::kTexturedSampleLit:
        return drawSurface<T, Surface::kTexturedSampleLit>(canvas, screen, targets, zbuffer,
                                                           fill);
    }
}

}  // namespace
OPENCV_SHADING_ISA_END

void OPENCV_SHADING_BANDS_NAMESPACE::drawScreenMesh(Mat& canvas, const ScreenMesh& screen,
                                                    const DepthTargets& targets, bool zbuffer,
                                                    const Scalar* background)
{
    if (canvas.depth() == CV_8U)
        drawScreenMeshAs<uchar>(canvas, screen, targets, zbuffer, background);
    else
        drawScreenMeshAs<float>(canvas, screen, targets, zbuffer, background);
}

}  // namespace detail
}  // namespace shading
}  // namespace cv
