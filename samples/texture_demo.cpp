// This file is part of opencv_shading. License: Apache-2.0.
//
// texture_demo: a rippled grid of triangles textured with texturedTriangles, from a generated
// checkerboard with a colour gradient or from your image; nearest (left) and bilinear (right)
// side by side. Each pixel is what cv::remap gives for the interpolated texture coordinate.
//
//   ./texture_demo [image.png] [--out texture_demo.png] [--no-gui]
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

//! A 64 x 64 RGB checkerboard (8 px squares) tinted by a red-to-blue gradient, CV_8UC3.
cv::Mat makeTexture()
{
    cv::Mat tex(64, 64, CV_8UC3);
    for (int y = 0; y < tex.rows; y++)
        for (int x = 0; x < tex.cols; x++) {
            const bool dark = ((x / 8) + (y / 8)) % 2;
            const double g = (x + y) / 126.0;
            const double level = dark ? 0.25 : 1.0;
            tex.at<cv::Vec3b>(y, x) = cv::Vec3b(cv::saturate_cast<uchar>(255 * level * (1 - g)),
                                                cv::saturate_cast<uchar>(255 * level * 0.6),
                                                cv::saturate_cast<uchar>(255 * level * g));
        }
    return tex;
}

}  // namespace

int main(int argc, char** argv)
{
    shading_samples::DemoOptions opt;
    cv::Mat texture;  // RGB, as the library's colours
    const int status = shading_samples::parseTextureSampleOptions(argc, argv, "texture_demo", makeTexture,
                                                                  opt, texture);
    if (status >= 0)
        return status;

    // A (n + 1) x (n + 1) vertex grid over a 400 x 400 panel, rippled; texture coordinates span
    // the texture twice over, so BORDER_WRAP tiles it.
    const int n = 24, side = 400;
    std::vector<cv::Point2d> verts, uv;
    std::vector<cv::Vec3i> faces;
    for (int j = 0; j <= n; j++)
        for (int i = 0; i <= n; i++) {
            const double x = 20 + side * i / double(n), y = 20 + side * j / double(n);
            verts.emplace_back(x + 9 * std::sin(y / 37.0), y + 9 * std::sin(x / 29.0));
            uv.emplace_back(2.0 * texture.cols * i / n - 0.5, 2.0 * texture.rows * j / n - 0.5);
        }
    for (int j = 0; j < n; j++)
        for (int i = 0; i < n; i++) {
            const int a = j * (n + 1) + i, b = a + 1, c = a + n + 1, d = c + 1;
            faces.emplace_back(a, b, d);
            faces.emplace_back(a, d, c);
        }
    cv::Mat img(440, 880, CV_8UC3, cv::Scalar::all(255));
    double ms[2];
    const int modes[2] = {cv::INTER_NEAREST, cv::INTER_LINEAR};
    for (int k = 0; k < 2; k++) {
        cv::Mat panel = img.colRange(440 * k, 440 * (k + 1));
        const auto start = std::chrono::steady_clock::now();
        cv::shading::texturedTriangles(panel, verts, faces, uv, texture, modes[k],
                                       cv::BORDER_WRAP);
        ms[k] = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() -
                                                          start).count();
    }
    std::cout << faces.size() << " textured triangles, " << texture.cols << "x" << texture.rows
              << " texture: nearest " << ms[0] << " ms, bilinear " << ms[1] << " ms\n";
    return shading_samples::saveOrShow("texture_demo", img, opt.out, opt.gui) ? 0 : 1;
}
