// This file is part of opencv_shading. License: Apache-2.0.
//
// demo_gouraud: renders a triangle mesh with Gouraud shading (vertex colours interpolated
// linearly across each triangle), painted far to near on a white 512x512 canvas, and times it.
//
//   ./demo_gouraud                        built-in torus knot -> demo_gouraud.png (and a window)
//   ./demo_gouraud mesh.json --out b.png  your mesh (verts2d, faces, vcolors, depth; YAML/JSON)
//   ./demo_gouraud --no-gui               only write the PNG (or set OPENCV_SHADING_NO_GUI=1)
//
// Everything but the render call lives in demo_scene.hpp, shared with demo_flat.
#include <opencv2/shading.hpp>

#include "demo_scene.hpp"

int main(int argc, char** argv)
{
    using shading_samples::MeshScene;
    return shading_samples::runRenderDemo(argc, argv, "demo_gouraud",
                                          [](const MeshScene& s, cv::Mat& img) {
        // The scene's colours were lit per vertex; interpolating them hides the facets that
        // demo_flat shows. To draw into an existing image (8-bit too) use cv::shading::drawMesh.
        cv::shading::render(s.verts2d, s.faces, s.vcolors, s.depth, img,
                            cv::shading::SHADE_GOURAUD, cv::Size(512, 512), cv::Scalar::all(1.0));
    });
}
