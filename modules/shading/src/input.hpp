// This file is part of opencv_shading. License: Apache-2.0.
//
// The API edge: every InputArray form a user may pass is checked and converted here, once, into
// plain vectors. Code past this point never validates again.
#ifndef OPENCV_SHADING_INPUT_HPP
#define OPENCV_SHADING_INPUT_HPP

#include <opencv2/core.hpp>

#include <vector>

namespace cv {
namespace shading {
namespace detail {

// Each reader accepts rows of CV_32F/CV_64F/CV_32S values (see the public header for the forms)
// and fills `out` (reusing its capacity). `expectedCount` < 0 accepts any count. Errors name
// `argName` and say what was expected and given.
void readPoints(InputArray arr, const char* argName, int expectedCount, std::vector<Point2d>& out);
void readColors(InputArray arr, const char* argName, int expectedCount, std::vector<Vec3d>& out);
//! Faces as zero-based index triples, each checked against [0, vertexCount).
void readFaces(InputArray arr, const char* argName, int vertexCount, std::vector<Vec3i>& out);
//! Depths: `expectedCount` values, or none when `arr` is empty.
void readDepths(InputArray arr, const char* argName, int expectedCount, std::vector<double>& out);

//! Checks that `canvas` is a non-empty CV_32FC3 or CV_8UC3 image.
void checkCanvas(InputOutputArray canvas, const char* argName);
void checkShadeType(int shadeType);

}  // namespace detail
}  // namespace shading
}  // namespace cv

#endif  // OPENCV_SHADING_INPUT_HPP
