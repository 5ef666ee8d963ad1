// This file is part of opencv_shading. License: Apache-2.0.
//
// fillpoly_coverage: draws the same triangles with opencv_shading and with cv::fillConvexPoly,
// one at a time, counts how often each pixel is painted, and pictures the difference:
//   green   painted once by both          red     OpenCV only       blue   opencv_shading only
//   yellow  painted 2+ times by OpenCV    magenta 2+ times by opencv_shading   white  2+ by both
// OpenCV's fill includes every edge pixel, so neighbouring triangles paint their shared edge
// twice (a problem for blending or counting); opencv_shading's top-left rule paints every pixel
// of a closed mesh exactly once.
//
//   ./fillpoly_coverage                 16x16 jittered integer grid -> fillpoly_coverage.png
//   ./fillpoly_coverage --scene         the front faces of demo_flat's torus knot (where the knot
//                                       crosses itself both paint 2+ times, rightly)
//   ./fillpoly_coverage mesh.yml        your mesh (verts2d, faces, ...; YAML/JSON)
//   add --no-gui to only write the PNG, --out FILE.png to choose its name.
#include <opencv2/shading.hpp>

#include "demo_scene.hpp"

#include <cmath>
#include <iostream>
#include <string>

namespace {

using shading_samples::MeshScene;

const cv::Size kCanvas(512, 512);

// A closed planar mesh with integer vertices: a 16x16 grid of 28 px squares, each split along a
// random diagonal, vertices jittered by up to 6 px (border vertices only along the border). A
// jitter below 28 / 4 keeps every triangle's orientation, so the triangles tile the square
// without overlap. Windings are then mixed at random: coverage must not depend on them.
MeshScene makeJitteredGrid()
{
    const int cells = 16, cell = 28, jitter = 6;
    const int origin = (kCanvas.width - cells * cell) / 2;
    cv::RNG rng(20240611);  // fixed seed: the same picture every run

    MeshScene m;
    m.verts2d.create((cells + 1) * (cells + 1), 2, CV_32F);
    for (int r = 0; r <= cells; ++r) {
        for (int c = 0; c <= cells; ++c) {
            const int dx = (c == 0 || c == cells) ? 0 : rng.uniform(-jitter, jitter + 1);
            const int dy = (r == 0 || r == cells) ? 0 : rng.uniform(-jitter, jitter + 1);
            m.verts2d.at<float>(r * (cells + 1) + c, 0) = static_cast<float>(origin + c * cell + dx);
            m.verts2d.at<float>(r * (cells + 1) + c, 1) = static_cast<float>(origin + r * cell + dy);
        }
    }
    std::vector<cv::Vec3i> faces;
    for (int r = 0; r < cells; ++r) {
        for (int c = 0; c < cells; ++c) {
            const int a = r * (cells + 1) + c, b = a + 1, d = a + cells + 1, e = d + 1;
            const bool otherDiagonal = rng.uniform(0, 2) == 1;
            cv::Vec3i t0 = otherDiagonal ? cv::Vec3i(a, b, d) : cv::Vec3i(a, b, e);
            cv::Vec3i t1 = otherDiagonal ? cv::Vec3i(b, e, d) : cv::Vec3i(a, e, d);
            for (cv::Vec3i* t : {&t0, &t1}) {
                if (rng.uniform(0, 2) == 1)
                    std::swap((*t)[1], (*t)[2]);
                faces.push_back(*t);
            }
        }
    }
    m.faces = cv::Mat(faces, true).reshape(1);
    m.vcolors = cv::Mat(m.verts2d.rows, 3, CV_32F, cv::Scalar(1));
    return m;
}

// The faces of the built-in scene that face the eye: clockwise on screen (see makeDemoScene).
// Without back faces the tube is a single layer except where the knot passes over itself.
MeshScene frontFaces(MeshScene m)
{
    const auto vertex = [&m](int v) {
        return cv::Point2f(m.verts2d.at<float>(v, 0), m.verts2d.at<float>(v, 1));
    };
    std::vector<cv::Vec3i> kept;
    for (int f = 0; f < m.faces.rows; ++f) {
        const int* t = m.faces.ptr<int>(f);
        const cv::Point2f a = vertex(t[0]), b = vertex(t[1]), c = vertex(t[2]);
        if ((b - a).cross(c - a) < 0)
            kept.emplace_back(t[0], t[1], t[2]);
    }
    m.faces = cv::Mat(kept, true).reshape(1);
    return m;
}

// The pixels a triangle may touch: its bounding box (sample points are integer), clipped.
cv::Rect pixelBounds(const cv::Point2f p[3])
{
    const float x0 = std::min({p[0].x, p[1].x, p[2].x}), x1 = std::max({p[0].x, p[1].x, p[2].x});
    const float y0 = std::min({p[0].y, p[1].y, p[2].y}), y1 = std::max({p[0].y, p[1].y, p[2].y});
    if (!(x0 <= kCanvas.width && y0 <= kCanvas.height && x1 >= 0 && y1 >= 0))
        return {};  // off the canvas (or NaN)
    const cv::Point lo(static_cast<int>(std::floor(std::max(x0, 0.f))),
                       static_cast<int>(std::floor(std::max(y0, 0.f))));
    const cv::Point hi(static_cast<int>(std::ceil(std::min(x1, float(kCanvas.width)))) + 1,
                       static_cast<int>(std::ceil(std::min(y1, float(kCanvas.height)))) + 1);
    return cv::Rect(lo, hi) & cv::Rect(cv::Point(), kCanvas);
}

// Adds what one triangle painted into the scratch image (channel 0 of its box) to the count,
// then clears the box for the next triangle. Touching only the box keeps this O(triangle area);
// anything written outside the boxes is left behind and reported at the end.
void accumulate(cv::Mat& count, cv::Mat& scratch, const cv::Rect& box)
{
    cv::Mat painted, roi = count(box);
    cv::extractChannel(scratch(box), painted, 0);
    cv::add(roi, painted, roi, cv::noArray(), CV_16U);
    scratch(box).setTo(cv::Scalar::all(0));
}

struct PaintCounts {
    cv::Mat opencv, shading;           // CV_16U: times each pixel was painted
    int opencvStray = 0, shadingStray = 0;  // pixels written outside a triangle's bounding box
};

PaintCounts countPaints(const MeshScene& mesh)
{
    // Whole-pixel vertices go to fillConvexPoly as they are (what users do); fractional ones
    // in 24.8 fixed point (shift = 8), the same 1/256 grid opencv_shading snaps to.
    cv::Mat ptsF = mesh.verts2d.reshape(1);
    bool integral = true;
    for (int i = 0; i < ptsF.rows && integral; ++i)
        integral = ptsF.at<float>(i, 0) == std::round(ptsF.at<float>(i, 0)) &&
                   ptsF.at<float>(i, 1) == std::round(ptsF.at<float>(i, 1));
    const int shift = integral ? 0 : 8;

    PaintCounts pc;
    pc.opencv = cv::Mat::zeros(kCanvas, CV_16U);
    pc.shading = cv::Mat::zeros(kCanvas, CV_16U);
    cv::Mat ocvScratch = cv::Mat::zeros(kCanvas, CV_8U);
    cv::Mat libScratch = cv::Mat::zeros(kCanvas, CV_8UC3);
    // Paint value 1 (an 8-bit canvas takes colours in [0, 255] units), once per vertex.
    const std::vector<cv::Vec3f> ones(3, cv::Vec3f(1, 1, 1));

    for (int f = 0; f < mesh.faces.rows; ++f) {
        cv::Point2f tri[3];
        cv::Point fixedPt[3];
        for (int k = 0; k < 3; ++k) {
            const int v = mesh.faces.at<int>(f, k);
            tri[k] = {ptsF.at<float>(v, 0), ptsF.at<float>(v, 1)};
            fixedPt[k] = {static_cast<int>(std::lround(tri[k].x * (1 << shift))),
                          static_cast<int>(std::lround(tri[k].y * (1 << shift)))};
        }
        const cv::Rect box = pixelBounds(tri);
        if (box.empty())
            continue;

        cv::fillConvexPoly(ocvScratch, fixedPt, 3, cv::Scalar(1), cv::LINE_8, shift);
        accumulate(pc.opencv, ocvScratch, box);

        cv::shading::flats(libScratch, std::vector<cv::Point2f>(tri, tri + 3), ones);
        accumulate(pc.shading, libScratch, box);
    }
    pc.opencvStray = cv::countNonZero(ocvScratch);
    pc.shadingStray = cv::countNonZero(libScratch.reshape(1));
    return pc;
}

// The picture: one colour per kind of pixel (see the header comment), on dark grey.
cv::Mat coveragePicture(const PaintCounts& pc)
{
    const cv::Mat o = pc.opencv, s = pc.shading;
    cv::Mat pic(kCanvas, CV_32FC3, cv::Scalar::all(0.12));  // RGB
    pic.setTo(cv::Scalar(0.85, 0.1, 0.1), (o > 0) & (s == 0));
    pic.setTo(cv::Scalar(0.2, 0.35, 1.0), (o == 0) & (s > 0));
    pic.setTo(cv::Scalar(0.2, 0.7, 0.25), (o > 0) & (s > 0));
    pic.setTo(cv::Scalar(1.0, 0.9, 0.1), o > 1);
    pic.setTo(cv::Scalar(1.0, 0.2, 1.0), s > 1);
    pic.setTo(cv::Scalar::all(1.0), (o > 1) & (s > 1));

    // A legend in the bottom margin, each word in its own colour.
    const struct { const char* text; cv::Scalar rgb; } legend[] = {
        {"both", {0.2, 0.7, 0.25}},       {"OpenCV only", {0.85, 0.1, 0.1}},
        {"shading only", {0.2, 0.35, 1.0}}, {"OpenCV 2+", {1.0, 0.9, 0.1}},
        {"shading 2+", {1.0, 0.2, 1.0}}};
    int x = 8;
    for (const auto& item : legend) {
        cv::putText(pic, item.text, {x, kCanvas.height - 8}, cv::FONT_HERSHEY_SIMPLEX, 0.42,
                    item.rgb, 1, cv::LINE_AA);
        int baseline = 0;
        x += cv::getTextSize(item.text, cv::FONT_HERSHEY_SIMPLEX, 0.42, 1, &baseline).width + 14;
    }
    return pic;
}

}  // namespace

