// This file is part of opencv_shading. License: Apache-2.0.
//
// Polygons (seed 003): scan conversion with an active edge table and the even-odd or nonzero
// rule, and tessellation into triangles that cover the same samples (contours that cross or
// touch go through polygon_arrangement.cpp first).
#include <opencv2/core/utility.hpp>
#include <opencv2/shading.hpp>

#include "input.hpp"
#include "polygon_geometry.hpp"
#include "raster.hpp"
#include "shaders.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

namespace cv {
namespace shading {

using namespace detail;

namespace {

//! The contours' snapped points, concatenated; contour c is points[start[c] .. start[c + 1]).
struct Contours {
    std::vector<FixedPoint> points;
    std::vector<int> start = {0};
    int count() const { return int(start.size()) - 1; }
};

void checkFillRule(int fillRule)
{
    if (fillRule != FILL_EVEN_ODD && fillRule != FILL_NONZERO)
        CV_Error(Error::StsBadFlag,
                 format("fillRule: expected FILL_EVEN_ODD (0) or FILL_NONZERO (1), got %d",
                        fillRule));
}

/** Reads every contour and checks every point before anything is drawn. A vector of contours
(any form fillPoly takes) or a single contour. */
void readContours(InputArrayOfArrays polygons, Contours& out)
{
    const _InputArray::KindFlag kind = polygons.kind();
    const bool many = kind == _InputArray::STD_VECTOR_VECTOR ||
                      kind == _InputArray::STD_VECTOR_MAT || kind == _InputArray::STD_ARRAY_MAT;
    std::vector<Mat> mats;
    if (many) {
        const int n = int(polygons.total());
        for (int i = 0; i < n; i++)
            mats.push_back(polygons.getMat(i));
    } else if (kind != _InputArray::NONE && !polygons.empty()) {
        mats.push_back(polygons.getMat());
    }
    std::vector<Point2d> pts;
    for (size_t c = 0; c < mats.size(); c++) {
        const std::string name = format("polygons[%zu]", c);
        readPoints(mats[c], name.c_str(), -1, pts);
        for (size_t i = 0; i < pts.size(); i++) {
            const FixedPoint p = snapToGrid(pts[i]);
            if (p.x == kInvalidCoordinate)
                CV_Error(Error::StsOutOfRange,
                         format("polygons: contour %zu, point %zu is (%g, %g); expected finite "
                                "coordinates with |x|, |y| <= 2^40",
                                c, i, pts[i].x, pts[i].y));
            out.points.push_back(p);
        }
        out.start.push_back(int(out.points.size()));
    }
}

// ---- scan conversion ------------------------------------------------------------------------

//! A non-horizontal edge, top to bottom, with its sample rows [rowBegin, rowEnd) on the canvas.
struct PolyEdge {
    FixedPoint top, bottom;
    int rowBegin, rowEnd;
    int dir;  //!< +1: the contour goes down along it, -1: up
    bool narrow;
};

struct ActiveEdge {
    EdgeWalker walker;  //!< walker.x = ceil(crossing) on the current row
    int rowEnd;
    int dir;
};

inline bool leftOf(const ActiveEdge& l, const ActiveEdge& r) { return l.walker.x < r.walker.x; }

/** Sorts by crossing column. Edges of simple contours never swap places from one row to the
next, so insertion sort is linear; where many edges cross (zigzags of self-intersecting
contours) it gives up and std::sort finishes. */
void sortActive(ActiveEdge* a, size_t n)
{
    size_t budget = 8 * n + 32;
    for (size_t i = 1; i < n; i++) {
        if (a[i - 1].walker.x <= a[i].walker.x)
            continue;
        const ActiveEdge e = a[i];
        size_t j = i;
        while (j > 0 && a[j - 1].walker.x > e.walker.x) {
            a[j] = a[j - 1];
            j--;
        }
        a[j] = e;
        if ((i - j) > budget) {
            std::sort(a, a + n, leftOf);
            return;
        }
        budget -= i - j;
    }
}

/** The edge table of a canvas: edges sorted by first row, firstEdge[r] the first with
rowBegin >= r. */
struct EdgeTable {
    std::vector<PolyEdge> edges;
    std::vector<int> firstEdge;  //!< height + 1 entries
    int rowBegin = 0, rowEnd = 0;
};

void buildEdgeTable(const Contours& contours, Size size, EdgeTable& table)
{
    const int64_t canvasExtent = int64_t(std::max(size.width, size.height)) * kSubpixelOne;
    const int64_t lastColumn = int64_t(size.width - 1) * kSubpixelOne;
    std::vector<PolyEdge>& edges = table.edges;
    for (int c = 0; c < contours.count(); c++) {
        const int first = contours.start[c], n = contours.start[c + 1] - first;
        if (n < 3)
            continue;  // documented: fewer than 3 points contribute nothing
        for (int i = 0; i < n; i++) {
            const FixedPoint& a = contours.points[first + i];
            const FixedPoint& b = contours.points[first + (i + 1) % n];
            if (a.y == b.y)
                continue;  // horizontal edges are never active
            PolyEdge e;
            e.dir = a.y < b.y ? 1 : -1;
            e.top = a.y < b.y ? a : b;
            e.bottom = a.y < b.y ? b : a;
            e.rowBegin = ceilToPixel(e.top.y, size.height);
            e.rowEnd = ceilToPixel(e.bottom.y, size.height);
            // An edge right of the last column only bounds samples off the canvas.
            if (e.rowBegin >= e.rowEnd || std::min(a.x, b.x) > lastColumn)
                continue;
            const int64_t extent = std::max({std::abs(a.x), std::abs(b.x), std::abs(a.y),
                                             std::abs(b.y)});
            e.narrow = extent < kNarrowLimit && canvasExtent < kNarrowLimit;
            edges.push_back(e);
        }
    }
    // Bucket by first row (a counting sort keeps the contours' order within a row).
    std::vector<int>& first = table.firstEdge;
    first.assign(size_t(size.height) + 2, 0);
    for (const PolyEdge& e : edges)
        first[size_t(e.rowBegin) + 1]++;
    for (int r = 0; r <= size.height; r++)
        first[size_t(r) + 1] += first[size_t(r)];
    std::vector<PolyEdge> sorted(edges.size());
    std::vector<int> fill(first.begin(), first.end() - 1);
    for (const PolyEdge& e : edges)
        sorted[size_t(fill[size_t(e.rowBegin)]++)] = e;
    edges.swap(sorted);
    table.rowBegin = size.height, table.rowEnd = 0;
    for (const PolyEdge& e : edges) {
        table.rowBegin = std::min(table.rowBegin, e.rowBegin);
        table.rowEnd = std::max(table.rowEnd, e.rowEnd);
    }
}

/** Calls spanFn(row, xBegin, xEnd) for the covered spans of rows [r0, r1), clipped to
[0, width). The active list is built at r0 from the whole table (so bands are independent),
then updated row by row: finished edges leave, edges starting on the row join, walkers step. */
template <typename SpanFn>
void scanRows(const EdgeTable& table, int r0, int r1, int width, bool evenOdd, SpanFn&& spanFn)
{
    std::vector<ActiveEdge> active, merged;
    const std::vector<PolyEdge>& edges = table.edges;
    auto join = [&](const PolyEdge& e, int row) {
        ActiveEdge a;
        a.walker.start(e.top, e.bottom, row, e.narrow);
        a.rowEnd = e.rowEnd;
        a.dir = e.dir;
        active.push_back(a);
    };
    for (int i = 0; i < table.firstEdge[size_t(r0) + 1]; i++)
        if (edges[size_t(i)].rowEnd > r0)
            join(edges[size_t(i)], r0);
    std::sort(active.begin(), active.end(), leftOf);
    for (int row = r0; row < r1; row++) {
        if (row > r0) {
            // Step the active edges (dropping finished ones) and keep them sorted, then merge
            // in the edges starting on this row, sorted among themselves: O(n + k log k).
            size_t kept = 0;
            for (size_t i = 0; i < active.size(); i++) {
                // Stepped in a local copy: stepping in place and then copying the edge reads
                // back the fresh stores wider than they were written, a forwarding stall.
                ActiveEdge e = active[i];
                if (e.rowEnd <= row)
                    continue;
                e.walker.nextRow();
                active[kept++] = e;
            }
            active.resize(kept);
            sortActive(active.data(), kept);
            for (int i = table.firstEdge[size_t(row)]; i < table.firstEdge[size_t(row) + 1]; i++)
                join(edges[size_t(i)], row);
            if (active.size() > kept) {
                std::sort(active.begin() + std::ptrdiff_t(kept), active.end(), leftOf);
                merged.resize(active.size());
                std::merge(active.begin(), active.begin() + std::ptrdiff_t(kept),
                           active.begin() + std::ptrdiff_t(kept), active.end(), merged.begin(),
                           leftOf);
                active.swap(merged);
            }
        }
        // Winding left of each group of equal crossings; a span opens where the rule starts
        // holding and closes where it stops.
        int winding = 0;
        bool inside = false;
        int64_t spanStart = 0;
        for (size_t i = 0; i < active.size();) {
            const int64_t x = active[i].walker.x;
            for (; i < active.size() && active[i].walker.x == x; i++)
                winding += active[i].dir;
            const bool now = evenOdd ? (winding & 1) != 0 : winding != 0;
            if (now == inside)
                continue;
            inside = now;
            if (now) {
                spanStart = x;
                continue;
            }
            const int64_t xb = std::max<int64_t>(spanStart, 0);
            const int64_t xe = std::min<int64_t>(x, width);
            if (xb < xe)
                spanFn(row, int(xb), int(xe));
        }
        // Still inside: the closing edges lie right of the canvas and were left out.
        if (inside && spanStart < width)
            spanFn(row, int(std::max<int64_t>(spanStart, 0)), width);
    }
}

template <typename T>
void fillTable(Mat& canvas, const EdgeTable& table, const Scalar& color, bool evenOdd)
{
    T c[3];
    for (int k = 0; k < 3; k++)
        c[k] = saturate_cast<T>(color[k]);
    const int rows = table.rowEnd - table.rowBegin;
    if (rows <= 0)
        return;
    auto span = [&](int y, int xb, int xe) { fillPixels(canvas.ptr<T>(y), xb, xe, c); };
    // Bands of at least 32 rows; each rebuilds its active list, which costs one pass over the
    // edges starting above it: worth it only with enough rows per band.
    constexpr int kBandRows = 32;
    const int bands = std::min(rows / kBandRows, 8 * std::max(getNumThreads(), 1));
    if (bands <= 1) {
        scanRows(table, table.rowBegin, table.rowEnd, canvas.cols, evenOdd, span);
        return;
    }
    parallel_for_(Range(0, bands), [&](const Range& r) {
        const int r0 = table.rowBegin + int(int64_t(rows) * r.start / bands);
        const int r1 = table.rowBegin + int(int64_t(rows) * r.end / bands);
        scanRows(table, r0, r1, canvas.cols, evenOdd, span);
    }, bands);
}

// ---- tessellation ---------------------------------------------------------------------------

/** Drops repeated points and points collinear with their neighbours (straight runs and
spikes): neither changes the winding number anywhere off the contour. */
void cleanContour(std::vector<Vtx>& ring)
{
    std::vector<Vtx> out;
    auto flat = [](const Vtx& a, const Vtx& b, const Vtx& c) { return orient(a.p, b.p, c.p) == 0; };
    for (const Vtx& v : ring) {
        out.push_back(v);
        while (out.size() >= 3 && flat(out[out.size() - 3], out[out.size() - 2], out.back()))
            out.erase(out.end() - 2);
    }
    size_t head = 0;  // the wrap-around: out[head ..] is the ring
    for (bool changed = true; changed && out.size() - head >= 3;) {
        changed = false;
        if (flat(out[out.size() - 2], out.back(), out[head])) {
            out.pop_back();
            changed = true;
        } else if (flat(out.back(), out[head], out[head + 1])) {
            head++;
            changed = true;
        }
    }
    ring.assign(out.begin() + std::ptrdiff_t(head), out.end());
    if (ring.size() < 3)
        ring.clear();
}

//! Winding number (the fill's convention: +1 per downward edge left of q) of ring around q,
//! q not on it, evaluated at (q.x + e, q.y + e^2).
int windingAt(const std::vector<Vtx>& ring, const FixedPoint& q)
{
    int w = 0;
    for (size_t i = 0; i < ring.size(); i++) {
        const FixedPoint& a = ring[i].p;
        const FixedPoint& b = ring[(i + 1) % ring.size()].p;
        if (a.y == b.y)
            continue;
        const FixedPoint& t = a.y < b.y ? a : b;
        const FixedPoint& u = a.y < b.y ? b : a;
        if (q.y < t.y || q.y >= u.y)
            continue;
        // The crossing is left of q: q right of the downward line t -> u.
        if (Int128(q.x - t.x) * (u.y - t.y) - Int128(q.y - t.y) * (u.x - t.x) >= 0)
            w += a.y < b.y ? 1 : -1;
    }
    return w;
}

//! Whether direction d from poly[k] points into the polygon's interior corner at poly[k].
bool inCorner(const std::vector<Vtx>& poly, size_t k, const FixedPoint& d)
{
    const size_t n = poly.size();
    const FixedPoint& v = poly[k].p;
    const FixedPoint& p = poly[(k + n - 1) % n].p;
    const FixedPoint& q = poly[(k + 1) % n].p;
    const FixedPoint o = {0, 0};
    const FixedPoint in = {v.x - p.x, v.y - p.y}, out = {q.x - v.x, q.y - v.y};
    const bool leftOut = orient(o, out, d) > 0, leftIn = orient(o, in, d) > 0;
    return orient(p, v, q) > 0 ? (leftOut && leftIn) : (leftOut || leftIn);
}

/** Joins `hole` (negative area) into `poly` (positive area) with a two-way bridge from the
hole's rightmost point to the nearest polygon point the bridge reaches without meeting an edge:
one weakly simple contour with the same winding numbers. Holes must arrive by decreasing
rightmost x, so that unjoined holes lie left of the bridge. Either may pass a point twice: the
bridge leaves from and arrives at the pass whose corner it enters. */
void joinHole(std::vector<Vtx>& poly, std::vector<Vtx> hole)
{
    size_t m = 0;
    for (size_t i = 1; i < hole.size(); i++)
        if (hole[i].p.x > hole[m].p.x)
            m = i;
    const FixedPoint M = hole[m].p;
    std::vector<std::pair<Int128, size_t>> candidates;
    for (size_t k = 0; k < poly.size(); k++) {
        const FixedPoint& v = poly[k].p;
        if (v.x > M.x) {
            const Int128 dx = v.x - M.x, dy = v.y - M.y;
            candidates.push_back({dx * dx + dy * dy, k});
        }
    }
    // Nearest first, taken from a heap: usually the first few are visible.
    auto farther = [](const std::pair<Int128, size_t>& l, const std::pair<Int128, size_t>& r) {
        return l > r;
    };
    std::make_heap(candidates.begin(), candidates.end(), farther);
    const size_t n = poly.size();
    while (!candidates.empty()) {
        std::pop_heap(candidates.begin(), candidates.end(), farther);
        const size_t k = candidates.back().second;
        candidates.pop_back();
        const FixedPoint V = poly[k].p;
        if (!inCorner(poly, k, {M.x - V.x, M.y - V.y}))
            continue;
        bool blocked = false;
        for (size_t j = 0; j < n && !blocked; j++) {
            const FixedPoint& a = poly[j].p;
            const FixedPoint& b = poly[(j + 1) % n].p;
            if (same(a, V) || same(b, V)) {  // meets the bridge at V; blocks if it runs along it
                const FixedPoint& other = same(a, V) ? b : a;
                blocked = !same(other, V) && orient(M, V, other) == 0 && withinBox(M, V, other);
            } else {
                blocked = segmentsMeet(M, V, a, b);
            }
        }
        if (blocked)
            continue;
        for (size_t j = 0; j < hole.size(); j++)
            if (same(hole[j].p, M) && inCorner(hole, j, {V.x - M.x, V.y - M.y})) {
                m = j;
                break;
            }
        std::rotate(hole.begin(), hole.begin() + std::ptrdiff_t(m), hole.end());
        std::vector<Vtx> joined(poly.begin(), poly.begin() + std::ptrdiff_t(k) + 1);
        joined.insert(joined.end(), hole.begin(), hole.end());
        joined.push_back(hole[0]);
        joined.insert(joined.end(), poly.begin() + std::ptrdiff_t(k), poly.end());
        poly.swap(joined);
        return;
    }
    CV_Error(Error::StsInternal, "triangulatePolygons: no bridge from a hole to its contour");
}

//! Whether q lies in the closed triangle a, b, c (positive orientation).
inline bool inTriangle(const FixedPoint& a, const FixedPoint& b, const FixedPoint& c,
                       const FixedPoint& q)
{
    return orient(a, b, q) >= 0 && orient(b, c, q) >= 0 && orient(c, a, q) >= 0;
}

/** Ear clipping of a weakly simple contour of positive area. Only triangles of positive area
are emitted (zero-area corners are dropped), and their chains sum to the contour's, so their
winding numbers, each 0 or 1, add up to the contour's, also 0 or 1: they never overlap and
cover exactly its inside. A contour without an ear would need a negative triangle: an error,
never a wrong result. */
void clipEars(const std::vector<Vtx>& poly, std::vector<Vec3i>& faces)
{
    const int n = int(poly.size());
    if (n < 3)
        return;
    std::vector<int> prev(static_cast<size_t>(n)), next(static_cast<size_t>(n));
    for (int i = 0; i < n; i++) {
        prev[size_t(i)] = (i + n - 1) % n;
        next[size_t(i)] = (i + 1) % n;
    }
    auto P = [&](int i) -> const FixedPoint& { return poly[size_t(i)].p; };
    // A uniform grid of the points (about 2 per cell), so that an ear test looks only at the
    // points in the cells its bounding box touches: far below O(n) per test on big contours.
    int64_t xMin = P(0).x, xMax = xMin, yMin = P(0).y, yMax = yMin;
    for (int k = 1; k < n; k++) {
        xMin = std::min(xMin, P(k).x), xMax = std::max(xMax, P(k).x);
        yMin = std::min(yMin, P(k).y), yMax = std::max(yMax, P(k).y);
    }
    const int grid = std::max(1, int(std::sqrt(n / 2.0)));
    // Monotone in the coordinate (doubles round monotonically): a box maps to a cell range.
    const double sx = grid / (double(xMax - xMin) + 1), sy = grid / (double(yMax - yMin) + 1);
    auto cellX = [&](int64_t x) { return std::min(grid - 1, int(double(x - xMin) * sx)); };
    auto cellY = [&](int64_t y) { return std::min(grid - 1, int(double(y - yMin) * sy)); };
    std::vector<std::vector<int>> cells(size_t(grid) * size_t(grid));
    for (int k = 0; k < n; k++)
        cells[size_t(cellY(P(k).y)) * size_t(grid) + size_t(cellX(P(k).x))].push_back(k);
    std::vector<uchar> alive(size_t(n), 1);
    auto dropVertex = [&](int i) {
        next[size_t(prev[size_t(i)])] = next[size_t(i)];
        prev[size_t(next[size_t(i)])] = prev[size_t(i)];
        alive[size_t(i)] = 0;
    };
    auto isEar = [&](int a, int b, int c) {
        const FixedPoint &pa = P(a), &pb = P(b), &pc = P(c);
        const int x0 = cellX(std::min({pa.x, pb.x, pc.x}));
        const int x1 = cellX(std::max({pa.x, pb.x, pc.x}));
        const int y0 = cellY(std::min({pa.y, pb.y, pc.y}));
        const int y1 = cellY(std::max({pa.y, pb.y, pc.y}));
        for (int cy = y0; cy <= y1; cy++)
            for (int cx = x0; cx <= x1; cx++)
                for (int q : cells[size_t(cy) * size_t(grid) + size_t(cx)]) {
                    if (!alive[size_t(q)] || q == a || q == b || q == c)
                        continue;
                    const FixedPoint& pq = P(q);
                    if (same(pq, pa) || same(pq, pb) || same(pq, pc))
                        continue;
                    if (orient(P(prev[size_t(q)]), pq, P(next[size_t(q)])) > 0)
                        continue;  // a convex corner cannot be the only point inside an ear
                    if (inTriangle(pa, pb, pc, pq))
                        return false;
                }
        return true;
    };
    int remaining = n, i = 0, stall = 0;
    while (remaining > 3) {
        const int a = prev[size_t(i)], c = next[size_t(i)];
        const Int128 turn = orient(P(a), P(i), P(c));
        if (turn == 0 || (turn > 0 && isEar(a, i, c))) {
            if (turn > 0)
                faces.push_back(Vec3i(poly[size_t(a)].id, poly[size_t(i)].id,
                                      poly[size_t(c)].id));
            dropVertex(i);
            remaining--;
            i = turn == 0 ? a : c;
            stall = 0;
            continue;
        }
        i = c;
        if (++stall > remaining)
            CV_Error(Error::StsInternal, "triangulatePolygons: ear clipping found no ear");
    }
    const int a = prev[size_t(i)], c = next[size_t(i)];
    const Int128 turn = orient(P(a), P(i), P(c));
    if (turn < 0)
        CV_Error(Error::StsInternal, "triangulatePolygons: ear clipping ended inverted");
    if (turn > 0)
        faces.push_back(Vec3i(poly[size_t(a)].id, poly[size_t(i)].id, poly[size_t(c)].id));
}

/** Regions of contours that neither cross nor touch: each is classified by the fill state on
its two sides (the winding of the others is the same on both, its own adds -sign(area) inside,
the fill's +1 per downward edge). Outers get positive area, holes negative; the rest bound
nothing. Each hole belongs to the smallest outer around it. */
void classifySimpleContours(std::vector<std::vector<Vtx>>& rings, bool evenOdd,
                            std::vector<Region>& regions)
{
    auto rule = [&](int w) { return evenOdd ? (w & 1) != 0 : w != 0; };
    std::vector<int> role(rings.size(), 0);  // +1 outer, -1 hole, 0 ignored
    std::vector<Int128> areas(rings.size());
    for (size_t c = 0; c < rings.size(); c++) {
        areas[c] = signedArea2(rings[c]);
        int outside = 0;
        for (size_t d = 0; d < rings.size(); d++)
            if (d != c)
                outside += windingAt(rings[d], rings[c][0].p);
        const bool filledOut = rule(outside), filledIn = rule(outside - signOf(areas[c]));
        if (filledIn == filledOut)
            continue;
        role[c] = filledIn ? 1 : -1;
    }
    for (size_t c = 0; c < rings.size(); c++)  // after all windings are taken
        if (role[c] != 0 && (areas[c] > 0) != (role[c] > 0)) {
            std::reverse(rings[c].begin(), rings[c].end());
            areas[c] = -areas[c];
        }
    std::vector<int> regionOf(rings.size(), -1);
    for (size_t o = 0; o < rings.size(); o++)
        if (role[o] == 1) {
            regionOf[o] = int(regions.size());
            regions.push_back({rings[o], {}});
        }
    for (size_t h = 0; h < rings.size(); h++) {
        if (role[h] != -1)
            continue;
        size_t best = rings.size();
        for (size_t o = 0; o < rings.size(); o++)
            if (role[o] == 1 && windingAt(rings[o], rings[h][0].p) != 0 &&
                (best == rings.size() || areas[o] < areas[best]))
                best = o;
        CV_Assert(best < rings.size());
        regions[size_t(regionOf[best])].holes.push_back(rings[h]);
    }
}

}  // namespace

void fillPolygons(InputOutputArray canvasArr, InputArrayOfArrays polygons, const Scalar& color,
                  int fillRule)
{
    checkCanvas(canvasArr, "canvas");
    checkFillRule(fillRule);
    Contours contours;
    readContours(polygons, contours);
    Mat canvas = canvasArr.getMat();
    EdgeTable table;
    buildEdgeTable(contours, canvas.size(), table);
    if (canvas.depth() == CV_8U)
        fillTable<uchar>(canvas, table, color, fillRule == FILL_EVEN_ODD);
    else
        fillTable<float>(canvas, table, color, fillRule == FILL_EVEN_ODD);
}

void triangulatePolygons(InputArrayOfArrays polygons, OutputArray facesArr, int fillRule,
                         OutputArray verticesArr)
{
    checkFillRule(fillRule);
    Contours contours;
    readContours(polygons, contours);
    std::vector<std::vector<Vtx>> rings;
    for (int c = 0; c < contours.count(); c++) {
        std::vector<Vtx> ring;
        for (int i = contours.start[c]; i < contours.start[c + 1]; i++)
            ring.push_back({contours.points[size_t(i)], i});
        cleanContour(ring);
        if (!ring.empty())
            rings.push_back(std::move(ring));
    }
    const bool evenOdd = fillRule == FILL_EVEN_ODD;
    std::vector<Region> regions;
    std::vector<FixedPoint> added;
    if (!arrangeContours(rings, contours.points, evenOdd, regions, added))
        classifySimpleContours(rings, evenOdd, regions);

    std::vector<Vec3i> faces;
    for (Region& region : regions) {
        auto maxX = [](const std::vector<Vtx>& ring) {
            int64_t m = ring[0].p.x;
            for (const Vtx& v : ring)
                m = std::max(m, v.p.x);
            return m;
        };
        std::stable_sort(region.holes.begin(), region.holes.end(),
                         [&](const std::vector<Vtx>& l, const std::vector<Vtx>& r) {
                             return maxX(l) > maxX(r);
                         });
        std::vector<Vtx> poly = region.outer;
        for (const std::vector<Vtx>& hole : region.holes)
            joinHole(poly, hole);
        clipEars(poly, faces);
    }
    if (facesArr.kind() == _InputArray::STD_VECTOR) {
        facesArr.create(int(faces.size()), 1, CV_32SC3);
    } else {
        facesArr.create(int(faces.size()), 3, CV_32S);
    }
    if (!faces.empty()) {
        Mat dst = facesArr.getMat();
        Mat(dst.rows, dst.cols, dst.type(), faces.data()).copyTo(dst);
    }
    if (verticesArr.needed()) {
        std::vector<Point2d> vertices;
        for (const std::vector<FixedPoint>* list : {&contours.points, &added})
            for (const FixedPoint& p : *list)
                vertices.push_back(Point2d(double(p.x), double(p.y)) / double(kSubpixelOne));
        if (verticesArr.kind() == _InputArray::STD_VECTOR) {
            verticesArr.create(int(vertices.size()), 1, CV_64FC2);
        } else {
            verticesArr.create(int(vertices.size()), 2, CV_64F);
        }
        if (!vertices.empty()) {
            Mat dst = verticesArr.getMat();
            Mat(dst.rows, dst.cols, dst.type(), vertices.data()).copyTo(dst);
        }
    }
}

}  // namespace shading
}  // namespace cv
