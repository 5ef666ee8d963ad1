// This file is part of opencv_shading. License: Apache-2.0.
//
// Contours that cross or touch, made ready for ear clipping: edges split where they meet, the
// faces of the resulting planar arrangement with their winding numbers, and the boundaries of
// the regions the fill rule selects.
//
// When every crossing lies on the 1/256 px grid, edges are split at the points on them: exact.
// Otherwise each crossing moves to a grid point near it and every edge becomes the polyline
// through its crossings' points (throughGridPoints), checked exactly to keep every sample's
// winding number; the new rings go through the same steps again (their pieces may cross other
// edges off the grid). Last resort (counted, snapRoundingFallbacks): snap rounding (Hobby;
// Guibas and Marimont): the grid points whose half-open cell [x - 1/2, x + 1/2) x [y - 1/2,
// y + 1/2) holds a vertex or a rounded crossing are "hot", and every edge becomes the polyline
// through the hot points whose cells it meets. Such polylines never cross; each lies within
// 1/2 unit (1/512 px, in x and in y) of its edge, so the winding number changes only there.
#include "polygon_geometry.hpp"

#include <opencv2/core.hpp>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <tuple>
#include <utility>
#include <vector>

namespace cv {
namespace shading {
namespace detail {

namespace {

__extension__ typedef unsigned __int128 UInt128;

//! sign(a * b - c * d), exact although the products may need 256 bits.
int compareProducts(Int128 a, Int128 b, Int128 c, Int128 d)
{
    const int s1 = signOf(a) * signOf(b), s2 = signOf(c) * signOf(d);
    if (s1 != s2)
        return s1 < s2 ? -1 : 1;
    if (s1 == 0)
        return 0;
    auto magnitude = [](Int128 x, Int128 y, UInt128& hi, UInt128& lo) {
        const UInt128 u = UInt128(x < 0 ? -x : x), v = UInt128(y < 0 ? -y : y);
        const UInt128 mask = ~uint64_t(0);
        const UInt128 p00 = (u & mask) * (v & mask), p01 = (u & mask) * (v >> 64);
        const UInt128 p10 = (u >> 64) * (v & mask), p11 = (u >> 64) * (v >> 64);
        const UInt128 mid = (p00 >> 64) + (p01 & mask) + (p10 & mask);
        lo = (mid << 64) | (p00 & mask);
        hi = p11 + (p01 >> 64) + (p10 >> 64) + (mid >> 64);
    };
    UInt128 hi1, lo1, hi2, lo2;
    magnitude(a, b, hi1, lo1);
    magnitude(c, d, hi2, lo2);
    const int m = hi1 != hi2 ? (hi1 < hi2 ? -1 : 1) : lo1 != lo2 ? (lo1 < lo2 ? -1 : 1) : 0;
    return s1 > 0 ? m : -m;
}

//! floor(x + 1/2) for x = p + r num / den (den > 0); clears `exact` unless x is an integer.
int64_t roundCrossing(int64_t p, int64_t r, Int128 num, Int128 den, bool& exact)
{
    int64_t c = p + int64_t(std::floor(double(r) * (double(num) / double(den)) + 0.5));
    // c - 1/2 <= x  <=>  (2 (c - p) - 1) den <= 2 r num, and x < c + 1/2 likewise.
    while (compareProducts(2 * Int128(c - p) - 1, den, 2 * Int128(r), num) > 0)
        c--;
    while (compareProducts(2 * Int128(c - p) + 1, den, 2 * Int128(r), num) <= 0)
        c++;
    if (compareProducts(Int128(c - p), den, Int128(r), num) != 0)
        exact = false;
    return c;
}

//! Whether segment [a, b] meets the half-open cell [c - 1/2, c + 1/2)^2 of hot point c.
bool meetsCell(const FixedPoint& a, const FixedPoint& b, const FixedPoint& c)
{
    // In doubled coordinates: P(t) = A + t D, t in [0, 1], against [C - 1, C + 1) per axis.
    // Bounds on t are fractions num / den (den > 0) with a flag: closed or open.
    struct Bound {
        Int128 num, den;
        bool closed;
    };
    Bound lo = {0, 1, true}, hi = {1, 1, true};
    auto cmp = [](const Bound& l, const Bound& r) { return signOf(l.num * r.den - r.num * l.den); };
    const int64_t A[2] = {2 * a.x, 2 * a.y}, D[2] = {2 * (b.x - a.x), 2 * (b.y - a.y)};
    const int64_t C[2] = {2 * c.x, 2 * c.y};
    for (int k = 0; k < 2; k++) {
        const int64_t L = C[k] - 1, U = C[k] + 1;
        if (D[k] == 0) {
            if (A[k] < L || A[k] >= U)
                return false;
            continue;
        }
        // D > 0: t >= (L - A) / D (closed), t < (U - A) / D (open); D < 0 mirrored.
        const Bound low = D[k] > 0 ? Bound{L - A[k], D[k], true} : Bound{A[k] - U, -D[k], false};
        const Bound high = D[k] > 0 ? Bound{U - A[k], D[k], false} : Bound{A[k] - L, -D[k], true};
        const int l = cmp(low, lo), h = cmp(high, hi);
        if (l > 0 || (l == 0 && !low.closed))
            lo = low;
        if (h < 0 || (h == 0 && !high.closed))
            hi = high;
    }
    const int s = cmp(lo, hi);
    return s < 0 || (s == 0 && lo.closed && hi.closed);
}

inline bool onSegment(const FixedPoint& a, const FixedPoint& b, const FixedPoint& q)
{
    return orient(a, b, q) == 0 && withinBox(a, b, q);
}

/** Cells over a bounding box, about `items` of them. cellsNear() lists, conservatively, the
cells that hold points within `pad` units (in x and y) of a segment. */
class UniformGrid {
public:
    UniformGrid(int64_t xMin, int64_t xMax, int64_t yMin, int64_t yMax, size_t items)
        : x0_(double(xMin)), y0_(double(yMin))
    {
        side_ = std::max(1, std::min(2048, int(std::sqrt(4.0 * double(items)))));
        sx_ = side_ / (double(xMax - xMin) + 1), sy_ = side_ / (double(yMax - yMin) + 1);
    }
    int count() const { return side_ * side_; }
    int cellOf(const FixedPoint& p) const { return row(double(p.y)) * side_ + column(double(p.x)); }

