// This file is part of opencv_shading. License: Apache-2.0.
//
// Mesh drawing on the core. The painter's image (faces far to near, each overwriting) is built
// front to back instead, so every pixel is written once: a coverage bit mask keeps the first
// (frontmost) write of each pixel, which is exactly what the painter's algorithm leaves visible.
//
// The canvas is cut into bands of rows, rendered in parallel. Each band sorts its own faces and
// runs sequentially, so the image never depends on the thread count. Per face, only a sort key
// and a row range are kept between passes: setup happens in the band that draws the face.
#ifndef OPENCV_SHADING_MESH_HPP
#define OPENCV_SHADING_MESH_HPP

#include "raster.hpp"

#include <opencv2/core.hpp>
#include <opencv2/core/utility.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <optional>
#include <utility>
#include <vector>

namespace cv {
namespace shading {
namespace detail {

//! A key whose unsigned order is the order of `v` (v not NaN; -0 and +0 share a key).
inline uint64_t ascendingKey(double v)
{
    if (v == 0)
        v = 0.0;
    uint64_t bits;
    std::memcpy(&bits, &v, sizeof bits);
    return (bits >> 63) ? ~bits : bits | (uint64_t(1) << 63);
}

/** Stable LSD radix sort of (key, value) pairs by key, 8 bits a pass; passes where every key
has the same byte are skipped (depths in a narrow range share most high bytes). */
inline void radixSortByKey(std::vector<std::pair<uint64_t, int>>& items,
                           std::vector<std::pair<uint64_t, int>>& scratch)
{
    scratch.resize(items.size());
    for (int shift = 0; shift < 64; shift += 8) {
        size_t offset[257] = {};
        for (const auto& item : items)
            offset[((item.first >> shift) & 0xff) + 1]++;
        if (std::find(offset + 1, offset + 257, items.size()) != offset + 257)
            continue;
        for (int b = 0; b < 256; b++)
            offset[b + 1] += offset[b];
        for (const auto& item : items)
            scratch[offset[(item.first >> shift) & 0xff]++] = item;
        items.swap(scratch);
    }
}

/** Which pixels of a band are final, one bit per pixel, so a span tests 64 pixels at a time. */
class CoverageBits {
public:
    CoverageBits(int rows, int width)
        : wordsPerRow_((width + 63) / 64), bits_(size_t(rows) * wordsPerRow_)
    {
    }

    void clear() { std::fill(bits_.begin(), bits_.end(), uint64_t(0)); }

