// This file is part of opencv_shading. License: Apache-2.0.
//
// OpenCV's pinhole camera, read and checked once at the API edge: Xc = R Xw + t, then
// u = fx Xc/Zc + s Yc/Zc + cx, v = fy Yc/Zc + cy, evaluated exactly as cv::projectPoints does.
#ifndef OPENCV_SHADING_CAMERA_HPP
#define OPENCV_SHADING_CAMERA_HPP

#include <opencv2/core.hpp>

namespace cv {
namespace shading {
namespace detail {

struct Camera {
    double fx, fy, skew, cx, cy;
    Matx33d R;
    Vec3d t;

    //! World to camera coordinates, summed in cv::projectPoints's order.
    Vec3d toCamera(const Vec3d& w) const
    {
        return {R(0, 0) * w[0] + R(0, 1) * w[1] + R(0, 2) * w[2] + t[0],
                R(1, 0) * w[0] + R(1, 1) * w[1] + R(1, 2) * w[2] + t[1],
                R(2, 0) * w[0] + R(2, 1) * w[1] + R(2, 2) * w[2] + t[2]};
    }

    /** Pixel coordinates of camera point c (c[2] > 0), rounded as cv::projectPoints rounds them
    (x = X * (1 / Z), then x fx + cx), so the 2D functions see the very same points. */
    Point2d project(const Vec3d& c) const
    {
        const double invZ = 1.0 / c[2];
        const double x = c[0] * invZ, y = c[1] * invZ;
        return {x * fx + skew * y + cx, y * fy + cy};
    }

    //! The camera centre in world coordinates, -R^T t.
    Vec3d centre() const { return -(R.t() * t); }
};

//! Reads and checks cameraMatrix, rvec and tvec (errors name the argument).
Camera readCamera(InputArray cameraMatrix, InputArray rvec, InputArray tvec);

}  // namespace detail
}  // namespace shading
}  // namespace cv

#endif  // OPENCV_SHADING_CAMERA_HPP
