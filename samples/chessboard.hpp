// This file is part of opencv_shading. License: Apache-2.0.
//
// chessboard.hpp: a synthetic camera photo of a chessboard calibration target, rendered with
// cv::shading::drawMesh3d. Shared by the pose_overlay sample and test/test_pose.cpp.
//
// Board coordinates are those cv::findChessboardCorners + cv::solvePnP use: inner corner (i, j)
// (row i, column j) at (j * square, i * square, 0), x along a row, y down the columns, the
// printed side facing -z. The top-left square (beyond corner (0, 0)) is black.
#ifndef OPENCV_SHADING_SAMPLES_CHESSBOARD_HPP
#define OPENCV_SHADING_SAMPLES_CHESSBOARD_HPP

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/shading.hpp>

#include "demo_scene.hpp"

#include <vector>

namespace shading_samples {

struct Chessboard {
    cv::Size corners{9, 6};   //!< inner corners per row and per column (the patternSize)
    double square = 25.0;     //!< side of a square, in the unit of the pose (here mm)
    int border = 1;           //!< white margin around the squares, in squares
    double black = 25;        //!< 8-bit grey levels: printed ink is never quite 0 or 255
    double white = 230;
};

//! The inner corners in board coordinates, in cv::findChessboardCorners' order (row by row).
inline std::vector<cv::Point3f> chessboardCorners3d(const Chessboard& b)
{
    std::vector<cv::Point3f> pts;
    for (int i = 0; i < b.corners.height; ++i)
        for (int j = 0; j < b.corners.width; ++j)
            pts.emplace_back(static_cast<float>(j * b.square), static_cast<float>(i * b.square),
                             0.f);
    return pts;
}

/** The board with its margin as a mesh: one quad (two triangles) per square, each with its own 4
vertices so neighbouring colours do not blend. Squares sharing an edge get bit-identical edge
vertices, so the exact rasterizer leaves no seam. Faces are wound counter-clockwise seen from
-z (the printed side): CULL_BACK keeps them for a camera in front. Colours are 8-bit greys. */
inline Mesh3d makeChessboardMesh(const Chessboard& b)
{
    const int cols = b.corners.width + 1 + 2 * b.border;   // squares across, margin included
    const int rows = b.corners.height + 1 + 2 * b.border;
    std::vector<cv::Vec3f> verts, colors;
    std::vector<cv::Vec3i> faces;
    const auto coord = [&b](int k) { return static_cast<float>((k - 1 - b.border) * b.square); };
    for (int r = 0; r < rows; ++r) {
        for (int c = 0; c < cols; ++c) {
            const int rb = r - b.border, cb = c - b.border;  // square index on the printed grid
            const bool inside =
                rb >= 0 && rb <= b.corners.height && cb >= 0 && cb <= b.corners.width;
            const float grey = static_cast<float>(inside && (rb + cb) % 2 == 0 ? b.black : b.white);
            const int v0 = static_cast<int>(verts.size());
            verts.insert(verts.end(), {{coord(c), coord(r), 0.f}, {coord(c + 1), coord(r), 0.f},
                                       {coord(c + 1), coord(r + 1), 0.f},
                                       {coord(c), coord(r + 1), 0.f}});
            colors.insert(colors.end(), 4, cv::Vec3f::all(grey));
            // (top-left, bottom-right, top-right): normal (x + y) x x = -z, towards the camera.
            faces.emplace_back(v0, v0 + 2, v0 + 1);
            faces.emplace_back(v0, v0 + 3, v0 + 2);
        }
    }
    Mesh3d m;
    m.verts3d = cv::Mat(verts, true).reshape(1);
    m.vcolors = cv::Mat(colors, true).reshape(1);
    m.faces = cv::Mat(faces, true).reshape(1);
    return m;
}

/** A camera's 8-bit view of the board on a grey background, drawn unlit (colours as given) with
the pinhole model of cv::projectPoints (no distortion). Like a sensor pixel, each pixel averages
`supersample` x `supersample` samples (1: one sample at the pixel centre, hard aliased edges, on
which cv::cornerSubPix scatters by ~0.3 px). Then `noiseSigma` grey levels of Gaussian sensor
noise (fixed seed: the same image every run). */
inline cv::Mat renderChessboardPhoto(const Chessboard& b, const cv::Matx33d& K,
                                     cv::InputArray rvec, cv::InputArray tvec,
                                     cv::Size size = {640, 480}, double noiseSigma = 2.0,
                                     int supersample = 4)
{
    CV_Assert(supersample >= 1);
    const Mesh3d board = makeChessboardMesh(b);
    // Pixel x covers fine pixels s x .. s x + s - 1, centred on s x + (s - 1) / 2: scale the
    // focal lengths and shift the principal point by that.
    const double s = supersample, shift = (s - 1) * 0.5;
    const cv::Matx33d fineK(s * K(0, 0), s * K(0, 1), s * K(0, 2) + shift, 0, s * K(1, 1),
                            s * K(1, 2) + shift, 0, 0, 1);
    cv::Mat fine(size * supersample, CV_8UC3, cv::Scalar::all(128));
    cv::shading::drawMesh3d(fine, board.verts3d, board.faces, board.vcolors, fineK, rvec, tvec);
    cv::Mat photo;
    cv::resize(fine, photo, size, 0, 0, cv::INTER_AREA);  // the mean of each s x s block
    if (noiseSigma > 0) {
        cv::Mat noise(size, CV_16SC3);
        cv::RNG rng(20240611);
        rng.fill(noise, cv::RNG::NORMAL, 0, noiseSigma);
        cv::Mat sum;
        cv::add(photo, noise, sum, cv::noArray(), CV_16S);
        sum.convertTo(photo, CV_8U);  // saturates
    }
    return photo;
}

}  // namespace shading_samples

#endif  // OPENCV_SHADING_SAMPLES_CHESSBOARD_HPP
