// Coverage compared with OpenCV's own polygon filling (cv::fillConvexPoly / cv::fillPoly):
// OpenCV paints each polygon's boundary pixels too, this library applies the top-left rule. So
// everything this library covers OpenCV paints as well, OpenCV's extra pixels lie on the
// triangle's boundary (an edge passes within one pixel of them, in chessboard distance), and on a closed mesh OpenCV paints shared edges twice where this library
// paints every pixel once.
#include "test_common.hpp"

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>
#include <opencv2/shading.hpp>

#include <algorithm>
#include <cmath>

using namespace cv;

namespace {

Mat ourMask(Size size, const std::vector<Point>& tri)
{
    Mat canvas(size, CV_8UC3, Scalar::all(0));
    shading::flats(canvas, tri, std::vector<Vec3f>(3, Vec3f(1, 1, 1)));
    Mat m;
    extractChannel(canvas, m, 0);
    return m;
}

Mat openCvMask(Size size, const std::vector<Point>& tri)
{
    Mat m(size, CV_8U, Scalar(0));
    fillConvexPoly(m, tri, Scalar(1), LINE_8);
    return m;
}

// Chessboard (L-infinity) distance from p to segment ab: <= 1 means the segment passes through
// the 3 x 3 block of pixels around p. The distance along the segment is convex in the segment
// parameter, so a ternary search finds its minimum.
double chessboardDistanceToSegment(Point2d p, Point2d a, Point2d b)
{
    auto at = [&](double t) {
        const Point2d q = a + (b - a) * t;
        return std::max(std::abs(q.x - p.x), std::abs(q.y - p.y));
    };
    double lo = 0, hi = 1;
    for (int i = 0; i < 100; i++) {
        const double m1 = lo + (hi - lo) / 3, m2 = hi - (hi - lo) / 3;
        if (at(m1) < at(m2))
            hi = m2;
        else
            lo = m1;
    }
    return at((lo + hi) / 2);
}

}  // namespace

// Vertices stay on the canvas: OpenCV clips edges with off-canvas vertices approximately (its
// boundary then strays more than a pixel from the true edge), which is OpenCV's matter, not ours.
TEST(ShadingVsFillPoly, RandomIntegerTrianglesDifferOnlyOnTheBoundary)
{
    const Size size(64, 64);
    RNG rng(2024);
    int64 ours = 0, extraOpenCv = 0;
    for (int n = 0; n < 2000; n++) {
        std::vector<Point> tri(3);
        for (Point& p : tri)
            p = Point(rng.uniform(0, 64), rng.uniform(0, 64));
        const Mat m = ourMask(size, tri), p = openCvMask(size, tri);
        ours += countNonZero(m);
        ASSERT_EQ(countNonZero(m & ~p), 0) << "triangle " << n << " covers pixels OpenCV does not";
        const Mat extra = p & ~m;
        for (int y = 0; y < size.height; y++)
            for (int x = 0; x < size.width; x++) {
                if (!extra.at<uchar>(y, x))
                    continue;
                extraOpenCv++;
                double d = 1e9;
                for (int k = 0; k < 3; k++)
                    d = std::min(d, chessboardDistanceToSegment(Point2d(x, y), tri[k], tri[(k + 1) % 3]));
                ASSERT_LE(d, 1.0 + 1e-9) << "OpenCV-only pixel (" << x << "," << y << ") is off the boundary"
                                  << " of triangle " << n;
            }
    }
    EXPECT_GT(ours, 0);
    EXPECT_GT(extraOpenCv, 0);  // OpenCV's boundary pixels really exist
    RecordProperty("pixels_covered_by_both", std::to_string(ours));
    RecordProperty("pixels_painted_by_opencv_only", std::to_string(extraOpenCv));
}

// A closed integer mesh: a 12 x 12 grid of jittered cells over the whole canvas, two triangles
// per cell. This library covers every pixel once; cv::fillPoly per triangle paints the shared
// edges more than once.
TEST(ShadingVsFillPoly, ClosedMeshSeamsPaintedOnceHereTwiceByOpenCv)
{
    const Size size(96, 96);
    const int n = 12;
    RNG rng(11);
    std::vector<Point> verts;
    for (int j = 0; j <= n; j++)
        for (int i = 0; i <= n; i++) {
            Point p(i * size.width / n, j * size.height / n);
            if (i > 0 && i < n && j > 0 && j < n)
                p += Point(rng.uniform(-1, 2), rng.uniform(-1, 2));
            verts.push_back(p);
        }
    Mat ourCount(size, CV_32S, Scalar(0)), cvCount(size, CV_32S, Scalar(0));
    for (int j = 0; j < n; j++)
        for (int i = 0; i < n; i++) {
            const int a = j * (n + 1) + i, b = a + 1, c = a + n + 1, d = c + 1;
            for (const std::vector<Point>& tri : {std::vector<Point>{verts[a], verts[b], verts[d]},
                                                  std::vector<Point>{verts[a], verts[d], verts[c]}}) {
                Mat m32;
                ourMask(size, tri).convertTo(m32, CV_32S);
                ourCount += m32;
                Mat p(size, CV_8U, Scalar(0));
                const Point* pts = tri.data();
                const int npts = 3;
                fillPoly(p, &pts, &npts, 1, Scalar(1), LINE_8);
                p.convertTo(m32, CV_32S);
                cvCount += m32;
            }
        }
    // The mesh covers [0, 96) x [0, 96) minus the right column x = 96 and bottom row y = 96,
    // which lie outside the canvas: every canvas sample is covered by exactly one triangle.
    double lo, hi;
    minMaxLoc(ourCount, &lo, &hi);
    EXPECT_EQ(lo, 1.0);
    EXPECT_EQ(hi, 1.0);
    const int cvTwice = countNonZero(cvCount > 1), cvMissed = countNonZero(cvCount == 0);
    EXPECT_GT(cvTwice, 96 * 12) << "OpenCV should paint the shared edges more than once";
    EXPECT_EQ(cvMissed, 0);
    RecordProperty("opencv_pixels_painted_more_than_once", std::to_string(cvTwice));
    RecordProperty("opencv_shading_pixels_painted_more_than_once",
                   std::to_string(countNonZero(ourCount > 1)));
}