    template <typename Fn>
    void cellsNear(const FixedPoint& a, const FixedPoint& b, int64_t pad, Fn&& fn) const
    {
        // One unit more than `pad` absorbs the rounding of the doubles (far below a unit).
        const double margin = double(pad) + 1;
        const double xl = double(std::min(a.x, b.x)), xr = double(std::max(a.x, b.x));
        const double yl = double(std::min(a.y, b.y)), yr = double(std::max(a.y, b.y));
        const int c0 = column(xl - margin), c1 = column(xr + margin);
        const double slope = a.x == b.x ? 0 : double(b.y - a.y) / double(b.x - a.x);
        for (int cx = c0; cx <= c1; cx++) {
            double ylo = yl, yhi = yr;
            if (a.x != b.x && c0 < c1) {  // the segment's y over the column, widened
                const double xs = std::max(xl, x0_ + cx / sx_ - margin);
                const double xe = std::min(xr, x0_ + (cx + 1) / sx_ + margin);
                const double ys = double(a.y) + (xs - double(a.x)) * slope;
                const double ye = double(a.y) + (xe - double(a.x)) * slope;
                ylo = std::max(yl, std::min(ys, ye)), yhi = std::min(yr, std::max(ys, ye));
            }
            for (int cy = row(ylo - margin), cy1 = row(yhi + margin); cy <= cy1; cy++)
                fn(cy * side_ + cx);
        }
    }

private:
    int column(double x) const { return clampCell((x - x0_) * sx_); }
    int row(double y) const { return clampCell((y - y0_) * sy_); }
    int clampCell(double v) const { return int(std::min(double(side_ - 1), std::max(0.0, v))); }
    double x0_, y0_, sx_, sy_;
    int side_;
};

//! Items per cell, stored contiguously: cell c holds items[start[c] .. start[c + 1]).
struct CellLists {
    std::vector<int> start, items;
    template <typename ForEachItemCell>
    void build(int cells, ForEachItemCell&& forEach)  // forEach(fn): fn(cell, item) per pair
    {
        start.assign(size_t(cells) + 1, 0);
        forEach([&](int cell, int) { start[size_t(cell) + 1]++; });
        std::partial_sum(start.begin(), start.end(), start.begin());
        items.resize(size_t(start.back()));
        std::vector<int> fill(start.begin(), start.end() - 1);
        forEach([&](int cell, int item) { items[size_t(fill[size_t(cell)]++)] = item; });
    }
};

struct DisjointSets {
    std::vector<int> parent;
    explicit DisjointSets(size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), 0); }
    int find(int i)
    {
        while (parent[size_t(i)] != i)
            i = parent[size_t(i)] = parent[size_t(parent[size_t(i)])];
        return i;
    }
    void join(int a, int b) { parent[size_t(find(a))] = find(b); }
};

struct Segment {
    FixedPoint a, b;  //!< in the contour's direction
    int ring, index;
};

//! A proper crossing of segments s and u, at parameter sNum / sDen along s (from s.a) and
//! uNum / uDen along u; denominators > 0, parameters in (0, 1).
struct Crossing {
    int s, u;
    Int128 sNum, sDen, uNum, uDen;
};

/** Finds the proper crossings of the edges, testing the pairs that share a grid cell (a pair
sharing several reports its crossing from the cell that holds it only). Returns whether any two
edges meet other than consecutive ones at their shared point; `crossings` gets the rounded
crossing points, `exact` whether all of them were on the grid and `records` the exact ones.
With `fresh`, only pairs with at least one fresh edge are tested (the others are known not to
cross). */
bool findCrossings(const std::vector<Segment>& segs, const std::vector<int>& ringSize,
                   const UniformGrid& grid, std::vector<FixedPoint>& crossings, bool& exact,
                   std::vector<Crossing>& records, const std::vector<uchar>* fresh = nullptr)
{
    const int n = int(segs.size());
    std::vector<int64_t> box(4 * size_t(n));  // x min, x max, y min, y max
    for (int i = 0; i < n; i++) {
        const Segment& s = segs[size_t(i)];
        int64_t* b = &box[4 * size_t(i)];
        b[0] = std::min(s.a.x, s.b.x), b[1] = std::max(s.a.x, s.b.x);
        b[2] = std::min(s.a.y, s.b.y), b[3] = std::max(s.a.y, s.b.y);
    }
    bool meet = false;
    exact = true;
    // cell < 0: every pair is tested once, no grid.
    auto test = [&](int i, int j, int cell, const UniformGrid& cellGrid) {
        const int64_t *bi = &box[4 * size_t(i)], *bj = &box[4 * size_t(j)];
        if (bi[0] > bj[1] || bj[0] > bi[1] || bi[2] > bj[3] || bj[2] > bi[3])
            return;
        const Segment& s = segs[size_t(i)];
        const Segment& t = segs[size_t(j)];
        const int len = ringSize[size_t(s.ring)];
        if (s.ring == t.ring &&
            ((s.index + 1) % len == t.index || (t.index + 1) % len == s.index))
            return;  // consecutive: they share their point only (contours are cleaned)
        const Int128 o1 = orient(s.a, s.b, t.a), o2 = orient(s.a, s.b, t.b);
        const Int128 o3 = orient(t.a, t.b, s.a), o4 = orient(t.a, t.b, s.b);
        if (signOf(o1) * signOf(o2) < 0 && signOf(o3) * signOf(o4) < 0) {
            meet = true;
            // s.a + r num / den with r = s.b - s.a: num / den = o3 / (o3 - o4), in (0, 1).
            Int128 num = o3, den = o3 - o4;
            if (den < 0)
                num = -num, den = -den;
            const FixedPoint r = {s.b.x - s.a.x, s.b.y - s.a.y};
            if (cell >= 0) {
                const double f = double(num) / double(den);
                // Within a unit of the crossing: both edges are listed in its cell.
                const FixedPoint near = {s.a.x + std::llround(double(r.x) * f),
                                         s.a.y + std::llround(double(r.y) * f)};
                if (cellGrid.cellOf(near) != cell)
                    return;
            }
            crossings.push_back({roundCrossing(s.a.x, r.x, num, den, exact),
                                 roundCrossing(s.a.y, r.y, num, den, exact)});
            // Along t: orient(s.a, s.b, t.a + q (t.b - t.a)) = 0 at q = o1 / (o1 - o2).
            Int128 tNum = o1, tDen = o1 - o2;
            if (tDen < 0)
                tNum = -tNum, tDen = -tDen;
            records.push_back({i, j, num, den, tNum, tDen});
        } else if (!meet && segmentsMeet(s.a, s.b, t.a, t.b)) {
            meet = true;  // they touch at a vertex, which is a hot point already
        }
    };
    auto isFresh = [&](int i) { return fresh == nullptr || (*fresh)[size_t(i)] != 0; };
    if (n <= 48) {
        for (int i = 0; i < n; i++)
            for (int j = i + 1; j < n; j++)
                if (isFresh(i) || isFresh(j))
                    test(i, j, -1, grid);
        return meet;
    }
    // A grid over the fresh edges only (later passes: a few among many): fresh pairs meet in
    // its cells, and every other edge near the fresh ones looks up the cells it passes.
    std::vector<int> freshList;
    int64_t xMin = INT64_MAX, xMax = INT64_MIN, yMin = INT64_MAX, yMax = INT64_MIN;
    for (int i = 0; i < n; i++)
        if (isFresh(i)) {
            const int64_t* b = &box[4 * size_t(i)];
            freshList.push_back(i);
            xMin = std::min(xMin, b[0]), xMax = std::max(xMax, b[1]);
            yMin = std::min(yMin, b[2]), yMax = std::max(yMax, b[3]);
        }
    if (freshList.empty())
        return meet;
    const UniformGrid freshGrid = fresh == nullptr
                                      ? grid
                                      : UniformGrid(xMin, xMax, yMin, yMax, freshList.size());
    CellLists cells;
    cells.build(freshGrid.count(), [&](auto&& fn) {
        for (int i : freshList)
            freshGrid.cellsNear(segs[size_t(i)].a, segs[size_t(i)].b, 0,
                                [&](int cell) { fn(cell, i); });
    });
    for (int c = 0; c < freshGrid.count(); c++)
        for (int i = cells.start[size_t(c)]; i < cells.start[size_t(c) + 1]; i++)
            for (int j = i + 1; j < cells.start[size_t(c) + 1]; j++)
                test(cells.items[size_t(i)], cells.items[size_t(j)], c, freshGrid);
    for (int j = 0; j < n && fresh != nullptr; j++) {
        const int64_t* b = &box[4 * size_t(j)];
        if (isFresh(j) || b[0] > xMax || b[1] < xMin || b[2] > yMax || b[3] < yMin)
            continue;
        freshGrid.cellsNear(segs[size_t(j)].a, segs[size_t(j)].b, 0, [&](int c) {
            for (int i = cells.start[size_t(c)]; i < cells.start[size_t(c) + 1]; i++)
                test(cells.items[size_t(i)], j, c, freshGrid);
        });
    }
    return meet;
}

//! Directions out of a vertex in counterclockwise order, starting at +x.
bool angleLess(const FixedPoint& d1, const FixedPoint& d2)
{
    const bool lower1 = d1.y < 0 || (d1.y == 0 && d1.x < 0);
    const bool lower2 = d2.y < 0 || (d2.y == 0 && d2.x < 0);
    if (lower1 != lower2)
        return lower2;
    return Int128(d1.x) * d2.y - Int128(d1.y) * d2.x > 0;
}

/** The planar arrangement of the split edges: half-edges 2e (from edge e's first vertex to its
second) and 2e + 1, each carrying the net number of contour passes along it, and the faces left
of them. */
struct Arrangement {
    std::vector<FixedPoint> points;
    std::vector<int> from;            //!< per half-edge: its origin
    std::vector<int> passes;          //!< per half-edge: contour passes along it, net
    std::vector<int> outStart, out;   //!< per vertex: outgoing half-edges, counterclockwise
    std::vector<int> slot;            //!< per half-edge: its place in its origin's list
    std::vector<int> cycle;           //!< per half-edge: the face cycle left of it
    std::vector<Int128> cycleArea;    //!< twice the signed area of each face cycle

