// This file is part of opencv_shading. License: Apache-2.0.
#ifndef OPENCV_SHADING_MESH3D_HPP
#define OPENCV_SHADING_MESH3D_HPP

#ifndef OPENCV_SHADING_HPP
#error "include <opencv2/shading.hpp>, not this sub-header"
#endif

#include <opencv2/imgproc.hpp>

#include <vector>

/**
@addtogroup shading

### 3D meshes (drawMesh3d)
- **Camera, as in `cv::projectPoints`.** `Xc = R Xw + t` (`rvec` a Rodrigues vector or a 3 x 3
  rotation matrix, `tvec`); the camera looks along +z, x right, y down. A point projects to
  `u = fx Xc/Zc + s Yc/Zc + cx`, `v = fy Yc/Zc + cy` (double precision, no distortion), which the
  2D rules then snap and cover. So a mesh wholly in front of the near plane covers exactly the
  pixels #drawMesh covers for its `cv::projectPoints` image.
- **Near plane.** Triangles are clipped against `Zc = zNear` in camera space before projection,
  attributes interpolated linearly in 3D along the cut edges: nothing behind it is drawn. A quad
  left by the cut is split along the diagonal from the cut point that follows the vertex behind,
  whichever vertex the face lists first.
- **Depth** of a sample is its camera `Zc` on the triangle, perspective-correct (`1/Zc` is affine
  in screen space, over the snapped triangle that decides coverage, so it may differ from the
  exact ray depth by what the 1/256 px snap moves; stored as float). #VISIBILITY_ZBUFFER draws a sample where its depth is strictly smaller than
  the buffer's (equal depths: the earlier face in `faces` wins); #VISIBILITY_PAINTER draws faces
  from the largest mean vertex `Zc` to the smallest, ties in `faces` order, without a depth test.
  Either way the image does not depend on the thread count.
- **Culling.** With `n = (v1 - v0) x (v2 - v0)` (world space) and the camera centre
  `E = -R^T t`: #CULL_BACK skips faces with `n.(E - v0) <= 0`, #CULL_FRONT those with `>= 0`.
- **Normals.** Face normal `normalize((v1 - v0) x (v2 - v0))` (zero for a degenerate face);
  vertex normal the normalized mean of the unit normals of the faces using the vertex (zero where
  that sum is zero). Normals are used one-sided, as given.
- **Lighting (Phong model)**, colours in [0, 1]: at a point P with unit normal N, colour c, eye E
  and lights (p_i, I_i), with `V = normalize(E - P)`, `L_i = normalize(p_i - P)`,
  `R_i = 2 (N.L_i) N - L_i`:
  `I = c * (ka Ia + kd sum_i I_i max(N.L_i, 0)) + ks sum_i I_i [N.L_i > 0] max(R_i.V, 0)^shininess`
  per channel (the highlight takes the light's colour), each channel clamped to [0, 1]. On a
  `CV_8UC3` canvas the lighting works on c / 255 and writes the result x 255, rounded. With no
  lights the mesh is unlit: vertex colours as given, not clamped.
- **Shading.** #SHADE_FLAT: one colour per face, lit at its 3D centroid with its face normal and
  the mean of its vertex colours. #SHADE_GOURAUD: each vertex lit with its own position, normal
  and colour, the results interpolated. #SHADE_PHONG: position, normal and colour interpolated to
  every sample, the normal renormalized (a zero normal gets the ambient term only), lit there. All
  interpolation is perspective-correct.
*/

