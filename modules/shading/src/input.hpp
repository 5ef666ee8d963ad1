// This file is part of opencv_shading. License: Apache-2.0.
//
// The API edge: every InputArray form a user may pass is checked and converted here, once, into
// plain vectors. Code past this point never validates again.
#ifndef OPENCV_SHADING_INPUT_HPP
#define OPENCV_SHADING_INPUT_HPP

#include <opencv2/core.hpp>

#include <atomic>
#include <vector>

namespace cv {
namespace shading {
namespace detail {

/** What a conversion checks in the values it has just written, while they are in cache: that
CV_32S values are indices in [0, limit), or that CV_64F values are finite. A failed check sets
`failed`; the caller then finds and reports the first bad value. */
struct ConversionCheck {
    //! kColorRange: every value within +-kGouraudColorLimit (so not NaN).
    enum Kind { kNone, kIndices, kFinite, kColorRange } kind = kNone;
    int limit = 0;                         //!< kIndices: the vertex count
    std::atomic<bool>* failed = nullptr;  //!< set when a value fails
};

/** Conversions of large inputs, collected by the readers and then run together, in slices, in
parallel: a mesh's four arrays are copied in a fraction of the time one thread takes. */
class PendingConversions {
public:
    //! Converts src into dst (same size and channels, dst's depth) now or in run(), then checks
    //! what it wrote.
    void add(const Mat& src, Mat& dst, const ConversionCheck& check = ConversionCheck());
    void run();

private:
    struct Job {
        Mat src, dst;  //!< flattened to single rows of values
        ConversionCheck check;
    };
    std::vector<Job> jobs_;
};

// Each reader accepts rows of CV_32F/CV_64F/CV_32S values (see the public header for the forms)
// and fills `out` (reusing its capacity). `expectedCount` < 0 accepts any count. Errors name
// `argName` and say what was expected and given. With `pending`, the values may arrive only when
// pending->run() returns.
void readPoints(InputArray arr, const char* argName, int expectedCount, std::vector<Point2d>& out,
                PendingConversions* pending = nullptr);
/** Colours. With `outOfRange`, it is set when some value lies beyond +-kGouraudColorLimit or is
NaN (checked as the values are converted, in parallel, while they are in cache). */
void readColors(InputArray arr, const char* argName, int expectedCount, std::vector<Vec3d>& out,
                PendingConversions* pending = nullptr, std::atomic<bool>* outOfRange = nullptr);
/** 3D points or vectors (vertices, normals): rows of x, y, z. With `nonFinite`, it is set when
some value is not finite (checked as the values are converted, once they have arrived). */
void readVectors(InputArray arr, const char* argName, int expectedCount, std::vector<Vec3d>& out,
                 PendingConversions* pending = nullptr,
                 std::atomic<bool>* nonFinite = nullptr);
/** Rows of three values (points, vectors or colours) as doubles, from where they are: the
caller's own continuous CV_32F values (no copy; float to double is exact, so both forms give the
same values), or values converted into a vector. Valid while both live. */
class Rows3 {
public:
    Rows3() = default;
    Rows3(const float* values, size_t count) : floats_(values), size_(count) {}
    explicit Rows3(const std::vector<Vec3d>& values) : doubles_(values.data()), size_(values.size())
    {
    }

    size_t size() const { return size_; }
    bool empty() const { return size_ == 0; }

    Vec3d operator[](size_t i) const
    {
        if (floats_) {
            const float* v = floats_ + 3 * i;
            return Vec3d(v[0], v[1], v[2]);
        }
        return doubles_[i];
    }

    //! The caller's floats (3 a row), or null: then doubles() holds the rows.
    const float* floats() const { return floats_; }
    const Vec3d* doubles() const { return doubles_; }

private:
    const float* floats_ = nullptr;
    const Vec3d* doubles_ = nullptr;
    size_t size_ = 0;
};

/** 2D points from where they are, as Rows3 holds rows of three: the caller's own continuous
CV_32F points, or points converted into a vector. Valid while both live. */
class PointRows {
public:
    PointRows() = default;
    PointRows(const Point2f* points, size_t count) : floats_(points), size_(count) {}
    explicit PointRows(const std::vector<Point2d>& points)
        : doubles_(points.data()), size_(points.size())
    {
    }

    size_t size() const { return size_; }
    bool empty() const { return size_ == 0; }
    //! The caller's floats, or null: then doubles() holds the points.
    const Point2f* floats() const { return floats_; }
    const Point2d* doubles() const { return doubles_; }

private:
    const Point2f* floats_ = nullptr;
    const Point2d* doubles_ = nullptr;
    size_t size_ = 0;
};

/** Faces as index triples, from where they are: the caller's own continuous CV_32S values (no
copy), or values converted into a vector. Valid while both live. */
class FaceRows {
public:
    FaceRows() = default;
    FaceRows(const Vec3i* faces, size_t count) : faces_(faces), size_(count) {}
    explicit FaceRows(const std::vector<Vec3i>& faces) : FaceRows(faces.data(), faces.size()) {}

    size_t size() const { return size_; }
    bool empty() const { return size_ == 0; }
    const Vec3i& operator[](size_t i) const { return faces_[i]; }
    const Vec3i* data() const { return faces_; }

private:
    const Vec3i* faces_ = nullptr;
    size_t size_ = 0;
};

/** readVectors (`nonFinite` given) or readColors (not) without a copy where the values are
continuous CV_32F: those as they are; else converted into `storage`, as the readers do. */
Rows3 readRows3(InputArray arr, const char* argName, int expectedCount, std::vector<Vec3d>& storage,
                PendingConversions* pending, std::atomic<bool>* nonFinite = nullptr);
/** readPoints without a copy where the points are continuous CV_32F: those as they are; else
converted into `storage`, as readPoints does. */
PointRows readPointRows(InputArray arr, const char* argName, int expectedCount,
                        std::vector<Point2d>& storage, PendingConversions* pending);
/** readDepths without a copy where the depths are continuous CV_32F: returns those (`storage`
left empty); else null, having converted them into `storage` as readDepths does. */
const float* readDepthFloats(InputArray arr, const char* argName, int expectedCount,
                             std::vector<double>& storage, PendingConversions* pending);
//! Depths: `expectedCount` values, or none when `arr` is empty.
void readDepths(InputArray arr, const char* argName, int expectedCount, std::vector<double>& out,
                PendingConversions* pending = nullptr);
/** Faces as zero-based index triples, each checked against [0, vertexCount). With `pending`,
runs it (the other readers' conversions too) before checking: call it last. */
void readFaces(InputArray arr, const char* argName, int vertexCount, std::vector<Vec3i>& out,
               PendingConversions* pending = nullptr);

/** readFaces without a copy where the indices are continuous CV_32S: those, checked where they
are; else converted into `storage`, as readFaces does. Call it last, as readFaces. */
FaceRows readFaceRows(InputArray arr, const char* argName, int vertexCount,
                      std::vector<Vec3i>& storage, PendingConversions* pending);

//! Checks that `canvas` is a non-empty CV_32FC3 or CV_8UC3 image.
void checkCanvas(InputOutputArray canvas, const char* argName);
//! 2D functions: SHADE_FLAT or SHADE_GOURAUD.
void checkShadeType(int shadeType);

}  // namespace detail
}  // namespace shading
}  // namespace cv

#endif  // OPENCV_SHADING_INPUT_HPP
