// This file is part of opencv_shading. License: Apache-2.0.
//
// Affine texture mapping on the one core: each face's spans (raster.hpp) get the texture
// coordinate interpolated with exact weights (ExactWeights), then sampled the way cv::remap
// samples a CV_32FC1 map (OpenCV 4.x imgwarp.cpp: remapNearest, remapBilinear), so the result
// is remap's, pixel for pixel.
#include <opencv2/shading.hpp>

#include "input.hpp"
#include "raster.hpp"
#include "shaders.hpp"

#include <opencv2/core/utility.hpp>

#include <algorithm>
#include <cmath>
#include <type_traits>
#include <vector>

namespace cv {
namespace shading {

using namespace detail;

namespace {

//! remap's fixed point: coordinates in 1/32 px (INTER_TAB_SIZE), 8-bit weights out of 2^15.
constexpr int kTabBits = 5;
constexpr int kTabSize = 1 << kTabBits;
constexpr int kCoefBits = 15;

//! OpenCV's clip(x, a, b) in imgwarp.cpp: x clamped to [a, b - 1].
inline int clipTo(int x, int a, int b)
{
    return x >= a ? (x < b ? x : b - 1) : a;
}

/** Samples a texture as cv::remap does with float maps. Coordinates are clamped to +-1e6 first:
the same result for every |coordinate| below 2^31 (remap saturates indices to 16 bits anyway),
and defined beyond. */
template <typename T>
struct RemapSampler {
    using Acc = typename std::conditional<std::is_same<T, uchar>::value, int, float>::type;

    const uchar* data;
    size_t step;
    int cols, rows;
    int border;
    bool linear;

    RemapSampler(const Mat& tex, int interpolation, int borderMode)
        : data(tex.data), step(tex.step[0]), cols(tex.cols), rows(tex.rows), border(borderMode),
          linear(interpolation == INTER_LINEAR)
    {
    }

    const T* texel(int x, int y) const
    {
        return reinterpret_cast<const T*>(data + size_t(y) * step) + 3 * x;
    }

    static float clampCoordinate(float v)
    {
        return std::min(std::max(v, -1e6f), 1e6f);
    }

    void sample(float u, float v, T* out) const
    {
        if (linear)
            sampleLinear(clampCoordinate(u), clampCoordinate(v), out);
        else
            sampleNearest(clampCoordinate(u), clampCoordinate(v), out);
    }

    void sampleNearest(float u, float v, T* out) const
    {
        int sx = saturate_cast<short>(u), sy = saturate_cast<short>(v);  // cvRound, as remap
        if (unsigned(sx) >= unsigned(cols) || unsigned(sy) >= unsigned(rows)) {
            if (border == BORDER_CONSTANT) {
                out[0] = out[1] = out[2] = T(0);
                return;
            }
            if (border == BORDER_REPLICATE) {
                sx = clipTo(sx, 0, cols);
                sy = clipTo(sy, 0, rows);
            } else {
                sx = borderInterpolate(sx, cols, border);
                sy = borderInterpolate(sy, rows, border);
            }
        }
        const T* s = texel(sx, sy);
        out[0] = s[0], out[1] = s[1], out[2] = s[2];
    }