namespace cv {
namespace shading {

//! @addtogroup shading
//! @{

//! Which faces decide a pixel in #drawMesh3d.
enum Visibility {
    VISIBILITY_ZBUFFER = 0,  //!< per sample, the nearest depth (strict test: earlier face wins ties)
    VISIBILITY_PAINTER = 1   //!< faces by decreasing mean vertex depth, each overwriting
};

//! Which faces #drawMesh3d skips by their orientation towards the camera.
enum CullMode {
    CULL_NONE = 0,   //!< draw every face
    CULL_BACK = 1,   //!< skip faces whose normal points away from the camera (or edge-on)
    CULL_FRONT = 2   //!< skip faces whose normal points towards the camera (or edge-on)
};

//! A point light: position in world coordinates, RGB intensity.
struct CV_EXPORTS_W_SIMPLE PointLight {
    //! At the origin, white (1, 1, 1).
    CV_WRAP PointLight();
    CV_WRAP PointLight(const Point3d& position, const Vec3d& intensity);
    CV_PROP_RW Point3d position;  //!< world coordinates
    CV_PROP_RW Vec3d intensity;   //!< RGB, usually in [0, 1]
};

//! How #drawMesh3d shades and which faces it keeps.
struct CV_EXPORTS_W_SIMPLE RenderSettings {
    //! Gouraud, z-buffer, no culling, zNear 1e-3, no lights (unlit), ambient (1, 1, 1),
    //! ka 0.2, kd 0.7, ks 0.5, shininess 16; textures bilinear, border replicated; no clear.
    CV_WRAP RenderSettings();
    CV_PROP_RW int shadeType;    //!< #SHADE_FLAT, #SHADE_GOURAUD (default) or #SHADE_PHONG
    CV_PROP_RW int visibility;   //!< #VISIBILITY_ZBUFFER (default) or #VISIBILITY_PAINTER
    CV_PROP_RW int cullMode;     //!< #CULL_NONE (default), #CULL_BACK or #CULL_FRONT
    CV_PROP_RW double zNear;     //!< near clipping plane, camera z > 0 (default 1e-3)
    //! Point lights; empty (default): the mesh is unlit, its vertex colours drawn as given.
    CV_PROP_RW std::vector<PointLight> lights;
    CV_PROP_RW Vec3d ambient;    //!< ambient intensity Ia, RGB (default (1, 1, 1))
    CV_PROP_RW double ka;        //!< ambient reflectance (default 0.2)
    CV_PROP_RW double kd;        //!< diffuse reflectance (default 0.7)
    CV_PROP_RW double ks;        //!< specular reflectance (default 0.5)
    CV_PROP_RW double shininess; //!< Phong exponent (default 16)
    //! #drawTexturedMesh3d: `INTER_LINEAR` (default) or `INTER_NEAREST`, as `cv::remap`'s.
    CV_PROP_RW int textureInterpolation;
    //! #drawTexturedMesh3d: `BORDER_REPLICATE` (default), `BORDER_CONSTANT` (black),
    //! `BORDER_REFLECT`, `BORDER_WRAP` or `BORDER_REFLECT_101`, as `cv::remap`'s.
    CV_PROP_RW int textureBorder;
    /** Start a new frame (default false: draw over the canvas and test against the depth
    buffer's content). The image is then the one `canvas.setTo(background)` and, when given,
    `depthBuffer.setTo(+inf)` before the call would give, but the clearing is done band by
    band, in parallel, just before each band is drawn, as a GPU's fast clear: no pass of its own
    over the images. */
    CV_PROP_RW bool clear;
    //! The colour #clear sets, in the canvas's units (default black); must be finite.
    CV_PROP_RW Scalar background;
};

/** @brief Face and vertex normals of a triangle mesh (seed 004's rule).

Face normal: `normalize((v1 - v0) x (v2 - v0))`, right-handed in the face's vertex order, zero for
a degenerate face. Vertex normal: the normalized sum of the unit normals of the faces that use
the vertex (each face counted once per corner it has there), zero where that sum is zero or the
vertex is unused.

@param verts3d L vertices (x, y, z): `CV_32F`, `CV_64F` or `CV_32S` L x 3, or
`std::vector<Point3f|Point3d|Vec3f|Vec3d>`.
@param faces K triangles, each 3 zero-based indices into `verts3d`.
@param vertexNormals Output, L x 3 `CV_32F`.
@param faceNormals Optional output, K x 3 `CV_32F`.
*/
CV_EXPORTS_W void computeNormals(InputArray verts3d, InputArray faces, OutputArray vertexNormals,
                                 OutputArray faceNormals = noArray());

/** @brief The OpenCV camera pose (`rvec`, `tvec`) of a camera at `eye` looking at `target`.

The camera frame is `zc = normalize(target - eye)`, `yc = normalize(-(up - (up.zc) zc))` (image
rows grow against `up`), `xc = yc x zc`; `R` has rows `xc, yc, zc` and `t = -R eye`. For eye
(0, 0, d), target 0, up +y the image is not mirrored: world +x appears to the right, +y up.

@param eye Camera centre in world coordinates.
@param target Point the camera looks at; must differ from `eye`.
@param up World direction that appears up in the image; must not be parallel to the view.
@param rvec Output Rodrigues rotation vector, 3 x 1 `CV_64F`.
@param tvec Output translation, 3 x 1 `CV_64F`.
*/
CV_EXPORTS_W void lookAt(const Point3d& eye, const Point3d& target, const Vec3d& up,
                         OutputArray rvec, OutputArray tvec);

/** @brief Draws a 3D triangle mesh seen by an OpenCV camera, lit and shaded, with a z-buffer.

Vertices are moved into the camera frame (`Xc = R Xw + t`), faces are culled (settings.cullMode),
clipped against the near plane, projected with `cameraMatrix`, and drawn by the same exact
rasterizer as #drawMesh (sample points and fill rule alike), shaded per settings.shadeType under
settings.lights. See the group's conventions for every formula. Faces with a non-finite vertex
are skipped. The result does not depend on the number of threads.

@param canvas Image to draw over, `CV_32FC3` (colours in [0, 1] when lit) or `CV_8UC3` (0..255),
possibly an ROI. Its content is the background (unless settings.clear).
@param verts3d L vertices in world coordinates (as for #computeNormals).
@param faces K triangles, each 3 zero-based indices into `verts3d`.
@param vcolors L vertex colours in the canvas's units.
@param cameraMatrix 3 x 3 intrinsics `[fx s cx; 0 fy cy; 0 0 1]`, `CV_32F` or `CV_64F`, finite,
nonzero focal lengths.
@param rvec Rotation, world to camera: 3 x 1 (or 1 x 3) Rodrigues vector or 3 x 3 matrix.
@param tvec Translation, world to camera: 3 x 1 or 1 x 3.
@param settings Shading, visibility, culling, near plane, lights and material.
@param normals L vertex normals (world space), or empty to compute them as #computeNormals does.
@param depthBuffer Optional in/out, canvas-sized `CV_32FC1`. Empty: created and filled with +inf
first. Given: #VISIBILITY_ZBUFFER tests against it (against +inf with settings.clear), so several
meshes drawn into one canvas with one buffer composite correctly. Either way it ends holding the
depth (`Zc`) of every drawn sample.
@param faceIds Optional output, canvas-sized `CV_32SC1`: the index in `faces` of the face that
coloured each pixel, -1 elsewhere.
*/
CV_EXPORTS_W void drawMesh3d(InputOutputArray canvas, InputArray verts3d, InputArray faces,
                             InputArray vcolors, InputArray cameraMatrix, InputArray rvec,
                             InputArray tvec, const RenderSettings& settings = RenderSettings(),
                             InputArray normals = noArray(),
                             InputOutputArray depthBuffer = noArray(),
                             OutputArray faceIds = noArray());

/** @brief #drawMesh3d with a texture in place of the vertex colours.

Everything #drawMesh3d does (camera, culling, near plane, depth, visibility, outputs) is done the
same way, and the same samples are covered. Each covered sample's texture coordinate is the
perspective-correct interpolation of its face's vertex `texCoords` (the weights that interpolate
every 3D attribute), rounded to float and sampled as #texturedTriangles samples it: what
`cv::remap` gives with `settings.textureInterpolation` and `settings.textureBorder`. The texel
`t` (in the canvas's units) takes the vertex colour's place:
- no lights: `t` as sampled;
- lit, the Phong model splits into `I = c D + S` (D: ambient and diffuse factor, S: highlight,
  per channel), and the sample gets `clamp(t D + S)`, with D and S taken per face at its 3D
  centroid with its face normal (#SHADE_FLAT), per vertex and interpolated
  perspective-correctly (#SHADE_GOURAUD), or at the sample itself (#SHADE_PHONG: `c = t` in
  the lighting model). So a uniform texture of colour c gives #drawMesh3d's image for vertex
  colours c, up to rounding, where Gouraud's vertex colours are not clamped.

@param canvas,verts3d,faces,cameraMatrix,rvec,tvec,settings,normals,depthBuffer,faceIds As for
#drawMesh3d; `settings.textureInterpolation` and `settings.textureBorder` choose the sampling.
@param texCoords L texture coordinates (u, v), one per vertex, in texture pixels as
#texturedTriangles takes them ((0, 0) the centre of the texture's top-left pixel). A face whose
coordinates are not finite or exceed 1e30 is skipped. Seams need their vertices duplicated (as
#loadMesh gives them). A file's normalized (u, v) (0 and 1 at the texture's edges, v up) are the
pixel coordinates `(u cols - 0.5, (1 - v) rows - 0.5)`.
@param texture `CV_8UC3` or `CV_32FC3`, not empty; a texture of the other depth than the canvas
is converted as for #texturedTriangles.
*/
CV_EXPORTS_W void drawTexturedMesh3d(InputOutputArray canvas, InputArray verts3d, InputArray faces,
                                     InputArray texCoords, InputArray texture,
                                     InputArray cameraMatrix, InputArray rvec, InputArray tvec,
                                     const RenderSettings& settings = RenderSettings(),
                                     InputArray normals = noArray(),
                                     InputOutputArray depthBuffer = noArray(),
                                     OutputArray faceIds = noArray());

//! @}

}  // namespace shading
}  // namespace cv

#endif  // OPENCV_SHADING_MESH3D_HPP
