// This file is part of opencv_shading. License: Apache-2.0.
#ifndef OPENCV_SHADING_TEXTURE_HPP
#define OPENCV_SHADING_TEXTURE_HPP

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

namespace cv {
namespace shading {

//! @addtogroup shading
//! @{

/** @brief Draws triangles textured from an image (affine texture mapping, in face order).

Each sample a face covers (exactly the samples #flats covers) gets the texture sampled at the
affine interpolation of its vertices' texture coordinates in screen space (the exact barycentric
weights of #forEachSample), and sampled as `cv::remap` samples: the interpolated coordinate is
rounded to float, the value of a `CV_32FC1` map, and the pixel equals `cv::remap(texture, dst,
mapX, mapY, interpolation, borderMode)` at that pixel, bit for bit (remap's 1/32-pixel bilinear
weights, its 8-bit fixed-point rounding, its borders). Faces are drawn in the order given:
later faces cover earlier ones. A face with a NaN, infinite or too large vertex (beyond 2^40)
or texture coordinate (beyond 1e30) is skipped. Interpolated coordinates are clamped to +-1e6
before sampling, which changes nothing remap defines (it saturates texel indices to 16 bits).

@param canvas Image to draw into, `CV_32FC3` or `CV_8UC3`, possibly an ROI.
@param verts2d L vertices (x, y) in pixels.
@param faces K triangles, each 3 zero-based indices into `verts2d` (and `texCoords`).
@param texCoords L texture coordinates (u, v) in texture pixels, as remap's maps hold them:
(0, 0) is the centre of the texture's top-left pixel, (cols - 1, rows - 1) its bottom-right one.
@param texture `CV_8UC3` or `CV_32FC3`, not empty. A texture of the other depth than the canvas
is sampled as if converted first: 8-bit to float scaled by 1/255 (as `convertTo` does it; read
in place, no copy is made), float to 8-bit scaled by 255 (rounded, saturated; a copy), so
colours stay in the canvas's units.
@param interpolation `INTER_NEAREST` or `INTER_LINEAR`.
@param borderMode `BORDER_CONSTANT` (black), `BORDER_REPLICATE`, `BORDER_REFLECT`,
`BORDER_WRAP` or `BORDER_REFLECT_101`: where the coordinate leaves the texture.
*/
CV_EXPORTS_W void texturedTriangles(InputOutputArray canvas, InputArray verts2d, InputArray faces,
                                    InputArray texCoords, InputArray texture,
                                    int interpolation = INTER_LINEAR,
                                    int borderMode = BORDER_REPLICATE);

//! @}

}  // namespace shading
}  // namespace cv

#endif  // OPENCV_SHADING_TEXTURE_HPP
