// This file is part of opencv_shading. License: Apache-2.0.
//
// Affine texture mapping on the one core: each face's spans (raster.hpp) get the texture
// coordinate interpolated with exact weights (ExactWeights), then sampled as cv::remap samples
// (texture_sampler.hpp), so the result is remap's, pixel for pixel.
#include <opencv2/shading.hpp>

#include "input.hpp"
#include "raster.hpp"
#include "shaders.hpp"
#include "texture_sampler.hpp"

#include <opencv2/core/utility.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <type_traits>
#include <vector>

namespace cv {
namespace shading {

namespace detail {

void checkTexture(const Mat& tex, const char* argName)
{
    if (tex.empty() || (tex.type() != CV_8UC3 && tex.type() != CV_32FC3) || tex.dims > 2)
        CV_Error(Error::StsUnsupportedFormat,
                 format("%s: expected a non-empty CV_8UC3 or CV_32FC3 image, got %s%s", argName,
                        typeToString(tex.type()).c_str(), tex.empty() ? " (empty)" : ""));
}

void checkSampling(int interpolation, const char* interpolationName, int borderMode,
                   const char* borderName)
{
    if (interpolation != INTER_NEAREST && interpolation != INTER_LINEAR)
        CV_Error(Error::StsBadFlag,
                 format("%s: expected INTER_NEAREST (0) or INTER_LINEAR (1), got %d",
                        interpolationName, interpolation));
    if (borderMode != BORDER_CONSTANT && borderMode != BORDER_REPLICATE &&
        borderMode != BORDER_REFLECT && borderMode != BORDER_WRAP &&
        borderMode != BORDER_REFLECT_101)
        CV_Error(Error::StsBadFlag,
                 format("%s: expected BORDER_CONSTANT (0), BORDER_REPLICATE (1), "
                        "BORDER_REFLECT (2), BORDER_WRAP (3) or BORDER_REFLECT_101 (4), got %d",
                        borderName, borderMode));
}

const float* byteTexelUnits()
{
    // convertTo(CV_32F, 1.0 / 255) computes float(t) * float(1.0 / 255) in float.
    static const std::array<float, 256> units = [] {
        std::array<float, 256> u;
        for (int t = 0; t < 256; t++)
            u[size_t(t)] = float(t) * float(1.0 / 255.0);
        return u;
    }();
    return units.data();
}

Mat textureInUnitsOf(const Mat& tex, int canvasDepth)
{
    if (tex.depth() == canvasDepth || canvasDepth == CV_32F)
        return tex;  // a float canvas reads 8-bit texels through byteTexelUnits()
    Mat texels;
    tex.convertTo(texels, CV_8U, 255.0);
    return texels;
}

}  // namespace detail

using namespace detail;

namespace {

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
            valid &= usableTexCoord(*q);
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
    checkTexture(tex, "texture");
    checkSampling(interpolation, "interpolation", borderMode, "borderMode");
    Mat canvas = canvasArr.getMat();
    const Mat texels = textureInUnitsOf(tex, canvas.depth());
    if (canvas.depth() == CV_8U)
        drawTextured<uchar>(canvas, verts, f, uv,
                            RemapSampler<uchar>(texels, interpolation, borderMode));
    else
        drawTextured<float>(canvas, verts, f, uv,
                            RemapSampler<float>(texels, interpolation, borderMode));
}

}  // namespace shading
}  // namespace cv
