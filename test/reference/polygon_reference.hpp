// This file is part of opencv_shading. License: Apache-2.0.
//
// polygon_ref: a brute-force reference for fillPolygons, written independently of the library.
//
// For every canvas sample (x, y) it computes the winding number of all contours around the
// nudged point P = (x + e, y + e^2), e > 0 infinitely small, exactly, and applies the fill rule.
// The library scans rows (a horizontal ray); this reference casts the *vertical* ray from P
// upward (towards smaller y) instead, so the two agree only if both get the nudge right.
//
// Derivation, with fixed-point vertices (X = llround(256 x)) and the sample at (X0, Y0) =
// (256 x, 256 y):
//  - The edge a -> b meets the vertical line through P, X = X0 + e, iff
//    min(a.X, b.X) < X0 + e < max(a.X, b.X), i.e. min <= X0 < max for integers. Vertical edges
//    (a.X == b.X) never meet it.
//  - There the edge's Y is Yc(X0) + s e with s = dY / dX its slope. It lies on the upward ray
//    (above P) iff Yc(X0) + s e < Y0 + e^2: iff Yc(X0) < Y0, or Yc(X0) == Y0 and s e < e^2,
//    i.e. s <= 0 (s < e, and s is a finite fraction).
//  - Each such crossing adds -1 when the edge goes right (a.X < b.X) and +1 when it goes left.
//    The sign convention only has to be the same for all edges: both fill rules are symmetric
//    under w -> -w.
//  - The sum over all edges of all contours with at least 3 points is w; the sample is covered
//    when w is odd (even-odd) or nonzero (nonzero).
#ifndef OPENCV_SHADING_TEST_POLYGON_REFERENCE_HPP
#define OPENCV_SHADING_TEST_POLYGON_REFERENCE_HPP

#include <opencv2/core.hpp>

#include <cmath>
#include <vector>

namespace polygon_ref {

__extension__ typedef __int128 Int128;

struct Fixed {
    long long x = 0, y = 0;
};

inline Fixed snap(const cv::Point2d& p)
{
    return Fixed{std::llround(p.x * 256.0), std::llround(p.y * 256.0)};
}

//! Contribution of the edge a -> b to the winding number around the nudged sample (X0, Y0).
inline int crossing(const Fixed& a, const Fixed& b, long long X0, long long Y0)
{
    if (a.x == b.x)
        return 0;
    const Fixed& l = a.x < b.x ? a : b;  // left end
    const Fixed& r = a.x < b.x ? b : a;
    if (!(l.x <= X0 && X0 < r.x))
        return 0;
    // Yc(X0) = l.y + (X0 - l.x) (r.y - l.y) / (r.x - l.x); compare with Y0 times (r.x - l.x) > 0.
    const Int128 lhs = Int128(l.y) * (r.x - l.x) + Int128(X0 - l.x) * (r.y - l.y);
    const Int128 rhs = Int128(Y0) * (r.x - l.x);
    const bool above = lhs < rhs || (lhs == rhs && r.y - l.y <= 0);
    if (!above)
        return 0;
    return a.x < b.x ? -1 : 1;
}

inline int winding(const std::vector<std::vector<Fixed>>& contours, int x, int y)
{
    const long long X0 = 256LL * x, Y0 = 256LL * y;
    int w = 0;
    for (const std::vector<Fixed>& c : contours) {
        if (c.size() < 3)
            continue;
        for (size_t i = 0; i < c.size(); i++)
            w += crossing(c[i], c[(i + 1) % c.size()], X0, Y0);
    }
    return w;
}

inline bool covered(int w, bool evenOdd) { return evenOdd ? (w % 2 != 0) : w != 0; }

//! CV_8U mask of the covered samples of a `size` canvas.
inline cv::Mat coverage(const std::vector<std::vector<cv::Point2d>>& polygons, cv::Size size,
                        bool evenOdd)
{
    std::vector<std::vector<Fixed>> fixed;
    for (const auto& c : polygons) {
        fixed.emplace_back();
        for (const cv::Point2d& p : c)
            fixed.back().push_back(snap(p));
    }
    cv::Mat mask(size, CV_8U, cv::Scalar(0));
    for (int y = 0; y < size.height; y++)
        for (int x = 0; x < size.width; x++)
            mask.at<uchar>(y, x) = covered(winding(fixed, x, y), evenOdd) ? 255 : 0;
    return mask;
}

//! The reference drawing: `color` (saturated to 8 bits on CV_8UC3) at the covered samples.
inline void fill(cv::Mat& canvas, const std::vector<std::vector<cv::Point2d>>& polygons,
                 const cv::Scalar& color, bool evenOdd)
{
    const cv::Mat mask = coverage(polygons, canvas.size(), evenOdd);
    canvas.setTo(color, mask);
}

}  // namespace polygon_ref

#endif
