// Bad input: every rejected argument raises cv::Exception whose message names the argument and
// what was expected, and the canvas (or render's output) is left untouched.
#include "test_common.hpp"

#include <gtest/gtest.h>
#include <opencv2/shading.hpp>

#include <climits>
#include <functional>
#include <string>

using namespace cv;

namespace {

const std::vector<Point2f> kTri = {{1, 1}, {8, 2}, {3, 9}};
const std::vector<Vec3f> kColors = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
const std::vector<Point2f> kVerts = {{1, 1}, {8, 2}, {3, 9}, {9, 9}};
const std::vector<Vec3i> kFaces = {{0, 1, 2}, {1, 3, 2}};
const std::vector<Vec3f> kMeshColors = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 1, 1}};
const std::vector<float> kDepth = {1, 2, 3, 4};

struct BadCall {
    const char* what;
    std::function<void(Mat&)> call;  // draws into the canvas it is given
    std::vector<std::string> messageParts;
};

void expectRejected(const BadCall& bad, Mat canvas)
{
    const Mat before = canvas.clone();
    try {
        bad.call(canvas);
        ADD_FAILURE() << bad.what << ": no exception";
    } catch (const cv::Exception& e) {
        for (const std::string& part : bad.messageParts) {
            EXPECT_NE(e.err.find(part), std::string::npos)
                << bad.what << ": message \"" << e.err << "\" lacks \"" << part << "\"";
        }
    }
    if (!before.empty()) {
        EXPECT_EQ(shading_test::maxAbsDiff(canvas, before), 0.0) << bad.what << ": canvas changed";
    }
}

}  // namespace

TEST(ShadingErrors, TriangleFunctionsRejectBadArguments)
{
    Mat m3x3 = Mat::ones(3, 3, CV_32F), m8u(3, 2, CV_8U, Scalar(1)), m2x2 = Mat::ones(2, 2, CV_32F);
    const std::vector<Point2f> two = {{1, 1}, {2, 2}}, four = {{1, 1}, {2, 2}, {3, 1}, {0, 0}};
    const std::vector<BadCall> calls = {
        {"2 vertices", [&](Mat& c) { shading::flats(c, two, kColors); }, {"vertices", "expected 3", "got 2"}},
        {"4 vertices", [&](Mat& c) { shading::gouraud(c, four, kColors); }, {"vertices", "expected 3", "got 4"}},
        {"3x3 vertices", [&](Mat& c) { shading::flats(c, m3x3, kColors); }, {"vertices", "N x 2", "3x3"}},
        {"8-bit vertices", [&](Mat& c) { shading::flats(c, m8u, kColors); }, {"vertices", "CV_32F, CV_64F or CV_32S", "CV_8U"}},
        {"2 colours", [&](Mat& c) { shading::flats(c, kTri, std::vector<Vec3f>(2)); }, {"vcolors", "expected 3", "got 2"}},
        {"2x2 colours", [&](Mat& c) { shading::gouraud(c, kTri, m2x2); }, {"vcolors", "N x 3"}},
    };
    for (const BadCall& bad : calls)
        expectRejected(bad, Mat(10, 10, CV_32FC3, Scalar::all(-1)));
}

TEST(ShadingErrors, CanvasMustBeNonEmptyFloatOrByteRgb)
{
    for (int type : {CV_8UC1, CV_32FC1, CV_64FC3, CV_16UC3, CV_8UC4, CV_32FC4}) {
        const std::string name = typeToString(type);
        expectRejected({name.c_str(), [&](Mat& c) { shading::flats(c, kTri, kColors); },
                        {"canvas", "CV_32FC3 or CV_8UC3", name}},
                       Mat(10, 10, type, Scalar::all(3)));
        expectRejected({name.c_str(), [&](Mat& c) {
                            shading::drawMesh(c, kVerts, kFaces, kMeshColors, kDepth);
                        }, {"canvas", "CV_32FC3 or CV_8UC3", name}},
                       Mat(10, 10, type, Scalar::all(3)));
    }
    expectRejected({"empty canvas", [&](Mat& c) { shading::gouraud(c, kTri, kColors); },
                    {"canvas", "empty"}}, Mat());
}

