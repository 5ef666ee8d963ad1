// This file is part of opencv_shading. License: Apache-2.0.
//
// loadMesh/saveMesh: files written here by hand, loaded and checked against what they say;
// round trips through every format saveMesh writes; every error names its file or argument.
#include <gtest/gtest.h>
#include <opencv2/shading.hpp>

#include <algorithm>
#include <array>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <map>
#include <set>
#include <string>
#include <vector>

#include <unistd.h>

namespace {

namespace fs = std::filesystem;
using cv::Vec3f;
using cv::Vec3i;

class MeshIO : public ::testing::Test {
protected:
    void SetUp() override
    {
        const ::testing::TestInfo* info = ::testing::UnitTest::GetInstance()->current_test_info();
        dir_ = fs::temp_directory_path() /
               ("opencv_shading_meshio_" + std::string(info->name()) + "_" +
                std::to_string(getpid()));
        fs::remove_all(dir_);
        fs::create_directories(dir_);
    }
    void TearDown() override { fs::remove_all(dir_); }

    std::string path(const std::string& name) const { return (dir_ / name).string(); }

    std::string write(const std::string& name, const std::string& text) const
    {
        std::ofstream(path(name), std::ios::binary) << text;
        return path(name);
    }

    fs::path dir_;
};

//! Runs `fn`, expects a cv::Exception whose message holds every one of `parts`.
void expectError(const std::function<void()>& fn, const std::vector<std::string>& parts)
{
    try {
        fn();
        ADD_FAILURE() << "no exception; expected one mentioning '" << parts[0] << "'";
    } catch (const cv::Exception& e) {
        for (const std::string& p : parts)
            EXPECT_NE(e.err.find(p), std::string::npos) << "'" << p << "' not in: " << e.err;
    }
}

Vec3f row3(const cv::Mat& m, int i) { return Vec3f(m.ptr<float>(i)); }

//! The row of `vertices` at `p` (exactly), or -1.
int findVertex(const cv::Mat& vertices, const Vec3f& p)
{
    for (int i = 0; i < vertices.rows; i++)
        if (row3(vertices, i) == p)
            return i;
    return -1;
}

Vec3f faceNormal(const cv::Mat& v, const Vec3i& f)
{
    const Vec3f a = row3(v, f[0]), b = row3(v, f[1]), c = row3(v, f[2]);
    return cv::normalize((b - a).cross(c - a));
}

// ---------------------------------------------------------------------------------------------
// Files written by hand

TEST_F(MeshIO, ObjQuadIsTwoTrianglesSharingTheDiagonal)
{
    // A unit square as one quad, with texture coordinates equal to (x, y) and one normal.
    const std::string file = write("quad.obj",
                                   "# a quad\n"
                                   "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
                                   "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
                                   "vn 0 0 1\n"
                                   "f 1/1/1 2/2/1 3/3/1 4/4/1\n");
    cv::Mat v, f, n, c, t;
    cv::shading::loadMesh(file, v, f, n, c, t);
    ASSERT_EQ(v.rows, 4);
    ASSERT_EQ(v.cols, 3);
    EXPECT_EQ(v.type(), CV_32F);
    ASSERT_EQ(f.rows, 2);
    ASSERT_EQ(f.cols, 3);
    EXPECT_EQ(f.type(), CV_32S);
    for (const Vec3f& corner : {Vec3f(0, 0, 0), Vec3f(1, 0, 0), Vec3f(1, 1, 0), Vec3f(0, 1, 0)})
        EXPECT_GE(findVertex(v, corner), 0) << corner;

    // The two triangles use 3 distinct vertices each, share exactly two (a diagonal), and keep
    // the quad's counter-clockwise winding (+z).
    std::set<int> a, b;
    for (int k = 0; k < 3; k++)
        a.insert(f.at<int>(0, k)), b.insert(f.at<int>(1, k));
    EXPECT_EQ(a.size(), 3u);
    EXPECT_EQ(b.size(), 3u);
    std::vector<int> shared;
    std::set_intersection(a.begin(), a.end(), b.begin(), b.end(), std::back_inserter(shared));
    EXPECT_EQ(shared.size(), 2u);
    for (int i = 0; i < 2; i++)
        EXPECT_EQ(faceNormal(v, f.at<Vec3i>(i)), Vec3f(0, 0, 1));
    const Vec3f d0 = row3(v, shared[0]), d1 = row3(v, shared[1]);
    EXPECT_EQ(d0[0] + d1[0], 1.f);  // a diagonal joins opposite corners
    EXPECT_EQ(d0[1] + d1[1], 1.f);

    ASSERT_EQ(n.size(), cv::Size(3, 4));
    ASSERT_EQ(t.size(), cv::Size(2, 4));
    EXPECT_TRUE(c.empty());  // no colours in the file
    for (int i = 0; i < 4; i++) {
        EXPECT_EQ(row3(n, i), Vec3f(0, 0, 1));
        EXPECT_EQ(t.at<float>(i, 0), v.at<float>(i, 0));
        EXPECT_EQ(t.at<float>(i, 1), v.at<float>(i, 1));
    }

    // Vector outputs get the same values.
    std::vector<Vec3f> vv;
    std::vector<Vec3i> ff;
    std::vector<cv::Point2f> tt;
    cv::shading::loadMesh(file, vv, ff, cv::noArray(), cv::noArray(), tt);
    ASSERT_EQ(vv.size(), 4u);
    ASSERT_EQ(ff.size(), 2u);
    ASSERT_EQ(tt.size(), 4u);
    for (int i = 0; i < 4; i++) {
        EXPECT_EQ(vv[size_t(i)], row3(v, i));
        EXPECT_EQ(tt[size_t(i)], cv::Point2f(t.at<float>(i, 0), t.at<float>(i, 1)));
    }
    for (int i = 0; i < 2; i++)
        EXPECT_EQ(ff[size_t(i)], f.at<Vec3i>(i));
}

TEST_F(MeshIO, ObjObjectsAreConcatenated)
{
    // Two objects: a triangle and a quad (2 triangles), 7 vertices, no normals.
    const std::string file = write("two.obj",
                                   "o tri\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"
                                   "o quad\nv 0 0 5\nv 1 0 5\nv 1 1 5\nv 0 1 5\nf 4 5 6 7\n");
    cv::Mat v, f, n;
    cv::shading::loadMesh(file, v, f, n);
    EXPECT_EQ(v.rows, 7);
    EXPECT_EQ(f.rows, 3);
    EXPECT_TRUE(n.empty());
    double lo = 0, hi = 0;
    cv::minMaxLoc(f, &lo, &hi);
    EXPECT_EQ(lo, 0);
    EXPECT_EQ(hi, 6);
}

TEST_F(MeshIO, PlyVertexColours)
{
    const std::string file = write("colours.ply",
                                   "ply\nformat ascii 1.0\n"
                                   "element vertex 3\n"
                                   "property float x\nproperty float y\nproperty float z\n"
                                   "property uchar red\nproperty uchar green\nproperty uchar blue\n"
                                   "element face 1\nproperty list uchar int vertex_indices\n"
                                   "end_header\n"
                                   "0 0 0 255 0 0\n1 0 0 0 255 0\n0 1 0 0 0 51\n"
                                   "3 0 1 2\n");
    cv::Mat v, f, n, c, t;
    cv::shading::loadMesh(file, v, f, n, c, t);
    ASSERT_EQ(v.rows, 3);
    ASSERT_EQ(f.rows, 1);
    ASSERT_EQ(c.size(), cv::Size(3, 3));
    EXPECT_EQ(c.type(), CV_32F);
    EXPECT_TRUE(n.empty());
    EXPECT_TRUE(t.empty());
    const std::map<int, Vec3f> expected = {{findVertex(v, {0, 0, 0}), {1, 0, 0}},
                                           {findVertex(v, {1, 0, 0}), {0, 1, 0}},
                                           {findVertex(v, {0, 1, 0}), {0, 0, 0.2f}}};
    ASSERT_EQ(expected.size(), 3u);
    for (const auto& e : expected) {
        ASSERT_GE(e.first, 0);
        const Vec3f got = row3(c, e.first);
        for (int k = 0; k < 3; k++)
            EXPECT_NEAR(got[k], e.second[k], 1e-6) << "vertex " << e.first;
    }
    EXPECT_EQ(faceNormal(v, f.at<Vec3i>(0)), Vec3f(0, 0, 1));
}

TEST_F(MeshIO, StlKeepsOneVertexPerFacetCorner)
{
    // A tetrahedron: four facets with four different normals, so no corner is shared.
    const std::string file = write("tet.stl",
                                   "solid tet\n"
                                   "facet normal 0 0 -1\nouter loop\n"
                                   "vertex 0 0 0\nvertex 0 1 0\nvertex 1 0 0\nendloop\nendfacet\n"
                                   "facet normal 0 -1 0\nouter loop\n"
                                   "vertex 0 0 0\nvertex 1 0 0\nvertex 0 0 1\nendloop\nendfacet\n"
                                   "facet normal -1 0 0\nouter loop\n"
                                   "vertex 0 0 0\nvertex 0 0 1\nvertex 0 1 0\nendloop\nendfacet\n"
                                   "facet normal 0.57735 0.57735 0.57735\nouter loop\n"
                                   "vertex 1 0 0\nvertex 0 1 0\nvertex 0 0 1\nendloop\nendfacet\n"
                                   "endsolid tet\n");
    cv::Mat v, f, n;
    cv::shading::loadMesh(file, v, f, n);
    ASSERT_EQ(f.rows, 4);
    EXPECT_EQ(v.rows, 12);
    ASSERT_EQ(n.rows, 12);
    for (int i = 0; i < 4; i++) {
        const Vec3i face = f.at<Vec3i>(i);
        const Vec3f geometric = faceNormal(v, face);
        for (int k = 0; k < 3; k++) {
            EXPECT_LT(cv::norm(row3(n, face[k]) - geometric), 1e-4) << "face " << i;
        }
    }
}

TEST_F(MeshIO, OffPolygons)
{
    const std::string file = write("shape.off",
                                   "OFF\n5 2 0\n"
                                   "0 0 0\n1 0 0\n1 1 0\n0 1 0\n2 2 2\n"
                                   "4 0 1 2 3\n3 1 4 2\n");
    cv::Mat v, f;
    cv::shading::loadMesh(file, v, f);
    EXPECT_EQ(v.rows, 5);
    EXPECT_EQ(f.rows, 3);
    const int apex = findVertex(v, {2, 2, 2});
    ASSERT_GE(apex, 0);
    int uses = 0;
    for (int i = 0; i < f.rows; i++)
        for (int k = 0; k < 3; k++)
            uses += f.at<int>(i, k) == apex;
    EXPECT_EQ(uses, 1);
}

// ---------------------------------------------------------------------------------------------
// Round trips

//! A 4 x 4 grid of a bumpy surface with positions that decimal text cannot hold exactly.
struct TestMesh {
    cv::Mat v, f, n, c, t;
};

TestMesh makeTestMesh()
{
    TestMesh m;
    const int side = 4;
    std::vector<Vec3f> v, c;
    std::vector<cv::Vec2f> t;
    for (int y = 0; y < side; y++)
        for (int x = 0; x < side; x++) {
            v.emplace_back(0.1f * x, 0.1f * y + 0.3f, 0.07f * float((x * y) % 3) - 0.01f);
            c.emplace_back(x / 3.f, y / 3.f, 0.3f);
            t.emplace_back(x / 3.f, 1.f - y / 3.f);
        }
    std::vector<Vec3i> f;
    for (int y = 0; y + 1 < side; y++)
        for (int x = 0; x + 1 < side; x++) {
            const int a = y * side + x;
            f.emplace_back(a, a + 1, a + side + 1);
            f.emplace_back(a, a + side + 1, a + side);
        }
    m.v = cv::Mat(v, true).reshape(1);
    m.f = cv::Mat(f, true).reshape(1);
    m.c = cv::Mat(c, true).reshape(1);
    m.t = cv::Mat(t, true).reshape(1);
    cv::shading::computeNormals(m.v, m.f, m.n);
    return m;
}

//! The faces as corner positions, each rotated to start at its smallest corner (the winding
//! is kept), sorted: equal for two meshes with the same triangles whatever their indexing.
std::vector<std::array<Vec3f, 3>> triangles(const cv::Mat& v, const cv::Mat& f)
{
    auto less = [](const Vec3f& a, const Vec3f& b) {
        return std::lexicographical_compare(a.val, a.val + 3, b.val, b.val + 3);
    };
    std::vector<std::array<Vec3f, 3>> out;
    for (int i = 0; i < f.rows; i++) {
        std::array<Vec3f, 3> tri;
        for (int k = 0; k < 3; k++)
            tri[size_t(k)] = row3(v, f.at<int>(i, k));
        std::rotate(tri.begin(), std::min_element(tri.begin(), tri.end(), less), tri.end());
        out.push_back(tri);
    }
    std::sort(out.begin(), out.end(), [&](const auto& a, const auto& b) {
        return std::lexicographical_compare(a.begin(), a.end(), b.begin(), b.end(), less);
    });
    return out;
}

struct FormatCase {
    const char* ext;
    bool shares;   // vertices shared between faces after reload
    bool normals;  // the format stores vertex normals
    bool colors;   // ... vertex colours
    bool uv;       // ... texture coordinates
    double colorTolerance = 1e-6;  // PLY stores 8-bit colours
};

TEST_F(MeshIO, RoundTripsThroughEveryFormat)
{
    const TestMesh m = makeTestMesh();
    const FormatCase cases[] = {
        {"obj", true, true, false, true},   {"ply", true, true, true, true, 0.5 / 255 + 1e-6},
        {"stl", false, false, false, false}, {"gltf", true, true, true, true},
        {"glb", true, true, true, true},    {"off", true, false, false, false},
        {"dae", true, true, true, true}};
    for (const FormatCase& fc : cases) {
        SCOPED_TRACE(fc.ext);
        const std::string file = path(std::string("mesh.") + fc.ext);
        cv::shading::saveMesh(file, m.v, m.f, m.n, m.c, m.t);
        ASSERT_TRUE(fs::exists(file));
        cv::Mat v, f, n, c, t;
        cv::shading::loadMesh(file, v, f, n, c, t);
        ASSERT_EQ(f.rows, m.f.rows);
        if (fc.shares) {
            EXPECT_EQ(v.rows, m.v.rows);
        } else {  // STL: corners merge only where the facet normals agree too
            EXPECT_GT(v.rows, m.v.rows);
            EXPECT_LE(v.rows, 3 * m.f.rows);
        }
        // Every format here stores floats as float or with 9 significant digits: exact.
        EXPECT_EQ(triangles(v, f), triangles(m.v, m.f));
        // Attributes, matched through the (unique) positions.
        for (int i = 0; i < v.rows; i++) {
            const int src = findVertex(m.v, row3(v, i));
            ASSERT_GE(src, 0);
            if (fc.normals) {
                ASSERT_EQ(n.rows, v.rows);
                EXPECT_LT(cv::norm(row3(n, i) - row3(m.n, src)), 1e-6);
            }
            if (fc.colors) {
                ASSERT_EQ(c.rows, v.rows);
                EXPECT_LE(cv::norm(row3(c, i) - row3(m.c, src), cv::NORM_INF), fc.colorTolerance);
            }
            if (fc.uv) {
                ASSERT_EQ(t.rows, v.rows);
                EXPECT_NEAR(t.at<float>(i, 0), m.t.at<float>(src, 0), 1e-6);
                EXPECT_NEAR(t.at<float>(i, 1), m.t.at<float>(src, 1), 1e-6);
            }
        }
    }
}

TEST_F(MeshIO, SavesPositionsAndFacesAlone)
{
    const TestMesh m = makeTestMesh();
    std::vector<cv::Point3d> v;
    for (int i = 0; i < m.v.rows; i++)
        v.emplace_back(row3(m.v, i));
    const std::string file = path("plain.ply");
    cv::shading::saveMesh(file, v, m.f);
    cv::Mat v2, f2, n2, c2;
    cv::shading::loadMesh(file, v2, f2, n2, c2);
    EXPECT_EQ(triangles(v2, f2), triangles(m.v, m.f));
    EXPECT_TRUE(n2.empty());
    EXPECT_TRUE(c2.empty());
}

// ---------------------------------------------------------------------------------------------
// Errors

TEST_F(MeshIO, LoadErrorsNameTheFile)
{
    cv::Mat v, f;
    const std::string missing = path("missing.obj");
    expectError([&] { cv::shading::loadMesh(missing, v, f); }, {missing, "does not exist"});
    expectError([&] { cv::shading::loadMesh(dir_.string(), v, f); }, {dir_.string()});

    std::string noise;
    for (int i = 0; i < 4096; i++)
        noise += char((i * 7919 + 13) % 256);
    for (const char* name : {"garbage.ply", "garbage.stl", "garbage.glb", "garbage.xyz"}) {
        const std::string file = write(name, noise);
        expectError([&] { cv::shading::loadMesh(file, v, f); }, {file});
    }
    const std::string lines = write("lines.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nl 1 2\nl 2 3\n");
    expectError([&] { cv::shading::loadMesh(lines, v, f); }, {lines, "no triangles"});
    const std::string points = write("points.ply",
                                     "ply\nformat ascii 1.0\nelement vertex 2\n"
                                     "property float x\nproperty float y\nproperty float z\n"
                                     "end_header\n0 0 0\n1 1 1\n");
    expectError([&] { cv::shading::loadMesh(points, v, f); }, {points});
    const std::string empty = write("empty.off", "");
    expectError([&] { cv::shading::loadMesh(empty, v, f); }, {empty});
}

TEST_F(MeshIO, SaveErrorsNameTheArgumentAndWriteNothing)
{
    const TestMesh m = makeTestMesh();
    const std::string file = path("out.ply");
    const cv::Mat badFaces = (cv::Mat_<int>(1, 3) << 0, 1, 16);
    const cv::Mat nanVerts = [&] {
        cv::Mat v = m.v.clone();
        v.at<float>(2, 1) = std::numeric_limits<float>::quiet_NaN();
        return v;
    }();
    const cv::Mat bright = [&] {
        cv::Mat c = m.c.clone();
        c.at<float>(5, 0) = 1.5f;
        return c;
    }();
    const std::vector<std::pair<std::function<void()>, std::string>> calls = {
        {[&] { cv::shading::saveMesh(file, m.v.colRange(0, 2), m.f); }, "vertices"},
        {[&] { cv::shading::saveMesh(file, cv::Mat(), m.f); }, "vertices"},
        {[&] { cv::shading::saveMesh(file, nanVerts, m.f); }, "vertices"},
        {[&] { cv::shading::saveMesh(file, m.v, badFaces); }, "faces"},
        {[&] { cv::shading::saveMesh(file, m.v, m.f.colRange(0, 2)); }, "faces"},
        {[&] { cv::shading::saveMesh(file, m.v, cv::Mat()); }, "faces"},
        {[&] { cv::shading::saveMesh(file, m.v, m.f, m.n.rowRange(0, 3)); }, "normals"},
        {[&] { cv::shading::saveMesh(file, m.v, m.f, m.n, m.c.rowRange(1, 4)); }, "colors"},
        {[&] { cv::shading::saveMesh(file, m.v, m.f, m.n, bright); }, "colors"},
        {[&] { cv::shading::saveMesh(file, m.v, m.f, m.n, m.c, cv::Mat::zeros(16, 4, CV_32F)); },
         "texCoords"},
        {[&] { cv::shading::saveMesh(file, m.v, m.f, m.n, m.c, m.t.rowRange(0, 2)); },
         "texCoords"},
    };
    for (const auto& call : calls) {
        SCOPED_TRACE(call.second);
        expectError(call.first, {call.second});
        EXPECT_FALSE(fs::exists(file));
    }
    const std::string unknown = path("mesh.xyz");
    expectError([&] { cv::shading::saveMesh(unknown, m.v, m.f); }, {unknown, "extension"});
    EXPECT_FALSE(fs::exists(unknown));
    const std::string nowhere = path("no/such/folder/mesh.obj");
    expectError([&] { cv::shading::saveMesh(nowhere, m.v, m.f); }, {nowhere});
    const std::string nowhereOff = path("no/such/folder/mesh.off");
    expectError([&] { cv::shading::saveMesh(nowhereOff, m.v, m.f); }, {nowhereOff});
}

}  // namespace
