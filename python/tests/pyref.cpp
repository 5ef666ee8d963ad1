// This file is part of opencv_shading. License: Apache-2.0.
// Test helper for python/tests: renders a scene read from a FileStorage file (written by the
// tests with cv2.FileStorage) through the C++ API and writes the result, so the bindings are
// compared with the library called directly, not with themselves.
//   opencv_shading_pyref <in.yml> <out.yml>
// in.yml: op ("render", "drawMesh", "drawMesh3d") and the op's arguments by their C++ names;
// out.yml: img (and depth, faceIds for drawMesh3d).
#include <opencv2/shading.hpp>

#include <iostream>

namespace {

cv::Mat readMat(const cv::FileStorage& fs, const char* name) {
    cv::Mat m;
    if (!fs[name].empty())
        fs[name] >> m;
    return m;
}

int readInt(const cv::FileStorage& fs, const char* name, int def) {
    return fs[name].empty() ? def : static_cast<int>(fs[name]);
}

double readDouble(const cv::FileStorage& fs, const char* name, double def) {
    return fs[name].empty() ? def : static_cast<double>(fs[name]);
}

}  // namespace

int main(int argc, char** argv) {
    if (argc != 3) {
        std::cerr << "usage: opencv_shading_pyref in.yml out.yml\n";
        return 2;
    }
    try {
        cv::FileStorage in(argv[1], cv::FileStorage::READ);
        const std::string op = static_cast<std::string>(in["op"]);
        cv::FileStorage out(argv[2], cv::FileStorage::WRITE);
        const int shadeType = readInt(in, "shadeType", cv::shading::SHADE_GOURAUD);
        if (op == "render") {
            cv::Mat img;
            cv::Mat bg = readMat(in, "background");
            cv::Scalar background = cv::Scalar::all(1);
            for (int i = 0; i < static_cast<int>(bg.total()) && i < 4; ++i)
                background[i] = bg.at<double>(i);
            cv::shading::render(readMat(in, "verts2d"), readMat(in, "faces"),
                                readMat(in, "vcolors"), readMat(in, "depth"), img, shadeType,
                                cv::Size(readInt(in, "width", 512), readInt(in, "height", 512)),
                                background);
            out << "img" << img;
        } else if (op == "drawMesh") {
            cv::Mat canvas = readMat(in, "canvas");
            cv::shading::drawMesh(canvas, readMat(in, "verts2d"), readMat(in, "faces"),
                                  readMat(in, "vcolors"), readMat(in, "depth"), shadeType);
            out << "img" << canvas;
        } else if (op == "drawMesh3d") {
            cv::shading::RenderSettings s;
            s.shadeType = shadeType;
            s.visibility = readInt(in, "visibility", s.visibility);
            s.cullMode = readInt(in, "cullMode", s.cullMode);
            s.zNear = readDouble(in, "zNear", s.zNear);
            s.ka = readDouble(in, "ka", s.ka);
            s.kd = readDouble(in, "kd", s.kd);
            s.ks = readDouble(in, "ks", s.ks);
            s.shininess = readDouble(in, "shininess", s.shininess);
            cv::Mat lights = readMat(in, "lights");  // N x 6 float64: position, intensity
            for (int i = 0; i < lights.rows; ++i) {
                const double* l = lights.ptr<double>(i);
                s.lights.emplace_back(cv::Point3d(l[0], l[1], l[2]), cv::Vec3d(l[3], l[4], l[5]));
            }
            cv::Mat canvas = readMat(in, "canvas"), depth, faceIds;
            cv::shading::drawMesh3d(canvas, readMat(in, "verts3d"), readMat(in, "faces"),
                                    readMat(in, "vcolors"), readMat(in, "cameraMatrix"),
                                    readMat(in, "rvec"), readMat(in, "tvec"), s,
                                    readMat(in, "normals"), depth, faceIds);
            out << "img" << canvas << "depth" << depth << "faceIds" << faceIds;
        } else {
            std::cerr << "unknown op '" << op << "'\n";
            return 2;
        }
    } catch (const cv::Exception& e) {
        std::cerr << e.what() << "\n";
        return 1;
    }
    return 0;
}
