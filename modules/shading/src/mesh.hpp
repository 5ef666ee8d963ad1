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
    std::vector<double> mean(faces.size());
    for (int i = 0; i < int(faces.size()); i++) {
        const Vec3i& f = faces[i];
        mean[i] = (depth[f[0]] + depth[f[1]] + depth[f[2]]) / 3.0;
        if (!std::isnan(mean[i]))
            order.push_back(i);
    }
    std::stable_sort(order.begin(), order.end(),
                     [&](int a, int b) { return mean[a] > mean[b]; });
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
    std::vector<TriangleSetup> triangles;
    std::vector<Shader> shaders;
    triangles.reserve(drawOrder.size());
    shaders.reserve(drawOrder.size());
    for (auto it = drawOrder.rbegin(); it != drawOrder.rend(); ++it) {
        const Vec3i& f = faces[*it];
        const Point2d v[3] = {vertices[f[0]], vertices[f[1]], vertices[f[2]]};
        const Vec3d c[3] = {colors[f[0]], colors[f[1]], colors[f[2]]};
        TriangleSetup setup;
        int order[3];
        if (setupTriangle(v, size, setup, order)) {
            triangles.push_back(setup);
            shaders.emplace_back(setup, order, c);
        }
    }

    // Bin triangle indices by band (counting sort: each band keeps front-to-back order).
    const int bandCount = (size.height + kBandRows - 1) / kBandRows;
    std::vector<int> bandStart(bandCount + 1, 0);
    for (const TriangleSetup& t : triangles)
        for (int b = t.rowBegin / kBandRows; b <= (t.rowEnd - 1) / kBandRows; b++)
            bandStart[b + 1]++;
    for (int b = 0; b < bandCount; b++)
        bandStart[b + 1] += bandStart[b];
    std::vector<int> binned(bandStart[bandCount]);
    {
        std::vector<int> cursor(bandStart.begin(), bandStart.end() - 1);
        for (int i = 0; i < int(triangles.size()); i++) {
            const TriangleSetup& t = triangles[i];
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
