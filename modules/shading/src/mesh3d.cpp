// This file is part of opencv_shading. License: Apache-2.0.
//
// drawMesh3d: a 3D mesh becomes projected, clipped triangles with per-vertex 1/Zc and
// attributes, drawn by the one 2D engine (mesh.hpp) with the 3D span shaders (shaders3d.hpp).
//
//   checks (all, before anything is written) -> camera coordinates -> normals and lighting
//   inputs -> per face: cull, clip at zNear, project -> bands (z-buffer or painter's order)
#include <opencv2/shading.hpp>

#include "camera.hpp"
#include "input.hpp"
#include "raster.hpp"
#include "bands.hpp"
#include "shaders3d.hpp"

#include <opencv2/core/utility.hpp>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>

namespace cv {
namespace shading {

PointLight::PointLight() : position(0, 0, 0), intensity(1, 1, 1) {}

PointLight::PointLight(const Point3d& position_, const Vec3d& intensity_)
    : position(position_), intensity(intensity_)
{
}

RenderSettings::RenderSettings()
    : shadeType(SHADE_GOURAUD), visibility(VISIBILITY_ZBUFFER), cullMode(CULL_NONE), zNear(1e-3),
      ambient(1, 1, 1), ka(0.2), kd(0.7), ks(0.5), shininess(16),
      textureInterpolation(INTER_LINEAR), textureBorder(BORDER_REPLICATE), clear(false),
      background(0, 0, 0, 0)
{
}

using namespace detail;

namespace {

inline bool isFinite(const Vec3d& v)
{
    return std::isfinite(v[0]) && std::isfinite(v[1]) && std::isfinite(v[2]);
}

/** Items per parallel chunk of the screen mesh's passes (transforming, lighting, clipping) for
`count` items: at most `most`, and few enough per chunk to make 32 chunks, so that the threads
get even shares of a small mesh (the knot's 5,000 vertices were two chunks of 4,096 and 904),
but not fewer than 512. It depends on the count only: passes that index per-chunk tables by
begin / chunk agree, whatever the thread count. */
inline int chunkSizeFor(int count, int most)
{
    return std::max(512, std::min(most, (count + 31) / 32));
}

//! Splits [0, count) into chunks for parallel_for_ and calls fn(begin, end) for each.
template <typename Fn>
void forChunks(int count, int chunk, Fn&& fn)
{
    parallel_for_(Range(0, (count + chunk - 1) / chunk), [&](const Range& r) {
        for (int c = r.start; c < r.end; c++)
            fn(c * chunk, std::min(count, (c + 1) * chunk));
    });
}

//! The index of the first vector of `v` with a non-finite value, or -1.
int firstNonFinite(const Rows3& v)
{
    for (size_t i = 0; i < v.size(); i++)
        if (!isFinite(v[i]))
            return int(i);
    return -1;
}

/** Vertex normals (seed 004): the normalized sum of the unit normals of the faces using each
vertex. Face normals in parallel; the sums in face order, serially, so that they never depend on
the thread count. */
void vertexNormalsOf(const Rows3& verts, const FaceRows& faces,
                     std::vector<Vec3d>& normals, std::vector<Vec3d>& perFace)
{
    perFace.resize(faces.size());
    forChunks(int(faces.size()), 8192, [&](int begin, int end) {
        for (int i = begin; i < end; i++) {
            const Vec3i& f = faces[i];
            perFace[i] = faceNormal(verts[f[0]], verts[f[1]], verts[f[2]]);
        }
    });
    normals.assign(verts.size(), Vec3d(0, 0, 0));
    for (size_t i = 0; i < faces.size(); i++)
        for (int k = 0; k < 3; k++)
            normals[faces[i][k]] += perFace[i];
    forChunks(int(normals.size()), 8192, [&](int begin, int end) {
        for (int i = begin; i < end; i++)
            normals[i] = unitOrZero(normals[i]);
    });
}

void writeRows(const std::vector<Vec3d>& values, OutputArray out)
{
    Mat(int(values.size()), 3, CV_64F, const_cast<Vec3d*>(values.data())).convertTo(out, CV_32F);
}

void checkSettings(const RenderSettings& s)
{
    if (s.shadeType != SHADE_FLAT && s.shadeType != SHADE_GOURAUD && s.shadeType != SHADE_PHONG)
        CV_Error(Error::StsBadFlag, format("settings.shadeType: expected SHADE_FLAT (0), "
                                           "SHADE_GOURAUD (1) or SHADE_PHONG (2), got %d",
                                           s.shadeType));
    if (s.visibility != VISIBILITY_ZBUFFER && s.visibility != VISIBILITY_PAINTER)
        CV_Error(Error::StsBadFlag, format("settings.visibility: expected VISIBILITY_ZBUFFER (0) "
                                           "or VISIBILITY_PAINTER (1), got %d", s.visibility));
    if (s.cullMode != CULL_NONE && s.cullMode != CULL_BACK && s.cullMode != CULL_FRONT)
        CV_Error(Error::StsBadFlag, format("settings.cullMode: expected CULL_NONE (0), CULL_BACK "
                                           "(1) or CULL_FRONT (2), got %d", s.cullMode));
    if (!(s.zNear > 0 && std::isfinite(s.zNear)))
        CV_Error(Error::StsOutOfRange,
                 format("settings.zNear: expected a finite value > 0, got %g", s.zNear));
    const std::pair<const char*, double> material[] = {
        {"ka", s.ka}, {"kd", s.kd}, {"ks", s.ks}, {"shininess", s.shininess}};
    for (const auto& m : material)
        if (!(m.second >= 0 && std::isfinite(m.second)))
            CV_Error(Error::StsOutOfRange, format("settings.%s: expected a finite value >= 0, "
                                                  "got %g", m.first, m.second));
    if (!isFinite(s.ambient))
        CV_Error(Error::StsOutOfRange, "settings.ambient: values must be finite");
    if (!isFinite(Vec3d(s.background[0], s.background[1], s.background[2])))
        CV_Error(Error::StsOutOfRange, "settings.background: values must be finite");
    for (size_t i = 0; i < s.lights.size(); i++)
        if (!isFinite(Vec3d(s.lights[i].position)) || !isFinite(s.lights[i].intensity))
            CV_Error(Error::StsOutOfRange,
                     format("settings.lights[%zu]: position and intensity must be finite", i));
}

//! The inputs of drawMesh3d, checked, and converted where they are not read in place.
struct Mesh3dInput {
    //! The caller's values where they are continuous CV_32F, else converted into the storage.
    Rows3 verts, colors, normals;
    std::vector<Vec3d> vertStorage, colorStorage, normalStorage;
    std::vector<Point2d> texCoords;  //!< textured meshes (then `colors` is empty)
    std::vector<Vec3d> faceNormals;  //!< scratch of vertexNormalsOf
    std::vector<double> cameraZ;     //!< per vertex: camera z (NaN: a coordinate not finite)
    std::vector<uint8_t> side;       //!< per vertex: where it lies, a VertexSide
    FaceRows faces;  //!< the caller's where they are continuous CV_32S, else faceStorage
    std::vector<Vec3i> faceStorage;
};

/** Points waiting to be lit together (Lighting::lightRows), staged in the kernel's rows. */
struct LightBlock {
    alignas(32) float in[9][kLightBatch];
    alignas(32) float out[6][kLightBatch];
};

//! Where a vertex lies for clipping at zNear (Mesh3dInput::side).
enum VertexSide : uint8_t { kNotFinite = 0, kBehind = 1, kInFront = 2 };

//! The surface a mesh is drawn with, from its shading, lights and texture.
Surface surfaceFor(int shadeType, bool lit, bool textured)
{
    if (!textured)
        return shadeType == SHADE_FLAT                 ? Surface::kFlat
               : shadeType == SHADE_PHONG && lit       ? Surface::kPhong
                                                       : Surface::kGouraud;  // unlit Phong too
    if (!lit)
        return Surface::kTextured;
    return shadeType == SHADE_FLAT      ? Surface::kTexturedFaceLit
           : shadeType == SHADE_GOURAUD ? Surface::kTexturedVertexLit
                                        : Surface::kTexturedSampleLit;
}

/** Moves the mesh into the camera frame, culls, clips at zNear and projects: fills `screen`,
with the attributes of `screen.surface` per vertex (see Surface). */
void buildScreenMesh(Mesh3dInput& in, const Camera& cam, const RenderSettings& settings,
                     const Lighting& lighting, ScreenMesh& screen, StageTimer& timer)
{
    const int vertexCount = int(in.verts.size()), faceCount = int(in.faces.size());
    const bool lit = lighting.lit();
    const bool textured = !in.texCoords.empty();
    const int shade = settings.shadeType;
    const Surface surface = surfaceFor(shade, lit, textured);
    const int stride = attributeCount(surface);
    screen.surface = surface;
    screen.stride = stride;
    const double zNear = settings.zNear;
    const bool painter = settings.visibility == VISIBILITY_PAINTER;
    const Vec3d eye = cam.centre();

    // Vertices: camera depth, side of the near plane, the projection of those in front,
    // attributes. The faces' passes read a byte per vertex, not its camera coordinates: the
    // vertices of a big mesh's faces come from all over its arrays.
    std::vector<double>& cameraZ = in.cameraZ;
    cameraZ.resize(vertexCount);
    std::vector<uint8_t>& side = in.side;
    side.resize(vertexCount);
    // Projected straight onto the band pass's subpixel grid: it snaps nothing itself.
    screen.mesh.vertices = PointRows();
    std::vector<FixedPoint>& projected = screen.mesh.snapped;
    projected.resize(vertexCount);
    screen.invZ.resize(vertexCount);
    screen.attributes.resize(size_t(vertexCount) * stride);
    const double nan = std::numeric_limits<double>::quiet_NaN();
    // Gouraud: each vertex lit once, its colour (or D and S when textured, after the uv).
    // Normals are used as unit normals (one-sided, as given), normalized where they are read.
    const bool litVertices =
        surface == Surface::kTexturedVertexLit || (surface == Surface::kGouraud && lit);
    std::atomic<bool> allInFront(true);  // and, textured, every texture coordinate usable
    forChunks(vertexCount, chunkSizeFor(vertexCount, 4096), [&](int begin, int end) {
        if (litVertices) {
            LightBlock block;
            const int outStride = textured ? 6 : 3;
            const int first = stride - outStride;  // after the uv
            for (int b = begin; b < end; b += kLightBatch) {
                const int count = std::min(kLightBatch, end - b);
                for (int j = 0; j < count; j++) {
                    const Vec3d vertex = in.verts[b + j], normal = unitOrZero(in.normals[b + j]);
                    const Vec3d color = textured ? Vec3d() : in.colors[b + j];
                    for (int k = 0; k < 3; k++) {
                        block.in[k][j] = float(vertex[k]);
                        block.in[3 + k][j] = float(normal[k]);
                        block.in[6 + k][j] = float(color[k]);  // (unread when textured)
                    }
                }
                lighting.lightRows(textured, block.in, block.out, count);
                for (int j = 0; j < count; j++)
                    for (int k = 0; k < outStride; k++)
                        screen.attributes[size_t(b + j) * stride + first + k] = block.out[k][j];
            }
        }
        bool chunkInFront = true;
        for (int i = begin; i < end; i++) {
            const Vec3d c = cam.toCamera(in.verts[i]);
            const bool finite = isFinite(c);
            cameraZ[i] = finite ? c[2] : nan;
            const bool front = finite && c[2] >= zNear;
            chunkInFront &= front && (!textured || usableTexCoord(in.texCoords[i]));
            side[i] = !finite ? kNotFinite : front ? kInFront : kBehind;
            // Not in front: used by no face once the faces are cut at the near plane.
            projected[i] = front ? snapToGrid(cam.project(c)) : kUnusedPoint;
            screen.invZ[i] = 1.0 / c[2];
            double* a = screen.attributes.data() + size_t(i) * stride;
            if (textured) {
                a[0] = in.texCoords[i].x, a[1] = in.texCoords[i].y;
                a += 2;
            }
            if (surface == Surface::kGouraud && !lit) {
                const Vec3d color = in.colors[i];
                std::copy(color.val, color.val + 3, a);
            } else if (surface == Surface::kPhong || surface == Surface::kTexturedSampleLit) {
                const Vec3d vertex = in.verts[i], normal = unitOrZero(in.normals[i]);
                std::copy(vertex.val, vertex.val + 3, a);
                std::copy(normal.val, normal.val + 3, a + 3);
                if (!textured) {
                    const Vec3d color = in.colors[i];
                    std::copy(color.val, color.val + 3, a + 6);
                }
            }
        }
        if (!chunkInFront)
            allInFront.store(false, std::memory_order_relaxed);
    });

    timer.mark("vertices");
    // A mesh wholly in front of the near plane, without culling: every face is drawn whole. The
    // faces are then the caller's, and the band pass takes their sort keys from the vertices'
    // camera z (the painter's mean, the z-buffer's nearest): the faces' passes below are skipped,
    // but for the values of flat faces (unlit: their mean colours; textured and lit: D and S).
    const bool whole = allInFront && settings.cullMode == CULL_NONE;
    // Faces, in two parallel passes over chunks: what each face becomes (culled, whole, or cut
    // into one or two triangles with two new vertices), then, at offsets from prefix sums, the
    // faces and new vertices themselves. Face order (and so the tie order) is kept.
    enum : uint8_t { kSkip = 0, kWhole = 1, kCutOne = 2, kCutTwo = 3 };  // vertices behind
    std::vector<uint8_t> kind(whole ? 0 : faceCount);
    const int faceChunk = chunkSizeFor(faceCount, 4096);
    const int chunks = (faceCount + faceChunk - 1) / faceChunk;
    std::vector<int> chunkFaces(chunks + 1, 0), chunkVertices(chunks + 1, 0);
    // (Nothing to classify for a whole mesh: no chunks.)
    forChunks(whole ? 0 : faceCount, faceChunk, [&](int begin, int end) {
        int faces = 0, vertices = 0;
        for (int i = begin; i < end; i++) {
            const Vec3i& f = in.faces[i];
            const int s0 = side[f[0]], s1 = side[f[1]], s2 = side[f[2]];
            kind[i] = kSkip;
            if (s0 == kNotFinite || s1 == kNotFinite || s2 == kNotFinite)
                continue;
            if (textured && !(usableTexCoord(in.texCoords[f[0]]) &&
                              usableTexCoord(in.texCoords[f[1]]) &&
                              usableTexCoord(in.texCoords[f[2]])))
                continue;
            if (settings.cullMode != CULL_NONE) {
                const Vec3d v0 = in.verts[f[0]];
                const double facing = (in.verts[f[1]] - v0).cross(in.verts[f[2]] - v0).dot(eye - v0);
                if (settings.cullMode == CULL_BACK ? !(facing > 0) : !(facing < 0))
                    continue;
            }
            const int behind = (s0 == kBehind) + (s1 == kBehind) + (s2 == kBehind);
            kind[i] = behind == 0 ? kWhole : behind == 1 ? kCutOne : behind == 2 ? kCutTwo : kSkip;
            faces += kind[i] == kWhole || kind[i] == kCutTwo ? 1 : kind[i] == kCutOne ? 2 : 0;
            vertices += kind[i] >= kCutOne ? 2 : 0;
        }
        chunkFaces[begin / faceChunk + 1] = faces;
        chunkVertices[begin / faceChunk + 1] = vertices;
    });
    timer.mark("faces");
    for (int c = 0; c < chunks; c++) {
        chunkFaces[c + 1] += chunkFaces[c];
        chunkVertices[c + 1] += chunkVertices[c];
    }
    const int outFaces = whole ? faceCount : chunkFaces[chunks];
    const int outVertices = vertexCount + chunkVertices[chunks];
    screen.mesh.faceStorage.resize(whole ? 0 : outFaces);  // whole: the caller's faces
    screen.source.resize(whole ? 0 : outFaces);
    screen.mesh.faceDepth.resize(whole ? 0 : outFaces);
    screen.mesh.depth.clear();
    // Flat: per output face its colour, or when textured and lit its D and S. Lit flat faces
    // without a texture are lit by the band pass instead, as it sets them up (ScreenMesh::
    // flatLit): only faces that cover samples, and with the z-buffer are not hidden before.
    const bool lazyLit = surface == Surface::kFlat && lit;
    const int faceStride = surface == Surface::kFlat && !lit      ? 3
                           : surface == Surface::kTexturedFaceLit ? 6
                                                                  : 0;
    screen.faceStride = faceStride;
    screen.faceValues.resize(size_t(outFaces) * faceStride);
    const bool litFaces = surface == Surface::kTexturedFaceLit;
    projected.resize(outVertices);
    screen.invZ.resize(outVertices);
    screen.attributes.resize(size_t(outVertices) * stride);

    // The outputs, sized above: each chunk writes the pieces of its own faces.
    Vec3i* const outFace = screen.mesh.faceStorage.data();
    int* const source = screen.source.data();
    double* const faceDepth = screen.mesh.faceDepth.data();
    const double* const invZ = screen.invZ.data();
    float* const faceValues = screen.faceValues.data();
    forChunks(whole && faceStride == 0 ? 0 : faceCount, faceChunk, [&](int begin, int end) {
        int nextFace = whole ? begin : chunkFaces[begin / faceChunk];
        int nextVertex = vertexCount + chunkVertices[begin / faceChunk];
        // The point where edge front -> back meets the near plane, as a new vertex. Always
        // computed from the vertex in front, so faces sharing the edge share the point exactly.
        auto cut = [&](int front, int back) {
            const Vec3d a = cam.toCamera(in.verts[front]), b = cam.toCamera(in.verts[back]);
            const double s = (a[2] - zNear) / (a[2] - b[2]);
            const Vec3d c(a[0] + s * (b[0] - a[0]), a[1] + s * (b[1] - a[1]), zNear);
            const int v = nextVertex++;
            projected[v] = snapToGrid(cam.project(c));
            screen.invZ[v] = 1.0 / zNear;
            const double* fa = screen.attributes.data() + size_t(front) * stride;
            const double* ba = screen.attributes.data() + size_t(back) * stride;
            double* va = screen.attributes.data() + size_t(v) * stride;
            for (int k = 0; k < stride; k++)
                va[k] = fa[k] + s * (ba[k] - fa[k]);
            return v;
        };
        // Textured lit flat faces: each lit once, at its centroid with its face normal, into its
        // D and S, a batch at a time; the result goes to its pieces [first, end) of the output
        // faces. (Untextured ones are lit by the band pass: ScreenMesh::flatLit.)
        LightBlock block;
        int firstPiece[kLightBatch], endPiece[kLightBatch];
        int staged = 0;
        auto lightStaged = [&]() {
            lighting.lightRows(true, block.in, block.out, staged);
            for (int j = 0; j < staged; j++)
                for (int k = firstPiece[j]; k < endPiece[j]; k++)
                    for (int c = 0; c < 6; c++)
                        faceValues[size_t(k) * 6 + c] = block.out[c][j];
            staged = 0;
        };
        auto lightFace = [&](const Vec3i& f, int first, int pieceEnd) {
            stageFace(in.verts, nullptr, f, block.in, staged);
            firstPiece[staged] = first, endPiece[staged] = pieceEnd;
            if (++staged == kLightBatch)
                lightStaged();
        };
        for (int i = begin; i < end; i++) {
            const uint8_t faceKind = whole ? uint8_t(kWhole) : kind[i];
            if (faceKind == kSkip)
                continue;
            const Vec3i& f = in.faces[i];
            const int first = nextFace;
            // Painter's: the face's mean depth; z-buffer: each piece's nearest vertex, the order
            // that lets nearer faces hide farther ones before their setup.
            const double depth =
                painter && !whole ? (cameraZ[f[0]] + cameraZ[f[1]] + cameraZ[f[2]]) / 3.0 : 0;
            auto emit = [&](int v0, int v1, int v2) {
                outFace[nextFace] = Vec3i(v0, v1, v2);
                source[nextFace] = i;
                faceDepth[nextFace] =
                    painter ? depth : 1.0 / std::max(std::max(invZ[v0], invZ[v1]), invZ[v2]);
                nextFace++;
            };
            if (whole) {
                nextFace++;  // face i as the caller gave it
            } else if (faceKind == kWhole) {
                emit(f[0], f[1], f[2]);
            } else {
                // Rotate so that f[r] is the vertex alone on its side of the plane; rotation
                // keeps the winding.
                const bool aloneInFront = faceKind == kCutTwo;
                int r = 0;
                while ((side[f[r]] == kBehind) == aloneInFront)
                    r++;
                const int a = f[r], b = f[(r + 1) % 3], c = f[(r + 2) % 3];
                if (aloneInFront) {  // a in front: triangle a, ab, ca
                    const int ab = cut(a, b), ca = cut(a, c);
                    emit(a, ab, ca);
                } else {  // a behind: quad ab, b, c, ca as two triangles
                    const int ab = cut(b, a), ca = cut(c, a);
                    emit(ab, b, c);
                    emit(ab, c, ca);
                }
            }
            if (litFaces) {
                lightFace(f, first, nextFace);
            } else if (surface == Surface::kFlat && !lit) {  // the mean, as the 2D flats() takes it
                const Vec3d c0 = in.colors[f[0]], c1 = in.colors[f[1]], c2 = in.colors[f[2]];
                float mean[3];
                for (int j = 0; j < 3; j++)
                    mean[j] = float((c0[j] + c1[j] + c2[j]) / 3.0);
                for (int k = first; k < nextFace; k++)
                    std::copy(mean, mean + 3, faceValues + size_t(k) * 3);
            }
        }
        lightStaged();
    });
    screen.mesh.faces = whole ? in.faces : FaceRows(screen.mesh.faceStorage);
    if (whole)
        screen.mesh.depth.swap(cameraZ);
    screen.flatLit = {};
    if (lazyLit)
        screen.flatLit = {in.verts, in.colors, in.faces.data()};
}

}  // namespace

void computeNormals(InputArray verts3d, InputArray faces, OutputArray vertexNormals,
                    OutputArray faceNormals)
{
    std::vector<Vec3d> verts, normals, perFace;
    std::vector<Vec3i> faceList;
    readVectors(verts3d, "verts3d", -1, verts);
    readFaces(faces, "faces", int(verts.size()), faceList);
    vertexNormalsOf(Rows3(verts), FaceRows(faceList), normals, perFace);
    writeRows(normals, vertexNormals);
    if (faceNormals.needed())
        writeRows(perFace, faceNormals);
}

namespace {

/** drawMesh3d and drawTexturedMesh3d: `vcolors` for the one, `texCoords` and `texture` for the
other (the unused ones empty). */
void renderMesh3d(InputOutputArray canvasArr, InputArray verts3d, InputArray faces,
                  InputArray vcolors, InputArray texCoords, InputArray texture,
                  InputArray cameraMatrix, InputArray rvec, InputArray tvec,
                  const RenderSettings& settings, InputArray normals,
                  InputOutputArray depthBuffer, OutputArray faceIds, bool textured)
{
    StageTimer timer;
    // Every argument is checked before anything is written.
    checkCanvas(canvasArr, "canvas");
    checkSettings(settings);
    Mat tex;
    if (textured) {
        tex = texture.getMat();
        checkTexture(tex, "texture");
        checkSampling(settings.textureInterpolation, "settings.textureInterpolation",
                      settings.textureBorder, "settings.textureBorder");
    }
    const Camera cam = readCamera(cameraMatrix, rvec, tvec);
    thread_local Mesh3dInput in;
    // Shapes are checked as each array is read; the values not read in place are converted
    // together, in parallel, by readFaceRows.
    PendingConversions pending;
    in.verts = readRows3(verts3d, "verts3d", -1, in.vertStorage, &pending);
    const int vertexCount = int(in.verts.size());
    if (textured) {
        readPoints(texCoords, "texCoords", vertexCount, in.texCoords, &pending);
        in.colors = Rows3();
    } else {
        in.colors = readRows3(vcolors, "vcolors", vertexCount, in.colorStorage, &pending);
        in.texCoords.clear();
    }
    std::atomic<bool> normalsNonFinite(false);  // checked as they are converted
    in.normals = Rows3();
    if (!normals.empty())
        in.normals = readRows3(normals, "normals", vertexCount, in.normalStorage, &pending,
                               &normalsNonFinite);
    // Last: runs the conversions.
    in.faces = readFaceRows(faces, "faces", vertexCount, in.faceStorage, &pending);
    timer.mark("read");
    const bool lit = !settings.lights.empty();
    const bool needNormals = lit && settings.shadeType != SHADE_FLAT;
    if (!normals.empty()) {
        if (normalsNonFinite)
            CV_Error(Error::StsOutOfRange,
                     format("normals: normal %d is not finite", firstNonFinite(in.normals)));
    } else if (needNormals) {
        vertexNormalsOf(in.verts, in.faces, in.normalStorage, in.faceNormals);
        in.normals = Rows3(in.normalStorage);
    }
    const Size size = canvasArr.size();
    const bool depthGiven = !depthBuffer.empty();
    if (depthGiven && (depthBuffer.type() != CV_32FC1 || depthBuffer.size() != size))
        CV_Error(Error::StsBadArg,
                 format("depthBuffer: expected a %dx%d CV_32FC1 image (the canvas's size) or an "
                        "empty one, got %dx%d %s", size.width, size.height,
                        depthBuffer.size().width, depthBuffer.size().height,
                        typeToString(depthBuffer.type()).c_str()));

    Mat canvas = canvasArr.getMat();
    Lighting lighting;
    lighting.unit = canvas.depth() == CV_8U ? 255.0 : 1.0;
    lighting.eye = cam.centre();
    lighting.ambient = settings.ambient * settings.ka;
    lighting.kd = settings.kd, lighting.ks = settings.ks, lighting.shininess = settings.shininess;
    for (const PointLight& l : settings.lights)
        lighting.lights.push_back({Vec3d(l.position), l.intensity});
    lighting.prepare();
    timer.mark("normals");
    thread_local ScreenMesh screen;
    buildScreenMesh(in, cam, settings, lighting, screen, timer);
    timer.mark("pieces");

    // Outputs: created only now that every argument passed.
    const bool zbuffer = settings.visibility == VISIBILITY_ZBUFFER;
    Mat depth;
    thread_local Mat keptDepth;  // the z-buffer of calls without one: no new pages per call
    if (depthGiven) {
        depth = depthBuffer.getMat();
    } else if (depthBuffer.needed() || zbuffer) {
        if (depthBuffer.needed()) {
            depthBuffer.create(size, CV_32FC1);
            depth = depthBuffer.getMat();
        } else {
            keptDepth.create(size, CV_32FC1);
            depth = keptDepth;
        }
    }
    Mat ids;
    if (faceIds.needed()) {
        faceIds.create(size, CV_32SC1);
        ids = faceIds.getMat();
    }
    timer.mark("outputs");
    DepthTargets targets;
    targets.depth = depth.empty() ? nullptr : depth.data;
    targets.depthStep = depth.empty() ? 0 : depth.step[0];
    targets.ids = ids.empty() ? nullptr : ids.data;
    targets.idsStep = ids.empty() ? 0 : ids.step[0];
    targets.width = size.width;
    // settings.clear: the given buffer is cleared (+inf) as a created one is, band by band.
    targets.fillDepth = (!depthGiven || settings.clear) && !depth.empty();
    targets.fillIds = !ids.empty();
    targets.lighting = &lighting;
    const Mat texels = textured ? textureInUnitsOf(tex, canvas.depth()) : Mat();
    const Scalar* const clearTo = settings.clear ? &settings.background : nullptr;
    if (canvas.depth() == CV_8U) {
        const RemapSampler<uchar> sampler(texels, settings.textureInterpolation,
                                          settings.textureBorder);
        targets.sampler8u = &sampler;
        drawScreenMesh(canvas, screen, targets, zbuffer, clearTo);
    } else {
        const RemapSampler<float> sampler(texels, settings.textureInterpolation,
                                          settings.textureBorder);
        targets.sampler32f = &sampler;
        drawScreenMesh(canvas, screen, targets, zbuffer, clearTo);
    }
    if (screen.capacityBytes() > MeshWorkspace::kKeepBytes)
        screen = ScreenMesh();
    if ((in.vertStorage.capacity() + in.colorStorage.capacity() + in.normalStorage.capacity()) *
                sizeof(Vec3d) +
            in.faceStorage.capacity() * sizeof(Vec3i) >
        MeshWorkspace::kKeepBytes)
        in = Mesh3dInput();
    if (keptDepth.total() * sizeof(float) > MeshWorkspace::kKeepBytes)
        keptDepth.release();
}

}  // namespace

void drawMesh3d(InputOutputArray canvas, InputArray verts3d, InputArray faces,
                InputArray vcolors, InputArray cameraMatrix, InputArray rvec, InputArray tvec,
                const RenderSettings& settings, InputArray normals,
                InputOutputArray depthBuffer, OutputArray faceIds)
{
    renderMesh3d(canvas, verts3d, faces, vcolors, noArray(), noArray(), cameraMatrix, rvec, tvec,
                 settings, normals, depthBuffer, faceIds, false);
}

void drawTexturedMesh3d(InputOutputArray canvas, InputArray verts3d, InputArray faces,
                        InputArray texCoords, InputArray texture, InputArray cameraMatrix,
                        InputArray rvec, InputArray tvec, const RenderSettings& settings,
                        InputArray normals, InputOutputArray depthBuffer, OutputArray faceIds)
{
    renderMesh3d(canvas, verts3d, faces, noArray(), texCoords, texture, cameraMatrix, rvec, tvec,
                 settings, normals, depthBuffer, faceIds, true);
}

}  // namespace shading
}  // namespace cv
