// This file is part of opencv_shading. License: Apache-2.0.
//
// The projected mesh drawMesh3d hands to the band pass (bands.hpp).
#ifndef OPENCV_SHADING_SCREEN_MESH_HPP
#define OPENCV_SHADING_SCREEN_MESH_HPP

#include "mesh.hpp"
#include "shaders3d.hpp"

#include <opencv2/core.hpp>

#include <vector>

namespace cv {
namespace shading {
namespace detail {

/** The mesh as the band pass draws it: projected, clipped triangles, and per vertex 1 / Zc and
the surface's attributes (interpolated perspective-correctly by SurfaceShader). */
struct ScreenMesh {
    //! Projected vertices and faces; the sort keys as faceDepth, or (no face clipped) per
    //! vertex as depth, the camera z.
    MeshData mesh;
    std::vector<double> invZ;        //!< per vertex
    std::vector<double> attributes;  //!< per vertex, `stride` values
    Surface surface = Surface::kFlat;
    int stride = 0;                  //!< attributeCount(surface)
    //! Per face: its index in the caller's faces; empty when the faces are the caller's.
    std::vector<int> source;
    //! Per face, faceStride values: kFlat its colour (canvas units, 3), kTexturedFaceLit its D
    //! and S (6); empty for the other surfaces.
    std::vector<float> faceValues;
    int faceStride = 0;
    /** kFlat with lights: the caller's vertices, colours and faces (indexed by sourceOf), from
    which the band pass lights each face it sets up (stageFace); null faces otherwise. */
    struct FlatLit {
        Rows3 verts, colors;
        const Vec3i* faces = nullptr;
    } flatLit;

    int sourceOf(int face) const { return source.empty() ? face : source[face]; }

    size_t capacityBytes() const
    {
        return mesh.capacityBytes() + (invZ.capacity() + attributes.capacity()) * sizeof(double) +
               source.capacity() * sizeof(int) + faceValues.capacity() * sizeof(float);
    }
};

}  // namespace detail
}  // namespace shading
}  // namespace cv

#endif  // OPENCV_SHADING_SCREEN_MESH_HPP
