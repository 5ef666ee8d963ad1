// This file is part of opencv_shading. License: Apache-2.0.
#ifndef OPENCV_SHADING_HPP
#define OPENCV_SHADING_HPP

#include <opencv2/core.hpp>

/**
@defgroup shading Triangle scan conversion and shading

Scan-converts triangles onto `cv::Mat` canvases and shades them with a flat colour or with
Gouraud (linearly interpolated) vertex colours; `render` and `drawMesh` paint whole meshes in
painter's order (far to near).

### Conventions
- Pixel `(x, y)` is `canvas.at<Vec3f>(y, x)`: column x, row y. Its sample point is the integer
  point `(x, y)`, as in OpenCV's own drawing functions.
- Vertices are snapped to a 1/256 pixel grid (`llround(v * 256)`) and edges are evaluated exactly
  in integer arithmetic, so coverage is exact and independent of vertex order and winding.
- Fill rule: a sample strictly inside a triangle is covered; a sample exactly on an edge is
  covered only if that edge is a *top* edge (horizontal, triangle below it) or a *left* edge
  (triangle interior to its right). Triangles sharing an edge therefore cover every sample of a
  closed mesh exactly once. Zero-area triangles cover nothing.
- Vertices may lie anywhere with `|x|, |y| <= 2^40`; only canvas pixels are written. A triangle
  with a NaN, infinite or larger coordinate is skipped (it writes nothing).
- Colours are written channel by channel in the order given (no RGB/BGR swap), in the canvas's
  own units: `[0, 1]` floats for `CV_32FC3`, `[0, 255]` for `CV_8UC3` (rounded and saturated).
- Painter's order: faces are drawn from the largest mean vertex depth to the smallest (mean in
  double precision); faces with equal means keep their order in `faces`.

Accepted input forms: a `Mat` of `CV_32F`, `CV_64F` or `CV_32S` with one row per item (N x 2
points, N x 3 colours or faces, N x 1 or 1 x N depths), the same as an N x 1 or 1 x N
multi-channel `Mat`, or `std::vector<Point2f|Point2d|Point>`, `std::vector<Vec3f|Vec3d|Vec3i>`,
`std::vector<float|double>`.
*/

namespace cv {
namespace shading {

//! @addtogroup shading
//! @{

//! How triangle interiors are coloured.
enum ShadeType {
    SHADE_FLAT = 0,     //!< one colour per triangle: the mean of its three vertex colours
    SHADE_GOURAUD = 1,  //!< vertex colours interpolated linearly (perspective-correct in 3D)
    SHADE_PHONG = 2     //!< normals interpolated and lit per sample (#drawMesh3d only)
};

/** @brief Fills one triangle with the mean of its vertex colours (flat shading).

@param canvas Image to draw into, `CV_32FC3` or `CV_8UC3`, possibly an ROI. Only the triangle's
covered pixels are written.
@param vertices The 3 vertices (x, y) in pixel coordinates; any accepted point form.
@param vcolors The 3 vertex colours, one per vertex, in the canvas's units.
*/
CV_EXPORTS_W void flats(InputOutputArray canvas, InputArray vertices, InputArray vcolors);

/** @brief Fills one triangle interpolating its vertex colours (Gouraud shading).

Each covered pixel gets the affine interpolation of the three vertex colours at its sample point,
the same value the classic two-stage interpolation (along the edges, then along the span) gives.

@param canvas Image to draw into, `CV_32FC3` or `CV_8UC3`, possibly an ROI.
@param vertices The 3 vertices (x, y) in pixel coordinates.
@param vcolors The 3 vertex colours, in the canvas's units.
*/
CV_EXPORTS_W void gouraud(InputOutputArray canvas, InputArray vertices, InputArray vcolors);

/** @brief Draws a triangle mesh onto an existing image in painter's order.

Faces are drawn from the largest mean vertex depth to the smallest; the image shows, at every
covered pixel, the colour of the last face drawn there. Pixels no face covers are left as they
were. The result is identical for any number of threads (`cv::setNumThreads`).

@param canvas Image to draw into, `CV_32FC3` or `CV_8UC3`, possibly an ROI.
@param verts2d L vertices (x, y).
@param faces K triangles, each 3 zero-based indices into `verts2d`.
@param vcolors L vertex colours, in the canvas's units.
@param depth L vertex depths (larger is farther), or empty to draw faces in the order given.
A face whose mean depth is NaN has no place in the order and is not drawn.
@param shadeType #SHADE_FLAT or #SHADE_GOURAUD (#SHADE_PHONG needs normals: see #drawMesh3d).
*/
CV_EXPORTS_W void drawMesh(InputOutputArray canvas, InputArray verts2d, InputArray faces,
                           InputArray vcolors, InputArray depth,
                           int shadeType = SHADE_GOURAUD);

/** @brief Renders a triangle mesh into a new image (the seed's `render`).

Creates `img` as a `size` image of type `CV_32FC3` filled with `background`, then calls
#drawMesh.

@param verts2d L vertices (x, y).
@param faces K triangles, each 3 zero-based indices into `verts2d`.
@param vcolors L vertex colours in [0, 1].
@param depth L vertex depths (larger is farther), or empty to keep the order of `faces`.
@param img Output image, `size` and `CV_32FC3`.
@param shadeType #SHADE_FLAT or #SHADE_GOURAUD.
@param size Image size; both dimensions must be positive.
@param background Colour of the pixels no face covers (default white).
*/
CV_EXPORTS_W void render(InputArray verts2d, InputArray faces, InputArray vcolors,
                         InputArray depth, OutputArray img, int shadeType = SHADE_GOURAUD,
                         Size size = Size(512, 512), const Scalar& background = Scalar::all(1));

//! @}

}  // namespace shading
}  // namespace cv

#include "shading/mesh3d.hpp"
#include "shading/meshio.hpp"
#include "shading/polygon.hpp"
#include "shading/line.hpp"
#include "shading/texture.hpp"
#include "shading/interpolate.hpp"

#endif  // OPENCV_SHADING_HPP