    void sampleLinear(float u, float v, T* out) const
    {
        const int sx = cvRound(u * float(kTabSize)), sy = cvRound(v * float(kTabSize));
        const int fx = sx & (kTabSize - 1), fy = sy & (kTabSize - 1);
        const int ix = saturate_cast<short>(sx >> kTabBits);
        const int iy = saturate_cast<short>(sy >> kTabBits);
        // remap's BilinearTab: (1 - fy)(1 - fx), (1 - fy) fx, fy (1 - fx), fy fx at 1/32 steps,
        // exact in float; the 8-bit table is the same times 2^15, exact integers.
        const int gx = kTabSize - fx, gy = kTabSize - fy;
        Acc w[4];
        if constexpr (std::is_same<T, uchar>::value) {
            const int scale = (1 << kCoefBits) / (kTabSize * kTabSize);
            w[0] = Acc(gy * gx * scale), w[1] = Acc(gy * fx * scale);
            w[2] = Acc(fy * gx * scale), w[3] = Acc(fy * fx * scale);
        } else {
            const float scale = 1.f / float(kTabSize * kTabSize);
            w[0] = Acc(float(gy * gx) * scale), w[1] = Acc(float(gy * fx) * scale);
            w[2] = Acc(float(fy * gx) * scale), w[3] = Acc(float(fy * fx) * scale);
        }
        static const T zero[3] = {T(0), T(0), T(0)};
        const T *v0, *v1, *v2, *v3;
        if (unsigned(ix) < unsigned(std::max(cols - 1, 0)) &&
            unsigned(iy) < unsigned(std::max(rows - 1, 0))) {
            v0 = texel(ix, iy), v1 = v0 + 3;
            v2 = texel(ix, iy + 1), v3 = v2 + 3;
        } else if (border == BORDER_CONSTANT &&
                   (ix >= cols || ix + 1 < 0 || iy >= rows || iy + 1 < 0)) {
            out[0] = out[1] = out[2] = T(0);
            return;
        } else if (border == BORDER_REPLICATE) {
            const int x0 = clipTo(ix, 0, cols), x1 = clipTo(ix + 1, 0, cols);
            const int y0 = clipTo(iy, 0, rows), y1 = clipTo(iy + 1, 0, rows);
            v0 = texel(x0, y0), v1 = texel(x1, y0), v2 = texel(x0, y1), v3 = texel(x1, y1);
        } else {
            const int x0 = borderInterpolate(ix, cols, border);
            const int x1 = borderInterpolate(ix + 1, cols, border);
            const int y0 = borderInterpolate(iy, rows, border);
            const int y1 = borderInterpolate(iy + 1, rows, border);
            v0 = x0 >= 0 && y0 >= 0 ? texel(x0, y0) : zero;
            v1 = x1 >= 0 && y0 >= 0 ? texel(x1, y0) : zero;
            v2 = x0 >= 0 && y1 >= 0 ? texel(x0, y1) : zero;
            v3 = x1 >= 0 && y1 >= 0 ? texel(x1, y1) : zero;
        }
        for (int k = 0; k < 3; k++) {
            // remap's sum, in its order and type (int for 8-bit, float otherwise).
            const Acc t = Acc(v0[k] * w[0] + v1[k] * w[1] + v2[k] * w[2] + v3[k] * w[3]);
            if constexpr (std::is_same<T, uchar>::value)
                out[k] = saturate_cast<uchar>((t + (1 << (kCoefBits - 1))) >> kCoefBits);
            else
                out[k] = t;
        }
    }
};

//! Largest accepted |texture coordinate|; larger (or non-finite) ones skip their face.
constexpr double kMaxTexCoord = 1e30;

//! A face ready to draw: its setup and its texture coordinates in the setup's vertex order.
struct TexturedFace {
    TriangleSetup t;
    const Point2d* uv[3];
};

//! Draws the faces' samples in rows [rowBegin, rowEnd), faces in order.
template <typename T>
void drawTexturedRows(Mat& canvas, const std::vector<TexturedFace>& faces,
                      const RemapSampler<T>& sampler, int rowBegin, int rowEnd)
{
    for (const TexturedFace& face : faces) {
        const TriangleSetup& t = face.t;
        if (t.rowEnd <= rowBegin || t.rowBegin >= rowEnd)
            continue;
        const ExactWeights weights(t);
        double dw[3];
        weights.stepX(t, dw);
        const Point2d* const* c = face.uv;
        const double du = dw[0] * c[0]->x + dw[1] * c[1]->x + dw[2] * c[2]->x;
        const double dv = dw[0] * c[0]->y + dw[1] * c[1]->y + dw[2] * c[2]->y;
        walkTriangle(t, rowBegin, rowEnd, canvas.cols, [&](int y, int xBegin, int xEnd) {
            double w0, w1, w2;
            weights.at(t, xBegin, y, w0, w1, w2);
            const double u0 = w0 * c[0]->x + w1 * c[1]->x + w2 * c[2]->x;
            const double v0 = w0 * c[0]->y + w1 * c[1]->y + w2 * c[2]->y;
            T* row = canvas.ptr<T>(y);
            for (int x = xBegin; x < xEnd; x++) {
                const double k = double(x - xBegin);
                // The coordinate as a CV_32FC1 map would hold it.
                sampler.sample(float(u0 + du * k), float(v0 + dv * k), row + 3 * x);
            }
        });
    }
}

//! Rows of face spans below which the faces are drawn on the calling thread alone.
constexpr int64_t kParallelRows = 1024;

template <typename T>
void drawTextured(Mat& canvas, const std::vector<Point2d>& verts, const std::vector<Vec3i>& faces,
                  const std::vector<Point2d>& uv, const RemapSampler<T>& sampler)
{
    std::vector<TexturedFace> ready;
    ready.reserve(faces.size());
    int64_t rows = 0;
    for (const Vec3i& f : faces) {
        const Point2d* tc[3] = {&uv[f[0]], &uv[f[1]], &uv[f[2]]};
        bool valid = true;
        for (const Point2d* q : tc)
            valid &= std::abs(q->x) <= kMaxTexCoord && std::abs(q->y) <= kMaxTexCoord;
        if (!valid)
            continue;
        const FixedPoint p[3] = {snapToGrid(verts[f[0]]), snapToGrid(verts[f[1]]),
                                 snapToGrid(verts[f[2]])};
        TexturedFace face;
        int order[3];
        if (!setupTriangle(p, canvas.size(), face.t, order))
            continue;
        for (int k = 0; k < 3; k++)
            face.uv[k] = tc[order[k]];
        rows += face.t.rowEnd - face.t.rowBegin;
        ready.push_back(face);
    }
    const int threads = getNumThreads();
    const int bands = std::min(canvas.rows / 16, 4 * threads);
    if (threads <= 1 || bands <= 1 || rows < kParallelRows) {
        drawTexturedRows(canvas, ready, sampler, 0, canvas.rows);
        return;
    }
    // Row bands, each drawing every face in order within its rows: a pixel's value depends only
    // on its face, so the image is the sequential one for any thread count.
    parallel_for_(Range(0, bands), [&](const Range& r) {
        for (int b = r.start; b < r.end; b++)
            drawTexturedRows(canvas, ready, sampler, int(int64_t(canvas.rows) * b / bands),
                             int(int64_t(canvas.rows) * (b + 1) / bands));
    });
}

}  // namespace

void texturedTriangles(InputOutputArray canvasArr, InputArray verts2d, InputArray faces,
                       InputArray texCoords, InputArray texture, int interpolation,
                       int borderMode)
{
    checkCanvas(canvasArr, "canvas");
    std::vector<Point2d> verts, uv;
    std::vector<Vec3i> f;
    readPoints(verts2d, "verts2d", -1, verts);
    const int count = int(verts.size());
    readPoints(texCoords, "texCoords", count, uv);
    readFaces(faces, "faces", count, f);
    const Mat tex = texture.getMat();
    if (tex.empty() || (tex.type() != CV_8UC3 && tex.type() != CV_32FC3) || tex.dims > 2)
        CV_Error(Error::StsUnsupportedFormat,
                 format("texture: expected a non-empty CV_8UC3 or CV_32FC3 image, got %s%s",
                        typeToString(tex.type()).c_str(), tex.empty() ? " (empty)" : ""));
    if (interpolation != INTER_NEAREST && interpolation != INTER_LINEAR)
        CV_Error(Error::StsBadFlag,
                 format("interpolation: expected INTER_NEAREST (0) or INTER_LINEAR (1), got %d",
                        interpolation));
    if (borderMode != BORDER_CONSTANT && borderMode != BORDER_REPLICATE &&
        borderMode != BORDER_REFLECT && borderMode != BORDER_WRAP &&
        borderMode != BORDER_REFLECT_101)
        CV_Error(Error::StsBadFlag,
                 format("borderMode: expected BORDER_CONSTANT (0), BORDER_REPLICATE (1), "
                        "BORDER_REFLECT (2), BORDER_WRAP (3) or BORDER_REFLECT_101 (4), got %d",
                        borderMode));
    Mat canvas = canvasArr.getMat();
    Mat texels = tex;
    if (tex.depth() != canvas.depth())  // into the canvas's units: [0, 1] float, 0..255 8-bit
        tex.convertTo(texels, canvas.depth(), canvas.depth() == CV_8U ? 255.0 : 1.0 / 255.0);
    if (canvas.depth() == CV_8U)
        drawTextured<uchar>(canvas, verts, f, uv,
                            RemapSampler<uchar>(texels, interpolation, borderMode));
    else
        drawTextured<float>(canvas, verts, f, uv,
                            RemapSampler<float>(texels, interpolation, borderMode));
}

}  // namespace shading
}  // namespace cv
