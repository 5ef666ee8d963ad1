// This file is part of opencv_shading. License: Apache-2.0.
//
// demo_lighting: the 3D API. A mesh is framed with cv::shading::lookAt, lit by three coloured
// point lights (a white key light upper left, a red fill from the right, a blue one from below
// left) and drawn with cv::shading::drawMesh3d (z-buffer, back faces culled) three times: flat,
// Gouraud and Phong shading side by side, each render timed.
//
//   ./demo_lighting                         built-in torus knot -> demo_lighting.png (+ a window)
//   ./demo_lighting mesh.yml --out a.png    your mesh (verts3d, faces, vcolors, [normals])
//   ./demo_lighting --no-gui                only write the PNG (or set OPENCV_SHADING_NO_GUI=1)
#include <opencv2/shading.hpp>

#include "demo_scene.hpp"

#include <iomanip>
#include <iostream>
#include <string>
#include <vector>

namespace {

namespace sh = cv::shading;

const char* const kUsage =
    "usage: demo_lighting [MESH.yml|MESH.json] [--out FILE.png] [--no-gui]\n"
    "  MESH: OpenCV FileStorage file with verts3d, faces, vcolors and optionally normals\n"
    "  (default: the built-in torus knot)\n";

const cv::Size kPanel(512, 512);
const cv::Scalar kBackground(0.08, 0.08, 0.10);  // RGB: dark, so the coloured lights show

// A camera looking at a mesh, and the view's axes in world coordinates (to place the lights).
struct View {
    cv::Matx33d K;
    cv::Mat rvec, tvec;
    cv::Point3d centre;           // the bounding box's centre
    double radius = 0;            // the farthest vertex from it
    cv::Vec3d right, up, back;    // image right, image up, towards the eye
};

// Puts the eye on a ray from the mesh's centre (direction `from`, world +y up in the image), far
// enough for a mild perspective, with the focal length that fits the bounding sphere in 90% of
// a panel.
View frameMesh(const cv::Mat& verts3d, const cv::Vec3d& from)
{
    View view;
    cv::Mat lo, hi;
    cv::reduce(verts3d, lo, 0, cv::REDUCE_MIN);
    cv::reduce(verts3d, hi, 0, cv::REDUCE_MAX);
    view.centre = cv::Point3d((cv::Vec3f(lo) + cv::Vec3f(hi)) * 0.5f);  // 1 x 3 -> Vec3f
    for (int v = 0; v < verts3d.rows; ++v) {
        const cv::Point3d p(*verts3d.ptr<cv::Vec3f>(v));
        view.radius = std::max(view.radius, cv::norm(p - view.centre));
    }
    view.back = cv::normalize(from);
    view.right = cv::normalize(cv::Vec3d(0, 1, 0).cross(view.back));
    view.up = view.back.cross(view.right);

    const double distance = 3.0 * view.radius;
    const cv::Point3d eye = view.centre + cv::Point3d(distance * view.back);
    sh::lookAt(eye, view.centre, {0, 1, 0}, view.rvec, view.tvec);
    // The sphere's silhouette has the half-angle asin(radius / distance).
    const double f = 0.45 * kPanel.width / std::tan(std::asin(view.radius / distance));
    view.K = {f, 0, (kPanel.width - 1) * 0.5, 0, f, (kPanel.height - 1) * 0.5, 0, 0, 1};
    return view;
}

// Lights placed relative to the view, so any mesh gets the same look. World position = centre +
// radius * (r right + u up + b back).
std::vector<sh::PointLight> threeLights(const View& view)
{
    const auto at = [&view](double r, double u, double b) {
        const cv::Vec3d offset = r * view.right + u * view.up + b * view.back;
        return view.centre + cv::Point3d(view.radius * offset);
    };
    return {sh::PointLight(at(-1.5, 2.0, 2.5), {0.85, 0.85, 0.85}),   // white key, upper left
            sh::PointLight(at(3.0, 0.3, 0.8), {0.75, 0.12, 0.08}),    // red fill, right
            sh::PointLight(at(-2.0, -2.0, 0.5), {0.10, 0.25, 0.90})}; // blue fill, lower left
}

void label(cv::Mat& panel, const std::string& text)
{
    cv::putText(panel, text, {16, 36}, cv::FONT_HERSHEY_SIMPLEX, 0.9, cv::Scalar::all(1.0), 2,
                cv::LINE_AA);
}

}  // namespace

int main(int argc, char** argv)
{
    const std::string name = "demo_lighting";
    try {
        const shading_samples::DemoOptions opt =
            shading_samples::parseDemoOptions(argc, argv, name + ".png");
        if (opt.help) {
            std::cout << kUsage;
            return 0;
        }
        const shading_samples::Mesh3d mesh = opt.input.empty()
                                                 ? shading_samples::makeDemoMesh3d()
                                                 : shading_samples::loadMesh3d(opt.input);
        std::cout << "mesh: " << (opt.input.empty() ? "built-in torus knot" : opt.input) << ", "
                  << mesh.verts3d.rows << " vertices, " << mesh.faces.rows << " triangles\n";

        // Seen from the front (+z), a little from the right and above.
        const View view = frameMesh(mesh.verts3d, {0.3, 0.55, 0.8});

        sh::RenderSettings settings;  // z-buffer (the default), material defaults
        settings.lights = threeLights(view);
        settings.shininess = 32;
        // The built-in knot is wound outward, so its back faces can be skipped unseen; a file's
        // winding is unknown, and the z-buffer alone hides what is behind.
        settings.cullMode = opt.input.empty() ? sh::CULL_BACK : sh::CULL_NONE;
        // Each frame starts cleared: drawMesh3d clears each band of the canvas as it draws it,
        // no pass of its own (what panel.setTo(kBackground) before the call would give).
        settings.clear = true;
        settings.background = kBackground;

        const std::vector<std::pair<int, std::string>> modes = {
            {sh::SHADE_FLAT, "flat"}, {sh::SHADE_GOURAUD, "Gouraud"}, {sh::SHADE_PHONG, "Phong"}};
        std::vector<cv::Mat> panels;
        for (const auto& [shadeType, title] : modes) {
            settings.shadeType = shadeType;
            cv::Mat panel(kPanel, CV_32FC3);
            const double ms = shading_samples::medianMs([&] {
                sh::drawMesh3d(panel, mesh.verts3d, mesh.faces, mesh.vcolors, view.K, view.rvec,
                               view.tvec, settings, mesh.normals);
            });
            std::cout << std::setw(8) << title << ": " << std::fixed << std::setprecision(2)
                      << ms << " ms (drawMesh3d with clear, median of 20 runs, "
                      << cv::getNumThreads() << " threads)\n";
            label(panel, title);  // no time on the image: the same PNG every run
            panels.push_back(panel);
        }
        cv::Mat image;
        cv::hconcat(panels, image);
        return shading_samples::saveOrShow(name, image, opt.out, opt.gui) ? 0 : 1;
    } catch (const std::invalid_argument& e) {
        std::cerr << name << ": " << e.what() << '\n' << kUsage;
        return 2;
    } catch (const std::exception& e) {  // cv::Exception included: its text says what was wrong
        std::cerr << name << ": " << e.what() << '\n';
        return 1;
    }
}
