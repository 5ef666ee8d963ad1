// This file is part of opencv_shading. License: Apache-2.0.
//
// pose_overlay: an augmented-reality round trip through OpenCV.
//   1. A "photo" of a 9x6 chessboard (25 mm squares) is synthesized with cv::shading::drawMesh3d
//      from a known camera matrix and pose (the board as black and white quads, plus noise).
//   2. The pose is recovered as from a real photo: cv::findChessboardCorners, cv::cornerSubPix,
//      cv::solvePnP. The recovered and true poses and the reprojection error are printed.
//   3. A lit 3D model is drawn onto the photo with the recovered pose (z-buffer, Phong shading,
//      three lights, the 8-bit photo as canvas), and the board's axes with cv::drawFrameAxes.
//
//   ./pose_overlay                        built-in torus knot -> pose_overlay.png (+ a window)
//   ./pose_overlay mesh.yml --out a.png   your model (verts3d, faces, vcolors, [normals])
//   ./pose_overlay --no-gui               only write the PNG (or set OPENCV_SHADING_NO_GUI=1)
//
// The photo is BGR, as cv::imread and cv::VideoCapture give it; the library draws channels in
// the order given, so the model's colours and the lights' intensities are given in BGR too.
#include <opencv2/calib3d.hpp>
#include <opencv2/shading.hpp>

#include "chessboard.hpp"
#include "demo_scene.hpp"

#include <iomanip>
#include <iostream>
#include <string>
#include <vector>

namespace {

namespace sh = cv::shading;

const char* const kUsage =
    "usage: pose_overlay [MESH.yml|MESH.json] [--out FILE.png] [--no-gui]\n"
    "  MESH: the model to stand on the board, an OpenCV FileStorage file with verts3d, faces,\n"
    "  vcolors and optionally normals (default: the built-in torus knot)\n";
using shading_samples::Chessboard;
using shading_samples::Mesh3d;

cv::Vec3d bgr(double r, double g, double b) { return {b, g, r}; }

// Scales the model to span 60% of the board's width and stands it on the board's centre. The
// board's up is -z (the side the camera sees), so the model is turned 180 degrees about x (its
// +z up) and shifted until its largest z touches z = 0. Colours become 8-bit BGR.
Mesh3d placeOnBoard(const Mesh3d& model, const Chessboard& board)
{
    const cv::Matx33f flip(1, 0, 0, 0, -1, 0, 0, 0, -1);
    Mesh3d m;
    cv::transform(model.verts3d.reshape(3), m.verts3d, flip);
    if (!model.normals.empty())
        cv::transform(model.normals.reshape(3), m.normals, flip);

    cv::Mat lo, hi;
    cv::reduce(m.verts3d.reshape(1), lo, 0, cv::REDUCE_MIN);
    cv::reduce(m.verts3d.reshape(1), hi, 0, cv::REDUCE_MAX);
    const cv::Vec3f low(lo), high(hi);
    const double boardWidth = (board.corners.width + 1) * board.square;
    const double scale = 0.6 * boardWidth / std::max(high[0] - low[0], high[1] - low[1]);
    const cv::Vec3d boardCentre((board.corners.width - 1) * board.square * 0.5,
                                (board.corners.height - 1) * board.square * 0.5, 0);
    const cv::Vec3d modelBase((low[0] + high[0]) * 0.5, (low[1] + high[1]) * 0.5, high[2]);
    // p -> scale * (p - modelBase) + boardCentre, as one affine transform.
    const cv::Vec3d shift = boardCentre - scale * modelBase;
    cv::Mat placed;
    cv::transform(m.verts3d, placed,
                  cv::Matx34d(scale, 0, 0, shift[0], 0, scale, 0, shift[1], 0, 0, scale, shift[2]));
    m.verts3d = placed.reshape(1);
    if (!m.normals.empty())
        m.normals = m.normals.reshape(1);

    cv::Mat rgb = model.vcolors.reshape(3);  // RGB in [0, 1] -> BGR in [0, 255]
    cv::cvtColor(rgb * 255.0, m.vcolors, cv::COLOR_RGB2BGR);
    m.vcolors = m.vcolors.reshape(1);
    m.faces = model.faces;
    return m;
}

// The angle of the rotation between two orientations.
double rotationErrorDeg(cv::InputArray rvecA, cv::InputArray rvecB)
{
    cv::Matx33d ra, rb;
    cv::Vec3d rdiff;
    cv::Rodrigues(rvecA, ra);
    cv::Rodrigues(rvecB, rb);
    cv::Rodrigues(ra.t() * rb, rdiff);
    return cv::norm(rdiff) * 180.0 / CV_PI;
}

}  // namespace