int main(int argc, char** argv)
{
    const std::string name = "fillpoly_coverage";
    const std::string extraUsage = " [--scene]\n  default mesh: a 16x16 jittered integer grid;"
                                   " --scene: the built-in torus knot";
    try {
        const auto opt = shading_samples::parseDemoOptions(argc, argv, name + ".png", {"--scene"});
        if (opt.help) {
            std::cout << shading_samples::usage(name, extraUsage);
            return 0;
        }
        const bool scene = shading_samples::hasFlag(opt, "--scene");
        const MeshScene mesh = !opt.input.empty() ? shading_samples::loadScene(opt.input)
                               : scene            ? frontFaces(shading_samples::makeDemoScene(kCanvas))
                                                  : makeJitteredGrid();
        std::cout << "mesh: "
                  << (!opt.input.empty() ? opt.input
                      : scene            ? std::string("built-in torus knot, front faces")
                                         : std::string("16x16 jittered integer grid (closed, mixed winding)"))
                  << ", " << mesh.faces.rows << " triangles\n";

        const PaintCounts pc = countPaints(mesh);
        const cv::Mat o = pc.opencv, s = pc.shading;
        std::cout << "pixels covered by both:                       " << cv::countNonZero((o > 0) & (s > 0)) << '\n'
                  << "pixels covered by OpenCV only:                " << cv::countNonZero((o > 0) & (s == 0)) << '\n'
                  << "pixels covered by opencv_shading only:        " << cv::countNonZero((o == 0) & (s > 0)) << '\n'
                  << "pixels OpenCV paints more than once:          " << cv::countNonZero(o > 1) << '\n'
                  << "pixels opencv_shading paints more than once:  " << cv::countNonZero(s > 1) << '\n';
        if (pc.opencvStray != 0 || pc.shadingStray != 0)
            std::cout << "pixels written outside their triangle's box:  OpenCV " << pc.opencvStray
                      << ", opencv_shading " << pc.shadingStray << '\n';

        return shading_samples::saveOrShow(name, coveragePicture(pc), opt.out, opt.gui) ? 0 : 1;
    } catch (const std::invalid_argument& e) {
        std::cerr << name << ": " << e.what() << '\n' << shading_samples::usage(name, extraUsage);
        return 2;
    } catch (const std::exception& e) {
        std::cerr << name << ": " << e.what() << '\n';
        return 1;
    }
}
