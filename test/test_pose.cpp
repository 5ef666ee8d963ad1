// The chessboard round trip through OpenCV (samples/pose_overlay.cpp as a test): a 9x6 board
// rendered with drawMesh3d from a known camera and pose, its corners found with
// cv::findChessboardCorners + cv::cornerSubPix, its pose recovered with cv::solvePnP. The corners
// must land where cv::projectPoints puts them (the renderer's camera model is OpenCV's) and the
// pose must come back.
#include "../samples/chessboard.hpp"

#include <gtest/gtest.h>
#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/shading.hpp>

#include <cmath>
#include <string>
#include <vector>

using namespace cv;
using shading_samples::Chessboard;

namespace {

const Matx33d kCamera(600, 0, 320, 0, 600, 240, 0, 0, 1);

struct Pose {
    Vec3d rvec, tvec;
};

// The board's corner centre 0.5 m (or `distance` mm) in front of the camera, turned by rvec.
Pose poseFacing(const Vec3d& rvec, double distance)
{
    Matx33d r;
    Rodrigues(rvec, r);
    const Chessboard board;
    const Vec3d centre((board.corners.width - 1) * board.square * 0.5,
                       (board.corners.height - 1) * board.square * 0.5, 0);
    return {rvec, Vec3d(0, 0, distance) - r * centre};
}

// pose_overlay's pose (~25 degrees), a steeper one about y and z, a closer one tilted the
// other way.
std::vector<Pose> testPoses()
{
    return {poseFacing({0.40, -0.15, 0.08}, 500), poseFacing({0.10, 0.55, 0.35}, 600),
            poseFacing({-0.35, 0.20, -0.10}, 420)};
}

std::string describe(const Pose& p)
{
    return format("rvec (%g, %g, %g), tvec (%g, %g, %g)", p.rvec[0], p.rvec[1], p.rvec[2],
                  p.tvec[0], p.tvec[1], p.tvec[2]);
}

// Corners found in the photo, refined, in findChessboardCorners' order.
std::vector<Point2f> findCorners(const Mat& photo, const Chessboard& board)
{
    Mat grey;
    cvtColor(photo, grey, COLOR_BGR2GRAY);
    std::vector<Point2f> corners;
    if (!findChessboardCorners(grey, board.corners, corners))
        return {};
    cornerSubPix(grey, corners, {5, 5}, {-1, -1},
                 {TermCriteria::EPS + TermCriteria::COUNT, 50, 1e-3});
    return corners;
}

std::vector<Point2f> projectTrue(const Chessboard& board, const Pose& p)
{
    std::vector<Point2f> projected;
    projectPoints(shading_samples::chessboardCorners3d(board), p.rvec, p.tvec, kCamera,
                  noArray(), projected);
    return projected;
}

}  // namespace

TEST(ShadingPose, ChessboardRoundTripRecoversThePose)
{
    const Chessboard board;
    const std::vector<Point3f> object = shading_samples::chessboardCorners3d(board);
    for (const Pose& truth : testPoses()) {
        SCOPED_TRACE(describe(truth));
        // Area-averaged pixels (4 x 4 samples) and noise, as a camera would see it.
        const Mat photo = shading_samples::renderChessboardPhoto(board, kCamera, truth.rvec,
                                                                 truth.tvec, {640, 480}, 2.0, 4);
        const std::vector<Point2f> corners = findCorners(photo, board);
        ASSERT_EQ(corners.size(), object.size()) << "chessboard not found";

        // The renderer projects as cv::projectPoints does: every corner within 0.3 px, and on
        // average within 0.05 px in x and in y (measured: 0.015; a renderer sampling pixel
        // corners instead of centres would be off by 0.13 here).
        const std::vector<Point2f> expected = projectTrue(board, truth);
        Point2d bias(0, 0);
        for (size_t i = 0; i < corners.size(); ++i) {
            EXPECT_LT(norm(corners[i] - expected[i]), 0.3)
                << "corner " << i << " found at " << corners[i] << ", projects to "
                << expected[i];
            bias += Point2d(corners[i] - expected[i]) / double(corners.size());
        }
        EXPECT_LT(std::abs(bias.x), 0.05);
        EXPECT_LT(std::abs(bias.y), 0.05);

        Vec3d rvec, tvec;
        ASSERT_TRUE(solvePnP(object, corners, kCamera, noArray(), rvec, tvec));
        Matx33d rTrue, rFound;
        Rodrigues(truth.rvec, rTrue);
        Rodrigues(rvec, rFound);
        Vec3d rDiff;
        Rodrigues(rTrue.t() * rFound, rDiff);
        EXPECT_LT(norm(rDiff) * 180 / CV_PI, 0.5) << "rotation error, degrees";
        EXPECT_LT(norm(tvec - truth.tvec), 0.01 * norm(truth.tvec)) << "translation error, mm";

        std::vector<Point2f> reprojected;
        projectPoints(object, rvec, tvec, kCamera, noArray(), reprojected);
        double meanError = 0;
        for (size_t i = 0; i < corners.size(); ++i)
            meanError += norm(reprojected[i] - corners[i]) / double(corners.size());
        EXPECT_LT(meanError, 0.2) << "mean reprojection error, px";
    }
}

// One sample per pixel, at its centre: hard edges scatter cornerSubPix by up to 0.7 px, but the
// scatter mostly averages out over the 54 corners (measured: at most 0.04 px). A renderer
// sampling half a pixel off (pixel corners instead of centres) would shift them all by 0.5 px.
TEST(ShadingPose, SingleSampleCornersAreUnbiased)
{
    const Chessboard board;
    for (const Pose& truth : testPoses()) {
        SCOPED_TRACE(describe(truth));
        const Mat photo = shading_samples::renderChessboardPhoto(board, kCamera, truth.rvec,
                                                                 truth.tvec, {640, 480}, 0.0, 1);
        const std::vector<Point2f> corners = findCorners(photo, board);
        ASSERT_EQ(corners.size(), size_t(board.corners.area())) << "chessboard not found";
        const std::vector<Point2f> expected = projectTrue(board, truth);
        Point2d bias(0, 0);
        for (size_t i = 0; i < corners.size(); ++i) {
            EXPECT_LT(norm(corners[i] - expected[i]), 1.0) << "corner " << i;
            bias += Point2d(corners[i] - expected[i]) / double(corners.size());
        }
        EXPECT_LT(std::abs(bias.x), 0.1);
        EXPECT_LT(std::abs(bias.y), 0.1);
    }
}
