// This file is part of opencv_shading. License: Apache-2.0.
#ifndef OPENCV_SHADING_MESHIO_HPP
#define OPENCV_SHADING_MESHIO_HPP

#ifndef OPENCV_SHADING_HPP
#error "include <opencv2/shading.hpp>, not this sub-header"
#endif

/**
@addtogroup shading

### Mesh files (loadMesh, saveMesh)
Read and written through the Open Asset Import Library (assimp), with the signatures of OpenCV
5's `cv::loadMesh`/`cv::saveMesh`, faces being triangles (K x 3). Every array is one row per
item: vertices, normals and colours L x 3 `CV_32F`, texture coordinates L x 2 (or L x 3)
`CV_32F`, faces K x 3 `CV_32S`, ready for #drawMesh3d.
*/

namespace cv {
namespace shading {

//! @addtogroup shading
//! @{

/** @brief Loads a triangle mesh from a file: OBJ, PLY, STL, glTF/GLB, OFF, COLLADA, FBX, 3DS
and the other formats assimp reads (chosen by content and extension).

Polygons are triangulated, identical vertices (same position, normal, colour and texture
coordinate) are merged so the faces of a smooth surface share them, and every mesh of the file is
moved by its node's transform and appended, in the file's order, into one mesh. Points and lines
are dropped. A vertex keeps one normal, colour and texture coordinate: where the file gives a
position several of them (an STL facet's normal, an OBJ seam), it becomes several vertices.

@param filename Path of the file.
@param vertices Output, L x 3 `CV_32F`: positions (x, y, z).
@param faces Output, K x 3 `CV_32S`: zero-based vertex indices of each triangle, in the file's
winding.
@param normals Optional output, L x 3 `CV_32F`: the file's vertex normals; empty when any mesh of
the file has none (#drawMesh3d then computes them).
@param colors Optional output, L x 3 `CV_32F`: the first set of vertex colours as RGB in [0, 1]
(alpha dropped; 8-bit files are divided by 255); empty when any mesh of the file has none.
@param texCoords Optional output, L x 2 `CV_32F` (L x 3 when the file's coordinates have 3
components): the first set of texture coordinates (u, v), as stored (v not flipped); empty when
any mesh of the file has none.

Vector outputs of matching items (`std::vector<Vec3f>`, `std::vector<Point3d>`,
`std::vector<Vec3i>`, `std::vector<Point2f>`, ...) are filled too.

@throws cv::Exception naming the file when it does not exist, cannot be parsed, or holds no
triangle.
*/
CV_EXPORTS_W void loadMesh(const String& filename, OutputArray vertices, OutputArray faces,
                           OutputArray normals = noArray(), OutputArray colors = noArray(),
                           OutputArray texCoords = noArray());

/** @brief Saves a triangle mesh, in the format its extension names.

What each format keeps of the optional arrays:

| extension | normals | colours | texCoords | notes |
|---|---|---|---|---|
| `.obj` | yes | no | yes | no material file |
| `.ply` | yes | 8-bit | yes | text |
| `.stl` | no | no | no | binary; vertices are not shared (one per facet corner) |
| `.gltf`, `.glb` | yes | yes | yes | `.gltf` writes a `.bin` beside it |
| `.dae` | yes | yes | yes | |
| `.off` | no | no | no | written directly (assimp has no OFF exporter) |

`.fbx`, `.x3d`, `.3mf`, `.x` and `.3ds` go to assimp's exporters as they are. Values are stored
as `float` (text formats with 9 significant digits, which give every float back exactly), so
positions reload exactly; `CV_64F` input rounds to the nearest float.
Every argument is checked before the file is opened, so a rejected call writes nothing.

@param filename Path of the file to write (its folder must exist).
@param vertices L x 3 positions: `CV_32F`, `CV_64F` or `CV_32S`, or
`std::vector<Point3f|Point3d|Vec3f|Vec3d>`; at least one, all finite.
@param faces K x 3 zero-based indices into `vertices` (at least one triangle).
@param normals Optional L x 3 vertex normals, finite.
@param colors Optional L x 3 RGB vertex colours in [0, 1].
@param texCoords Optional L x 2 (or L x 3) texture coordinates, finite.

@throws cv::Exception naming the argument (wrong shape or type, counts that differ from the
vertex count, a face index outside [0, L), non-finite values, colours outside [0, 1]) or the file
(unknown extension, the exporter's failure).
*/
CV_EXPORTS_W void saveMesh(const String& filename, InputArray vertices, InputArray faces,
                           InputArray normals = noArray(), InputArray colors = noArray(),
                           InputArray texCoords = noArray());

//! @}

}  // namespace shading
}  // namespace cv

#endif  // OPENCV_SHADING_MESHIO_HPP
