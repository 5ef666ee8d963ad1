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

//! A key whose ascending unsigned order is the descending order of `v` (v not NaN).
inline uint64_t descendingKey(double v)
{
    if (v == 0)
        v = 0.0;  // -0 and +0 compare equal, so they must share a key
    uint64_t bits;
    std::memcpy(&bits, &v, sizeof bits);
    const uint64_t ascending = (bits >> 63) ? ~bits : bits | (uint64_t(1) << 63);
    return ~ascending;
}

/** Face indices in painter's (drawing) order: largest mean vertex depth first, ties in the order
of `faces`. Empty `depth` keeps the order of `faces`. A face whose mean depth is NaN is left
out: it has no place in the order and is not drawn.

An LSD radix sort on the depth keys: stable by construction, linear in the face count, and it
skips the byte positions all keys share (typically most of them). */
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
    std::vector<std::pair<uint64_t, int>> keyed, scratch;
    keyed.reserve(faces.size());
    for (int i = 0; i < int(faces.size()); i++) {
        const Vec3i& f = faces[i];
        const double mean = (depth[f[0]] + depth[f[1]] + depth[f[2]]) / 3.0;
        if (!std::isnan(mean))
            keyed.emplace_back(descendingKey(mean), i);
    }
    scratch.resize(keyed.size());
    for (int shift = 0; shift < 64; shift += 8) {
        size_t offset[257] = {};
        for (const auto& k : keyed)
            offset[((k.first >> shift) & 0xff) + 1]++;
        if (std::find(offset + 1, offset + 257, keyed.size()) != offset + 257)
            continue;  // every key has the same byte here
        for (int b = 0; b < 256; b++)
            offset[b + 1] += offset[b];
        for (const auto& k : keyed)
            scratch[offset[(k.first >> shift) & 0xff]++] = k;
        keyed.swap(scratch);
    }
    for (const auto& k : keyed)
        order.push_back(k.second);
    return order;
}

/** Which pixels of a band are final, one bit per pixel, so a span tests 64 pixels at a time. */
class CoverageBits {
public:
    CoverageBits(int rows, int width) : wordsPerRow_((width + 63) / 64), bits_(size_t(rows) * wordsPerRow_) {}

    void clear() { std::fill(bits_.begin(), bits_.end(), uint64_t(0)); }

    /** Marks [xBegin, xEnd) of `row` final and calls run(a, b) for every maximal run [a, b) of it
    that was not final before (split at 64-pixel word boundaries). Returns the pixels newly
    marked. */
    template <typename RunFn>
    int claim(int row, int xBegin, int xEnd, RunFn&& run)
    {
        uint64_t* words = bits_.data() + size_t(row) * wordsPerRow_;
        int claimed = 0;
        for (int x = xBegin; x < xEnd;) {
            const int word = x >> 6, first = x & 63;
            const int count = std::min(xEnd - x, 64 - first);
            const uint64_t span = (count == 64 ? ~uint64_t(0) : (uint64_t(1) << count) - 1) << first;
            uint64_t fresh = span & ~words[word];
            words[word] |= span;
            while (fresh) {
                const int a = ctz(fresh);
                const uint64_t rest = ~(fresh >> a);  // zero bits mark the run
                const int len = rest == 0 ? 64 - a : ctz(rest);
                run(word * 64 + a, word * 64 + a + len);
                claimed += len;
                fresh &= len + a >= 64 ? 0 : ~uint64_t(0) << (a + len);
            }
            x += count;
        }
        return claimed;
    }

private:
    static int ctz(uint64_t v) { return __builtin_ctzll(v); }  // v != 0

    int wordsPerRow_;
    std::vector<uint64_t> bits_;
};

//! Rows per band: small enough to balance threads and keep a band's canvas rows in cache.
constexpr int kBandRows = 16;

/** Draws faces in `drawOrder` (back to front) as if one after the other, writing each pixel once.

Triangles are visited front to back; a per-band coverage bit mask keeps only the first (frontmost)
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
        CoverageBits coverage(kBandRows, width);
        int rowLeft[kBandRows];
        for (int band = range.start; band < range.end; band++) {
            const int y0 = band * kBandRows, y1 = std::min(size.height, y0 + kBandRows);
            coverage.clear();
            std::fill(rowLeft, rowLeft + kBandRows, width);
            int64_t bandLeft = int64_t(y1 - y0) * width;
            for (int k = bandStart[band]; k < bandStart[band + 1] && bandLeft > 0; k++) {
                const int i = binned[k];
                const Shader& shader = shaders[i];
                const TriangleSetup& triangle = triangles[i];
                walkTriangle(triangle, y0, y1, width, [&](int y, int xBegin, int xEnd) {
                    int& left = rowLeft[y - y0];
                    if (left == 0)
                        return;
                    T* row = canvas.ptr<T>(y);
                    const int claimed = coverage.claim(y - y0, xBegin, xEnd, [&](int a, int b) {
                        shader(triangle, row, y, xBegin, a, b);
                    });
                    left -= claimed;
                    bandLeft -= claimed;
                });
            }
        }
    }, bandCount);
}

}  // namespace detail
}  // namespace shading
}  // namespace cv

#endif  // OPENCV_SHADING_MESH_HPP
