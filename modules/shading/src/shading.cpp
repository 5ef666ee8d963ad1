// This file is part of opencv_shading. License: Apache-2.0.
//
// The public functions: validate and normalise at the edge (input.cpp), then hand plain data to
// the one rasterization core (raster.hpp) with a span shader (shaders.hpp).
#include <opencv2/shading.hpp>

#include "bands.hpp"
#include "input.hpp"
#include "mesh.hpp"
#include "raster.hpp"
#include "shaders.hpp"

namespace cv {
namespace shading {

using namespace detail;

namespace {

template <template <typename...> class Shader, typename T>
void drawTriangle(Mat& canvas, const Point2d v[3], const Vec3d c[3])
{
    const FixedPoint p[3] = {snapToGrid(v[0]), snapToGrid(v[1]), snapToGrid(v[2])};
    TriangleSetup setup;
    int order[3];
    if (!setupTriangle(p, canvas.size(), setup, order))
        return;
    const Vec3d* const colors[3] = {&c[0], &c[1], &c[2]};
    const Shader<T> shader(setup, order, colors);
    walkTriangle(setup, 0, canvas.rows, canvas.cols, [&](int y, int xBegin, int xEnd) {
        shader(setup, canvas.ptr<T>(y), y, xBegin, xBegin, xEnd);
    });
}

template <template <typename...> class Shader>
void drawTriangle(InputOutputArray canvasArr, InputArray vertices, InputArray vcolors)
{
    checkCanvas(canvasArr, "canvas");
    std::vector<Point2d> v;
    std::vector<Vec3d> c;
    readPoints(vertices, "vertices", 3, v);
    readColors(vcolors, "vcolors", 3, c);
    Mat canvas = canvasArr.getMat();
    if (canvas.depth() == CV_8U)
        drawTriangle<Shader, uchar>(canvas, v.data(), c.data());
    else
        drawTriangle<Shader, float>(canvas, v.data(), c.data());
}

}  // namespace

void flats(InputOutputArray canvas, InputArray vertices, InputArray vcolors)
{
    drawTriangle<FlatShader>(canvas, vertices, vcolors);
}

void gouraud(InputOutputArray canvas, InputArray vertices, InputArray vcolors)
{
    drawTriangle<GouraudShader>(canvas, vertices, vcolors);
}

namespace {

/** Reads and checks the mesh arguments into this thread's MeshData, whose buffers are kept
between calls as the drawing's are (see MeshWorkspace). */
MeshData& readMesh(InputArray verts2d, InputArray faces, InputArray vcolors, InputArray depth,
                   int shadeType)
{
    checkShadeType(shadeType);
    thread_local MeshData mesh;
    PendingConversions pending;
    mesh.vertices = readPointRows(verts2d, "verts2d", -1, mesh.vertexStorage, &pending);
    const int count = int(mesh.vertices.size());
    // Flat: the caller's float colours read where they are (biggrid2048 0.91-0.93x the time).
    // Gouraud: converted, its range check riding on the conversion (see drawMeshAs); its
    // shaders reading floats took 1.03-1.05x (VertexColorShaders::withColors).
    std::atomic<bool> colorOutOfRange{false};
    if (shadeType == SHADE_GOURAUD) {
        readColors(vcolors, "vcolors", count, mesh.colorStorage, &pending, &colorOutOfRange);
        mesh.colors = Rows3(mesh.colorStorage);
    } else {
        mesh.colors = readRows3(vcolors, "vcolors", count, mesh.colorStorage, &pending);
    }
    mesh.depthFloats = readDepthFloats(depth, "depth", count, mesh.depth, &pending);
    // Last: runs the conversions.
    mesh.faces = readFaceRows(faces, "faces", count, mesh.faceStorage, &pending);
    mesh.colorsInGouraudRange = shadeType == SHADE_GOURAUD && !colorOutOfRange.load();
    return mesh;
}

//! Frees the mesh buffers after a call that needed more than MeshWorkspace::kKeepBytes.
void releaseIfBig(MeshData& mesh)
{
    if (mesh.capacityBytes() > MeshWorkspace::kKeepBytes)
        mesh = MeshData();
}

}  // namespace

void drawMesh(InputOutputArray canvas, InputArray verts2d, InputArray faces, InputArray vcolors,
              InputArray depth, int shadeType)
{
    checkCanvas(canvas, "canvas");
    MeshData& mesh = readMesh(verts2d, faces, vcolors, depth, shadeType);
    Mat img = canvas.getMat();
    drawVertexColorMesh(img, mesh, shadeType, nullptr);
    releaseIfBig(mesh);
}

void render(InputArray verts2d, InputArray faces, InputArray vcolors, InputArray depth,
            OutputArray img, int shadeType, Size size, const Scalar& background)
{
    if (size.width <= 0 || size.height <= 0)
        CV_Error(Error::StsBadSize, format("size: expected positive width and height, got %dx%d",
                                           size.width, size.height));
    MeshData& mesh = readMesh(verts2d, faces, vcolors, depth, shadeType);
    img.create(size, CV_32FC3);
    Mat canvas = img.getMat();
    drawVertexColorMesh(canvas, mesh, shadeType, &background);  // also fills the background
    releaseIfBig(mesh);
}

}  // namespace shading
}  // namespace cv
