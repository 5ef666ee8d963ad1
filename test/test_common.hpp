// Small helpers shared by the test files (not part of the library).
#ifndef OPENCV_SHADING_TEST_COMMON_HPP
#define OPENCV_SHADING_TEST_COMMON_HPP

#include <opencv2/core.hpp>
#include <opencv2/shading.hpp>

#include <cstdlib>
#include <set>
#include <utility>
#include <vector>

namespace shading_test {

//! A sentinel no test colour uses, so "written" is simply "differs from the sentinel".
inline cv::Mat sentinelCanvas(cv::Size size, int type = CV_32FC3)
{
    return cv::Mat(size, type, type == CV_8UC3 ? cv::Scalar(7, 7, 7) : cv::Scalar::all(-1));
}

inline double maxAbsDiff(const cv::Mat& a, const cv::Mat& b)
{
    return cv::norm(a, b, cv::NORM_INF);
}

//! CV_8U mask of the pixels of `canvas` that differ from `untouched`.
inline cv::Mat writtenMask(const cv::Mat& canvas, const cv::Mat& untouched)
{
    cv::Mat diff;
    cv::compare(canvas.reshape(1), untouched.reshape(1), diff, cv::CMP_NE);
    diff = diff.reshape(3);
    std::vector<cv::Mat> ch;
    cv::split(diff, ch);
    cv::Mat any = ch[0] | ch[1] | ch[2];
    return any;
}

//! Set of (x, y) written by drawing one flat triangle with a colour unlike the sentinel.
inline std::set<std::pair<int, int>> flatCoverage(cv::Size size, const std::vector<cv::Point2d>& v)
{
    cv::Mat canvas = sentinelCanvas(size), before = canvas.clone();
    const std::vector<cv::Vec3f> colors(3, cv::Vec3f(0.5f, 0.25f, 0.75f));
    cv::shading::flats(canvas, v, colors);
    const cv::Mat mask = writtenMask(canvas, before);
    std::set<std::pair<int, int>> covered;
    for (int y = 0; y < mask.rows; y++)
        for (int x = 0; x < mask.cols; x++)
            if (mask.at<uchar>(y, x))
                covered.insert({x, y});
    return covered;
}

/** While alive (with `on`), mesh draws draw every band in parts (a quarter and three, two
halves, or four quarters), as threads share the bands where they are few
(OPENCV_SHADING_SPLIT_BANDS). */
class SplitBands {
public:
    explicit SplitBands(bool on) : on_(on)
    {
        if (on_)
            setenv("OPENCV_SHADING_SPLIT_BANDS", "1", 1);
    }
    ~SplitBands()
    {
        if (on_)
            unsetenv("OPENCV_SHADING_SPLIT_BANDS");
    }
    SplitBands(const SplitBands&) = delete;
    SplitBands& operator=(const SplitBands&) = delete;

private:
    bool on_;
};

}  // namespace shading_test

#endif
