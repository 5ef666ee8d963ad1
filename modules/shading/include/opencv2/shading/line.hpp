// This file is part of opencv_shading. License: Apache-2.0.
#ifndef OPENCV_SHADING_LINE_HPP
#define OPENCV_SHADING_LINE_HPP

#include <opencv2/core.hpp>

namespace cv {
namespace shading {

//! @addtogroup shading
//! @{

//! How #lines scan-converts a segment.
enum LineAlgorithm {
    /** Endpoints rounded to the nearest pixel (`cvRound`: halves to even, as converting a
    `Point2f` to the `Point` `cv::line` takes), then the integer midpoint (Bresenham) algorithm:
    exactly the pixels of `cv::line(img, p0, p1, color, 1, LINE_8)` on an image containing both
    endpoints (see #lines for partly visible segments). */
    LINE_BRESENHAM = 0,
    /** Endpoints kept to 1/256 pixel (`llround(v * 256)`, as triangle vertices); one pixel per
    integer major-axis position from `round(start)` to `round(end)` (`round(v) = floor(v + 1/2)`),
    the minor coordinate of the exact line there rounded to the nearest pixel in exact integer
    arithmetic (no accumulated error). On integer endpoints it draws what #LINE_BRESENHAM does. */
    LINE_DDA = 1
};

/** @brief Draws line segments, their colours interpolated from one end to the other.

Segment i joins `points[2i]` and `points[2i + 1]`; segments are drawn in order (a later one
overwrites an earlier one where they cross).

- The major axis is x where `|dx| >= |dy|`, else y; one pixel is drawn per major-axis position
  (8-connected, as `LINE_8`), both endpoints included.
- The minor coordinate is the exact line's, rounded to the nearest pixel. A tie (exactly half
  way) goes toward the segment's left end (its endpoint of smaller x); on a horizontal or
  vertical segment, toward the smaller coordinate. This is the rule `cv::line`'s iterator
  follows, so on integer endpoints both algorithms cover exactly what `cv::line(canvas, p0, p1,
  color, 1, LINE_8)` covers when the canvas contains both endpoints. Off the canvas `cv::line`
  first clips the segment with rounded intersections, which may move its pixels by one;
  here the segment's pixels never depend on the canvas: a segment is drawn as on an unbounded
  canvas and only its on-canvas pixels are written (the first and last visible positions are
  computed, so endpoints at +-1e9 cost no more than the visible part).
- Colour: at major-axis position i, `t = (i - a) / (b - a)` with a, b the first and second
  endpoint's major coordinates (the rounded ones for #LINE_BRESENHAM, the 1/256 ones for
  #LINE_DDA), clamped to [0, 1]; `colors[2s] + t * (colors[2s + 1] - colors[2s])` in double,
  written as float or, on `CV_8UC3`, rounded to nearest (`cvRound`) and saturated. A segment
  whose endpoints coincide is one pixel of the first colour.
- A segment with a NaN, infinite or larger than 2^40 coordinate is skipped (draws nothing).
- The result does not depend on the number of threads (`cv::setNumThreads`).

@param canvas Image to draw into, `CV_32FC3` or `CV_8UC3`, possibly an ROI.
@param points 2N points (x, y) in pixels, any accepted point form: segment i is
`(points[2i], points[2i + 1])`.
@param colors 2N colours, one per point, in the canvas's units.
@param algorithm #LINE_BRESENHAM or #LINE_DDA.
*/
CV_EXPORTS_W void lines(InputOutputArray canvas, InputArray points, InputArray colors,
                        int algorithm = LINE_BRESENHAM);

//! @}

}  // namespace shading
}  // namespace cv

#endif  // OPENCV_SHADING_LINE_HPP