    /** Marks [xBegin, xEnd) of `row` final and calls run(a, b) for every maximal run [a, b) of it
    that was not final before (split at 64-pixel word boundaries). Returns the pixels newly
    marked. */
    template <typename RunFn>
    int claim(int row, int xBegin, int xEnd, RunFn&& run)
    {
        uint64_t* words = bits_.data() + size_t(row) * wordsPerRow_;
        if ((xBegin >> 6) == ((xEnd - 1) >> 6)) {
            // The common case for small faces: one word, and the span wholly new or wholly taken.
            const int count = xEnd - xBegin;
            const uint64_t span = (count == 64 ? ~uint64_t(0) : (uint64_t(1) << count) - 1)
                                  << (xBegin & 63);
            uint64_t& word = words[xBegin >> 6];
            if ((word & span) == 0) {
                word |= span;
                run(xBegin, xEnd);
                return count;
            }
            if ((word & span) == span)
                return 0;
        }
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

/** Rows per band: about 96 KB of canvas, so a band's rows stay in cache while it is drawn, but
at least 16 (tall faces are set up once per band they cross) and at most 32 (the band pass keeps
one bit per row). */
inline int bandRowsFor(const Mat& canvas)
{
    const size_t rowBytes = std::max<size_t>(size_t(canvas.cols) * canvas.elemSize(), 1);
    return int(std::clamp<size_t>((96 << 10) / rowBytes, 16, 32));
}

/** A mesh as the band pass reads it: normalised and validated at the API edge. */
struct MeshData {
    std::vector<Point2d> vertices;
    std::vector<Vec3i> faces;   //!< indices checked against vertices
    std::vector<Vec3d> colors;  //!< one per vertex
    std::vector<double> depth;  //!< one per vertex, or empty: draw in face order
};

/** Draws `mesh` as the painter's algorithm would (faces by decreasing mean depth, ties in face
order), writing each covered pixel once. With `background`, pixels no face covers are set to it
(so render() writes every pixel exactly once, with no separate clear). */
template <class Shader, typename T>
void drawMeshFrontToBack(Mat& canvas, const MeshData& mesh, const Vec<T, 3>* background)
{
    const Size size = canvas.size();
    const int faceCount = int(mesh.faces.size());
    const bool byDepth = !mesh.depth.empty();
    const int bandRows = bandRowsFor(canvas);
    const int bandCount = (size.height + bandRows - 1) / bandRows;

    // Pass 0, parallel over vertices: snap each once (a vertex is shared by ~6 faces).
    const int vertexCount = int(mesh.vertices.size());
    std::vector<FixedPoint> snapped(vertexCount);
    constexpr int kChunk = 4096;
    parallel_for_(Range(0, (vertexCount + kChunk - 1) / kChunk), [&](const Range& chunks) {
        const int end = std::min(vertexCount, chunks.end * kChunk);
        for (int i = chunks.start * kChunk; i < end; i++)
            snapped[i] = snapToGrid(mesh.vertices[i]);
    });

    // Pass 1, parallel over faces: the sort key and the rows each face may touch.
    struct FaceRows {
        int begin, end;  //!< rows [begin, end); empty: culled
    };
    std::vector<uint64_t> keys(byDepth ? faceCount : 0);
    std::vector<FaceRows> rows(faceCount);
    parallel_for_(Range(0, (faceCount + kChunk - 1) / kChunk), [&](const Range& chunks) {
        const int end = std::min(faceCount, chunks.end * kChunk);
        for (int i = chunks.start * kChunk; i < end; i++) {
            const Vec3i& f = mesh.faces[i];
            rows[i] = {0, 0};
            if (byDepth) {
                const double mean = (mesh.depth[f[0]] + mesh.depth[f[1]] + mesh.depth[f[2]]) / 3.0;
                if (std::isnan(mean))
                    continue;  // no place in the order: not drawn
                keys[i] = ascendingKey(mean);
            }
            const FixedPoint p[3] = {snapped[f[0]], snapped[f[1]], snapped[f[2]]};
            triangleRows(p, size, rows[i].begin, rows[i].end);
        }
    });

    // Pass 2: face indices binned by band, in face order (a counting sort).
    auto forEachBand = [&](const FaceRows& r, auto&& fn) {
        if (r.begin < r.end)
            for (int k = r.begin / bandRows; k <= (r.end - 1) / bandRows; k++)
                fn(k);
    };
    // size_t: a face on a tall canvas can cross thousands of bands.
    std::vector<size_t> bandStart(bandCount + 1, 0);
    for (const FaceRows& r : rows)
        forEachBand(r, [&](int k) { bandStart[k + 1]++; });
    for (int k = 0; k < bandCount; k++)
        bandStart[k + 1] += bandStart[k];
    std::vector<int> binned(bandStart[bandCount]);
    {
        std::vector<size_t> cursor(bandStart.begin(), bandStart.end() - 1);
        for (int i = 0; i < faceCount; i++)
            forEachBand(rows[i], [&](int k) { binned[cursor[k]++] = i; });
    }

    // Pass 3, parallel over bands: order the band's faces front to back, then draw them.
    parallel_for_(Range(0, bandCount), [&](const Range& range) {
        CoverageBits coverage(bandRows, size.width);
        std::vector<std::pair<uint64_t, int>> order, scratch;
        std::vector<int> rowLeft(bandRows);
        for (int band = range.start; band < range.end; band++) {
            const int y0 = band * bandRows, y1 = std::min(size.height, y0 + bandRows);
            // Front to back is the painter's order reversed: increasing mean depth, and among
            // equal means the later face first (the painter draws it last, on top).
            order.clear();
            for (size_t k = bandStart[band + 1]; k-- > bandStart[band];)
                order.emplace_back(byDepth ? keys[binned[k]] : 0, binned[k]);
            if (byDepth)
                radixSortByKey(order, scratch);  // stable: equal keys stay later-face-first

            coverage.clear();
            std::fill(rowLeft.begin(), rowLeft.end(), size.width);
            uint32_t fullRows = 0;  // bit r: row y0 + r is final everywhere
            const uint32_t allRows = uint32_t((uint64_t(1) << (y1 - y0)) - 1);
            for (size_t k = 0; k < order.size() && fullRows != allRows; k++) {
                const int face = order[k].second;
                // Skip a face whose rows here are all final before touching its vertices.
                const int r0 = std::max(rows[face].begin, y0) - y0;
                const int r1 = std::min(rows[face].end, y1) - y0;
                const uint32_t faceRows = uint32_t((uint64_t(1) << r1) - (uint64_t(1) << r0));
                if ((faceRows & ~fullRows) == 0)
                    continue;
                const Vec3i& f = mesh.faces[face];
                const FixedPoint p[3] = {snapped[f[0]], snapped[f[1]], snapped[f[2]]};
                TriangleSetup triangle;
                int vertexOrder[3];
                if (!setupTriangle(p, size, triangle, vertexOrder))
                    continue;
                // Built on the first pixel this face wins: hidden faces never read colours.
                std::optional<Shader> shader;
                walkTriangle(triangle, y0, y1, size.width, [&](int y, int xBegin, int xEnd) {
                    int& left = rowLeft[y - y0];
                    if (left == 0)
                        return;
                    T* row = canvas.ptr<T>(y);
                    left -= coverage.claim(y - y0, xBegin, xEnd, [&](int a, int b) {
                        if (!shader) {
                            const Vec3d c[3] = {mesh.colors[f[0]], mesh.colors[f[1]],
                                                mesh.colors[f[2]]};
                            shader.emplace(triangle, vertexOrder, c);
                        }
                        (*shader)(triangle, row, y, xBegin, a, b);
                    });
                    if (left == 0)
                        fullRows |= uint32_t(1) << (y - y0);
                });
            }
            if (background) {
                const Vec<T, 3> bg = *background;
                for (int y = y0; y < y1; y++) {
                    Vec<T, 3>* row = canvas.ptr<Vec<T, 3>>(y);
                    // Claiming the whole row visits exactly what no face covered.
                    coverage.claim(y - y0, 0, size.width, [&](int a, int b) {
                        std::fill(row + a, row + b, bg);
                    });
                }
            }
        }
    });
}

}  // namespace detail
}  // namespace shading
}  // namespace cv

#endif  // OPENCV_SHADING_MESH_HPP
