// This file is part of opencv_shading. License: Apache-2.0.
//
// Exact predicates on snapped (1/256 px) points shared by the polygon tessellator
// (polygon.cpp) and the arrangement of crossing contours (polygon_arrangement.cpp).
#ifndef OPENCV_SHADING_POLYGON_GEOMETRY_HPP
#define OPENCV_SHADING_POLYGON_GEOMETRY_HPP

#include "raster.hpp"

#include <algorithm>
#include <vector>

namespace cv {
namespace shading {
namespace detail {

//! A contour point: its snapped position and its index among the output vertices.
struct Vtx {
    FixedPoint p;
    int id;
};

inline bool same(const FixedPoint& a, const FixedPoint& b) { return a.x == b.x && a.y == b.y; }

inline bool lessXY(const FixedPoint& a, const FixedPoint& b)
{
    return a.x < b.x || (a.x == b.x && a.y < b.y);
}

//! (b - a) x (c - a): > 0 when a, b, c turn the way a positive-area contour does.
inline Int128 orient(const FixedPoint& a, const FixedPoint& b, const FixedPoint& c)
{
    return Int128(b.x - a.x) * (c.y - a.y) - Int128(b.y - a.y) * (c.x - a.x);
}

inline int signOf(Int128 v) { return (v > 0) - (v < 0); }

//! q on the closed segment [a, b], given that a, b, q are collinear.
inline bool withinBox(const FixedPoint& a, const FixedPoint& b, const FixedPoint& q)
{
    return std::min(a.x, b.x) <= q.x && q.x <= std::max(a.x, b.x) && std::min(a.y, b.y) <= q.y &&
           q.y <= std::max(a.y, b.y);
}

//! Whether the closed segments [a, b] and [c, d] share a point.
inline bool segmentsMeet(const FixedPoint& a, const FixedPoint& b, const FixedPoint& c,
                         const FixedPoint& d)
{
    const int o1 = signOf(orient(a, b, c)), o2 = signOf(orient(a, b, d));
    const int o3 = signOf(orient(c, d, a)), o4 = signOf(orient(c, d, b));
    if (o1 * o2 < 0 && o3 * o4 < 0)
        return true;
    return (o1 == 0 && withinBox(a, b, c)) || (o2 == 0 && withinBox(a, b, d)) ||
           (o3 == 0 && withinBox(c, d, a)) || (o4 == 0 && withinBox(c, d, b));
}

//! Twice the signed area of a closed contour (> 0: the orientation orient() calls positive).
inline Int128 signedArea2(const std::vector<Vtx>& ring)
{
    Int128 s = 0;
    for (size_t i = 0; i < ring.size(); i++) {
        const FixedPoint& a = ring[i].p;
        const FixedPoint& b = ring[(i + 1) % ring.size()].p;
        s += Int128(a.x) * b.y - Int128(b.x) * a.y;
    }
    return s;
}

//! A region to tessellate: an outer contour of positive area and holes of negative area.
struct Region {
    std::vector<Vtx> outer;
    std::vector<std::vector<Vtx>> holes;
};

/** The regions the fill rule selects in the arrangement of contours that cross or touch
(polygon_arrangement.cpp): contours weakly simple (a point may be passed twice, nothing
crosses), holes disjoint from their outer. Vertex ids: a point at an input point's position
takes the smallest such index; the others (crossings) are numbered from inputPoints.size() on,
their positions in `added`. Returns false, computing nothing, when no two edges meet other than
consecutive edges at their shared point. */
bool arrangeContours(const std::vector<std::vector<Vtx>>& rings,
                     const std::vector<FixedPoint>& inputPoints, bool evenOdd,
                     std::vector<Region>& regions, std::vector<FixedPoint>& added);

/** How many arrangements fell back to snap rounding since the library was loaded: exported for
the tests, which check that it stays rare. */
CV_EXPORTS uint64_t snapRoundingFallbacks();

}  // namespace detail
}  // namespace shading
}  // namespace cv

#endif  // OPENCV_SHADING_POLYGON_GEOMETRY_HPP
