// Extra memory of drawing a big mesh, measured. This executable replaces the global operator
// new/delete to track the bytes the library holds at once (its std::vector buffers); the canvas
// itself (cv::Mat, allocated by OpenCV's fastMalloc) is the caller's and not counted.
//
// Documented bound (README, "Hard use"): while drawing a mesh of K faces and L vertices, the
// library holds at most kBytesPerFace * K + kBytesPerVertex * L bytes (faces crossing several
// row bands add 8 bytes per extra band), plus a few kilobytes per thread for coverage masks.
// Buffers of at most 256 MB are kept by the calling thread for its next call (frames of a big
// mesh then cost no fresh pages); what a call leaves held stays within the bound, and the next
// call of the same size allocates nothing more (checked below).
#include <gtest/gtest.h>
#include <opencv2/core.hpp>
#include <opencv2/shading.hpp>

#include <malloc.h>

#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <new>

namespace {

std::atomic<long long> g_current{0}, g_peak{0};

void track(void* p)
{
    const long long now = g_current += (long long)malloc_usable_size(p);
    long long peak = g_peak.load();
    while (now > peak && !g_peak.compare_exchange_weak(peak, now)) {
    }
}

void* trackedAlloc(size_t n)
{
    void* p = std::malloc(n ? n : 1);
    if (!p)
        throw std::bad_alloc();
    track(p);
    return p;
}

void trackedFree(void* p) noexcept
{
    if (p) {
        g_current -= (long long)malloc_usable_size(p);
        std::free(p);
    }
}

constexpr long long kBytesPerFace = 48;
constexpr long long kBytesPerVertex = 64;
constexpr long long kSlack = 1 << 20;  // thread-local masks, bins' band table, gtest's own use

}  // namespace

void* operator new(size_t n) { return trackedAlloc(n); }
void* operator new[](size_t n) { return trackedAlloc(n); }
void operator delete(void* p) noexcept { trackedFree(p); }
void operator delete[](void* p) noexcept { trackedFree(p); }
void operator delete(void* p, size_t) noexcept { trackedFree(p); }
void operator delete[](void* p, size_t) noexcept { trackedFree(p); }

// A 1000 x 1000 grid of cells, two faces each: 2,000,000 faces, 1,002,001 vertices, 1024 x 1024.
TEST(ShadingMemory, TwoMillionFacesStayWithinTheDocumentedBound)
{
    const int n = 1000;
    std::vector<cv::Point2f> verts;
    std::vector<cv::Vec3f> colors;
    std::vector<float> depth;
    std::vector<cv::Vec3i> faces;
    for (int j = 0; j <= n; j++)
        for (int i = 0; i <= n; i++) {
            verts.emplace_back(i * 1.024f, j * 1.024f);
            colors.emplace_back(i / float(n), j / float(n), 0.5f);
            depth.push_back(float((i * 7 + j * 13) % 101));
        }
    for (int j = 0; j < n; j++)
        for (int i = 0; i < n; i++) {
            const int a = j * (n + 1) + i;
            faces.emplace_back(a, a + 1, a + n + 2);
            faces.emplace_back(a, a + n + 2, a + n + 1);
        }
    cv::Mat canvas(1024, 1024, CV_32FC3, cv::Scalar::all(1));
    const long long faceCount = (long long)faces.size(), vertexCount = (long long)verts.size();
    const long long bound = kBytesPerFace * faceCount + kBytesPerVertex * vertexCount + kSlack;
    const long long start = g_current.load();
    // Flat, Gouraud, and both again: Gouraud converts the colours (flat reads the caller's
    // floats), so its first call adds their copy; the repeated calls reuse everything.
    for (int call = 0; call < 4; call++) {
        const int shade = call % 2 ? cv::shading::SHADE_GOURAUD : cv::shading::SHADE_FLAT;
        const long long before = g_current.load();
        g_peak = before;
        cv::shading::drawMesh(canvas, verts, faces, colors, depth, shade);
        const long long extra = g_peak.load() - before;
        std::printf("shade %d: %lld faces, %lld vertices: peak extra %lld bytes = %.1f B/face "
                    "(bound %lld)\n", shade, faceCount, vertexCount, extra,
                    double(extra) / faceCount, bound);
        if (call < 2)
            RecordProperty(shade == cv::shading::SHADE_FLAT ? "flat_peak_bytes"
                                                            : "gouraud_peak_bytes",
                           std::to_string(extra));
        EXPECT_LE(extra, bound);
        // What outlives the call is the kept workspace: within the bound, and reused.
        const long long held = g_current.load() - start;
        EXPECT_LE(held, bound) << "memory held after the call";
        if (call == 0) {
            EXPECT_GT(extra, 0);  // the tracking does see the library's buffers
        } else if (call >= 2) {  // only its small per-call tables and masks
            EXPECT_LE(extra, 4 << 20) << "a repeated call reallocated its buffers";
        }
    }
}