    int to(int h) const { return from[size_t(h ^ 1)]; }
    int degree(int v) const { return outStart[size_t(v) + 1] - outStart[size_t(v)]; }
    int outAt(int v, int k) const { return out[size_t(outStart[size_t(v)] + k)]; }
    //! The half-edge out of to(h) next clockwise from h's twin.
    int clockwiseFromTwin(int h, int steps = 1) const
    {
        const int v = to(h), n = degree(v);
        return outAt(v, ((slot[size_t(h ^ 1)] - steps) % n + n) % n);
    }
    FixedPoint direction(int h) const
    {
        const FixedPoint& a = points[size_t(from[size_t(h)])];
        const FixedPoint& b = points[size_t(to(h))];
        return {b.x - a.x, b.y - a.y};
    }
};

/** Builds the arrangement from directed fragments (u, v) between point indices, passes added
up per undirected edge; edges passed equally often both ways bound nothing and are dropped. */
void buildArrangement(std::vector<std::pair<int, int>>& fragments, Arrangement& g)
{
    std::vector<std::pair<uint64_t, int>> keyed;
    keyed.reserve(fragments.size());
    for (const auto& f : fragments) {
        const int u = std::min(f.first, f.second), v = std::max(f.first, f.second);
        keyed.push_back({uint64_t(u) << 32 | uint64_t(v), f.first < f.second ? 1 : -1});
    }
    std::sort(keyed.begin(), keyed.end());
    for (size_t i = 0; i < keyed.size();) {
        int sum = 0;
        size_t j = i;
        for (; j < keyed.size() && keyed[j].first == keyed[i].first; j++)
            sum += keyed[j].second;
        if (sum != 0) {
            g.from.push_back(int(keyed[i].first >> 32));
            g.from.push_back(int(keyed[i].first & 0xffffffffu));
            g.passes.push_back(sum);
            g.passes.push_back(-sum);
        }
        i = j;
    }
    const int halfEdges = int(g.from.size()), vertices = int(g.points.size());
    g.outStart.assign(size_t(vertices) + 1, 0);
    for (int h = 0; h < halfEdges; h++)
        g.outStart[size_t(g.from[size_t(h)]) + 1]++;
    std::partial_sum(g.outStart.begin(), g.outStart.end(), g.outStart.begin());
    g.out.resize(size_t(halfEdges));
    std::vector<int> fill(g.outStart.begin(), g.outStart.end() - 1);
    for (int h = 0; h < halfEdges; h++)
        g.out[size_t(fill[size_t(g.from[size_t(h)])]++)] = h;
    g.slot.resize(size_t(halfEdges));
    for (int v = 0; v < vertices; v++) {
        const auto first = g.out.begin() + g.outStart[size_t(v)];
        const auto last = g.out.begin() + g.outStart[size_t(v) + 1];
        std::sort(first, last, [&](int a, int b) { return angleLess(g.direction(a), g.direction(b)); });
        for (auto it = first; it != last; ++it)
            g.slot[size_t(*it)] = int(it - first);
    }
    // Face cycles: the face stays on the left, so at each vertex turn to the next half-edge
    // clockwise from the one just arrived along.
    g.cycle.assign(size_t(halfEdges), -1);
    for (int h0 = 0; h0 < halfEdges; h0++) {
        if (g.cycle[size_t(h0)] >= 0)
            continue;
        const int id = int(g.cycleArea.size());
        Int128 area = 0;
        for (int h = h0; g.cycle[size_t(h)] < 0; h = g.clockwiseFromTwin(h)) {
            g.cycle[size_t(h)] = id;
            const FixedPoint& a = g.points[size_t(g.from[size_t(h)])];
            const FixedPoint& b = g.points[size_t(g.to(h))];
            area += Int128(a.x) * b.y - Int128(b.x) * a.y;
        }
        g.cycleArea.push_back(area);
    }
}

/** Joins the face cycles that bound the same face: each connected part of the arrangement lies
in a face of the others (or the unbounded face, id cycleArea.size()); a ray cast left from its
leftmost point finds which. */
void joinNestedCycles(const Arrangement& g, DisjointSets& faces)
{
    const int vertices = int(g.points.size()), halfEdges = int(g.from.size());
    const int unbounded = int(g.cycleArea.size());
    DisjointSets parts{size_t(vertices)};
    for (int h = 0; h < halfEdges; h += 2)
        parts.join(g.from[size_t(h)], g.from[size_t(h + 1)]);
    std::vector<int> leftmost(size_t(vertices), -1), outerCycle(size_t(vertices), -1);
    for (int v = 0; v < vertices; v++) {
        int& l = leftmost[size_t(parts.find(v))];
        if (l < 0 || lessXY(g.points[size_t(v)], g.points[size_t(l)]))
            l = v;
    }
    for (int h = 0; h < halfEdges; h++)
        if (g.cycleArea[size_t(g.cycle[size_t(h)])] < 0)
            outerCycle[size_t(parts.find(g.from[size_t(h)]))] = g.cycle[size_t(h)];
    std::vector<int> roots;
    for (int v = 0; v < vertices; v++)
        if (parts.find(v) == v && g.degree(v) > 0)
            roots.push_back(v);
    for (int root : roots)
        if (outerCycle[size_t(root)] < 0)
            CV_Error(Error::StsInternal, "triangulatePolygons: a part without an outer face");
    if (roots.size() == 1) {
        faces.join(outerCycle[size_t(roots[0])], unbounded);
        return;
    }
    // Horizontal strips of the non-horizontal edges, for the rays.
    int64_t yMin = g.points[0].y, yMax = yMin;
    for (const FixedPoint& p : g.points)
        yMin = std::min(yMin, p.y), yMax = std::max(yMax, p.y);
    const int strips = std::max(1, std::min(1024, int(std::sqrt(double(halfEdges / 2)))));
    const double scale = strips / (double(yMax - yMin) + 1);
    auto stripOf = [&](int64_t y) {
        return int(std::min(double(strips - 1), std::max(0.0, double(y - yMin) * scale)));
    };
    CellLists lists;
    lists.build(strips, [&](auto&& fn) {
        for (int h = 0; h < halfEdges; h += 2) {
            const int64_t ya = g.points[size_t(g.from[size_t(h)])].y;
            const int64_t yb = g.points[size_t(g.to(h))].y;
            if (ya != yb)
                for (int s = stripOf(std::min(ya, yb)); s <= stripOf(std::max(ya, yb)); s++)
                    fn(s, h);
        }
    });
    for (int root : roots) {
        const FixedPoint p = g.points[size_t(leftmost[size_t(root)])];
        // The ray from (p.x - d, p.y + e), e << d infinitely small, to the left: the nearest
        // edge it meets at height p.y + e. Crossing x = num / dy at height p.y.
        int best = -1;
        Int128 bestNum = 0;
        int64_t bestDx = 0, bestDy = 1;
        const int s = stripOf(p.y);
        for (int i = lists.start[size_t(s)]; i < lists.start[size_t(s) + 1]; i++) {
            const int h = lists.items[size_t(i)];
            if (parts.find(g.from[size_t(h)]) == root)
                continue;
            FixedPoint t = g.points[size_t(g.from[size_t(h)])], u = g.points[size_t(g.to(h))];
            if (t.y > u.y)
                std::swap(t, u);
            if (p.y < t.y || p.y >= u.y)
                continue;
            const int64_t dx = u.x - t.x, dy = u.y - t.y;
            const Int128 num = Int128(t.x) * dy + Int128(p.y - t.y) * dx;
            if (num >= Int128(p.x) * dy)
                continue;  // right of p (never through it: parts are disjoint)
            int c = best < 0 ? 1 : compareProducts(num, bestDy, bestNum, dy);
            if (c == 0)  // a shared endpoint at this height: compare just below it
                c = signOf(Int128(dx) * bestDy - Int128(bestDx) * dy);
            if (c > 0)
                best = h, bestNum = num, bestDx = dx, bestDy = dy;
        }
        int face = unbounded;
        if (best >= 0) {
            // The ray's start lies right of the edge: left of its upward half-edge.
            const bool bestGoesUp = g.points[size_t(g.to(best))].y < g.points[size_t(g.from[size_t(best)])].y;
            face = g.cycle[size_t(bestGoesUp ? best : best ^ 1)];
        }
        faces.join(outerCycle[size_t(root)], face);
    }
}

// ---- Crossings moved to grid points, exactly (see the header comment) ----------------------

//! base + delta * num / den (den > 0): a coordinate of a point on an edge, exact.
struct Rational {
    int64_t base, delta;
    Int128 num, den;
    double approx() const { return double(base) + double(delta) * (double(num) / double(den)); }
};

//! sign(r - v).
int compareTo(const Rational& r, int64_t v)
{
    return compareProducts(r.delta, r.num, Int128(v) - r.base, r.den);
}

int64_t floorOf(const Rational& r)
{
    int64_t c = r.base + int64_t(std::floor(double(r.delta) * (double(r.num) / double(r.den))));
    while (compareTo(r, c) < 0)
        c--;
    while (compareTo(r, c + 1) >= 0)
        c++;
    return c;
}

//! The sign of orient(a, b, q) for q on the line ab pushed by (e, e^2), e > 0 infinitely small.
int tieSide(const FixedPoint& a, const FixedPoint& b)
{
    if (a.y != b.y)
        return b.y < a.y ? 1 : -1;
    return (b.x > a.x) - (b.x < a.x);
}

//! The sign of orient(a, b, P), P = s + (e, e^2): never 0 unless a = b.
int sideOfSample(const FixedPoint& a, const FixedPoint& b, const FixedPoint& s)
{
    const int o = signOf(orient(a, b, s));
    return o != 0 ? o : tieSide(a, b);
}

/** What edge u -> v adds to the winding number around P = s + (e, e^2): the ray from P towards
+x, an edge counting on the rows u.y <= y < v.y (+1, P on its left) or v.y <= y < u.y (-1, P on
its right). `uBelow`: u.y <= s.y, which is u.y < P.y; likewise `vBelow`. */
inline int crossingCount(bool uBelow, bool vBelow, int side)
{
    if (uBelow == vBelow)
        return 0;
    return uBelow ? (side > 0) : -(side < 0);
}

struct Param {
    Int128 num, den;
};

/** Rewrites each edge (`segs`, with the proper crossings `crossings`) as the polyline through
grid points chosen for its crossings, in order along it (`out`: the rings). Candidates are the
grid points near each crossing, by distance, those on the side of each line through it that
keeps the samples on that line on their side first.

The choice is checked exactly. Each piece of an edge between consecutive split points moves;
the closed loop (old piece, the move of its end, the new piece backwards, the move of its start
backwards; a move as a horizontal then a vertical step) has, summed over all pieces, the
winding number old - new at each sample, since the moves cancel between consecutive pieces, and
it is 0 away from the loop. Where the sum is not 0, a moved end of the piece through that
sample goes to its next candidate that passes the sample on the old side; where none does (the
sample within a hair of the edge, another one on its other side further on), the piece bends
at a grid point beside the sample. False when no choice passes within a few rounds, or the
check would visit too many samples. */
bool throughGridPoints(const std::vector<Segment>& segs, const std::vector<Crossing>& crossings,
                       std::vector<std::vector<Vtx>>& out, double budget, double& visited)
{
    const int n = int(segs.size());
    //! A split point of an edge: its parameter and its group (the grid point it moves to).
    struct Split {
        int seg;
        Param t;
        int group;
    };
    auto tCompare = [](const Param& l, const Param& r) {
        return compareProducts(l.num, r.den, r.num, l.den);
    };
    std::vector<Split> splits;
    splits.reserve(2 * crossings.size());
    for (int c = 0; c < int(crossings.size()); c++) {
        const Crossing& x = crossings[size_t(c)];
        splits.push_back({x.s, {x.sNum, x.sDen}, c});
        splits.push_back({x.u, {x.uNum, x.uDen}, c});
    }
    std::vector<int> splitStart;
    auto sortSplits = [&]() {
        std::sort(splits.begin(), splits.end(), [&](const Split& l, const Split& r) {
            return l.seg != r.seg ? l.seg < r.seg : tCompare(l.t, r.t) < 0;
        });
        splitStart.assign(size_t(n) + 1, 0);
        for (const Split& i : splits)
            splitStart[size_t(i.seg) + 1]++;
        std::partial_sum(splitStart.begin(), splitStart.end(), splitStart.begin());
    };
    sortSplits();
    // Crossings at one point (three or more edges through it) share their grid point.
    {
        DisjointSets samePoint(crossings.size());
        for (size_t k = 1; k < splits.size(); k++)
            if (splits[k].seg == splits[k - 1].seg && tCompare(splits[k - 1].t, splits[k].t) == 0)
                samePoint.join(splits[k - 1].group, splits[k].group);
        std::vector<int> groupOfRoot(crossings.size(), -1);
        int groups = 0;
        for (Split& i : splits) {
            int& g = groupOfRoot[size_t(samePoint.find(i.group))];
            if (g < 0)
                g = groups++;
            i.group = g;
        }
    }
    // The check visits about (|dx| + |dy|) / 256 samples per edge with crossings: too many
    // (edges thousands of pixels long) and snap rounding is the answer.
    double estimate = 0;
    for (int e = 0; e < n; e++)
        if (splitStart[size_t(e)] < splitStart[size_t(e) + 1])
            estimate += (std::fabs(double(segs[size_t(e)].b.x - segs[size_t(e)].a.x)) +
                         std::fabs(double(segs[size_t(e)].b.y - segs[size_t(e)].a.y))) /
                            double(kSubpixelOne) +
                        2 * (splitStart[size_t(e) + 1] - splitStart[size_t(e)] + 1);
    if (visited + estimate > budget)
        return false;

    // Candidates per group: the 8 x 8 grid points around its exact point.
    const int side = 8, perGroup = side * side;
    std::vector<FixedPoint> candidates;
    std::vector<int> chosen;
    std::vector<double> gx, gy;
    std::vector<std::pair<std::pair<int, double>, int>> keyed;
    std::vector<FixedPoint> vertexPoints;
    for (const Segment& sg : segs)
        vertexPoints.push_back(sg.a);
    std::sort(vertexPoints.begin(), vertexPoints.end(), lessXY);
    // `wrongSide(q)` counts what speaks against candidate q. Among equals, an existing vertex
    // (every edge's end is the next one's start) comes first: nearly concurrent edges then meet
    // at a point they already have instead of making a new crossing near it, pass after pass.
    auto addGroup = [&](const Segment& s, const Param& t, auto&& wrongSide) {
        const Rational X = {s.a.x, s.b.x - s.a.x, t.num, t.den};
        const Rational Y = {s.a.y, s.b.y - s.a.y, t.num, t.den};
        gx.push_back(X.approx()), gy.push_back(Y.approx()), chosen.push_back(0);
        const int64_t fx = floorOf(X) - (side / 2 - 1), fy = floorOf(Y) - (side / 2 - 1);
        keyed.clear();
        for (int k = 0; k < perGroup; k++) {
            const FixedPoint q = {fx + k % side, fy + k / side};
            const double dx = double(q.x) - gx.back(), dy = double(q.y) - gy.back();
            const bool atVertex =
                std::binary_search(vertexPoints.begin(), vertexPoints.end(), q, lessXY);
            keyed.push_back({{wrongSide(q), atVertex ? -1.0 : dx * dx + dy * dy}, k});
        }
        std::sort(keyed.begin(), keyed.end());
        for (const auto& k : keyed)
            candidates.push_back({fx + k.second % side, fy + k.second / side});
    };
    {
        std::vector<std::vector<int>> lines;
        for (const Split& i : splits) {
            if (size_t(i.group) >= lines.size())
                lines.resize(size_t(i.group) + 1);
            lines[size_t(i.group)].push_back(i.seg);
        }
        std::vector<const Split*> first(lines.size(), nullptr);
        for (const Split& i : splits)
            if (!first[size_t(i.group)])
                first[size_t(i.group)] = &i;
        for (size_t g = 0; g < lines.size(); g++)
            // On the wrong side of a line through the crossing, the new pieces would pass the
            // samples on that line on the other side.
            addGroup(segs[size_t(first[g]->seg)], first[g]->t, [&](const FixedPoint& q) {
                int wrong = 0;
                for (int e : lines[g])
                    wrong += signOf(orient(segs[size_t(e)].a, segs[size_t(e)].b, q)) ==
                             tieSide(segs[size_t(e)].a, segs[size_t(e)].b);
                return wrong;
            });
    }
    auto position = [&](int g) {
        return candidates[size_t(g) * perGroup + size_t(chosen[size_t(g)])];
    };

    struct Entry {
        int64_t sy, sx;
        int delta, seg, gu, gv;  //!< the piece: its edge, its moved ends (or -1)
        Param tu, tv;
    };
    std::vector<Entry> entries;
    // The samples around one moved piece: per sample row, the x range of the loop's parts
    // within a unit of the row, widened by 2 units (the doubles are off by far less).
    auto checkPiece = [&](int e, const Param& tu, const Param& tv, const FixedPoint& u2,
                          const FixedPoint& v2, int gu, int gv) {
        const Segment& s = segs[size_t(e)];
        const Rational ux = {s.a.x, s.b.x - s.a.x, tu.num, tu.den};
        const Rational uy = {s.a.y, s.b.y - s.a.y, tu.num, tu.den};
        const Rational vx = {s.a.x, s.b.x - s.a.x, tv.num, tv.den};
        const Rational vy = {s.a.y, s.b.y - s.a.y, tv.num, tv.den};
        const double px[4] = {ux.approx(), vx.approx(), double(u2.x), double(v2.x)};
        const double py[4] = {uy.approx(), vy.approx(), double(u2.y), double(v2.y)};
        const double ylo = std::min({py[0], py[1], py[2], py[3]}) - 1;
        const double yhi = std::max({py[0], py[1], py[2], py[3]}) + 1;
        const double r0 = std::ceil(ylo / double(kSubpixelOne));
        const double r1 = std::floor(yhi / double(kSubpixelOne));
        visited += std::max(0.0, r1 - r0 + 1);
        if (visited > budget)
            return false;
        const int lineSide = tieSide(s.a, s.b);
        // The loop's parts: old piece, new piece, and the two moves (in the boxes of their ends).
        static const int parts[4][2] = {{0, 1}, {2, 3}, {0, 2}, {1, 3}};
        // Rows clear of both ends' moves cross only the two lines, whose x over [Y - 1, Y + 1]
        // is x(Y) -+ |slope|: a cheap test rules out most of them (no sample within reach).
        const double lowEnd = py[0] < py[1] ? std::max(py[0], py[2]) : std::max(py[1], py[3]);
        const double highEnd = py[0] < py[1] ? std::min(py[1], py[3]) : std::min(py[0], py[2]);
        const bool lines = py[0] != py[1] && py[2] != py[3];
        const double slope[2] = {lines ? (px[1] - px[0]) / (py[1] - py[0]) : 0,
                                 lines ? (px[3] - px[2]) / (py[3] - py[2]) : 0};
        // A floor by an offset truncation (no libm call), never below the true floor.
        auto floorAbove = [](double v) {
            return int64_t(v + 0x1p41) - (int64_t(1) << 41);  // v within +-2^50 here
        };
        for (int64_t r = int64_t(r0); r <= int64_t(r1); r++) {
            const double Y = double(r) * double(kSubpixelOne);
            if (lines && Y - 1 > lowEnd && Y + 1 < highEnd) {
                const double xo = px[0] + (Y - py[0]) * slope[0];
                const double xn = px[2] + (Y - py[2]) * slope[1];
                const double lo = std::min(xo - std::fabs(slope[0]), xn - std::fabs(slope[1]));
                const double hi = std::max(xo + std::fabs(slope[0]), xn + std::fabs(slope[1]));
                // A unit more of margin than below absorbs this form's own rounding.
                if (floorAbove((hi + 3) / double(kSubpixelOne)) <
                    -floorAbove(-(lo - 3) / double(kSubpixelOne)))
                    continue;
            }
            double xl = HUGE_VAL, xr = -HUGE_VAL;
            for (int k = 0; k < 4; k++) {
                const int i = parts[k][0], j = parts[k][1];
                if (std::max(py[i], py[j]) < Y - 1 || std::min(py[i], py[j]) > Y + 1)
                    continue;
                double x0 = px[i], x1 = px[j];
                if (k < 2 && py[i] != py[j]) {
                    const double d = py[j] - py[i];
                    const double t0 = std::min(1.0, std::max(0.0, (Y - 1 - py[i]) / d));
                    const double t1 = std::min(1.0, std::max(0.0, (Y + 1 - py[i]) / d));
                    x0 = px[i] + t0 * (px[j] - px[i]), x1 = px[i] + t1 * (px[j] - px[i]);
                }
                xl = std::min({xl, x0, x1}), xr = std::max({xr, x0, x1});
            }
            if (xl > xr)
                continue;
            const double c0 = std::ceil((xl - 2) / double(kSubpixelOne));
            const double c1 = std::floor((xr + 2) / double(kSubpixelOne));
            if (c0 > c1)
                continue;  // most rows: no sample within the loop's few units
            visited += c1 - c0 + 1;
            if (visited > budget)
                return false;
            const int64_t sy = r * kSubpixelOne;
            const bool uBelow = compareTo(uy, sy) <= 0, vBelow = compareTo(vy, sy) <= 0;
            const bool u2Below = u2.y <= sy, v2Below = v2.y <= sy;
            for (int64_t c = int64_t(c0); c <= int64_t(c1); c++) {
                const FixedPoint S = {c * kSubpixelOne, sy};
                // The old piece lies on line ab, in its direction: P's side is line ab's.
                const int o = signOf(orient(s.a, s.b, S));
                int w = crossingCount(uBelow, vBelow, o != 0 ? o : lineSide);
                w -= crossingCount(u2Below, v2Below, sideOfSample(u2, v2, S));
                if (S.x < v2.x)  // v -> (v2.x, v.y) -> v2, then u2 -> (u2.x, u.y) -> u
                    w += int(vBelow) - int(v2Below);
                if (S.x < u2.x)
                    w += int(u2Below) - int(uBelow);
                if (w != 0)
                    entries.push_back({sy, S.x, w, e, gu, gv, tu, tv});
            }
        }
        return true;
    };

    const Param zero = {0, 1}, one = {1, 1};
    //! How far group g's exact point lies from sample s; an unmoved end (-1) is never nearer.
    auto distance = [&](int g, const FixedPoint& s) {
        return g < 0 ? HUGE_VAL
                     : std::hypot(gx[size_t(g)] - double(s.x), gy[size_t(g)] - double(s.y));
    };
    const size_t maxGroups = chosen.size() + 64 + chosen.size() / 4;  // bends: a few
    // After the first round only the edges with a moved point are checked again: the other
    // edges' entries stand, so dense crossings that settle over many rounds stay cheap.
    std::vector<uchar> dirty(size_t(n), 1);
    for (int round = 0; round < 64; round++) {
        entries.erase(std::remove_if(entries.begin(), entries.end(),
                                     [&](const Entry& en) { return dirty[size_t(en.seg)] != 0; }),
                      entries.end());
        for (int e = 0; e < n; e++) {
            if (!dirty[size_t(e)] || splitStart[size_t(e)] == splitStart[size_t(e) + 1])
                continue;
            const Segment& s = segs[size_t(e)];
            Param tu = zero;
            FixedPoint u2 = s.a;
            int gu = -1;
            for (int k = splitStart[size_t(e)]; k <= splitStart[size_t(e) + 1]; k++) {
                const bool last = k == splitStart[size_t(e) + 1];
                const int gv = last ? -1 : splits[size_t(k)].group;
                if (!last && gv == gu)
                    continue;  // another crossing at the same point
                const Param tv = last ? one : splits[size_t(k)].t;
                const FixedPoint v2 = last ? s.b : position(gv);
                if (!checkPiece(e, tu, tv, u2, v2, gu, gv))
                    return false;
                tu = tv, u2 = v2, gu = gv;
            }
        }
        std::fill(dirty.begin(), dirty.end(), 0);
        std::sort(entries.begin(), entries.end(), [](const Entry& l, const Entry& r) {
            return std::tie(l.sy, l.sx, l.seg, l.gu, l.gv) < std::tie(r.sy, r.sx, r.seg, r.gu, r.gv);
        });
        std::vector<uchar> moved(chosen.size(), 0);
        bool changed = false, bent = false;
        for (size_t i = 0; i < entries.size();) {
            size_t j = i;
            int sum = 0;
            for (; j < entries.size() && entries[j].sy == entries[i].sy && entries[j].sx == entries[i].sx; j++)
                sum += entries[j].delta;
            if (sum == 0) {
                i = j;
                continue;
            }
            changed = true;
            const FixedPoint S = {entries[i].sx, entries[i].sy};
            bool fixed = false, busy = false;
            for (size_t k = i; k < j && !fixed; k++) {
                const Entry& en = entries[k];
                const Segment& s = segs[size_t(en.seg)];
                const int want = sideOfSample(s.a, s.b, S);
                int ends[2] = {en.gu, en.gv};
                if (distance(ends[1], S) < distance(ends[0], S))
                    std::swap(ends[0], ends[1]);
                for (int g : ends) {
                    if (g < 0)
                        continue;
                    if (moved[size_t(g)]) {
                        busy = true;  // already moved this round: check again first
                        continue;
                    }
                    const bool isU = g == en.gu;
                    const FixedPoint other = isU ? (en.gv >= 0 ? position(en.gv) : s.b)
                                                 : (en.gu >= 0 ? position(en.gu) : s.a);
                    for (int c = chosen[size_t(g)] + 1; c < perGroup && !fixed; c++) {
                        const FixedPoint q = candidates[size_t(g) * perGroup + size_t(c)];
                        if ((isU ? sideOfSample(q, other, S) : sideOfSample(other, q, S)) == want)
                            chosen[size_t(g)] = c, moved[size_t(g)] = 1, fixed = true;
                    }
                    if (fixed)
                        break;
                }
            }
            if (!fixed && !busy) {
                // Bend the piece beside the sample: at the grid points near the sample's
                // projection on the edge, those on the side away from the sample first.
                const Entry& en = entries[i];
                const Segment& s = segs[size_t(en.seg)];
                const FixedPoint d = {s.b.x - s.a.x, s.b.y - s.a.y};
                Param t = {Int128(S.x - s.a.x) * d.x + Int128(S.y - s.a.y) * d.y,
                           Int128(d.x) * d.x + Int128(d.y) * d.y};
                // The projection may fall past the piece's end, on the edge's next piece (a
                // sample beside a crossing, in a thin wedge no nearby grid point keeps it in):
                // bending there works as well, so only a projection at a split point or off
                // the edge counts as beside an end.
                bool inside = t.den != 0 && tCompare(t, zero) > 0 && tCompare(t, one) < 0;
                for (int k = splitStart[size_t(en.seg)]; inside && k < splitStart[size_t(en.seg) + 1];
                     k++)
                    inside = tCompare(t, splits[size_t(k)].t) != 0;
                if (!inside || chosen.size() >= maxGroups) {
                    // Beside an end: the nearer moved end's next candidate.
                    const int g = distance(en.gu, S) <= distance(en.gv, S) ? en.gu : en.gv;
                    if (++chosen[size_t(g)] == perGroup)
                        return false;
                    moved[size_t(g)] = 1;
                    i = j;
                    continue;
                }
                const int want = sideOfSample(s.a, s.b, S);
                splits.push_back({en.seg, t, int(chosen.size())});
                addGroup(s, t, [&](const FixedPoint& q) {
                    return int(signOf(orient(s.a, s.b, q)) != -want);
                });
                moved.push_back(1);
                bent = true;
            }
            i = j;
        }
        if (bent)
            sortSplits();
        for (const Split& i : splits)
            if (moved[size_t(i.group)])
                dirty[size_t(i.seg)] = 1;
        if (!changed) {
            out.clear();
            // Ids: 1 where the edge leaving the point is new, 0 where it is an input edge kept
            // as it was (edgesAndCrossings then skips pairs of those).
            std::vector<Vtx> ring;
            auto put = [&](const FixedPoint& p, int isNew) {
                if (ring.empty() || !same(ring.back().p, p))
                    ring.push_back({p, isNew});
                else
                    ring.back().id = isNew;  // the edge from here is the later one
            };
            for (int e = 0; e < n; e++) {
                const Segment& s = segs[size_t(e)];
                const bool split = splitStart[size_t(e)] < splitStart[size_t(e) + 1];
                put(s.a, split ? 1 : 0);
                for (int k = splitStart[size_t(e)]; k < splitStart[size_t(e) + 1]; k++)
                    put(position(splits[size_t(k)].group), 1);
                if (e + 1 == n || segs[size_t(e) + 1].ring != s.ring) {
                    while (ring.size() > 1 && same(ring.back().p, ring.front().p))
                        ring.pop_back();
                    if (ring.size() >= 3)
                        out.push_back(std::move(ring));
                    ring.clear();
                }
            }
            return true;
        }
    }
    return false;
}

/** The regions of the arrangement of `segs`, split at `hot` (the crossings, rounded): at the
points on each edge when `exact` (every crossing on the grid), else snap-rounded. */
void arrangeSegments(const std::vector<Segment>& segs, std::vector<FixedPoint> hot, bool exact,
                     const std::vector<FixedPoint>& inputPoints, bool evenOdd,
                     std::vector<Region>& regions, std::vector<FixedPoint>& added)
{
    // Hot points: the vertices and the (rounded) crossings, sorted and unique.
    for (const Segment& s : segs)
        hot.push_back(s.a);
    std::sort(hot.begin(), hot.end(), lessXY);
    hot.erase(std::unique(hot.begin(), hot.end(), same), hot.end());
    int64_t xMin = hot[0].x, xMax = xMin, yMin = hot[0].y, yMax = yMin;
    for (const FixedPoint& p : hot)  // rounded crossings may lie a unit outside the edges' box
        xMin = std::min(xMin, p.x), xMax = std::max(xMax, p.x),
        yMin = std::min(yMin, p.y), yMax = std::max(yMax, p.y);
    const UniformGrid grid(xMin, xMax, yMin, yMax, hot.size());
    CellLists cells;
    cells.build(grid.count(), [&](auto&& fn) {
        for (int i = 0; i < int(hot.size()); i++)
            fn(grid.cellOf(hot[size_t(i)]), i);
    });
    // The hot points on [a, b] (exact) or whose cells it meets (rounding), in order from a.
    std::vector<std::pair<Int128, int>> found;
    auto chain = [&](const FixedPoint& a, const FixedPoint& b, bool cellsToo) {
        found.clear();
        grid.cellsNear(a, b, cellsToo ? 1 : 0, [&](int cell) {
            for (int i = cells.start[size_t(cell)]; i < cells.start[size_t(cell) + 1]; i++) {
                const FixedPoint& q = hot[size_t(cells.items[size_t(i)])];
                if (cellsToo ? meetsCell(a, b, q) : onSegment(a, b, q))
                    found.push_back({Int128(q.x - a.x) * (b.x - a.x) + Int128(q.y - a.y) * (b.y - a.y),
                                     cells.items[size_t(i)]});
            }
        });
        std::sort(found.begin(), found.end());
    };
    // Fragments between consecutive hot points of each edge, in contour order; rounded ones
    // are split again at hot points right on them. Added points are ranked as first met.
    Arrangement g;
    g.points = hot;
    std::vector<std::pair<int, int>> fragments;
    std::vector<int> rank(hot.size(), -1);
    int ranked = 0;
    std::vector<int> path, piece;
    for (const Segment& s : segs) {
        chain(s.a, s.b, !exact);
        path.clear();
        for (const auto& f : found)
            path.push_back(f.second);
        for (size_t i = 0; i + 1 < path.size(); i++) {
            piece = {path[i], path[i + 1]};
            if (!exact) {
                chain(hot[size_t(path[i])], hot[size_t(path[i + 1])], false);
                piece.clear();
                for (const auto& f : found)
                    piece.push_back(f.second);
            }
            for (size_t k = 0; k + 1 < piece.size(); k++)
                fragments.push_back({piece[k], piece[k + 1]});
            for (int v : piece)
                if (rank[size_t(v)] < 0)
                    rank[size_t(v)] = ranked++;
        }
    }
    buildArrangement(fragments, g);
    const int cycles = int(g.cycleArea.size()), halfEdges = int(g.from.size());
    if (halfEdges == 0)
        return;

    // Winding numbers of the faces: 0 on the unbounded one, + passes across a half-edge from
    // its right to its left.
    DisjointSets faces(size_t(cycles) + 1);
    joinNestedCycles(g, faces);
    const int unset = INT32_MIN;
    std::vector<int> winding(size_t(cycles) + 1, unset);
    std::vector<int> edgeStart(size_t(cycles) + 2, 0), edgeList(static_cast<size_t>(halfEdges));
    for (int h = 0; h < halfEdges; h++)
        edgeStart[size_t(faces.find(g.cycle[size_t(h)])) + 1]++;
    std::partial_sum(edgeStart.begin(), edgeStart.end(), edgeStart.begin());
    {
        std::vector<int> fill(edgeStart.begin(), edgeStart.end() - 1);
        for (int h = 0; h < halfEdges; h++)
            edgeList[size_t(fill[size_t(faces.find(g.cycle[size_t(h)]))]++)] = h;
    }
    std::vector<int> queue = {faces.find(cycles)};
    winding[size_t(queue[0])] = 0;
    for (size_t qi = 0; qi < queue.size(); qi++) {
        const int f = queue[qi];
        for (int i = edgeStart[size_t(f)]; i < edgeStart[size_t(f) + 1]; i++) {
            const int h = edgeList[size_t(i)];
            const int across = faces.find(g.cycle[size_t(h ^ 1)]);
            const int w = winding[size_t(f)] - g.passes[size_t(h)];
            if (winding[size_t(across)] == unset) {
                winding[size_t(across)] = w;
                queue.push_back(across);
            } else if (winding[size_t(across)] != w) {
                CV_Error(Error::StsInternal, "triangulatePolygons: inconsistent winding numbers");
            }
        }
    }
    std::vector<uchar> selected(size_t(cycles) + 1, 0);
    for (int c = 0; c <= cycles; c++) {
        const int w = winding[size_t(faces.find(c))];
        if (w == unset)
            CV_Error(Error::StsInternal, "triangulatePolygons: a face without a winding number");
        selected[size_t(c)] = evenOdd ? (w & 1) != 0 : w != 0;
    }
    // Regions: selected faces joined across the edges between them.
    for (int h = 0; h < halfEdges; h += 2)
        if (selected[size_t(g.cycle[size_t(h)])] && selected[size_t(g.cycle[size_t(h + 1)])])
            faces.join(g.cycle[size_t(h)], g.cycle[size_t(h + 1)]);
    auto boundary = [&](int h) {
        return selected[size_t(g.cycle[size_t(h)])] && !selected[size_t(g.cycle[size_t(h ^ 1)])];
    };
    // Region boundaries, the region on the left: at each vertex the next boundary half-edge
    // clockwise, so that contours touching at a point stay apart there.
    std::vector<int> regionOf(size_t(cycles) + 1, -1);
    std::vector<uchar> traced(size_t(halfEdges), 0);
    std::vector<Vtx> ring;
    for (int h0 = 0; h0 < halfEdges; h0++) {
        if (traced[size_t(h0)] || !boundary(h0))
            continue;
        ring.clear();
        for (int h = h0; !traced[size_t(h)];) {
            traced[size_t(h)] = 1;
            ring.push_back({hot[size_t(g.from[size_t(h)])], g.from[size_t(h)]});
            int next = -1;
            for (int k = 1; k <= g.degree(g.to(h)) && next < 0; k++) {
                const int candidate = g.clockwiseFromTwin(h, k);
                if (boundary(candidate))
                    next = candidate;
            }
            if (next < 0)
                CV_Error(Error::StsInternal, "triangulatePolygons: an open region boundary");
            h = next;
        }
        int& r = regionOf[size_t(faces.find(g.cycle[size_t(h0)]))];
        if (r < 0) {
            r = int(regions.size());
            regions.emplace_back();
        }
        if (signedArea2(ring) > 0) {
            if (!regions[size_t(r)].outer.empty())
                CV_Error(Error::StsInternal, "triangulatePolygons: a region with two outlines");
            regions[size_t(r)].outer = ring;
        } else {
            regions[size_t(r)].holes.push_back(ring);
        }
    }

    // Vertex ids: an input point's (the smallest at that position), else added, by rank.
    std::vector<std::pair<FixedPoint, int>> inputs;
    for (int i = 0; i < int(inputPoints.size()); i++)
        inputs.push_back({inputPoints[size_t(i)], i});
    std::sort(inputs.begin(), inputs.end(), [](const auto& l, const auto& r) {
        return lessXY(l.first, r.first) || (same(l.first, r.first) && l.second < r.second);
    });
    std::vector<int> id(hot.size(), -1);
    std::vector<std::pair<int, int>> newPoints;  // (rank, hot index)
    auto assign = [&](Vtx& v) {
        int& i = id[size_t(v.id)];
        if (i == -1) {
            const auto it = std::lower_bound(
                inputs.begin(), inputs.end(), v.p,
                [](const auto& l, const FixedPoint& p) { return lessXY(l.first, p); });
            if (it != inputs.end() && same(it->first, v.p)) {
                i = it->second;
            } else {
                i = -2;
                newPoints.push_back({rank[size_t(v.id)], v.id});
            }
        }
    };
    for (Region& r : regions) {
        if (r.outer.empty())
            CV_Error(Error::StsInternal, "triangulatePolygons: a region without an outline");
        for (Vtx& v : r.outer)
            assign(v);
        for (auto& hole : r.holes)
            for (Vtx& v : hole)
                assign(v);
    }
    std::sort(newPoints.begin(), newPoints.end());
    for (const auto& np : newPoints) {
        id[size_t(np.second)] = int(inputPoints.size() + added.size());
        added.push_back(hot[size_t(np.second)]);
    }
    for (Region& r : regions) {
        for (Vtx& v : r.outer)
            v.id = id[size_t(v.id)];
        for (auto& hole : r.holes)
            for (Vtx& v : hole)
                v.id = id[size_t(v.id)];
    }
}

std::atomic<uint64_t> fallbacks{0};

/** The edges of `rings`, their proper crossings (rounded, and exact), whether any two meet.
With `freshIds`, a vertex's id says whether the edge leaving it is new (throughGridPoints' rings):
edges that are not new met no crossing the last time, so pairs of them are not tested again. */
bool edgesAndCrossings(const std::vector<std::vector<Vtx>>& rings, std::vector<Segment>& segs,
                       std::vector<FixedPoint>& hot, bool& exact, std::vector<Crossing>& records,
                       bool freshIds = false)
{
    std::vector<int> ringSize;
    std::vector<uchar> fresh;
    for (size_t c = 0; c < rings.size(); c++) {
        const int n = int(rings[c].size());
        ringSize.push_back(n);
        for (int i = 0; i < n; i++) {
            segs.push_back({rings[c][size_t(i)].p, rings[c][size_t((i + 1) % n)].p, int(c), i});
            fresh.push_back(rings[c][size_t(i)].id != 0);
        }
    }
    exact = true;
    if (segs.empty())
        return false;
    int64_t xMin = segs[0].a.x, xMax = xMin, yMin = segs[0].a.y, yMax = yMin;
    for (const Segment& s : segs) {
        xMin = std::min(xMin, s.a.x), xMax = std::max(xMax, s.a.x);
        yMin = std::min(yMin, s.a.y), yMax = std::max(yMax, s.a.y);
    }
    return findCrossings(segs, ringSize, UniformGrid(xMin, xMax, yMin, yMax, segs.size()), hot,
                         exact, records, freshIds ? &fresh : nullptr);
}

}  // namespace

uint64_t snapRoundingFallbacks() { return fallbacks.load(); }

bool arrangeContours(const std::vector<std::vector<Vtx>>& rings,
                     const std::vector<FixedPoint>& inputPoints, bool evenOdd,
                     std::vector<Region>& regions, std::vector<FixedPoint>& added)
{
    // Crossings off the grid: the edges through grid points near them, checked to keep every
    // sample's winding number. The new pieces may cross other edges off the grid again, so
    // again on the new rings, each pass with fewer crossings (dense ones take dozens; passes
    // after the first test only the new pieces, so they are cheap). Last resort: snap rounding
    // of the rings as far as they got (each pass kept every sample's winding number), so that
    // only samples within 1/512 px of an edge near the crossings still off the grid can change.
    constexpr int kMaxPasses = 64;
    // The check's rows and samples, over all rounds and passes, are bounded by a budget that
    // grows with the edges (stars of 10,000 to 100,000 points need about 77 per edge, in their
    // first round): long edges, not many, are what it stops.
    size_t edgeCount = 0;
    for (const std::vector<Vtx>& ring : rings)
        edgeCount += ring.size();
    const double budget = std::max(double(1 << 20), 256.0 * double(edgeCount));
    double visited = 0;
    std::vector<std::vector<Vtx>> current, next;
    const std::vector<std::vector<Vtx>>* base = &rings;
    for (int pass = 0;; pass++) {
        std::vector<Segment> segs;
        std::vector<FixedPoint> hot;
        std::vector<Crossing> crossings;
        bool exact = true;
        const bool meet = edgesAndCrossings(*base, segs, hot, exact, crossings, pass > 0);
        if (pass == 0 && !meet)
            return false;
        if (segs.empty())
            return true;  // every contour shrank to nothing, which the check allowed
        if (exact) {
            arrangeSegments(segs, std::move(hot), true, inputPoints, evenOdd, regions, added);
            return true;
        }
        if (pass == kMaxPasses || !throughGridPoints(segs, crossings, next, budget, visited))
            break;
        current.swap(next);
        base = &current;
    }
    fallbacks++;
    std::vector<Segment> segs;
    std::vector<FixedPoint> hot;
    std::vector<Crossing> crossings;
    bool exact = true;
    edgesAndCrossings(*base, segs, hot, exact, crossings);
    arrangeSegments(segs, std::move(hot), exact, inputPoints, evenOdd, regions, added);
    return true;
}

}  // namespace detail
}  // namespace shading
}  // namespace cv