TEST(ShadingErrors, MeshFunctionsRejectBadArguments)
{
    const std::vector<Vec3i> negative = {{0, 1, 2}, {1, -1, 2}}, tooBig = {{0, 1, 4}};
    Mat fractional = (Mat_<float>(1, 3) << 0, 1, 2.5f);
    Mat facesKx2 = (Mat_<int>(2, 2) << 0, 1, 1, 2);
    const std::vector<BadCall> calls = {
        {"negative index", [&](Mat& c) { shading::drawMesh(c, kVerts, negative, kMeshColors, kDepth); },
         {"faces", "face 1", "-1", "[0, 4)"}},
        {"index == L", [&](Mat& c) { shading::drawMesh(c, kVerts, tooBig, kMeshColors, kDepth); },
         {"faces", "face 0", "4", "[0, 4)"}},
        {"fractional index", [&](Mat& c) { shading::drawMesh(c, kVerts, fractional, kMeshColors, kDepth); },
         {"faces", "non-integer", "2.5"}},
        {"K x 2 faces", [&](Mat& c) { shading::drawMesh(c, kVerts, facesKx2, kMeshColors, kDepth); },
         {"faces", "N x 3", "2x2"}},
        {"colour count", [&](Mat& c) { shading::drawMesh(c, kVerts, kFaces, kColors, kDepth); },
         {"vcolors", "expected 4", "got 3"}},
        {"depth count", [&](Mat& c) { shading::drawMesh(c, kVerts, kFaces, kMeshColors, std::vector<float>(5)); },
         {"depth", "expected 4", "got 5"}},
        {"depth shape", [&](Mat& c) { shading::drawMesh(c, kVerts, kFaces, kMeshColors, Mat::ones(2, 2, CV_32F)); },
         {"depth", "N x 1 or 1 x N", "2x2"}},
        {"shadeType 2", [&](Mat& c) { shading::drawMesh(c, kVerts, kFaces, kMeshColors, kDepth, 2); },
         {"shadeType", "SHADE_FLAT", "got 2"}},
        {"shadeType -1", [&](Mat& c) { shading::drawMesh(c, kVerts, kFaces, kMeshColors, kDepth, -1); },
         {"shadeType", "got -1"}},
        {"verts2d shape", [&](Mat& c) { shading::drawMesh(c, Mat::ones(4, 3, CV_32F), kFaces, kMeshColors, kDepth); },
         {"verts2d", "N x 2", "4x3"}},
    };
    for (const BadCall& bad : calls) {
        expectRejected(bad, Mat(10, 10, CV_32FC3, Scalar::all(-1)));
        expectRejected(bad, Mat(10, 10, CV_8UC3, Scalar::all(7)));
    }
}

// The index check is vectorized: a bad index must be found in any lane, in the loop and in its
// tail, whatever its value, and with no vertices at all.
TEST(ShadingErrors, BadIndexFoundAnywhereInALongFaceList)
{
    const int faceCount = 37;  // 111 indices: SIMD blocks of 8 and a tail of 7
    std::vector<Vec3i> faces(faceCount);
    for (int i = 0; i < faceCount; i++)
        faces[i] = Vec3i(i % 4, (i + 1) % 4, (i + 2) % 4);
    for (int bad : {-1, 4, INT_MIN, INT_MAX, 1 << 30}) {
        for (int at = 0; at < 3 * faceCount; at++) {
            std::vector<Vec3i> f = faces;
            f[at / 3][at % 3] = bad;
            const std::string face = "face " + std::to_string(at / 3) + " ";
            expectRejected({"bad index", [&](Mat& c) {
                                shading::drawMesh(c, kVerts, f, kMeshColors, kDepth);
                            }, {"faces", face, std::to_string(bad), "[0, 4)"}},
                           Mat(10, 10, CV_32FC3, Scalar::all(-1)));
        }
    }
    expectRejected({"no vertices", [&](Mat& c) {
                        shading::drawMesh(c, std::vector<Point2f>(), faces, std::vector<Vec3f>(),
                                          std::vector<float>());
                    }, {"faces", "face 0 ", "[0, 0)"}},
                   Mat(10, 10, CV_32FC3, Scalar::all(-1)));
}

TEST(ShadingErrors, RenderRejectsBadArgumentsAndLeavesOutputAlone)
{
    const std::vector<Vec3i> tooBig = {{0, 1, 4}};
    const std::vector<BadCall> calls = {
        {"zero width", [&](Mat& img) { shading::render(kVerts, kFaces, kMeshColors, kDepth, img, shading::SHADE_FLAT, Size(0, 5)); },
         {"size", "positive", "0x5"}},
        {"negative height", [&](Mat& img) { shading::render(kVerts, kFaces, kMeshColors, kDepth, img, shading::SHADE_FLAT, Size(5, -1)); },
         {"size", "positive", "5x-1"}},
        {"bad shade", [&](Mat& img) { shading::render(kVerts, kFaces, kMeshColors, kDepth, img, 7); },
         {"shadeType", "got 7"}},
        {"bad face", [&](Mat& img) { shading::render(kVerts, tooBig, kMeshColors, kDepth, img); },
         {"faces", "[0, 4)"}},
    };
    for (const BadCall& bad : calls)
        expectRejected(bad, Mat(3, 4, CV_8UC1, Scalar(9)));  // output untouched, not reallocated
}
