// This file is part of opencv_shading. License: Apache-2.0.
//
// Mesh drawing on the core: painter's order, then the same image drawn front to back so that
// every pixel is written once. Triangles are binned into horizontal bands that are rendered in
// parallel; each band is processed sequentially, so the result never depends on thread count.
#ifndef OPENCV_SHADING_MESH_HPP
#define OPENCV_SHADING_MESH_HPP

#include "raster.hpp"

#include <opencv2/core.hpp>
#include <opencv2/core/utility.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <utility>
#include <vector>

namespace cv {
namespace shading {
namespace detail {

/** Face indices in painter's (drawing) order: largest mean vertex depth first, ties in the order
of `faces`. Empty `depth` keeps the order of `faces`. A face whose mean depth is NaN is left
out: it has no place in the order and is not drawn. */
inline std::vector<int> paintersOrder(const std::vector<Vec3i>& faces,
                                      const std::vector<double>& depth)
{
    std::vector<int> order;
    order.reserve(faces.size());
    if (depth.empty()) {
        for (int i = 0; i < int(faces.size()); i++)
            order.push_back(i);
        return order;
    }
    // Sorting (key, index) pairs with the index as tie-break is a stable sort on the key, and
    // much faster than std::stable_sort through an index indirection.
    std::vector<std::pair<double, int>> keyed;
    keyed.reserve(faces.size());
    for (int i = 0; i < int(faces.size()); i++) {
        const Vec3i& f = faces[i];
        const double mean = (depth[f[0]] + depth[f[1]] + depth[f[2]]) / 3.0;
        if (!std::isnan(mean))
            keyed.emplace_back(mean, i);
    }
    std::sort(keyed.begin(), keyed.end(), [](const std::pair<double, int>& a,
                                             const std::pair<double, int>& b) {
        return a.first > b.first || (a.first == b.first && a.second < b.second);
    });
    for (const auto& k : keyed)
        order.push_back(k.second);
    return order;
}

//! Rows per band: small enough to balance threads and keep a band's canvas rows in cache.
constexpr int kBandRows = 16;

/** Draws faces in `drawOrder` (back to front) as if one after the other, writing each pixel once.

Triangles are visited front to back; a per-band coverage mask keeps only the first (frontmost)
write of every pixel, which is exactly the pixel the painter's algorithm leaves visible. Rows
and bands whose pixels are all final stop consuming triangles. */
template <class Shader, typename T>
void drawMeshFrontToBack(Mat& canvas, const std::vector<Point2d>& vertices,
                         const std::vector<Vec3i>& faces, const std::vector<Vec3d>& colors,
                         const std::vector<int>& drawOrder)
{
    const Size size = canvas.size();
    const int count = int(drawOrder.size());
    // Set up every face once, in parallel, front to back. A face that covers nothing gets an
    // empty row range and is never binned.
    std::vector<TriangleSetup> triangles(count);
    std::vector<Shader> shaders(count);
    constexpr int kSetupChunk = 2048;
    parallel_for_(Range(0, (count + kSetupChunk - 1) / kSetupChunk), [&](const Range& chunks) {
        const int end = std::min(count, chunks.end * kSetupChunk);
        for (int i = chunks.start * kSetupChunk; i < end; i++) {
            const Vec3i& f = faces[drawOrder[count - 1 - i]];
            const Point2d v[3] = {vertices[f[0]], vertices[f[1]], vertices[f[2]]};
            const Vec3d c[3] = {colors[f[0]], colors[f[1]], colors[f[2]]};
            int order[3];
            TriangleSetup& t = triangles[i];
            if (setupTriangle(v, size, t, order))
                shaders[i] = Shader(t, order, c);
            else
                t.rowBegin = t.rowEnd = 0;
        }
    });

    // Bin triangle indices by band (counting sort: each band keeps front-to-back order).
    const int bandCount = (size.height + kBandRows - 1) / kBandRows;
    std::vector<int> bandStart(bandCount + 1, 0);
    for (const TriangleSetup& t : triangles)
        if (t.rowBegin < t.rowEnd)
            for (int b = t.rowBegin / kBandRows; b <= (t.rowEnd - 1) / kBandRows; b++)
                bandStart[b + 1]++;
    for (int b = 0; b < bandCount; b++)
        bandStart[b + 1] += bandStart[b];
    std::vector<int> binned(bandStart[bandCount]);
    {
        std::vector<int> cursor(bandStart.begin(), bandStart.end() - 1);
        for (int i = 0; i < int(triangles.size()); i++) {
            const TriangleSetup& t = triangles[i];
            if (t.rowBegin < t.rowEnd)
                for (int b = t.rowBegin / kBandRows; b <= (t.rowEnd - 1) / kBandRows; b++)
                    binned[cursor[b]++] = i;
        }
    }

    const int width = size.width;
    parallel_for_(Range(0, bandCount), [&](const Range& range) {
        std::vector<uchar> mask(size_t(kBandRows) * width);
        int rowLeft[kBandRows];
        for (int band = range.start; band < range.end; band++) {
            const int y0 = band * kBandRows, y1 = std::min(size.height, y0 + kBandRows);
            std::fill(mask.begin(), mask.end(), uchar(0));
            std::fill(rowLeft, rowLeft + kBandRows, width);
            int64_t bandLeft = int64_t(y1 - y0) * width;
            for (int k = bandStart[band]; k < bandStart[band + 1] && bandLeft > 0; k++) {
                const int i = binned[k];
                const Shader& shader = shaders[i];
                walkTriangle(triangles[i], y0, y1, width, [&](int y, int xBegin, int xEnd) {
                    int& left = rowLeft[y - y0];
                    if (left == 0)
                        return;
                    uchar* m = mask.data() + size_t(y - y0) * width;
                    T* row = canvas.ptr<T>(y);
                    // Shade each run of not-yet-final pixels, then mark it final.
                    for (int x = xBegin; x < xEnd;) {
                        while (x < xEnd && m[x])
                            x++;
                        const int runBegin = x;
                        while (x < xEnd && !m[x])
                            x++;
                        if (runBegin < x) {
                            shader(row, y, xBegin, runBegin, x);
                            std::memset(m + runBegin, 1, size_t(x - runBegin));
                            left -= x - runBegin;
                            bandLeft -= x - runBegin;
                        }
                    }
                });
            }
        }
    }, bandCount);
}

}  // namespace detail
}  // namespace shading
}  // namespace cv

#endif  // OPENCV_SHADING_MESH_HPP
