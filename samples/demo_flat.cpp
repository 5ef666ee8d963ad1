// This file is part of opencv_shading. License: Apache-2.0.
//
// demo_flat: renders a triangle mesh with flat shading (one colour per triangle, the mean of its
// vertex colours), painted far to near on a white 512x512 canvas, and times it.
//
//   ./demo_flat                          built-in torus knot -> demo_flat.png (and a window)
//   ./demo_flat mesh.yml --out a.png     your mesh (verts2d, faces, vcolors, depth; YAML/JSON)
//   ./demo_flat --no-gui                 only write the PNG (or set OPENCV_SHADING_NO_GUI=1)
//
// Everything but the render call lives in demo_scene.hpp, shared with demo_gouraud.
#include <opencv2/shading.hpp>

#include "demo_scene.hpp"

int main(int argc, char** argv)
{
    using shading_samples::MeshScene;
    return shading_samples::runRenderDemo(argc, argv, "demo_flat",
                                          [](const MeshScene& s, cv::Mat& img) {
        // Colours are RGB in [0, 1]; img becomes a 512x512 CV_32FC3 image, white where no
        // triangle lands. render sorts the faces by mean vertex depth, so no z-buffer is needed.
        cv::shading::render(s.verts2d, s.faces, s.vcolors, s.depth, img, cv::shading::SHADE_FLAT,
                            cv::Size(512, 512), cv::Scalar::all(1.0));
    });
}
