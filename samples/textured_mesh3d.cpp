// This file is part of opencv_shading. License: Apache-2.0.
//
// textured_mesh3d: drawTexturedMesh3d on a floor and a globe, textured from a generated
// checkerboard or your image, seen by an OpenCV camera (lookAt). Three panels:
//   left:   the floor's two triangles textured affinely in screen space (texturedTriangles of
//           their cv::projectPoints image): the classic warp along the diagonal;
//   middle: the same floor, perspective-correct (drawTexturedMesh3d, unlit);
//   right:  floor and globe under two coloured lights (Phong), z-buffered.
//
//   ./textured_mesh3d [image.png] [--out textured_mesh3d.png] [--no-gui]
#include <opencv2/calib3d.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/shading.hpp>

#include "demo_scene.hpp"

#include <chrono>
#include <cmath>
#include <iostream>
#include <string>
#include <vector>

namespace {

//! A 128 x 128 checkerboard (16 px squares) in two colours with a red border, CV_8UC3 RGB.
cv::Mat makeTexture()
{
    cv::Mat tex(128, 128, CV_8UC3);
    for (int y = 0; y < tex.rows; y++)
        for (int x = 0; x < tex.cols; x++) {
            const bool dark = ((x / 16) + (y / 16)) % 2;
            const bool border = x < 3 || y < 3 || x >= tex.cols - 3 || y >= tex.rows - 3;
            tex.at<cv::Vec3b>(y, x) = border ? cv::Vec3b(200, 30, 30)
                                      : dark ? cv::Vec3b(40, 60, 110)
                                             : cv::Vec3b(235, 225, 190);
        }
    return tex;
}

struct TexturedMesh {
    std::vector<cv::Vec3d> verts;
    std::vector<cv::Vec3i> faces;
    std::vector<cv::Point2d> uv;  //!< texture pixels
};

//! The square [-3, 3]^2 at z = 0 as two triangles, the texture tiled 3 x 3 (BORDER_WRAP).
TexturedMesh makeFloor(cv::Size tex)
{
    TexturedMesh m;
    for (int j = 0; j < 2; j++)
        for (int i = 0; i < 2; i++) {
            m.verts.emplace_back(6.0 * i - 3, 6.0 * j - 3, 0);
            m.uv.emplace_back(3.0 * tex.width * i - 0.5, 3.0 * tex.height * (1 - j) - 0.5);
        }
    m.faces = {{0, 1, 3}, {0, 3, 2}};  // counter-clockwise seen from above
    return m;
}

/** A latitude-longitude sphere (radius r, centre c), the texture wrapped around it twice. The
seam column is duplicated so that each vertex has one texture coordinate. */
TexturedMesh makeGlobe(cv::Size tex, cv::Vec3d c, double r, int slices = 48, int stacks = 24)
{
    TexturedMesh m;
    const double pi = 3.14159265358979323846;
    for (int j = 0; j <= stacks; j++)
        for (int i = 0; i <= slices; i++) {
            const double u = double(i) / slices, v = double(j) / stacks;
            const double phi = 2 * pi * u, theta = pi * v;
            m.verts.push_back(c + r * cv::Vec3d(std::sin(theta) * std::cos(phi),
                                                std::sin(theta) * std::sin(phi), std::cos(theta)));
            m.uv.emplace_back(2.0 * tex.width * u - 0.5, tex.height * v - 0.5);
        }
    for (int j = 0; j < stacks; j++)
        for (int i = 0; i < slices; i++) {
            const int a = j * (slices + 1) + i, b = a + 1, d = a + slices + 1, e = d + 1;
            m.faces.emplace_back(a, d, e);  // outward-facing
            m.faces.emplace_back(a, e, b);
        }
    return m;
}

void append(TexturedMesh& to, const TexturedMesh& m)
{
    const int offset = int(to.verts.size());
    to.verts.insert(to.verts.end(), m.verts.begin(), m.verts.end());
    to.uv.insert(to.uv.end(), m.uv.begin(), m.uv.end());
    for (const cv::Vec3i& f : m.faces)
        to.faces.emplace_back(f[0] + offset, f[1] + offset, f[2] + offset);
}

}  // namespace

int main(int argc, char** argv)
{
    shading_samples::DemoOptions opt;
    cv::Mat texture;  // RGB, as the library's colours
    const int status = shading_samples::parseTextureSampleOptions(argc, argv, "textured_mesh3d", makeTexture,
                                                                  opt, texture);
    if (status >= 0)
        return status;

    const cv::Size panelSize(480, 360);
    const cv::Matx33d K(420, 0, panelSize.width / 2.0, 0, 420, panelSize.height / 2.0, 0, 0, 1);
    cv::Mat rvec, tvec;
    cv::shading::lookAt(cv::Point3d(3.2, -4.6, 2.6), cv::Point3d(0, 0, 0.6), cv::Vec3d(0, 0, 1),
                        rvec, tvec);
    const TexturedMesh floor = makeFloor(texture.size());
    TexturedMesh scene = floor;
    append(scene, makeGlobe(texture.size(), cv::Vec3d(0, 0, 1.1), 1.1));

    cv::Mat img(panelSize.height, 3 * panelSize.width, CV_8UC3, cv::Scalar(20, 20, 28));
    cv::Mat affine = img.colRange(0, panelSize.width);
    cv::Mat perspective = img.colRange(panelSize.width, 2 * panelSize.width);
    cv::Mat lit = img.colRange(2 * panelSize.width, 3 * panelSize.width);

    // Left: what interpolating in screen space does to the floor.
    std::vector<cv::Point2d> projected;
    cv::projectPoints(floor.verts, rvec, tvec, K, cv::noArray(), projected);
    cv::shading::texturedTriangles(affine, projected, floor.faces, floor.uv, texture,
                                   cv::INTER_LINEAR, cv::BORDER_WRAP);

    // Middle: the same floor, perspective-correct.
    cv::shading::RenderSettings settings;
    settings.textureBorder = cv::BORDER_WRAP;
    cv::shading::drawTexturedMesh3d(perspective, floor.verts, floor.faces, floor.uv, texture, K,
                                    rvec, tvec, settings);

    // Right: the whole scene, lit per sample.
    settings.shadeType = cv::shading::SHADE_PHONG;
    settings.lights = {cv::shading::PointLight(cv::Point3d(4, -3, 5), cv::Vec3d(1.0, 0.9, 0.8)),
                       cv::shading::PointLight(cv::Point3d(-4, -2, 2), cv::Vec3d(0.3, 0.4, 0.7))};
    settings.ka = 0.35;
    settings.ks = 0.4;
    settings.shininess = 24;
    const auto start = std::chrono::steady_clock::now();
    cv::shading::drawTexturedMesh3d(lit, scene.verts, scene.faces, scene.uv, texture, K, rvec,
                                    tvec, settings);
    const double ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();

    const char* labels[] = {"affine (texturedTriangles)", "perspective-correct",
                            "Phong, two lights, z-buffer"};
    for (int k = 0; k < 3; k++)
        cv::putText(img, labels[k], cv::Point(panelSize.width * k + 10, 24),
                    cv::FONT_HERSHEY_SIMPLEX, 0.6, cv::Scalar(255, 255, 255), 1, cv::LINE_AA);
    std::cout << scene.faces.size() << " textured faces (" << texture.cols << "x" << texture.rows
              << " texture), Phong with 2 lights: " << ms << " ms\n";
    return shading_samples::saveOrShow("textured_mesh3d", img, opt.out, opt.gui) ? 0 : 1;
}
