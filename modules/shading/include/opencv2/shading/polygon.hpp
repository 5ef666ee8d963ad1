// This file is part of opencv_shading. License: Apache-2.0.
#ifndef OPENCV_SHADING_POLYGON_HPP
#define OPENCV_SHADING_POLYGON_HPP

#ifndef OPENCV_SHADING_HPP
#error "include <opencv2/shading.hpp>, not this sub-header"
#endif

/**
@addtogroup shading

### Polygons (fillPolygons, triangulatePolygons)
- **Input.** `polygons` takes what `cv::fillPoly` takes: a vector of contours, each a
  `std::vector<Point|Point2f|Point2d>` or an N x 2 (or N x 1 two-channel) `Mat` of `CV_32S`,
  `CV_32F` or `CV_64F`; a single contour (one vector or one Mat) is accepted too. Each contour
  is closed (its last point joins its first). Contours may be concave, nested (holes), touch,
  cross themselves and each other, and have collinear or repeated points. A contour with fewer
  than 3 points contributes nothing.
- **Snapping.** Points snap to the 1/256 px grid exactly as triangle vertices do
  (`llround(v * 256)`); every decision after that is exact integer arithmetic.
- **Coverage.** The sample `(x, y)` is covered when the fill rule holds for the winding number
  `w` of all contours together around the point `(x + e, y + e^2)`, `e > 0` infinitely small:
  #FILL_EVEN_ODD when `w` is odd, #FILL_NONZERO when `w != 0`. Equivalently, a scan line with
  half-open edges: an edge is active on the sample rows `min(a.y, b.y) <= y < max(a.y, b.y)`
  (horizontal edges never), the samples right of its crossing `x_c` are `x >= ceil(x_c)`, and
  the spans `[ceil(x_i), ceil(x_i+1))` between consecutive crossings are filled where the rule
  holds for the signed count of crossings left of them (+1 for an edge going down, -1 up).
  This is the top-left rule of triangles: a triangle given as a polygon covers exactly what
  #flats covers, and polygons that tile a region cover each of its samples once.
- **Errors.** Every point of every contour is checked before anything is drawn: a NaN,
  infinite or larger than `2^40` coordinate raises `cv::Exception` naming the contour and the
  point, and leaves the canvas untouched.
*/

namespace cv {
namespace shading {

//! @addtogroup shading
//! @{

//! Which winding numbers are inside a polygon (see #fillPolygons).
enum FillRule {
    FILL_EVEN_ODD = 0,  //!< odd winding numbers: the seed's odd-even (crossing parity) test
    FILL_NONZERO = 1    //!< nonzero winding numbers (an orientation-aware union)
};

/** @brief Fills polygons, with holes and self-intersections, by scan conversion.

An active edge table (edges bucketed by their first sample row, crossings stepped from row to
row in exact integers) yields the spans of each row, which are filled with `color`. Tall
polygons are scanned in row bands in parallel (`cv::parallel_for_`); the image does not depend
on the thread count. Cost: O(rows x crossings per row + covered pixels), independent of the
pixels a polygon covers off the canvas.

@param canvas Image to draw into, `CV_32FC3` or `CV_8UC3`, possibly an ROI. Only covered pixels
are written.
@param polygons Contours (see the conventions above): a vector of point vectors or of N x 2
`Mat`s, or one contour. All contours together form one shape: holes are contours inside others.
@param color Fill colour in the canvas's units (first three channels; `CV_8UC3`: rounded and
saturated).
@param fillRule #FILL_EVEN_ODD or #FILL_NONZERO.
*/
CV_EXPORTS_W void fillPolygons(InputOutputArray canvas, InputArrayOfArrays polygons,
                               const Scalar& color, int fillRule = FILL_EVEN_ODD);

/** @brief Splits polygons (holes, crossings included) into triangles that cover what
#fillPolygons covers.

Drawn with #flats or #drawMesh on `vertices`, the triangles cover each sample at most once;
triangles of zero area are left out, so a triangle given as a polygon gives one face. Contours
are cleaned first (repeated points and points collinear with their neighbours dropped).
Contours that neither cross nor touch are classified by the fill rule (a contour that separates
covered from uncovered samples bounds the shape, others are ignored); where contours cross or
touch, edges are split where they meet and the faces of that planar arrangement get their
winding numbers. The boundaries of the regions the rule selects have their holes bridged and
are ear-clipped with exact integer predicates.

**Vertices.** The input points (snapped: multiples of 1/256 px), then one point per crossing
(or bend, below) the triangles use, in the order the contours first reach them (each walked
from its first point the cleaning keeps). Every vertex is a point of the 1/256 px grid drawing
snaps vertices to; one at an input point's position uses that point instead.

**Coverage.** The triangles cover exactly the samples #fillPolygons covers with the same rule.
Crossings on the grid are used as they are. Each crossing off the grid moves to a grid point
near it (usually a corner of its 1/256 px cell, at most 7/256 px away) and its edges become
polylines through those points; the choice is checked exactly, sample by sample, to change
no winding number (a sample within a hair of an edge may make a piece bend at a grid point
beside it), and the new pieces' own crossings are treated the same way, pass after pass
(dense ones, a 30,000-point self-crossing star on 1024 x 1024, take a few dozen). Last
resort, when the check would visit too many samples (edges with crossings thousands of pixels
long, a budget that grows with the number of edges) or finds no choice (rare: 6 of 10,000
dense random triangulations in a stress test): the edges as placed so far are snap-rounded (each the polyline through the grid points whose cells it passes), and
coverage may then differ from #fillPolygons' at samples within 1/512 px, in x and in y, of an
edge.

Exactness does not rest on the ear tests: each region's triangles have boundaries that sum to
its contours, so their winding numbers (each 0 or 1, all triangles having positive area) add up
to the region's 0 or 1 at every sample: a triangulation that completes is exact. Cost: about
O(n log n) to O(n^2) in the number of points, plus O(k log k) for k crossings (uniform grids
speed up the crossing search and the ear tests; a random 10,000-point star takes about 45 ms,
a self-crossing one, 3,142 crossings, about 170 ms, two thirds of it placing the crossings on
the grid exactly).

@param polygons Contours, as for #fillPolygons.
@param faces Output K x 3 `CV_32S` (or `std::vector<Vec3i>`) indices into `vertices`: the
contours' points concatenated in order (contour 0's points first), then the added points.
@param fillRule #FILL_EVEN_ODD or #FILL_NONZERO.
@param vertices Optional output N x 2 `CV_64F` (or `std::vector<Point2d>`): the position of
every vertex in pixels, the snapped input points followed by the added points.
*/
CV_EXPORTS_W void triangulatePolygons(InputArrayOfArrays polygons, OutputArray faces,
                                      int fillRule = FILL_EVEN_ODD,
                                      OutputArray vertices = noArray());

//! @}

}  // namespace shading
}  // namespace cv

#endif  // OPENCV_SHADING_POLYGON_HPP