int main(int argc, char** argv)
{
    const std::string name = "pose_overlay";
    try {
        const shading_samples::DemoOptions opt =
            shading_samples::parseDemoOptions(argc, argv, name + ".png");
        if (opt.help) {
            std::cout << kUsage;
            return 0;
        }

        // 1. The photo: a known camera (fx = fy = 600 px) and pose (board ~25 degrees off the
        //    image plane, its centre 0.5 m in front of the camera; lengths in mm).
        const Chessboard board;
        const cv::Matx33d K(600, 0, 320, 0, 600, 240, 0, 0, 1);
        const cv::Vec3d rvecTrue(0.40, -0.15, 0.08);
        cv::Matx33d rotTrue;
        cv::Rodrigues(rvecTrue, rotTrue);
        const cv::Vec3d boardCentre(100.0, 62.5, 0.0);  // the middle of the 9 x 6 corners
        const cv::Vec3d tvecTrue = cv::Vec3d(0, 0, 500) - rotTrue * boardCentre;
        cv::Mat photo = shading_samples::renderChessboardPhoto(board, K, rvecTrue, tvecTrue);

        // 2. The pose, recovered from the photo alone.
        cv::Mat grey;
        cv::cvtColor(photo, grey, cv::COLOR_BGR2GRAY);
        std::vector<cv::Point2f> corners;
        if (!cv::findChessboardCorners(grey, board.corners, corners)) {
            std::cerr << name << ": no chessboard found in the photo\n";
            return 1;
        }
        cv::cornerSubPix(grey, corners, {5, 5}, {-1, -1},
                         {cv::TermCriteria::EPS + cv::TermCriteria::COUNT, 50, 1e-3});
        const std::vector<cv::Point3f> object = shading_samples::chessboardCorners3d(board);
        cv::Mat rvec, tvec;
        cv::solvePnP(object, corners, K, cv::noArray(), rvec, tvec);

        std::vector<cv::Point2f> reprojected;
        cv::projectPoints(object, rvec, tvec, K, cv::noArray(), reprojected);
        double reprojError = 0;
        for (size_t i = 0; i < corners.size(); ++i)
            reprojError += cv::norm(reprojected[i] - corners[i]) / corners.size();
        std::cout << std::fixed << std::setprecision(4) << "rvec true      " << rvecTrue
                  << "\nrvec recovered " << rvec.t() << "\ntvec true      " << tvecTrue
                  << " mm\ntvec recovered " << tvec.t() << " mm\nrotation error "
                  << rotationErrorDeg(rvecTrue, rvec) << " deg, translation error "
                  << cv::norm(tvec, tvecTrue) << " mm, mean reprojection error " << reprojError
                  << " px (" << corners.size() << " corners)\n";

        // 3. The model, lit and drawn with the recovered pose. Lights in board coordinates (mm;
        //    -z is above the board): a white key upper left, a warm fill right, a blue rim.
        const Mesh3d model =
            placeOnBoard(opt.input.empty() ? shading_samples::makeDemoMesh3d()
                                           : shading_samples::loadMesh3d(opt.input),
                         board);
        sh::RenderSettings settings;
        settings.shadeType = sh::SHADE_PHONG;
        settings.visibility = sh::VISIBILITY_ZBUFFER;
        settings.cullMode = opt.input.empty() ? sh::CULL_BACK : sh::CULL_NONE;
        settings.shininess = 32;
        settings.lights = {sh::PointLight({-200, -250, -500}, bgr(0.9, 0.9, 0.9)),
                           sh::PointLight({450, 100, -250}, bgr(0.6, 0.35, 0.1)),
                           sh::PointLight({0, 400, -150}, bgr(0.1, 0.2, 0.7))};
        cv::Mat overlay;
        const double ms = shading_samples::medianMs([&] {
            photo.copyTo(overlay);
            sh::drawMesh3d(overlay, model.verts3d, model.faces, model.vcolors, K, rvec, tvec,
                           settings, model.normals);
        });
        std::cout << "overlay: " << model.faces.rows << " triangles, " << std::setprecision(2)
                  << ms << " ms (copy + drawMesh3d, median of 20 runs, " << cv::getNumThreads()
                  << " threads)\n";
        cv::drawFrameAxes(overlay, K, cv::noArray(), rvec, tvec, 3 * board.square, 2);

        cv::Mat rgb;  // saveOrShow takes RGB, like the other samples' images
        cv::cvtColor(overlay, rgb, cv::COLOR_BGR2RGB);
        return shading_samples::saveOrShow(name, rgb, opt.out, opt.gui) ? 0 : 1;
    } catch (const std::invalid_argument& e) {
        std::cerr << name << ": " << e.what() << '\n' << kUsage;
        return 2;
    } catch (const std::exception& e) {  // cv::Exception included: its text says what was wrong
        std::cerr << name << ": " << e.what() << '\n';
        return 1;
    }
}
