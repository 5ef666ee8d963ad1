// The benchmark scenes (modules/shading/perf/perf_scenes.hpp: a grid that tiles the canvas, a UV
// sphere with back faces, random overlapping triangles, the demo mesh), at a small size: render
// equals the brute-force reference painter's pixel for pixel, with 1 and 2 threads, and the
// thread counts agree bit for bit.
#include "reference/shading_reference.hpp"
#include "test_common.hpp"

#include "../modules/shading/perf/perf_scenes.hpp"

#include <gtest/gtest.h>
#include <opencv2/core/utility.hpp>
#include <opencv2/shading.hpp>

#include <string>
#include <vector>

using namespace cv;

namespace {

template <typename T>
std::vector<T> rowsOf(const Mat& m)
{
    Mat converted;
    m.convertTo(converted, traits::Depth<T>::value);
    return std::vector<T>(converted.reshape(DataType<T>::channels, int(m.total() / DataType<T>::channels)));
}

}  // namespace

class ShadingScenes : public testing::TestWithParam<std::string> {};

namespace {

// The scene, stretched by xScale and yScale, against the reference.
void expectEqualReference(const shading_perf::Scene& scene, int xScale, int yScale = 1)
{
    const auto& m = scene.mesh;
    Mat verts2d = m.verts2d.clone();
    verts2d.reshape(1, m.verts2d.rows).col(0) *= xScale;
    verts2d.reshape(1, m.verts2d.rows).col(1) *= yScale;
    const Size size(scene.size.width * xScale, scene.size.height * yScale);
    const std::vector<Point2d> verts = rowsOf<Point2d>(verts2d);
    const std::vector<Vec3i> faces = rowsOf<Vec3i>(m.faces);
    const std::vector<Vec3d> colors = rowsOf<Vec3d>(m.vcolors);
    const std::vector<double> depth = rowsOf<double>(m.depth);
    const int saved = getNumThreads();
    for (bool gouraud : {false, true}) {
        const Mat expected = shading_ref::render(verts, faces, colors, depth, gouraud, size);
        Mat single;
        // 3: two threads with every band drawn in parts, as threads share bands where they
        // are few.
        for (int threads : {1, 2, 3}) {
            setNumThreads(std::min(threads, 2));
            shading_test::SplitBands parts(threads == 3);
            Mat img;
            shading::render(verts2d, m.faces, m.vcolors, m.depth, img,
                            gouraud ? shading::SHADE_GOURAUD : shading::SHADE_FLAT, size);
            // Flat: neighbouring faces have different mean colours, so a pixel given to the wrong
            // face shows; Gouraud: colours within float rounding of the double reference.
            EXPECT_LE(shading_test::maxAbsDiff(img, expected), gouraud ? 1e-4 : 1e-6)
                << scene.name << (gouraud ? " Gouraud" : " flat") << ", " << threads
                << (threads == 3 ? " (2 threads, bands in parts)" : " threads") << ", " << size;
            if (single.empty())
                single = img;
            else
                EXPECT_EQ(shading_test::maxAbsDiff(img, single), 0.0) << scene.name;
        }
    }
    setNumThreads(saved);
}

}  // namespace

TEST_P(ShadingScenes, EqualReferenceForAnyThreadCount)
{
    expectEqualReference(shading_perf::makeScene(GetParam(), 96), 1);
}

// 768 float pixels per row: bands painted back to front in slices of 16 rows (see paintRowsFor),
// as on big canvases.
TEST_P(ShadingScenes, WideCanvasEqualsReference)
{
    expectEqualReference(shading_perf::makeScene(GetParam(), 96), 8);
}

// 768 rows: 12 bands of 64 rows (see kBandRowsLog2), fewer than 8 per thread with 2 threads, so
// that runs end within bands and a thread done first draws parts of bands.
TEST_P(ShadingScenes, TallCanvasEqualsReference)
{
    expectEqualReference(shading_perf::makeScene(GetParam(), 96), 1, 8);
}

// A canvas of 16 MB or more (2048 x 700 float pixels): front-to-back bands are drawn in a scratch
// tile and streamed out to the canvas (see kStreamedCanvasBytes), in bands of 64 rows (or their
// parts). The tile gets its background before the faces where they cover it a few layers deep,
// after them where they cover it all: 1.5 layers, 4 and 12 (bands of both kinds in one image).
TEST(ShadingScenesBig, StreamedCanvasEqualsReference)
{
    const Size size(2048, 700);
    for (double layers : {1.5, 4.0, 12.0}) {
        SCOPED_TRACE(testing::Message() << layers << " layers");
        shading_perf::Scene scene{"random2048x700", size, shading_perf::makeRandom(2000, layers)};
        scene.mesh.verts2d.col(0) *= size.width;  // unit square -> canvas
        scene.mesh.verts2d.col(1) *= size.height;
        expectEqualReference(scene, 1, 1);
    }
}

INSTANTIATE_TEST_SUITE_P(BenchmarkScenes, ShadingScenes,
                         testing::Values("grid", "sphere", "random", "demo"));
