// This file is part of opencv_shading. License: Apache-2.0.
//
// polygon_fill: one self-intersecting polygon (a star with a square hole) filled the seed's three
// ways, side by side, with counts of where each differs from the exact even-odd fill:
//   1. fillPolygons, FILL_EVEN_ODD   (scan line, active edge table, odd-even rule)
//   2. fillPolygons, FILL_NONZERO    (the same scan line, winding numbers)
//   3. cv::fillPoly                  (OpenCV's scan line: even-odd, outline pixels included)
//   4. the outline drawn with lines, then cv::floodFill from a seed inside (flood fill)
//
//   ./polygon_fill [--out polygon_fill.png] [--no-gui]
#include <opencv2/shading.hpp>

#include "demo_scene.hpp"

#include <cmath>
#include <iostream>
#include <string>
#include <vector>

namespace {

constexpr int kSide = 320;

//! A seven-pointed star {7/3} (its middle is wound three times) and a square hole inside.
std::vector<std::vector<cv::Point>> starWithHole()
{
    std::vector<cv::Point> star;
    for (int k = 0; k < 7; k++) {
        const double a = 2 * CV_PI * 3 * k / 7 - CV_PI / 2;
        star.emplace_back(cvRound(kSide / 2 + 140 * std::cos(a)), cvRound(kSide / 2 + 140 * std::sin(a)));
    }
    const std::vector<cv::Point> hole = {{150, 150}, {150, 170}, {170, 170}, {170, 150}};
    return {star, hole};
}

//! Pixels set in `mask` (CV_8U, nonzero = covered).
cv::Mat coverage(const cv::Mat& canvas)
{
    cv::Mat gray;
    cv::cvtColor(canvas, gray, cv::COLOR_RGB2GRAY);
    return gray > 0;
}

cv::Mat panel(const cv::Mat& mask, const cv::Mat& reference, const std::string& title)
{
    // White: covered here and by even-odd; red: only here; blue: only by even-odd.
    cv::Mat out(mask.size(), CV_8UC3, cv::Scalar::all(40));
    out.setTo(cv::Scalar(255, 255, 255), mask & reference);
    out.setTo(cv::Scalar(255, 60, 60), mask & ~reference);
    out.setTo(cv::Scalar(60, 90, 255), ~mask & reference);
    cv::putText(out, title, {8, 22}, cv::FONT_HERSHEY_SIMPLEX, 0.55, cv::Scalar(255, 255, 0), 1,
                cv::LINE_AA);
    return out;
}

}  // namespace

int main(int argc, char** argv)
{
    std::string out = "polygon_fill.png";
    bool gui = true;
    for (int i = 1; i < argc; i++) {
        const std::string arg = argv[i];
        if (arg == "--no-gui")
            gui = false;
        else if (arg == "--out" && i + 1 < argc)
            out = argv[++i];
        else {
            std::cerr << "usage: polygon_fill [--out file.png] [--no-gui]\n";
            return 2;
        }
    }
    const std::vector<std::vector<cv::Point>> polygon = starWithHole();
    const cv::Scalar white(255, 255, 255);
    auto blank = [] { return cv::Mat(kSide, kSide, CV_8UC3, cv::Scalar::all(0)); };

    cv::Mat evenOdd = blank(), nonzero = blank(), fillPoly = blank(), flood = blank();
    cv::shading::fillPolygons(evenOdd, polygon, white, cv::shading::FILL_EVEN_ODD);
    cv::shading::fillPolygons(nonzero, polygon, white, cv::shading::FILL_NONZERO);
    cv::fillPoly(fillPoly, polygon, white);
    // The outline with lines (each edge a segment), then a flood fill from the star's tip
    // region: it fills only the region around the seed that the outline encloses.
    std::vector<cv::Point2f> segments;
    for (const auto& contour : polygon)
        for (size_t i = 0; i < contour.size(); i++) {
            segments.push_back(contour[i]);
            segments.push_back(contour[(i + 1) % contour.size()]);
        }
    cv::shading::lines(flood, segments, std::vector<cv::Vec3f>(segments.size(), cv::Vec3f(255, 255, 255)));
    cv::floodFill(flood, cv::Point(kSide / 2, 45), white);

    const cv::Mat reference = coverage(evenOdd);
    const std::vector<std::pair<std::string, cv::Mat>> methods = {
        {"fillPolygons even-odd", reference},
        {"fillPolygons nonzero", coverage(nonzero)},
        {"cv::fillPoly", coverage(fillPoly)},
        {"lines + cv::floodFill", coverage(flood)}};
    std::vector<cv::Mat> panels;
    for (const auto& m : methods) {
        const int onlyHere = cv::countNonZero(m.second & ~reference);
        const int onlyEvenOdd = cv::countNonZero(~m.second & reference);
        std::cout << m.first << ": " << cv::countNonZero(m.second) << " pixels; " << onlyHere
                  << " not in the even-odd fill, " << onlyEvenOdd << " of it missing\n";
        panels.push_back(panel(m.second, reference, m.first));
    }
    cv::Mat image;
    cv::hconcat(panels, image);
    return shading_samples::saveOrShow("polygon_fill", image, out, gui) ? 0 : 1;
}
