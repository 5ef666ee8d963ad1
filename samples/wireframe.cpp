// This file is part of opencv_shading. License: Apache-2.0.
//
// wireframe: the built-in mesh shaded with drawMesh (Gouraud), then every face's edges drawn
// over it with lines(), coloured from the vertex colours darkened (Bresenham: the pixels of
// cv::line) or with LINE_DDA for sub-pixel endpoints; writes wireframe.png.
//
//   ./wireframe [mesh.yml] [--dda] [--out wireframe.png] [--no-gui]
#include <opencv2/shading.hpp>

#include "demo_scene.hpp"

#include <chrono>
#include <cstring>
#include <iostream>
#include <string>
#include <vector>

int main(int argc, char** argv)
{
    int algorithm = cv::shading::LINE_BRESENHAM;
    std::string out = "wireframe.png";
    std::string meshPath;
    bool gui = true;
    for (int i = 1; i < argc; i++) {
        if (!std::strcmp(argv[i], "--dda"))
            algorithm = cv::shading::LINE_DDA;
        else if (!std::strcmp(argv[i], "--no-gui"))
            gui = false;
        else if (!std::strcmp(argv[i], "--out") && i + 1 < argc)
            out = argv[++i];
        else if (argv[i][0] != '-' && meshPath.empty())
            meshPath = argv[i];
        else {
            std::cerr << "usage: wireframe [mesh.yml] [--dda] [--out file.png] [--no-gui]\n";
            return 2;
        }
    }
    // The built-in knot with fewer, larger faces than the other demos, so the edges show.
    const shading_samples::MeshScene s = meshPath.empty()
                                             ? shading_samples::makeDemoScene({512, 512}, 2000)
                                             : shading_samples::loadScene(meshPath);
    cv::Mat img(512, 512, CV_32FC3, cv::Scalar::all(1));
    cv::shading::drawMesh(img, s.verts2d, s.faces, s.vcolors, s.depth);

    // Each face's three edges as segments; shared edges are simply drawn twice.
    std::vector<cv::Point2f> points;
    std::vector<cv::Vec3f> colors;
    for (int f = 0; f < s.faces.rows; f++) {
        const cv::Vec3i& face = *s.faces.ptr<cv::Vec3i>(f);
        for (int k = 0; k < 3; k++) {
            for (int end : {face[k], face[(k + 1) % 3]}) {
                points.push_back(*s.verts2d.ptr<cv::Point2f>(end));
                colors.push_back(*s.vcolors.ptr<cv::Vec3f>(end) * 0.35f);
            }
        }
    }
    const auto start = std::chrono::steady_clock::now();
    cv::shading::lines(img, points, colors, algorithm);
    const double ms = std::chrono::duration<double, std::milli>(
                          std::chrono::steady_clock::now() - start).count();
    std::cout << "mesh: " << s.faces.rows << " faces; " << points.size() / 2 << " edges drawn ("
              << (algorithm == cv::shading::LINE_DDA ? "DDA" : "Bresenham") << ") in " << ms
              << " ms\n";
    return shading_samples::saveOrShow("wireframe", img, out, gui) ? 0 : 1;
}
