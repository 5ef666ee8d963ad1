// This file is part of opencv_shading. License: Apache-2.0.
//
// The opencv_shading program (apps/), run as a user would: outputs and exit statuses.
// OPENCV_SHADING_APP is the program's path (set by test/CMakeLists.txt).
#include <gtest/gtest.h>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include <sys/wait.h>
#include <unistd.h>

namespace {

namespace fs = std::filesystem;

class Cli : public ::testing::Test {
protected:
    void SetUp() override
    {
        const ::testing::TestInfo* info = ::testing::UnitTest::GetInstance()->current_test_info();
        dir_ = fs::temp_directory_path() /
               ("opencv_shading_cli_" + std::string(info->name()) + "_" + std::to_string(getpid()));
        fs::remove_all(dir_);
        fs::create_directories(dir_);
    }
    void TearDown() override { fs::remove_all(dir_); }

    std::string path(const std::string& name) const { return (dir_ / name).string(); }

    //! Runs the program with `args` (each quoted); returns its exit status, keeps its output.
    int run(const std::vector<std::string>& args)
    {
        std::string cmd = std::string("'") + OPENCV_SHADING_APP + "'";
        for (const std::string& a : args)
            cmd += " '" + a + "'";
        cmd += " >'" + path("stdout.txt") + "' 2>'" + path("stderr.txt") + "'";
        const int status = std::system(cmd.c_str());
        out_ = read(path("stdout.txt"));
        err_ = read(path("stderr.txt"));
        return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    }

    static std::string read(const std::string& file)
    {
        std::ifstream f(file);
        std::stringstream s;
        s << f.rdbuf();
        return s.str();
    }

    //! A unit cube as 6 quads: a mesh file loadMesh reads.
    std::string writeCube() const
    {
        const std::string file = path("cube.obj");
        std::ofstream(file) << "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
                               "v 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n"
                               "f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\nf 4 1 5 8\n";
        return file;
    }

