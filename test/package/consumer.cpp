#include <opencv2/shading.hpp>

#include <cstdio>

int main()
{
    cv::Mat img;
    cv::shading::render(std::vector<cv::Point2f>{{0, 0}, {4, 0}, {0, 4}},
                        std::vector<cv::Vec3i>{{0, 1, 2}},
                        std::vector<cv::Vec3f>{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}, cv::noArray(),
                        img, cv::shading::SHADE_FLAT, cv::Size(6, 6));
    // x + y < 4 is covered (10 pixels); the rest stays white.
    int covered = 0;
    for (int y = 0; y < img.rows; y++)
        for (int x = 0; x < img.cols; x++)
            covered += img.at<cv::Vec3f>(y, x) != cv::Vec3f(1, 1, 1);
    std::printf("consumer: %d pixels covered\n", covered);
    return covered == 10 ? 0 : 1;
}
