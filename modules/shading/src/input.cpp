// This file is part of opencv_shading. License: Apache-2.0.
#include "input.hpp"
#include "raster.hpp"

#include <opencv2/core/hal/intrin.hpp>
#include <opencv2/core/utility.hpp>
#include <opencv2/shading.hpp>

#include <algorithm>
#include <climits>
#include <cmath>
#include <string>
#include <utility>

namespace cv {
namespace shading {
namespace detail {

static std::string describe(const Mat& m)
{
    return format("%dx%d %s", m.rows, m.cols, typeToString(m.type()).c_str());
}

//! Checks that `m` holds rows of `dims` CV_32F/CV_64F/CV_32S values; returns the row count.
static int countRows(const Mat& m, const char* argName, int dims, int expectedCount)
{
    const char* shape = dims == 1 ? "N x 1 or 1 x N" : dims == 2 ? "N x 2" : "N x 3";
    const int depth = m.depth();
    if (!m.empty() && depth != CV_32F && depth != CV_64F && depth != CV_32S)
        CV_Error(Error::StsUnsupportedFormat,
                 format("%s: expected elements of CV_32F, CV_64F or CV_32S, got %s", argName,
                        describe(m).c_str()));
    int count = -1;
    if (m.empty())
        count = 0;
    else if (m.dims == 2 && m.channels() == 1 && m.cols == dims)
        count = m.rows;  // one item per row
    else if (m.dims == 2 && m.channels() == dims && (m.rows == 1 || m.cols == 1))
        count = m.rows * m.cols;  // vector<Point2f>, vector<Vec3f>, ... or a row vector
    else if (m.dims == 2 && m.channels() == 1 && dims == 1 && m.rows == 1)
        count = m.cols;  // 1 x N depths
    if (count < 0)
        CV_Error(Error::StsBadSize, format("%s: expected %s values (one row per item), got %s",
                                           argName, shape, describe(m).c_str()));
    if (expectedCount >= 0 && count != expectedCount)
        CV_Error(Error::StsBadSize, format("%s: expected %d items, got %d (%s)", argName,
                                           expectedCount, count, describe(m).c_str()));
    return count;
}

//! Values per parallel slice: smaller inputs are converted at once.
constexpr int kConversionSlice = 1 << 15;

static bool anyIndexOutside(const int* indices, size_t n, int vertexCount);

//! Whether every one of v[0 .. n) is finite.
template <typename T>
static bool allFinite(const T* v, size_t n)
{
    bool finite = true;
    for (size_t i = 0; i < n; i++)
        finite &= v[i] - v[i] == 0;  // NaN for infinities and NaN; vectorizes
    return finite;
}

//! Whether every one of v[0 .. n) lies within +-limit (NaN does not).
static bool allWithin(const double* v, size_t n, double limit)
{
    bool within = true;
    for (size_t i = 0; i < n; i++)
        within &= std::abs(v[i]) <= limit;  // vectorizes
    return within;
}

//! Calls fn(begin, end) for the slices of [0, n), in parallel.
template <typename Fn>
static void forSlices(size_t n, Fn&& fn)
{
    const int slices = int((n + kConversionSlice - 1) / kConversionSlice);
    parallel_for_(Range(0, slices), [&](const Range& r) {
        fn(size_t(r.start) * kConversionSlice, std::min(n, size_t(r.end) * kConversionSlice));
    });
}

//! Runs `check` on the values of dst, a single row or a continuous matrix.
static void checkConverted(const Mat& dst, const ConversionCheck& check)
{
    const size_t n = dst.total() * dst.channels();
    if (check.kind == ConversionCheck::kIndices) {
        if (anyIndexOutside(dst.ptr<int>(), n, check.limit))
            check.failed->store(true, std::memory_order_relaxed);
    } else if (check.kind == ConversionCheck::kFinite) {
        if (!allFinite(dst.ptr<double>(), n))
            check.failed->store(true, std::memory_order_relaxed);
    } else if (check.kind == ConversionCheck::kColorRange) {
        if (!allWithin(dst.ptr<double>(), n, kGouraudColorLimit))
            check.failed->store(true, std::memory_order_relaxed);
    }
}

void PendingConversions::add(const Mat& src, Mat& dst, const ConversionCheck& check)
{
    if (!src.isContinuous() || src.total() * src.channels() <= size_t(kConversionSlice) ||
        src.total() * src.channels() > size_t(INT_MAX)) {
        src.convertTo(dst, dst.depth());  // dst has the right size and type: no reallocation
        checkConverted(dst, check);
        return;
    }
    jobs_.push_back({src.reshape(1, 1), dst.reshape(1, 1), check});
}

void PendingConversions::run()
{
    std::vector<std::pair<int, int>> slices;  // (job, first value)
    for (size_t j = 0; j < jobs_.size(); j++)
        for (int v = 0; v < jobs_[j].src.cols; v += kConversionSlice)
            slices.emplace_back(int(j), v);
    parallel_for_(Range(0, int(slices.size())), [&](const Range& r) {
        for (int i = r.start; i < r.end; i++) {
            const Job& job = jobs_[slices[i].first];
            const int begin = slices[i].second;
            const int end = std::min(begin + kConversionSlice, job.src.cols);
            Mat dst = job.dst.colRange(begin, end);
            job.src.colRange(begin, end).convertTo(dst, dst.depth());
            checkConverted(dst, job.check);
        }
    });
    jobs_.clear();
}

/** Whether any of indices[0 .. n) lies outside [0, vertexCount): one unsigned comparison per
index (a negative one wraps above any count), SIMD without a loop-carried min/max, which SSE2
lacks for 32-bit integers. */
static bool anyIndexOutside(const int* indices, size_t n, int vertexCount)
{
    if (vertexCount <= 0)
        return n > 0;
    size_t i = 0;
    bool outside = false;
#if OPENCV_SHADING_SIMD128
    // Unsigned a >= b as signed (a ^ sign) > (b - 1) ^ sign: SSE2 compares signed only.
    const v_int32x4 sign = v_setall_s32(INT_MIN);
    const v_int32x4 last = v_setall_s32(int(unsigned(vertexCount - 1) ^ 0x80000000u));
    v_int32x4 above0 = v_setzero_s32(), above1 = v_setzero_s32();
    for (; i + 8 <= n; i += 8) {
        above0 = above0 | ((v_load(indices + i) ^ sign) > last);
        above1 = above1 | ((v_load(indices + i + 4) ^ sign) > last);
    }
    outside = v_check_any(above0 | above1);
#endif
    for (; i < n; i++)
        outside |= unsigned(indices[i]) >= unsigned(vertexCount);
    return outside;
}

/** Reads `arr` as items of type T (Point2d, Vec3d, Vec3i, double) into `items`, converting
straight into its memory (now, or in pending->run()). */
template <typename T>
static void readItems(InputArray arr, const char* argName, int expectedCount,
                      std::vector<T>& items, PendingConversions* pending = nullptr,
                      const ConversionCheck& check = ConversionCheck())
{
    using Info = DataType<T>;
    static_assert(sizeof(T) == sizeof(typename Info::channel_type) * Info::channels,
                  "T must be packed channel values");
    const Mat m = arr.getMat();
    items.resize(size_t(countRows(m, argName, Info::channels, expectedCount)));
    if (!items.empty()) {
        Mat dst(m.rows, m.cols, CV_MAKETYPE(traits::Depth<T>::value, m.channels()), items.data());
        if (pending) {
            pending->add(m, dst, check);
        } else {
            m.convertTo(dst, traits::Depth<T>::value);  // the right size and type: no reallocation
            checkConverted(dst, check);
        }
    }
}

void readPoints(InputArray arr, const char* argName, int expectedCount, std::vector<Point2d>& out,
                PendingConversions* pending)
{
    readItems(arr, argName, expectedCount, out, pending);
}

void readColors(InputArray arr, const char* argName, int expectedCount, std::vector<Vec3d>& out,
                PendingConversions* pending, std::atomic<bool>* outOfRange)
{
    ConversionCheck check;
    if (outOfRange)
        check.kind = ConversionCheck::kColorRange, check.failed = outOfRange;
    readItems(arr, argName, expectedCount, out, pending, check);
}

void readVectors(InputArray arr, const char* argName, int expectedCount, std::vector<Vec3d>& out,
                 PendingConversions* pending, std::atomic<bool>* nonFinite)
{
    ConversionCheck check;
    if (nonFinite)
        check.kind = ConversionCheck::kFinite, check.failed = nonFinite;
    readItems(arr, argName, expectedCount, out, pending, check);
}

/** Whether `arr` (whose Mat is m) holds continuous CV_32F values the band pass may read where
they are: matrices and vectors only, whose memory is the caller's, not a mapping that ends with
m. */
static bool readableInPlace(InputArray arr, const Mat& m)
{
    return m.depth() == CV_32F && m.isContinuous() && (arr.isMat() || arr.isVector());
}

Rows3 readRows3(InputArray arr, const char* argName, int expectedCount, std::vector<Vec3d>& storage,
                PendingConversions* pending, std::atomic<bool>* nonFinite)
{
    const Mat m = arr.getMat();
    if (!readableInPlace(arr, m)) {
        readVectors(arr, argName, expectedCount, storage, pending, nonFinite);
        return Rows3(storage);
    }
    const size_t count = size_t(countRows(m, argName, 3, expectedCount));
    storage.clear();
    if (nonFinite)
        forSlices(3 * count, [&](size_t begin, size_t end) {
            if (!allFinite(m.ptr<float>() + begin, end - begin))
                nonFinite->store(true, std::memory_order_relaxed);
        });
    return Rows3(m.ptr<float>(), count);
}

PointRows readPointRows(InputArray arr, const char* argName, int expectedCount,
                        std::vector<Point2d>& storage, PendingConversions* pending)
{
    const Mat m = arr.getMat();
    if (!readableInPlace(arr, m)) {
        readPoints(arr, argName, expectedCount, storage, pending);
        return PointRows(storage);
    }
    const size_t count = size_t(countRows(m, argName, 2, expectedCount));
    storage.clear();
    return PointRows(m.ptr<Point2f>(), count);
}

//! Raises the error for the first index of faces[0 .. count) outside [0, vertexCount).
static void reportIndexOutside(const Vec3i* faces, size_t count, const char* argName,
                               int vertexCount)
{
    for (size_t i = 0; i < count; i++)
        for (int k = 0; k < 3; k++)
            if (faces[i][k] < 0 || faces[i][k] >= vertexCount)
                CV_Error(Error::StsOutOfRange,
                         format("%s: face %zu has index %d, outside [0, %d) (the vertex count)",
                                argName, i, faces[i][k], vertexCount));
}

void readFaces(InputArray arr, const char* argName, int vertexCount, std::vector<Vec3i>& faces,
               PendingConversions* pending)
{
    if (arr.depth() == CV_32S) {
        // Each slice is checked (one SIMD pass) as it is copied; the error path finds the first
        // bad index.
        std::atomic<bool> outside(false);
        ConversionCheck check;
        check.kind = ConversionCheck::kIndices, check.limit = vertexCount, check.failed = &outside;
        readItems(arr, argName, -1, faces, pending, check);
        if (pending)
            pending->run();
        if (outside)
            reportIndexOutside(faces.data(), faces.size(), argName, vertexCount);
        return;
    }
    // Floating-point indices: each is checked (range, then integrality) as it is converted.
    if (pending)
        pending->run();
    std::vector<Vec3d> values;
    readItems(arr, argName, -1, values);
    faces.resize(values.size());
    for (size_t i = 0; i < values.size(); i++)
        for (int k = 0; k < 3; k++) {
            const double index = values[i][k];
            if (!(index >= 0 && index < vertexCount))
                CV_Error(Error::StsOutOfRange,
                         format("%s: face %zu has index %g, outside [0, %d) (the vertex count)",
                                argName, i, index, vertexCount));
            if (index != std::floor(index))
                CV_Error(Error::StsBadArg,
                         format("%s: face %zu has non-integer index %g", argName, i, index));
            faces[i][k] = int(index);
        }
}

FaceRows readFaceRows(InputArray arr, const char* argName, int vertexCount,
                      std::vector<Vec3i>& storage, PendingConversions* pending)
{
    const Mat m = arr.getMat();
    // Matrices and vectors only: their memory is the caller's, not a mapping that ends with m.
    if (m.depth() != CV_32S || !m.isContinuous() || !(arr.isMat() || arr.isVector())) {
        readFaces(arr, argName, vertexCount, storage, pending);
        return FaceRows(storage);
    }
    const size_t count = size_t(countRows(m, argName, 3, -1));
    if (pending)
        pending->run();
    storage.clear();
    const int* indices = m.ptr<int>();
    std::atomic<bool> outside(false);
    forSlices(3 * count, [&](size_t begin, size_t end) {
        if (anyIndexOutside(indices + begin, end - begin, vertexCount))
            outside.store(true, std::memory_order_relaxed);
    });
    static_assert(sizeof(Vec3i) == 3 * sizeof(int), "a face is its three indices");
    const Vec3i* faces = reinterpret_cast<const Vec3i*>(indices);
    if (outside)
        reportIndexOutside(faces, count, argName, vertexCount);
    return FaceRows(faces, count);
}

void readDepths(InputArray arr, const char* argName, int expectedCount, std::vector<double>& out,
                PendingConversions* pending)
{
    if (arr.empty())
        out.clear();
    else
        readItems(arr, argName, expectedCount, out, pending);
}

const float* readDepthFloats(InputArray arr, const char* argName, int expectedCount,
                             std::vector<double>& storage, PendingConversions* pending)
{
    const Mat m = arr.getMat();
    if (m.empty() || !readableInPlace(arr, m)) {
        readDepths(arr, argName, expectedCount, storage, pending);
        return nullptr;
    }
    countRows(m, argName, 1, expectedCount);
    storage.clear();
    return m.ptr<float>();
}

void checkCanvas(InputOutputArray canvas, const char* argName)
{
    if (canvas.empty())
        CV_Error(Error::StsBadArg, format("%s: the image is empty; allocate it first (e.g. "
                                          "Mat(rows, cols, CV_32FC3, background))", argName));
    const int type = canvas.type();
    if (type != CV_32FC3 && type != CV_8UC3)
        CV_Error(Error::StsUnsupportedFormat,
                 format("%s: expected a CV_32FC3 or CV_8UC3 image, got %s", argName,
                        typeToString(type).c_str()));
    if (canvas.dims() > 2)
        CV_Error(Error::StsBadArg, format("%s: expected a 2D image, got %d dimensions", argName,
                                          canvas.dims()));
}

void checkShadeType(int shadeType)
{
    if (shadeType != SHADE_FLAT && shadeType != SHADE_GOURAUD)
        CV_Error(Error::StsBadFlag,
                 format("shadeType: expected SHADE_FLAT (0) or SHADE_GOURAUD (1), got %d%s",
                        shadeType,
                        shadeType == SHADE_PHONG ? " (SHADE_PHONG needs normals: drawMesh3d)" : ""));
}

}  // namespace detail
}  // namespace shading
}  // namespace cv