    fs::path dir_;
    std::string out_, err_;
};

// The default background, RGB (0.13, 0.14, 0.16), as the BGR bytes imwrite stores.
const cv::Vec3b kBackground(41, 36, 33);

TEST_F(Cli, DemoWritesImageOfRequestedSize)
{
    const std::string png = path("demo.png");
    ASSERT_EQ(run({"demo", "-o", png, "--size", "320x200"}), 0) << err_;
    const cv::Mat img = cv::imread(png, cv::IMREAD_UNCHANGED);
    ASSERT_FALSE(img.empty());
    EXPECT_EQ(img.size(), cv::Size(320, 200));
    EXPECT_EQ(img.type(), CV_8UC3);
    EXPECT_EQ(img.at<cv::Vec3b>(0, 0), kBackground);
    EXPECT_EQ(img.at<cv::Vec3b>(199, 319), kBackground);
    int drawn = 0;
    for (int y = 0; y < img.rows; y++)
        for (int x = 0; x < img.cols; x++)
            drawn += img.at<cv::Vec3b>(y, x) != kBackground;
    EXPECT_GT(drawn, img.total() / 10) << "the knot should fill a good part of the frame";
    EXPECT_NE(out_.find("10000 triangles"), std::string::npos) << out_;
}

TEST_F(Cli, MeshFileWithDepthAndIds)
{
    const std::string cube = writeCube(), png = path("cube.png"), depth = path("depth.png"),
                      ids = path("ids.png");
    ASSERT_EQ(run({cube, "-o", png, "--size", "160x120", "--depth", depth, "--ids", ids,
                   "--shade", "flat", "--cull", "back"}),
              0)
        << err_;
    const cv::Mat img = cv::imread(png), d = cv::imread(depth, cv::IMREAD_UNCHANGED),
                  f = cv::imread(ids, cv::IMREAD_UNCHANGED);
    ASSERT_EQ(img.size(), cv::Size(160, 120));
    ASSERT_EQ(d.size(), img.size());
    ASSERT_EQ(f.size(), img.size());
    EXPECT_EQ(d.type(), CV_16UC1);
    EXPECT_EQ(f.type(), CV_16UC1);
    // Depth and ids are nonzero exactly where the cube is drawn, background 0.
    int drawn = 0;
    for (int y = 0; y < img.rows; y++)
        for (int x = 0; x < img.cols; x++) {
            const bool covered = img.at<cv::Vec3b>(y, x) != kBackground;
            drawn += covered;
            EXPECT_EQ(d.at<ushort>(y, x) != 0, covered) << "(" << x << ", " << y << ")";
            EXPECT_EQ(f.at<ushort>(y, x) != 0, covered) << "(" << x << ", " << y << ")";
            EXPECT_LE(f.at<ushort>(y, x), 12);  // 6 quads: 12 triangles, ids 1..12
        }
    EXPECT_GT(drawn, 1000);
    double lo = 0, hi = 0;
    cv::minMaxLoc(d, &lo, &hi, nullptr, nullptr, d > 0);
    EXPECT_EQ(lo, 1);  // the visible depths span 1..65535
    EXPECT_EQ(hi, 65535);
}

TEST_F(Cli, DepthExrIsFloatCameraZ)
{
    const std::string cube = writeCube(), depth = path("depth.exr");
    const int rc = run({cube, "-o", path("cube.png"), "--size", "80x60", "--depth", depth});
    if (rc != 0) {  // an OpenCV built without OpenEXR: a clear error, no crash
        EXPECT_EQ(rc, 1);
        EXPECT_NE(err_.find("exr"), std::string::npos) << err_;
        return;
    }
    setenv("OPENCV_IO_ENABLE_OPENEXR", "1", 0);  // reading EXR is opt-in in OpenCV 4.x too
    const cv::Mat d = cv::imread(depth, cv::IMREAD_UNCHANGED);
    ASSERT_EQ(d.type(), CV_32FC1);
    ASSERT_EQ(d.size(), cv::Size(80, 60));
    EXPECT_EQ(d.at<float>(0, 0), std::numeric_limits<float>::infinity());
    const float centre = d.at<float>(30, 40);
    EXPECT_TRUE(centre > 0 && centre < 100) << centre;  // the cube's near side, a few units away
}

TEST_F(Cli, TurntableWritesNumberedFrames)
{
    const std::string pattern = path("frame_%03d.png");
    ASSERT_EQ(run({"--demo", "--turntable", "3", "--video", pattern, "--size", "64x48"}), 0)
        << err_;
    std::vector<cv::Mat> frames;
    for (const char* name : {"frame_000.png", "frame_001.png", "frame_002.png"}) {
        frames.push_back(cv::imread(path(name)));
        ASSERT_EQ(frames.back().size(), cv::Size(64, 48)) << name;
    }
    EXPECT_FALSE(fs::exists(path("frame_003.png")));
    EXPECT_GT(cv::norm(frames[0], frames[1], cv::NORM_L1), 0) << "the views should differ";
    EXPECT_NE(out_.find("3 turntable frames"), std::string::npos) << out_;
}

TEST_F(Cli, TurntableVideoOrAClearError)
{
    const std::string video = path("turn.mp4");
    const int rc = run({"demo", "--turntable", "4", "--video", video, "--size", "64x48"});
    if (rc == 0)
        EXPECT_GT(fs::file_size(video), 0u);
    else {  // OpenCV without an mp4v encoder: says so
        EXPECT_EQ(rc, 1);
        EXPECT_NE(err_.find("mp4v"), std::string::npos) << err_;
    }
}

TEST_F(Cli, HelpExitsZero)
{
    EXPECT_EQ(run({"--help"}), 0);
    EXPECT_NE(out_.find("usage: opencv_shading"), std::string::npos);
    EXPECT_NE(out_.find("--turntable"), std::string::npos);
}

TEST_F(Cli, BadArgumentsExitTwoWithUsage)
{
    const std::vector<std::vector<std::string>> bad = {
        {"demo", "--frobnicate"},
        {"demo", "--size", "640"},
        {"demo", "--size", "0x480"},
        {"demo", "--size", "640x"},
        {"demo", "--light", "1,2,3"},
        {"demo", "--light", "1,2,x,1,1,1"},
        {"demo", "--light", "1,2,3,1,1,1,1"},
        {"demo", "--background", "2,0,0"},
        {"demo", "--shade", "toon"},
        {"demo", "--cull", "sideways"},
        {"demo", "--depth", "depth.jpg"},
        {"demo", "--turntable", "3"},
        {"demo", "--turntable", "0", "--video", "x.mp4"},
        {"demo", "--turntable", "2", "--video", "frame_%s.png"},
        {"demo", "-o"},
        {"demo", "other.obj"},
        {},
    };
    for (const auto& args : bad) {
        std::string joined;
        for (const std::string& a : args)
            joined += a + " ";
        EXPECT_EQ(run(args), 2) << joined;
        EXPECT_NE(err_.find("usage: opencv_shading"), std::string::npos) << joined << err_;
        EXPECT_TRUE(out_.empty()) << joined << out_;
    }
}

TEST_F(Cli, TextureThroughTheFilesCoordinates)
{
    // A square facing the camera's default view (front +z, up +y), its texture coordinates
    // spanning [0, 1]; the texture's left half red, right half blue.
    const std::string quad = path("quad.obj"), tex = path("tex.png"), png = path("quad.png");
    std::ofstream(quad) << "v -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\n"
                           "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
                           "f 1/1 2/2 3/3\nf 1/1 3/3 4/4\n";
    cv::Mat texture(8, 8, CV_8UC3, cv::Scalar(0, 0, 255));  // BGR red
    texture.colRange(4, 8).setTo(cv::Scalar(255, 0, 0));      // BGR blue
    ASSERT_TRUE(cv::imwrite(tex, texture));
    ASSERT_EQ(run({quad, "--texture", tex, "-o", png, "--size", "120x120"}), 0) << err_;
    const cv::Mat img = cv::imread(png);
    ASSERT_EQ(img.size(), cv::Size(120, 120));
    // The square is seen from the front-right and above: its left part red, its right blue.
    int redLeft = 0, blueRight = 0, wrongSide = 0;
    for (int y = 0; y < img.rows; y++)
        for (int x = 0; x < img.cols; x++) {
            const cv::Vec3b p = img.at<cv::Vec3b>(y, x);
            const bool red = p[2] > 2 * p[0] + 20, blue = p[0] > 2 * p[2] + 20;
            redLeft += red && x < 55;
            blueRight += blue && x > 65;
            wrongSide += (red && x > 75) || (blue && x < 45);
        }
    EXPECT_GT(redLeft, 500);
    EXPECT_GT(blueRight, 500);
    EXPECT_EQ(wrongSide, 0);

    // No texture coordinates, an unreadable image, the demo knot: clear errors, exit 1.
    EXPECT_EQ(run({writeCube(), "--texture", tex, "-o", path("x.png")}), 1);
    EXPECT_NE(err_.find("no texture coordinates"), std::string::npos) << err_;
    EXPECT_EQ(run({quad, "--texture", path("missing.png"), "-o", path("x.png")}), 1);
    EXPECT_NE(err_.find("missing.png"), std::string::npos) << err_;
    EXPECT_EQ(run({"demo", "--texture", tex, "-o", path("x.png")}), 1);
    EXPECT_NE(err_.find("--texture"), std::string::npos) << err_;
    EXPECT_FALSE(fs::exists(path("x.png")));
}

TEST_F(Cli, UnreadableMeshExitsOne)
{
    const std::string missing = path("missing.obj");
    EXPECT_EQ(run({missing, "-o", path("x.png")}), 1);
    EXPECT_NE(err_.find(missing), std::string::npos) << err_;
    EXPECT_FALSE(fs::exists(path("x.png")));

    const std::string garbage = path("garbage.stl");
    std::ofstream(garbage) << "this is not a mesh";
    EXPECT_EQ(run({garbage, "-o", path("x.png")}), 1);
    EXPECT_NE(err_.find(garbage), std::string::npos) << err_;

    EXPECT_EQ(run({"demo", "-o", path("no/such/folder/x.png")}), 1);
    EXPECT_NE(err_.find("x.png"), std::string::npos) << err_;
}

}  // namespace
