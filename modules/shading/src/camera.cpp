// This file is part of opencv_shading. License: Apache-2.0.
#include "camera.hpp"

#include <opencv2/calib3d.hpp>
#include <opencv2/shading.hpp>

#include <cmath>

namespace cv {
namespace shading {
namespace detail {

static std::string describe(const Mat& m)
{
    return format("%dx%d %s", m.rows, m.cols, typeToString(m.type()).c_str());
}

//! `m` as doubles, checked: CV_32F or CV_64F, all finite.
static Mat finiteDoubles(const Mat& m, const char* argName)
{
    if (m.depth() != CV_32F && m.depth() != CV_64F)
        CV_Error(Error::StsUnsupportedFormat, format("%s: expected CV_32F or CV_64F values, got %s",
                                                     argName, describe(m).c_str()));
    Mat d;
    m.convertTo(d, CV_64F);
    if (!checkRange(d))
        CV_Error(Error::StsOutOfRange, format("%s: values must be finite", argName));
    return d;
}

Camera readCamera(InputArray cameraMatrix, InputArray rvec, InputArray tvec)
{
    Camera cam;
    const Mat k = cameraMatrix.getMat();
    if (k.dims != 2 || k.rows != 3 || k.cols != 3 || k.channels() != 1)
        CV_Error(Error::StsBadSize, format("cameraMatrix: expected a 3x3 matrix, got %s",
                                           describe(k).c_str()));
    const Matx33d K = finiteDoubles(k, "cameraMatrix");
    if (K(0, 0) == 0 || K(1, 1) == 0)
        CV_Error(Error::StsBadArg, format("cameraMatrix: focal lengths must be nonzero, got "
                                          "fx = %g, fy = %g", K(0, 0), K(1, 1)));
    if (K(1, 0) != 0 || K(2, 0) != 0 || K(2, 1) != 0 || K(2, 2) != 1)
        CV_Error(Error::StsBadArg,
                 format("cameraMatrix: expected [fx s cx; 0 fy cy; 0 0 1], got last rows "
                        "[%g %g %g; %g %g %g]", K(1, 0), K(1, 1), K(1, 2), K(2, 0), K(2, 1),
                        K(2, 2)));
    cam.fx = K(0, 0), cam.skew = K(0, 1), cam.cx = K(0, 2), cam.fy = K(1, 1), cam.cy = K(1, 2);

    const Mat r = rvec.getMat();
    if (r.dims == 2 && r.rows == 3 && r.cols == 3 && r.channels() == 1) {
        cam.R = Matx33d(finiteDoubles(r, "rvec"));
        // A rotation: R R^T = I (up to the rounding of a matrix given in float).
        if (norm(cam.R * cam.R.t(), Matx33d::eye(), NORM_INF) > 1e-4 || determinant(cam.R) < 0)
            CV_Error(Error::StsBadArg, "rvec: a 3x3 rvec must be a rotation matrix (orthonormal, "
                                       "determinant +1)");
    } else if (r.total() * r.channels() == 3 && (r.rows == 1 || r.cols == 1)) {
        Mat R;
        Rodrigues(finiteDoubles(r.reshape(1, 3), "rvec"), R);  // as cv::projectPoints does
        cam.R = Matx33d(R);
    } else {
        CV_Error(Error::StsBadSize,
                 format("rvec: expected a 3x1 Rodrigues vector or a 3x3 rotation matrix, got %s",
                        describe(r).c_str()));
    }

    const Mat t = tvec.getMat();
    if (t.total() * t.channels() != 3 || !(t.rows == 1 || t.cols == 1))
        CV_Error(Error::StsBadSize,
                 format("tvec: expected a 3x1 translation, got %s", describe(t).c_str()));
    cam.t = Vec3d(finiteDoubles(t.reshape(1, 3), "tvec"));
    return cam;
}

}  // namespace detail

void lookAt(const Point3d& eye, const Point3d& target, const Vec3d& up, OutputArray rvec,
            OutputArray tvec)
{
    const Vec3d e(eye), view = Vec3d(target) - e;
    if (!checkRange(Mat(e)) || !checkRange(Mat(Vec3d(target))) || !checkRange(Mat(up)))
        CV_Error(Error::StsOutOfRange, "lookAt: eye, target and up must be finite");
    const double viewLength = norm(view);
    if (!(viewLength > 0))
        CV_Error(Error::StsBadArg, "lookAt: eye and target must differ");
    const Vec3d zc = view * (1.0 / viewLength);
    const Vec3d upInPlane = up - zc * up.dot(zc);
    const double upLength = norm(upInPlane);
    // Relative test: an up vector within ~1e-6 rad of the view gives no usable frame.
    if (!(upLength > 1e-12 * norm(up)) || !(norm(up) > 0))
        CV_Error(Error::StsBadArg, "lookAt: up must be nonzero and not parallel to target - eye");
    const Vec3d yc = upInPlane * (-1.0 / upLength);  // image rows grow downwards
    const Vec3d xc = yc.cross(zc);
    const Matx33d R(xc[0], xc[1], xc[2], yc[0], yc[1], yc[2], zc[0], zc[1], zc[2]);
    Mat r;
    Rodrigues(Mat(R), r);
    r.copyTo(rvec);
    Mat(-(R * e)).copyTo(tvec);
}

}  // namespace shading
}  // namespace cv
