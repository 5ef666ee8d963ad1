// This file is part of opencv_shading. License: Apache-2.0.
//
// Mesh drawing on the core: the painter's image (faces far to near, each overwriting).
//
// The canvas is cut into bands of rows, rendered in parallel. Each band orders its own faces and
// runs sequentially, so the image never depends on the thread count. A band with little overdraw is
// painted: small faces in face order, unsorted, each sample keeping the nearest face so far (the
// later on a tie; tiny flat faces' samples found 8 faces at a time in 4 x 4 blocks), bigger ones
// sorted, back to front; a closed surface's band of many small faces (flat ones: of any count)
// also in face order, but its nearer winding first (a flat face's samples found in one
// 8 x 8 block) and the other's faces only where not yet hidden. One with more overdraw (or a
// closed surface's other band of few faces) is sorted and built front to back, where a coverage
// bit mask keeps the first (frontmost) write of each pixel: exactly what the painter's algorithm
// leaves visible, with each pixel written once, and a face whose sample box is already final is
// skipped before setup. Per face, only a depth, a sample box and its bin entries are kept between
// passes: setup happens in the band that draws the face.
#ifndef OPENCV_SHADING_MESH_HPP
#define OPENCV_SHADING_MESH_HPP

#include "input.hpp"
#include "raster.hpp"
#include "shaders.hpp"

#include <opencv2/core.hpp>
#include <opencv2/core/utility.hpp>

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace cv {
namespace shading {
namespace detail {
OPENCV_SHADING_ISA_BEGIN

/** Maps a mean depth to 32 bits, linearly over [lo, hi] (the finite means' range), so that the
map never decreases: equal depths share a key and a nearer depth never gets a larger one. Depths
closer than the 32-bit step may share a key too; refineEqualKeys orders those exactly. */
inline uint32_t quantizeDepth(double depth, double lo, double scale)
{
    double v = (depth - lo) * scale;  // each step rounds monotonically
    if (!(v >= 0))                    // below the range, or 0 * inf
        v = 0;
    if (!(v <= double(UINT32_MAX)))   // +inf
        v = double(UINT32_MAX);
    return uint32_t(v);
}

/** A face's entry in a band list: its quantized depth key in the high word, its index in the low
word. Sorting entries by the high word only, stably, from lists in decreasing face order, gives
the front-to-back order: nearer first, and among equal keys the later face first. */
inline uint64_t bandEntry(uint32_t key32, int face)
{
    return uint64_t(key32) << 32 | uint32_t(face);
}

inline int entryFace(uint64_t entry)
{
    return int(uint32_t(entry));
}

/** Sorts a band's entries by their high word, stably, approximately: the keys are narrowed to
`keyBits` bits, 1 to 24 (relative to the band's smallest, dropping low bits when the band's keys
span more), which one 8-bit LSD radix pass per byte sorts; entries with equal narrowed keys may
still be out of order (refineEqualKeys completes the order). The entries' high words become the
narrowed keys. Returns where the sorted entries are: `items`, or `scratch` after an odd number of
passes (valid until scratch is next resized; copying them back would cost a pass). */
inline uint64_t* sortBandEntries(uint64_t* items, size_t n, std::vector<uint64_t>& scratch,
                                 int keyBits = 16)
{
    CV_DbgAssert(keyBits >= 1 && keyBits <= 24);  // 0 bits would never narrow
    if (n < 2)
        return items;
    uint32_t lo = UINT32_MAX, hi = 0;
    for (size_t i = 0; i < n; i++) {
        const uint32_t key = uint32_t(items[i] >> 32);
        lo = std::min(lo, key);
        hi = std::max(hi, key);
    }
    const uint32_t keyMax = (uint32_t(1) << keyBits) - 1;
    int drop = 0;
    while (((hi - lo) >> drop) > keyMax)
        drop++;
    uint32_t count[3][256] = {};
    for (size_t i = 0; i < n; i++) {
        const uint32_t key = (uint32_t(items[i] >> 32) - lo) >> drop;
        items[i] = uint64_t(key) << 32 | uint32_t(items[i]);
        count[0][key & 0xff]++;
        if (keyBits > 8)  // one pass: no second byte to count
            count[1][(key >> 8) & 0xff]++;
        if (keyBits > 16)
            count[2][key >> 16]++;
    }
    scratch.resize(std::max(scratch.size(), n));
    uint64_t* src = items;
    uint64_t* dst = scratch.data();
    for (int pass = 0; pass < (keyBits + 7) / 8; pass++) {
        const int shift = 32 + 8 * pass;
        uint32_t* c = count[pass];
        if (c[(items[0] >> shift) & 0xff] == n)
            continue;  // every entry has this byte
        uint32_t sum = 0;
        for (int b = 0; b < 256; b++) {
            const uint32_t k = c[b];
            c[b] = sum;
            sum += k;
        }
        for (size_t i = 0; i < n; i++)
            dst[c[(src[i] >> shift) & 0xff]++] = src[i];
        std::swap(src, dst);
    }
    return src;
}

/** Completes the order of entries sorted by quantized key: within each run of equal quantized
keys, orders by the exact mean depth (ascending), then by face (descending). A run's exact keys are
gathered first (independent loads, which overlap), then checked: runs of equal depths are
usually in order already, as the radix sort leaves equal keys later face first. */
inline void refineEqualKeys(uint64_t* items, size_t n, const double* exactKeys,
                            std::vector<std::pair<double, uint64_t>>& run)
{
    auto frontFirst = [](const std::pair<double, uint64_t>& a,
                         const std::pair<double, uint64_t>& b) {
        return a.first < b.first ||
               (a.first == b.first && entryFace(a.second) > entryFace(b.second));
    };
    for (size_t begin = 0; begin + 1 < n;) {
        size_t end = begin + 1;
        while (end < n && (items[end] >> 32) == (items[begin] >> 32))
            end++;
        if (end - begin == 2) {  // the common case: two faces share a key
            const uint64_t a = items[begin], b = items[begin + 1];
            const double ka = exactKeys[entryFace(a)], kb = exactKeys[entryFace(b)];
            if (kb < ka || (kb == ka && entryFace(b) > entryFace(a))) {
                items[begin] = b;
                items[begin + 1] = a;
            }
        } else if (end - begin > 2) {
            run.clear();
            for (size_t i = begin; i < end; i++)
                run.emplace_back(exactKeys[entryFace(items[i])], items[i]);
            if (!std::is_sorted(run.begin(), run.end(), frontFirst)) {
                std::sort(run.begin(), run.end(), frontFirst);
                for (size_t i = begin; i < end; i++)
                    items[i] = run[i - begin].second;
            }
        }
        begin = end;
    }
}

/** p, held in one register from here on: the compiler then adds a loop's offsets to it in the
address (base + index), rather than to the parts it was computed from, an add or two each. */
template <typename Pointer>
inline Pointer inOneRegister(Pointer p)
{
#if defined(__GNUC__)
    asm("" : "+r"(p));
#endif
    return p;
}

//! Asks for the cache lines of [data, data + size) in advance, for writing.
inline void prefetchBytes(const uchar* data, size_t size)
{
    for (size_t offset = 0; offset < size; offset += 64)
        __builtin_prefetch(data + offset, 1);
}

/** Copies `size` bytes to `dst` with streaming stores (16 or 32 bytes, aligned): the lines go to
memory without first being read, as ordinary stores would read them. Call
streamingStoresDone() before anything else may read dst. */
inline void streamBytes(uchar* dst, const uchar* src, size_t size)
{
    size_t i = 0;
#if OPENCV_SHADING_SIMD128
#if CV_AVX2
    constexpr size_t kStreamAlign = 32;  // 32-byte streaming stores: random2048 0.5-1.5% faster
#else
    constexpr size_t kStreamAlign = 16;
#endif
    i = std::min(size, size_t(-reinterpret_cast<uintptr_t>(dst) & (kStreamAlign - 1)));
    std::memcpy(dst, src, i);
#if CV_AVX2
    for (; i + 128 <= size; i += 128) {
        const auto* from = reinterpret_cast<const __m256i*>(src + i);
        auto* to = reinterpret_cast<__m256i*>(dst + i);
        const __m256i a = _mm256_loadu_si256(from), b = _mm256_loadu_si256(from + 1);
        const __m256i c = _mm256_loadu_si256(from + 2), d = _mm256_loadu_si256(from + 3);
        _mm256_stream_si256(to, a);
        _mm256_stream_si256(to + 1, b);
        _mm256_stream_si256(to + 2, c);
        _mm256_stream_si256(to + 3, d);
    }
#endif
    for (; i + 64 <= size; i += 64) {
        const v_uint8x16 a = v_load(src + i), b = v_load(src + i + 16);
        const v_uint8x16 c = v_load(src + i + 32), d = v_load(src + i + 48);
        v_store_aligned_nocache(dst + i, a);
        v_store_aligned_nocache(dst + i + 16, b);
        v_store_aligned_nocache(dst + i + 32, c);
        v_store_aligned_nocache(dst + i + 48, d);
    }
    for (; i + 16 <= size; i += 16)
        v_store_aligned_nocache(dst + i, v_load(src + i));
#endif
    std::memcpy(dst + i, src + i, size - i);
}

//! Orders the streaming stores before the stores that follow (they bypass the usual order).
inline void streamingStoresDone()
{
#if CV_SSE2
    _mm_sfence();
#else
    std::atomic_thread_fence(std::memory_order_seq_cst);
#endif
}

//! Bits 0 .. n - 1 set, for n in [0, 64].
inline uint64_t rowsBelow(int n)
{
    return n >= 64 ? ~uint64_t(0) : (uint64_t(1) << n) - 1;
}

/** Which pixels of a band are final, one bit per pixel, so a span tests 64 pixels at a time. */
class CoverageBits {
public:
    //! Room for `rows` rows of `width` pixels; call clear() before use.
    void reset(int rows, int width)
    {
        wordsPerRow_ = (width + 63) / 64;
        bits_.resize(size_t(rows) * wordsPerRow_);
        knownFinal_.resize(wordsPerRow_);
    }

    size_t capacityBytes() const
    {
        return (bits_.capacity() + knownFinal_.capacity()) * sizeof(uint64_t);
    }

    void clear()
    {
        std::fill(bits_.begin(), bits_.end(), uint64_t(0));
        std::fill(knownFinal_.begin(), knownFinal_.end(), uint64_t(0));
    }

    //! Row r's bits, 64 pixels a word.
    const uint64_t* row(int r) const { return bits_.data() + size_t(r) * wordsPerRow_; }

    /** Bit r - rowBegin is set when pixels [colFirst, colLast] of row r are all final, for r in
    [rowBegin, rowEnd) (at most 64 rows): a face whose box lies within such rows adds nothing
    there. An occlusion test per face, far cheaper than walking it. With kUntilOpenRow, stops at
    the first open row found, and then reports only some of the final rows (none, or those above
    it): enough to tell whether any row is open.

    Boxes over two words or kRowScanRows rows are scanned a word column at a time by
    finalRowsByColumn, which remembers the words it sees wholly final; the others a row at a
    time. */
    template <bool kUntilOpenRow = false>
    uint64_t finalRows(int rowBegin, int rowEnd, int colFirst, int colLast)
    {
        const int first = colFirst >> 6, last = colLast >> 6;
        const uint64_t firstMask = ~uint64_t(0) << (colFirst & 63);
        const uint64_t lastMask = ~uint64_t(0) >> (63 - (colLast & 63));
        if (rowEnd - rowBegin > kRowScanRows || last > first + 1)
            return finalRowsByColumn<kUntilOpenRow>(rowBegin, rowEnd, first, last, firstMask,
                                                    lastMask);
        const uint64_t* words = bits_.data() + size_t(rowBegin) * wordsPerRow_;
        const uint64_t all = ~uint64_t(0);
        uint64_t result = 0;
        // One loop per box shape, so the rows' loop has no branch but its own.
        auto scan = [&](auto&& rowFinal) {
            for (int r = 0; r < rowEnd - rowBegin; r++, words += wordsPerRow_) {
                const bool final = rowFinal(words);
                result |= uint64_t(final) << r;
                if (kUntilOpenRow && !final)
                    break;
            }
        };
        // Bits outside the box are counted as final.
        if (first == last) {
            const uint64_t outside = ~(firstMask & lastMask);
            scan([&](const uint64_t* w) { return (w[first] | outside) == all; });
        } else {
            scan([&](const uint64_t* w) {
                return ((w[first] | ~firstMask) & (w[last] | ~lastMask)) == all;
            });
        }
        return result;
    }

    /** Marks [xBegin, xEnd) of `row` final and calls run(a, b), left to right, for every maximal
    run [a, b) of it that was not final before. Returns the pixels newly marked. */
    template <typename RunFn>
    int claim(int row, int xBegin, int xEnd, RunFn&& run)
    {
        uint64_t* words = bits_.data() + size_t(row) * wordsPerRow_;
        uint64_t* const at = words + (xBegin >> 6);
        const int wordX = xBegin & ~63;  // the column of at[0]'s bit 0
        int a = xBegin, b = xEnd;        // the one new run, where there is one
        if ((xBegin >> 6) == ((xEnd - 1) >> 6)) {
            // The common case for small faces: one word, and the span wholly new or wholly taken.
            const uint64_t span = (~uint64_t(0) >> (64 - (xEnd - xBegin))) << (xBegin & 63);
            const uint64_t fresh = span & ~at[0];
            if (fresh != span)  // wholly final, or runs for the run finder
                return fresh == 0 ? 0 : claimRuns(words, xBegin, xEnd, std::decay_t<RunFn>(run));
            at[0] |= span;
        } else if ((xBegin >> 6) + 1 == ((xEnd - 1) >> 6)) {
            // Two words: wholly final (common for the spans of faces deep in a stack), or new
            // in one run (near the front of one), without the run finder.
            const uint64_t head = ~uint64_t(0) << (xBegin & 63);
            const uint64_t tail = ~uint64_t(0) >> (63 - ((xEnd - 1) & 63));
            const uint64_t fresh0 = head & ~at[0], fresh1 = tail & ~at[1];
            if (fresh0 != head || fresh1 != tail) {
                if ((fresh0 | fresh1) == 0)
                    return 0;
                if (!isOneRun(fresh0 | UInt128(fresh1) << 64))
                    return claimRuns(words, xBegin, xEnd, std::decay_t<RunFn>(run));
                a = wordX + (fresh0 ? ctz(fresh0) : 64 + ctz(fresh1));
                b = wordX +
                    (fresh1 ? 128 - __builtin_clzll(fresh1) : 64 - __builtin_clzll(fresh0));
            }
            at[0] |= head;
            at[1] |= tail;
        } else {
            // `run` copied on this rare path, not passed on by reference (17M fewer instructions
            // a frame on bigsphere2048 with the callback's captures by copy; GCC still stores
            // part of the closure before the fast paths).
            return claimRuns(words, xBegin, xEnd, std::decay_t<RunFn>(run));
        }
        // One call of `run` for every fast path: a second inlined copy of it cost the knot in
        // painter's order 1-2% (history).
        run(a, b);
        return b - a;
    }

private:
    //! Boxes of up to this many rows within two words are scanned row by row, without
    //! knownFinal_ (cheaper for the small boxes of most faces).
    static constexpr int kRowScanRows = 16;

    /** finalRows for big boxes (over two words or kRowScanRows rows), a 64-pixel word column
    at a time, remembering the words found wholly final (knownFinal_): final pixels stay final,
    so a later box over the same words skips them, and a box hidden behind what earlier tests
    saw costs a load per column instead of one per row and word. Only these tests write the
    summary, not the claims: kept by the claims, for their many tiny spans, a summary cost more
    than it saved (history). With kUntilOpenRow the box's first row is tried first, across all
    its words, where most visible faces show: a column at a time, an open sample in a later
    column is found only after the earlier columns' rows. Out of line, so that the band loop
    testing small boxes stays as it was. */
    template <bool kUntilOpenRow>
    __attribute__((noinline)) uint64_t finalRowsByColumn(int rowBegin, int rowEnd, int first,
                                                         int last, uint64_t firstMask,
                                                         uint64_t lastMask)
    {
        const uint64_t all = ~uint64_t(0);
        if (kUntilOpenRow) {
            const uint64_t* words = bits_.data() + size_t(rowBegin) * wordsPerRow_;
            bool final = first == last
                             ? (words[first] | ~(firstMask & lastMask)) == all
                             : ((words[first] | ~firstMask) & (words[last] | ~lastMask)) == all;
            for (int w = first + 1; w < last && final; w++)
                final = words[w] == all;
            if (!final)
                return 0;
        }
        const uint64_t rows = rowsBelow(rowEnd - rowBegin) << rowBegin;
        uint64_t result = rows;  // the rows not found open yet
        for (int w = first; w <= last && result != 0; w++) {
            const uint64_t outside =
                ~((w == first ? firstMask : all) & (w == last ? lastMask : all));
            uint64_t known = knownFinal_[w];
            const uint64_t* column = bits_.data() + w;
            for (uint64_t unknown = result & ~known; unknown != 0; unknown &= unknown - 1) {
                const int r = ctz(unknown);
                const uint64_t word = column[size_t(r) * wordsPerRow_];
                // Without branches where the whole box is scanned: often mispredicted.
                known |= uint64_t(word == all) << r;
                const bool open = (word | outside) != all;
                if (kUntilOpenRow) {
                    if (open) {
                        knownFinal_[w] = known;
                        return 0;  // fewer final rows than there are: allowed
                    }
                } else {
                    result &= ~(uint64_t(open) << r);
                }
            }
            knownFinal_[w] = known;
        }
        return result >> rowBegin;
    }

    template <typename RunFn>
    __attribute__((noinline)) static int claimRuns(uint64_t* words, int xBegin, int xEnd, RunFn run)
    {
        int claimed = 0;
        int runBegin = 0, runEnd = -1;  // the run found last, held back: the next may extend it
        for (int x = xBegin; x < xEnd;) {
            const int word = x >> 6, first = x & 63;
            const int count = std::min(xEnd - x, 64 - first);
            const uint64_t span = (~uint64_t(0) >> (64 - count)) << first;
            uint64_t fresh = span & ~words[word];
            words[word] |= span;
            while (fresh) {
                const int a = ctz(fresh);
                const uint64_t rest = ~(fresh >> a);  // zero bits mark the run
                const int len = rest == 0 ? 64 - a : ctz(rest);
                const int begin = word * 64 + a;
                if (begin != runEnd) {  // not a continuation across the word boundary
                    if (runEnd >= 0)
                        run(runBegin, runEnd);
                    runBegin = begin;
                }
                runEnd = begin + len;
                claimed += len;
                fresh &= len + a >= 64 ? 0 : ~uint64_t(0) << (a + len);
            }
            x += count;
        }
        if (runEnd >= 0)
            run(runBegin, runEnd);
        return claimed;
    }

    static int ctz(uint64_t v) { return __builtin_ctzll(v); }  // v != 0

    //! Whether the set bits of v (not 0) are consecutive: adding its lowest carries them all out.
    static bool isOneRun(UInt128 v)
    {
        return ((v + (v & (~v + 1))) & v) == 0;
    }

    int wordsPerRow_ = 0;
    std::vector<uint64_t> bits_;
    //! Per word column, bit r: row r's word is wholly final, as far as finalRowsByColumn saw.
    std::vector<uint64_t> knownFinal_;
};

/** What a face-order band's depth row holds where no face has taken the sample yet: a NaN, which
every face takes (`!(NaN < depth)`), which ties with none, and which tells the samples left for
the background once the faces are drawn (paintUntouched). */
constexpr double kUntouchedDepth = std::numeric_limits<double>::quiet_NaN();

/** The first sample of depths[x .. end) that is (`untouched`) or is not (`!untouched`) still
kUntouchedDepth, or end. */
template <bool untouched>
inline int nextWhereUntouched(const double* depths, int x, int end)
{
#if OPENCV_SHADING_SIMD128 && CV_SIMD128_64F
    // Four samples a step, past those that are all taken (untouched) or all untouched: a taken
    // sample equals itself, a NaN does not.
    const int passed = untouched ? 0xf : 0;
#if CV_AVX2
    for (; x + 8 <= end; x += 8) {
        const v_float64x4 a = v256_load(depths + x), b = v256_load(depths + x + 4);
        const int taken = v_signmask(a == a), takenNext = v_signmask(b == b);
        if (taken != passed || takenNext != passed)
            break;
    }
#endif
    for (; x + 4 <= end; x += 4) {
        const v_float64x2 a = v_load(depths + x), b = v_load(depths + x + 2);
        if ((v_signmask(a == a) | v_signmask(b == b) << 2) != passed)
            break;
    }
#endif
    while (x < end && (depths[x] == depths[x]) == untouched)
        x++;
    return x;
}

/** Draws a small face's samples found in a block of rows kRowBits samples wide: bit
kRowBits r + c is sample (firstColumn + c, firstRow + r). Each is tested and stored as
paintSpan's tiny spans do (it takes the face where no nearer depth is stored), without a branch:
where a closed surface's faces overlap, which samples take a face is not predictable, and a
sample that does not take it stores into a discarded pixel and depth. A pen per row, from the
row's first sample as the walk's span starts there, where the shader reads weights (Gouraud);
one for the face otherwise. nearestAt, pixelAt: the block's first sample in the band's depths
and on the canvas; depthOffset and pixelOffset: each bit's offsets from them, in bytes, and
depthRowBytes, pixelRowBytes their rows' steps: with a pen per row, rows are walked one by one,
each sample's addresses the row's plus its column scaled (biggrid2048 in Gouraud 0.90-0.95x the
time; so walked, flat's 8 x 8 blocks took sphere512 1.05-1.08x, and keep the table). */
template <int kRowBits, bool kPenPerRow, typename T, typename SmallShader>
__attribute__((always_inline)) inline void putBlockSamples(uint64_t samples,
                                                           const SmallShader& shader,
                                                           int firstRow, int firstColumn,
                                                           double depth, uchar* nearestAt,
                                                           uchar* pixelAt,
                                                           const ptrdiff_t* depthOffset,
                                                           const ptrdiff_t* pixelOffset,
                                                           ptrdiff_t depthRowBytes,
                                                           ptrdiff_t pixelRowBytes)
{
    constexpr uint64_t kRow = (uint64_t(1) << kRowBits) - 1;
    // GCC 12 makes the discarded stores a branch over them, never taken where each sample is
    // drawn once (the million-face grid).
    double discardedDepth;
    T discardedPixel[3];
    auto put = [&](uint64_t bits, const auto& pen) {
        for (; bits; bits &= bits - 1) {
            const unsigned bit = unsigned(__builtin_ctzll(bits));
            double* const nearest = reinterpret_cast<double*>(nearestAt + depthOffset[bit]);
            const bool takes = !(*nearest < depth);
            *(takes ? nearest : &discardedDepth) = depth;
            pen.put(takes ? reinterpret_cast<T*>(pixelAt + pixelOffset[bit]) : discardedPixel,
                    firstColumn + int(bit % kRowBits));
        }
    };
    const TriangleSetup unread{};  // a small face's shader reads no setup
    if constexpr (!kPenPerRow) {
        (void)depthRowBytes, (void)pixelRowBytes;
        put(samples, shader.pen(unread, firstRow, firstColumn));
    } else {
        for (int row = firstRow; samples; row++) {
            if (const uint64_t inRow = samples & kRow) {
                const int first = __builtin_ctzll(inRow);
                const auto pen = shader.pen(unread, row, firstColumn + first);
                double* const nearestRow = reinterpret_cast<double*>(nearestAt);
                T* const pixelRow = reinterpret_cast<T*>(pixelAt);
                for (uint64_t bits = inRow; bits; bits &= bits - 1) {
                    const int column = __builtin_ctzll(bits);
                    double* const nearest = nearestRow + column;
                    const bool takes = !(*nearest < depth);
                    *(takes ? nearest : &discardedDepth) = depth;
                    pen.put(takes ? pixelRow + 3 * column : discardedPixel, firstColumn + column);
                }
            }
            samples >>= kRowBits;
            if (samples)  // (never a row past the block's last)
                nearestAt += depthRowBytes, pixelAt += pixelRowBytes;
        }
    }
}

/** Bits 0-3: which of depths[0 .. 4) are not nearer than `depth` (`!(d < depth)`: untouched
samples too). Reads four samples whatever the box it tests: the caller masks the bits. */
__attribute__((always_inline)) inline unsigned notNearerFour(const double* depths, double depth)
{
#if OPENCV_SHADING_SIMD128 && CV_SIMD128_64F
#if CV_AVX2
    const int nearer = v_signmask(v256_load(depths) < v256_setall_f64(depth));
#else
    const v_float64x2 d = v_setall_f64(depth);
    const int nearer = v_signmask(v_load(depths) < d) | v_signmask(v_load(depths + 2) < d) << 2;
#endif
    return ~unsigned(nearer) & 0xfu;
#else
    unsigned bits = 0;
    for (int i = 0; i < 4; i++)
        bits |= unsigned(!(depths[i] < depth)) << i;
    return bits;
#endif
}

/** Sets the pixels of `row` whose samples in `depths` (a face-order band's row of `columns`) no
face took to `color`: the background, painted after the faces instead of under them, so that a
covered pixel is written once. */
template <typename T>
inline void paintUntouched(T* row, const double* depths, int columns, const T color[3])
{
    for (int x = nextWhereUntouched<true>(depths, 0, columns); x < columns;) {
        const int end = nextWhereUntouched<false>(depths, x + 1, columns);
        fillPixels(row, x, end, color);
        x = nextWhereUntouched<true>(depths, end, columns);
    }
}

/** The depth test that draws the painter's image in face order: the samples of [xBegin, xEnd)
whose nearest depth so far (`nearest`, kUntouchedDepth where none) is not nearer than `depth`
take it, and `fn(a, b)` is called for each maximal run [a, b) of them. A face drawn later wins
a tie, as the painter's stable order draws it on top. */
template <typename RunFn>
__attribute__((always_inline)) inline void takeNearerOrEqual(double* nearest, int xBegin,
                                                             int xEnd, double depth, RunFn&& fn)
{
    for (int x = xBegin; x < xEnd;) {
        while (x < xEnd && nearest[x] < depth)  // behind a nearer face
            x++;
        const int runBegin = x;
        for (; x < xEnd && !(nearest[x] < depth); x++)
            nearest[x] = depth;
        if (runBegin < x)
            fn(runBegin, x);
    }
}

/** log2 of the rows per band: 64, the most the band pass's row bit masks hold. Taller bands mean
fewer faces crossing a band boundary, each sorted, tested and set up once per band it crosses:
32 rows instead of 16 cut the instructions per render by 7% on the 512 x 512 demo, 64 instead
of 16 by 13% on the deep random 2048 x 2048 scene; 64 instead of 32 took the demo 3-6% less
time with 2 threads, random512 10%. Where that leaves few bands per thread, the threads still
finish together, as runs end within bands (at a quarter) and the last bands are shared in
halves (BandSchedule). */
constexpr int kBandRowsLog2 = 6;

/** log2 of the rows of a band painted back to front at a time: 32 rows while that is at most
256 KB of canvas, else 16, so the rows being overwritten stay in a core's L2 cache. (Front to
back writes each pixel once, so a whole band at a time costs nothing there.) */
inline int paintRowsLog2For(const Mat& canvas)
{
    const size_t rowBytes = size_t(canvas.cols) * canvas.elemSize();
    return rowBytes * 32 <= (256 << 10) ? 5 : 4;
}

/** A band's z-buffer bookkeeping: per sample whether this draw wrote it (a bit) and if so the
face keeping it, and per block of 8 samples of a row an upper bound of the depths written there.
A face whose box holds only written samples, in blocks bounded by less than its nearest depth,
is hidden: nothing of it can pass the depth test. Blocks of 8 match small faces: a closed
surface's back faces hide behind front faces a few pixels wide. */
class ZBufferBlocks {
public:
    void reset(int rows, int width)
    {
        width_ = width;
        wordsPerRow_ = (width + 63) / 64;
        blocksPerRow_ = wordsPerRow_ << (6 - kDepthBoundShift);
        kept_.resize(size_t(rows) * width);  // read only where covered_ has the sample
        covered_.assign(size_t(rows) * wordsPerRow_, 0);
        bound_.assign(size_t(rows) * blocksPerRow_, 0.f);
    }

    int* keptRow(int r) { return kept_.data() + size_t(r) * width_; }
    uint64_t* coveredRow(int r) { return covered_.data() + size_t(r) * wordsPerRow_; }
    float* boundRow(int r) { return bound_.data() + size_t(r) * blocksPerRow_; }

    //! Whether rows [r0, r1), columns [c0, c1] are written and all nearer than `nearest`.
    __attribute__((always_inline)) bool hidden(int r0, int r1, int c0, int c1, float nearest) const
    {
        const int w0 = c0 >> 6, w1 = c1 >> 6;
        const int b0 = c0 >> kDepthBoundShift, b1 = c1 >> kDepthBoundShift;
        const uint64_t firstMask = ~uint64_t(0) << (c0 & 63);
        const uint64_t lastMask = ~uint64_t(0) >> (63 - (c1 & 63));
        for (int r = r0; r < r1; r++) {
            const uint64_t* covered = covered_.data() + size_t(r) * wordsPerRow_;
            const float* bound = bound_.data() + size_t(r) * blocksPerRow_;
            for (int b = b0; b <= b1; b++)
                if (!(bound[b] < nearest))
                    return false;
            if (w0 == w1) {
                if ((covered[w0] & firstMask & lastMask) != (firstMask & lastMask))
                    return false;
            } else {
                if ((covered[w0] & firstMask) != firstMask || (covered[w1] & lastMask) != lastMask)
                    return false;
                for (int w = w0 + 1; w < w1; w++)
                    if (covered[w] != ~uint64_t(0))
                        return false;
            }
        }
        return true;
    }

    size_t capacityBytes() const
    {
        return kept_.capacity() * sizeof(int) + covered_.capacity() * sizeof(uint64_t) +
               bound_.capacity() * sizeof(float);
    }

private:
    int width_ = 0, wordsPerRow_ = 0, blocksPerRow_ = 0;
    std::vector<int> kept_;
    std::vector<uint64_t> covered_;
    std::vector<float> bound_;
};

OPENCV_SHADING_ISA_END

/** A mesh as the band pass reads it: normalised and validated at the API edge. */
struct MeshData {
    //! The vertices (the caller's floats, or `vertexStorage`); unused when `snapped` is given.
    PointRows vertices;
    std::vector<Point2d> vertexStorage;  //!< the vertices, where they are not the caller's
    //! The vertices already snapped (snapToGrid), or empty: the band pass snaps `vertices`.
    std::vector<FixedPoint> snapped;
    FaceRows faces;                 //!< indices checked against vertices
    std::vector<Vec3i> faceStorage;  //!< the faces, where they are not the caller's
    Rows3 colors;  //!< one per vertex: the caller's floats, or `colorStorage`
    std::vector<Vec3d> colorStorage;  //!< the colours, where they are not the caller's
    //! Every colour is within +-kGouraudColorLimit (gouraudInRange); false when not known.
    bool colorsInGouraudRange = false;
    std::vector<double> depth;  //!< one per vertex, or empty: draw in face order (or by faceDepth)
    //! The caller's depths (continuous CV_32F), read where they are (`depth` is then empty).
    const float* depthFloats = nullptr;
    //! One per face, or empty: the painter's key of each face instead of its vertices' mean
    //! depth (3D: the mean camera depth of the face a clipped piece comes from).
    std::vector<double> faceDepth;

    size_t capacityBytes() const
    {
        return vertexStorage.capacity() * sizeof(Point2d) +
               snapped.capacity() * sizeof(FixedPoint) +
               faceStorage.capacity() * sizeof(Vec3i) +
               colorStorage.capacity() * sizeof(Vec3d) +
               (depth.capacity() + faceDepth.capacity()) * sizeof(double);
    }
};

OPENCV_SHADING_ISA_BEGIN

/** The per-face and per-vertex buffers of a mesh draw, kept by each calling thread between calls:
fresh ones would be fresh pages, and their page faults cost more than drawing a small mesh. */
struct MeshWorkspace {
    std::vector<FixedPoint> snapped;  //!< per vertex
    //! Per vertex, where the 8-face steps run: x's low 32 bits, then y's (see narrowPointWords).
    std::vector<uint64_t> narrowPoints;
    std::vector<double> depths;       //!< per face: its key from its vertices' depths
    std::vector<SampleBox> boxes;     //!< per face; no rows: culled
    std::vector<uint64_t> binned;     //!< per face and band it crosses
    std::vector<uint32_t> binnedFaces;  //!< the same, where every band is in face order
    std::vector<uint8_t> clockwise;   //!< per boxed face: 1 where wound clockwise (y down)

    //! Calls after one that needed more than this reallocate instead of holding it.
    static constexpr size_t kKeepBytes = size_t(256) << 20;

    size_t capacityBytes() const
    {
        return snapped.capacity() * sizeof(FixedPoint) +
               narrowPoints.capacity() * sizeof(uint64_t) + depths.capacity() * sizeof(double) +
               boxes.capacity() * sizeof(SampleBox) + binned.capacity() * sizeof(uint64_t) +
               binnedFaces.capacity() * sizeof(uint32_t) + clockwise.capacity();
    }

    static MeshWorkspace& ofThisThread()
    {
        thread_local MeshWorkspace workspace;
        return workspace;
    }
};

/** A band's scratch, kept by each thread that draws bands between calls (as MeshWorkspace):
fresh buffers of this size come from fresh pages, whose faults cost more than a small band. */
struct BandWorkspace {
    CoverageBits coverage;
    std::vector<uint64_t> scratch;                        //!< sortBandEntries'
    std::vector<std::pair<double, uint64_t>> refineRun;  //!< refineEqualKeys'
    std::vector<uchar> tile;         //!< streamed bands: their rows, drawn before streaming
    ZBufferBlocks zbuffer;           //!< depth-tested drawing: see BandOptions
    std::vector<float> keptWeights;  //!< deferred: per band sample, its kept face's weights
    std::vector<int> keptFaces;      //!< deferred painter's: per band sample, its face
    std::vector<double> bandDepths;   //!< painted in face order: per band sample, its depth
    std::vector<uint64_t> partEntries;  //!< parts of bands: the entries reaching their rows
    std::vector<int> splitFaces;  //!< closed surfaces in face order: the faces by winding

    size_t capacityBytes() const
    {
        return coverage.capacityBytes() +
               (scratch.capacity() + partEntries.capacity()) * sizeof(uint64_t) +
               refineRun.capacity() * sizeof(refineRun[0]) + tile.capacity() +
               zbuffer.capacityBytes() + keptWeights.capacity() * sizeof(float) +
               (keptFaces.capacity() + splitFaces.capacity()) * sizeof(int) +
               bandDepths.capacity() * sizeof(double);
    }

    static BandWorkspace& ofThisThread()
    {
        thread_local BandWorkspace workspace;
        return workspace;
    }
};

//! The background as the canvas's pixel type, in `storage`; null without one.
template <typename T>
inline const Vec<T, 3>* backgroundAs(const Scalar* background, Vec<T, 3>& storage)
{
    if (!background)
        return nullptr;
    for (int k = 0; k < 3; k++)
        storage[k] = saturate_cast<T>((*background)[k]);
    return &storage;
}

/** The span shaders of the 2D functions: built from the colours of a face's vertices. */
template <class ShaderType>
struct VertexColorShaders {
    using Shader = ShaderType;
    using SmallShader = typename Shader::Small;
    static constexpr bool kZBuffer = false;  //!< no depth-tested drawing (see ZBufferBlocks)
    //! No colours computed per set-up face (see SurfaceShaders::lightFaces).
    static constexpr bool kLightsFaces = false;
    const Vec3d* colors;  //!< one per vertex, unless colorFloats holds them
    //! Every colour is within the Gouraud shader's range (gouraudInRange), checked once.
    bool colorsInRange = false;
    //! The caller's colours (3 floats a vertex), or null: read where they are (flat only).
    const float* colorFloats = nullptr;

    void prefetchVertex(int vertex) const
    {
        if (colorFloats)
            __builtin_prefetch(colorFloats + 3 * size_t(vertex));
        else
            __builtin_prefetch(&colors[vertex]);
    }

    //! Called before a band's rows [y0, y1) are drawn: nothing to prepare.
    void beginBand(int /*y0*/, int /*y1*/) const {}

    /** build(c), c[i] pointing at the colour of vertex f[i]: in `colors` (Vec3d), or for flat
    shading in colorFloats (Vec3f), which its shader reads as they are. */
    template <typename Build>
    __attribute__((always_inline)) auto withColors(const Vec3i& f, Build&& build) const
    {
        // Gouraud always reads `colors` (readMesh): no second form of its shaders' setup,
        // whose code in the band unit then took 1.03-1.05x longer on biggrid2048.
        if constexpr (!Shader::kReadsWeights)
            if (colorFloats) {
                const Vec3f* const given = reinterpret_cast<const Vec3f*>(colorFloats);
                const Vec3f* const c[3] = {&given[f[0]], &given[f[1]], &given[f[2]]};
                return build(c);
            }
        const Vec3d* const c[3] = {&colors[f[0]], &colors[f[1]], &colors[f[2]]};
        return build(c);
    }

    Shader make(const TriangleSetup& t, const int* order, const Vec3i& f, int /*face*/) const
    {
        return withColors(f, [&](const auto* const* c) {
            return Shader(t, order, c, colorsInRange);
        });
    }

    //! Small faces' shaders give Shader's values for every face: Gouraud's where every colour
    //! is in range (they never shade per pixel).
    bool smallShadersFit() const { return !Shader::kReadsWeights || colorsInRange; }

    //! make() for a small face set up with others (setUpSmallFaces), for shaders that read
    //! their weights.
    SmallShader makeSmall(const SmallWeights& w, const int* order, const Vec3i& f,
                          int /*face*/) const
    {
        return withColors(f, [&](const auto* const* c) { return SmallShader(w, order, c); });
    }
};

/** Build with -DOPENCV_SHADING_STAGE_TIMES=1 to print each mesh draw's stage times (ms) to
stderr: where the time of a big mesh goes, at any thread count (a measuring aid, off by
default). */
#ifndef OPENCV_SHADING_STAGE_TIMES
#define OPENCV_SHADING_STAGE_TIMES 0
#endif

class StageTimer {
public:
    void mark(const char* stage)
    {
#if OPENCV_SHADING_STAGE_TIMES
        // Printed once the draw is done: a write to stderr between stages would be timed too.
        const int64 now = getTickCount();
        line_ += format("%s %.3f ms%s", stage, double(now - last_) * 1000.0 / getTickFrequency(),
                        std::strcmp(stage, "bands") == 0 ? "\n" : ", ");
        if (std::strcmp(stage, "bands") == 0)
            std::fputs(line_.c_str(), stderr);
        last_ = getTickCount();
#else
        (void)stage;
#endif
    }

#if OPENCV_SHADING_STAGE_TIMES
    //! Adds `text` to the line printed at the end.
    void note(const std::string& text) { line_ += text; }
#endif

private:
#if OPENCV_SHADING_STAGE_TIMES
    std::string line_;
    int64 last_ = getTickCount();
#endif
};

/** 1 where the first pass boxes 8 faces a step in 256-bit lanes, gathering their vertices, and
snapping takes two vertices a step: the AVX2 build. The baseline (SSE2, no gather instruction)
keeps the loops of one face and one vertex a step. */
#if OPENCV_SHADING_SIMD128 && CV_SIMD256
#define OPENCV_SHADING_BOX_EIGHT 1
#else
#define OPENCV_SHADING_BOX_EIGHT 0
#endif

#if OPENCV_SHADING_BOX_EIGHT
//! tab[idx[0..3]]. (v256_lut's gather starts from an undefined register, which GCC 12 warns of.)
inline v_float64x4 gatherDoubles(const double* tab, const int* idx)
{
    const __m256d all = _mm256_castsi256_pd(_mm256_set1_epi64x(-1));
    return v_float64x4(_mm256_mask_i32gather_pd(
        _mm256_setzero_pd(), tab, _mm_loadu_si128(reinterpret_cast<const __m128i*>(idx)), all, 8));
}

//! tab[idx[0..3]] as doubles (float to double is exact).
inline v_float64x4 gatherFloatsAsDoubles(const float* tab, const int* idx)
{
    const __m128 all = _mm_castsi128_ps(_mm_set1_epi32(-1));
    return v_float64x4(_mm256_cvtps_pd(_mm_mask_i32gather_ps(
        _mm_setzero_ps(), tab, _mm_loadu_si128(reinterpret_cast<const __m128i*>(idx)), all, 4)));
}
#endif

#if OPENCV_SHADING_BOX_EIGHT
//! Two points' coordinates, as doubles (float to double is exact).
inline __m256d twoPointsAt(const Point2d* p)
{
    return _mm256_loadu_pd(&p->x);
}
inline __m256d twoPointsAt(const Point2f* p)
{
    return _mm256_cvtps_pd(_mm_loadu_ps(&p->x));
}
#endif

/** The first pass's 8-face steps read each vertex as one 64-bit word, x's low 32 bits then
y's, which hold the coordinates where every vertex is narrow: two 4-lane gathers of them a
corner instead of two 8-lane gathers of 32-bit words from the 16-byte points, half the elements
(on the Zen 4 VM, 1.5 ns a face against 2.8 in cache). */
inline void narrowPointWords(const FixedPoint* in, uint64_t* out, int count)
{
    for (int i = 0; i < count; i++)
        out[i] = uint64_t(uint32_t(in[i].x)) | uint64_t(uint32_t(in[i].y)) << 32;
}

/** Snaps in[0 .. count) (Point2d, or the caller's Point2f) into out (snapToGrid, bit for bit);
returns whether every vertex is within kNarrowPixels on both axes (NaN is not), so lies on the
narrow grid, and writes each one's narrowPointWords word to narrowOut unless it is null. Only the
AVX2 build, whose first pass uses those, checks and writes them: the baseline returns false. */
template <typename Point>
inline bool snapPoints(const Point* in, FixedPoint* out, [[maybe_unused]] uint64_t* narrowOut,
                       int count)
{
    bool narrow = OPENCV_SHADING_BOX_EIGHT;
    int i = 0;
#if OPENCV_SHADING_BOX_EIGHT
    // A little stricter than the narrow grid (1 px of margin), checked on the input.
    constexpr double kNarrowPixels = double(kNarrowLimit / kSubpixelOne - 1);
    // Two vertices (four coordinates) a step: roundHalfAway as truncation plus the same
    // correction, then the integer-valued double (below 2^51) read off its bits beside 2^52 + 2^51.
    const __m256d scale = _mm256_set1_pd(double(kSubpixelOne)), half = _mm256_set1_pd(0.5);
    const __m256d minusHalf = _mm256_set1_pd(-0.5), one = _mm256_set1_pd(1.0);
    const __m256d magic = _mm256_set1_pd(6755399441055744.0);  // 2^52 + 2^51
    const __m256d absMask = _mm256_castsi256_pd(_mm256_set1_epi64x(INT64_MAX));
    const __m256d maxCoordinate = _mm256_set1_pd(kMaxCoordinate);
    const __m256d narrowBound = _mm256_set1_pd(kNarrowPixels);
    const __m256i invalid = _mm256_set_epi64x(0, kInvalidCoordinate, 0, kInvalidCoordinate);
    __m256d allNarrow = _mm256_castsi256_pd(_mm256_set1_epi64x(-1));
    for (; i + 2 <= count; i += 2) {
        const __m256d v = twoPointsAt(in + i);
        const __m256d magnitude = _mm256_and_pd(v, absMask);
        // A vertex is valid where both of its coordinates are in range (NaN is not).
        const __m256d inRange = _mm256_cmp_pd(magnitude, maxCoordinate, _CMP_LE_OQ);
        const __m256d valid = _mm256_and_pd(inRange, _mm256_permute_pd(inRange, 0x5));
        allNarrow = _mm256_and_pd(allNarrow, _mm256_cmp_pd(magnitude, narrowBound, _CMP_LT_OQ));
        const __m256d scaled = _mm256_mul_pd(v, scale);
        const __m256d truncated = _mm256_round_pd(scaled, _MM_FROUND_TO_ZERO | _MM_FROUND_NO_EXC);
        const __m256d frac = _mm256_sub_pd(scaled, truncated);
        const __m256d up = _mm256_and_pd(_mm256_cmp_pd(frac, half, _CMP_GE_OQ), one);
        const __m256d down = _mm256_and_pd(_mm256_cmp_pd(frac, minusHalf, _CMP_LE_OQ), one);
        const __m256d rounded = _mm256_sub_pd(_mm256_add_pd(truncated, up), down);
        const __m256i bits = _mm256_sub_epi64(_mm256_castpd_si256(_mm256_add_pd(rounded, magic)),
                                              _mm256_castpd_si256(magic));
        const __m256i snappedPair = _mm256_blendv_epi8(invalid, bits, _mm256_castpd_si256(valid));
        _mm256_storeu_si256(reinterpret_cast<__m256i*>(out + i), snappedPair);
        // narrowPointWords' two words: the low 32 bits of each coordinate.
        if (narrowOut)
            _mm_storeu_si128(reinterpret_cast<__m128i*>(narrowOut + i),
                             _mm256_castsi256_si128(_mm256_permutevar8x32_epi32(
                                 snappedPair, _mm256_setr_epi32(0, 2, 4, 6, 0, 2, 4, 6))));
    }
    narrow = _mm256_movemask_pd(allNarrow) == 0xf;
#endif
    for (; i < count; i++) {
        out[i] = snapToGrid(Point2d(in[i].x, in[i].y));
#if OPENCV_SHADING_BOX_EIGHT
        if (narrowOut)
            narrowPointWords(out + i, narrowOut + i, 1);
        narrow &= std::abs(in[i].x) < kNarrowPixels && std::abs(in[i].y) < kNarrowPixels;
#endif
    }
    return narrow;
}

#if OPENCV_SHADING_BOX_EIGHT
/** The x and y of the 8 vertices `index` from narrowPointWords' words, in index order. */
inline void gatherNarrowPoints(const long long* words, const v_int32x8& index, v_int32x8& x,
                               v_int32x8& y)
{
    // Vertices 0, 1, 4, 5 then 2, 3, 6, 7: the shuffles below then leave x and y in order.
    const __m256i order = _mm256_permutevar8x32_epi32(
        index.val, _mm256_setr_epi32(0, 1, 4, 5, 2, 3, 6, 7));
    const __m256 a = _mm256_castsi256_ps(
        _mm256_i32gather_epi64(words, _mm256_castsi256_si128(order), 8));
    const __m256 b = _mm256_castsi256_ps(
        _mm256_i32gather_epi64(words, _mm256_extracti128_si256(order, 1), 8));
    x = v_int32x8(_mm256_castps_si256(_mm256_shuffle_ps(a, b, 0x88)));
    y = v_int32x8(_mm256_castps_si256(_mm256_shuffle_ps(a, b, 0xdd)));
}

/** triangleBox of 8 faces of narrow vertices in 32-bit lanes, the same boxes (xs[j], ys[j]:
corner j's coordinates); `boxed`: all ones where triangleBox returns true. */
struct BoxLanes {
    v_int32x8 rowBegin, rowEnd, colFirst, colLast, boxed;
};
__attribute__((always_inline)) inline BoxLanes triangleBoxEight(const v_int32x8 xs[3],
                                                                const v_int32x8 ys[3], Size size)
{
    const v_int32x8 roundUp = v256_setall_s32(int(kSubpixelOne - 1)), zero = v256_setzero_s32();
    const v_int32x8 lastColumn = v256_setall_s32(size.width - 1);
    auto toPixel = [&](const v_int32x8& fixed, int limit) {
        return v_min(v_max((fixed + roundUp) >> kSubpixelBits, zero), v256_setall_s32(limit));
    };
    const v_int32x8 xMin = v_min(v_min(xs[0], xs[1]), xs[2]);
    const v_int32x8 xMax = v_max(v_max(xs[0], xs[1]), xs[2]);
    const v_int32x8 yMin = v_min(v_min(ys[0], ys[1]), ys[2]);
    const v_int32x8 yMax = v_max(v_max(ys[0], ys[1]), ys[2]);
    BoxLanes box;
    box.rowBegin = toPixel(yMin, size.height);
    box.rowEnd = toPixel(yMax, size.height);
    box.colFirst = v_min(toPixel(xMin, size.width), lastColumn);
    box.colLast = v_min(xMax >> kSubpixelBits, lastColumn);
    box.boxed = (xMax >= zero) & (xMin <= v256_setall_s32(int(size.width * kSubpixelOne))) &
                (box.rowBegin < box.rowEnd) & (box.colFirst <= box.colLast);
    return box;
}
#endif

/** Byte j of of[m]: bit j of m (eight flags from a lane mask, a byte each). */
struct BitBytes {
    uint64_t of[256];
    constexpr BitBytes() : of()
    {
        for (int m = 0; m < 256; m++)
            for (int j = 0; j < 8; j++)
                of[m] |= uint64_t(m >> j & 1) << (8 * j);
    }
};
constexpr BitBytes kBitBytes;

//! Whether a snapped vertex lies on the narrow grid (both coordinates below 2^28 subpixels, so
//! invalid ones do not): every box and area quantity of a face of such vertices fits 32-bit lanes.
inline bool isNarrowPoint(const FixedPoint& p)
{
    return p.x > -kNarrowLimit && p.x < kNarrowLimit && p.y > -kNarrowLimit && p.y < kNarrowLimit;
}

/** What BandSchedule::next hands out: a band, or some consecutive quarters of its rows (16
rows each). */
struct BandPart {
    static constexpr int kQuarters = 4;

    int band;      //!< -1: none left
    int quarter;   //!< the first quarter: 0 (the band's top rows) to 3
    int quarters;  //!< how many, 1 to 4 (4: the whole band)

    bool whole() const { return quarters == kQuarters; }
};

/** Hands the bands out to the threads. Each thread owns a run of consecutive bands of about
equal estimated cost and takes them in order, whole, as neighbouring bands share faces and
vertices still in its caches; a thread done with its run takes bands from the far end of the
run with the most left, so that the threads finish together. With few bands per thread, where one
band is a large share of a thread's work, it works in parts of bands: runs end where their share
of the cost does, within a band (at a quarter); thieves take half bands (a quarter where the run
ends within a half); an owner takes its last band in halves when no other run has a band left;
and threads beyond one per band start as thieves, up to one per half band. A part sets up again
the faces that reach the band's other parts, but a whole band would leave one thread waiting for
the other's last one. */
class BandSchedule {
public:
    /** `quarterCost`: the estimated cost of each band's four quarters, in order. `parts`: runs
    end within bands and bands are shared in parts (else runs and claims are whole bands).
    `splitAll`: every band is taken in parts, a quarter and three, two halves, or four quarters,
    by band (for testing that parts draw what whole bands do). */
    BandSchedule(const std::vector<double>& quarterCost, int workers, bool parts = true,
                 bool splitAll = false)
        : runs_(size_t(std::max(1, std::min(int(quarterCost.size() / kQ), workers)))),
          // Workers beyond one per band only take parts of the others' runs.
          workers_(std::max(1, std::min(int(quarterCost.size() / kQ) *
                                            (parts || splitAll ? 2 : 1),
                                        workers))),
          parts_(parts || splitAll), splitAll_(splitAll)
    {
        const int quarters = int(quarterCost.size() / kQ * kQ), runs = int(runs_.size());
        const int unit = parts_ ? 1 : int(kQ);  // runs end on a quarter, or on a band
        double total = 0;
        for (int q = 0; q < quarters; q++)
            total += quarterCost[q];
        int q = 0;
        double before = 0;  // cost of the quarters of earlier runs
        for (int w = 0; w < runs; w++) {
            const int first = q;
            const double share = total * (w + 1) / runs;
            while (q < quarters) {
                double cost = 0;
                for (int u = q; u < q + unit; u++)
                    cost += quarterCost[u];
                if (w != runs - 1 && before + cost / 2 > share)
                    break;
                before += cost;
                q += unit;
            }
            runs_[w].store(uint64_t(first) << 32 | uint32_t(q), std::memory_order_relaxed);
        }
    }

    //! How many workers to start: one per run, and where parts are taken, up to one per half.
    int workers() const { return workers_; }

    //! The next band or part of one for worker w; band -1 when every one is taken.
    BandPart next(int w)
    {
        if (w < runs()) {
            if (const BandPart part = take(w, true); part.band >= 0)
                return part;
        }
        for (;;) {
            int victim = -1;
            uint32_t most = 0;
            for (int v = 0; v < runs(); v++) {
                const uint64_t run = runs_[v].load(std::memory_order_relaxed);
                const uint32_t left = uint32_t(run) - uint32_t(run >> 32);
                if (uint32_t(run) > uint32_t(run >> 32) && left > most)
                    victim = v, most = left;
            }
            if (victim < 0)
                return {-1, 0, 0};
            if (const BandPart part = take(victim, false); part.band >= 0)
                return part;
        }
    }

private:
    static constexpr uint32_t kQ = BandPart::kQuarters;

    /** Claims from run w: for its owner, from the front, the rest of its next band within the
    run (its last band in halves when no other run has a band left); for a thief, from the far
    end, a half band, or a quarter where the run ends within a half. Band -1 when the run is
    empty. */
    BandPart take(int w, bool owner)
    {
        uint64_t run = runs_[w].load(std::memory_order_relaxed);
        for (;;) {
            const uint32_t begin = uint32_t(run >> 32), end = uint32_t(run);
            if (begin >= end)
                return {-1, 0, 0};
            uint32_t count;
            if (!parts_) {
                count = kQ;  // runs start and end on bands, and every claim is whole
            } else if (owner) {
                const uint32_t left = end - begin;
                const uint32_t piece = std::min(end, (begin / kQ + 1) * kQ) - begin;
                count = piece;
                if (splitAll_) {
                    const uint32_t pattern = begin / kQ % 3;  // 1 + 3, 2 + 2, four quarters
                    count = std::min(piece, pattern == 2 ? 1 : begin % kQ ? piece : 1 + pattern);
                } else if (piece == kQ && piece == left && !othersHaveBand(w)) {
                    count = 2;  // the upper half; the lower one is then the run's last piece
                }
            } else {
                const uint32_t piece = end - std::max(begin, (end - 1) / kQ * kQ);
                count = !splitAll_ && piece >= 2 && end % 2 == 0 ? 2 : 1;
            }
            const uint64_t taken = owner ? run + (uint64_t(count) << 32) : run - count;
            if (runs_[w].compare_exchange_weak(run, taken, std::memory_order_relaxed)) {
                const uint32_t first = owner ? begin : end - count;
                return {int(first / kQ), int(first % kQ), int(count)};
            }
        }
    }

    //! Whether a run other than w's has a band's worth of quarters left.
    bool othersHaveBand(int w) const
    {
        for (int v = 0; v < runs(); v++) {
            const uint64_t run = runs_[v].load(std::memory_order_relaxed);
            if (v != w && uint32_t(run) >= uint32_t(run >> 32) + kQ)
                return true;
        }
        return false;
    }

    int runs() const { return int(runs_.size()); }

    //! Per run (worker): its first quarter band << 32 | its end, in quarter bands.
    std::vector<std::atomic<uint64_t>> runs_;
    int workers_;
    bool parts_, splitAll_;
};

//! A face's cost in a band, in covered samples: fitted to the demo's band times at 1 thread
//! (62 ns a face, 0.6 ns a sample), which the knot in 3D and sphere512 follow too.
constexpr double kBandCostPerFace = 100;

/** How drawMeshInBands treats a mesh beyond the painter's order. */
struct BandOptions {
    /** 3D z-buffer: a sample takes the face of smallest (depth, face index) that is nearer than
    the depth buffer's value (what drawing in face order with a strict test gives), whatever
    order faces come in. Faces come nearest first (their sort key: the mesh's faceDepth, else
    their nearest vertex's depth, a bound no sample of the face is nearer than), each
    sample keeping its face (ZBufferBlocks), and a face whose sample box is covered by nearer
    samples already is skipped before setup. */
    bool depthTested = false;
    /** With depthTested or frontToBack: each sample's face and weights are kept, and the kept
    samples are shaded at the end of the band, a batch at a time (the shaders' keep() and
    shadeKeptRow()), which pays for costly shaders (Phong lighting). */
    bool deferred = false;
    //! Painter's order: always front to back (each pixel shaded once), for costly shaders.
    bool frontToBack = false;
};

/** Draws `mesh` as the painter's algorithm would (faces by decreasing mean depth, ties in face
order), each face coloured by the shader `shaders.make(...)` builds for it. With `background`,
pixels no face covers are set to it (render() needs no separate clear; with the z-buffer, each
band's rows are cleared to it first). See BandOptions for the z-buffer. */
template <class Shaders, typename T>
void drawMeshInBands(Mat& canvas, const MeshData& mesh, const Shaders& shaders,
                     const Vec<T, 3>* background, const BandOptions& options = BandOptions())
{
    using Shader = typename Shaders::Shader;
    const Size size = canvas.size();
    const int faceCount = int(mesh.faces.size());
    const bool byFaceDepth = !mesh.faceDepth.empty();
    const bool depthTested = options.depthTested;
    const bool byDepth = !mesh.depth.empty() || mesh.depthFloats || byFaceDepth;
    const int bandShift = kBandRowsLog2;
    const int bandRows = 1 << bandShift;
    const int paintShift = paintRowsLog2For(canvas);
    const int paintRows = 1 << paintShift;
    const int bandCount = (size.height + bandRows - 1) / bandRows;

    StageTimer timer;
    // Pass 0, parallel over vertices: snap each once (a vertex is shared by ~6 faces), unless
    // the caller did.
    MeshWorkspace& work = MeshWorkspace::ofThisThread();
    const bool snappedGiven = !mesh.snapped.empty() || mesh.vertices.empty();
    const Point2f* const vertexFloats = mesh.vertices.floats();
    const int vertexCount = snappedGiven ? 0 : int(mesh.vertices.size());
    work.snapped.resize(vertexCount);
    const FixedPoint* const snapped = snappedGiven ? mesh.snapped.data() : work.snapped.data();
    constexpr int kVertexChunk = 2048;
    // The first pass's 8-face steps read the low 32 bits of each coordinate (narrowPointWords),
    // which hold it where every vertex is on the narrow grid (checked here), on a canvas whose
    // every box quantity fits 32-bit lanes.
    const int pointCount = snappedGiven ? int(mesh.snapped.size()) : vertexCount;
    const bool boxEightFits =
        OPENCV_SHADING_BOX_EIGHT &&
        int64_t(std::max(size.width, size.height)) * kSubpixelOne < kNarrowLimit;
    std::atomic<bool> allNarrow(boxEightFits);
    const int passCount = boxEightFits ? pointCount : vertexCount;
    work.narrowPoints.resize(boxEightFits ? pointCount : 0);
    parallel_for_(Range(0, (passCount + kVertexChunk - 1) / kVertexChunk), [&](const Range& r) {
        const int end = std::min(passCount, r.end * kVertexChunk);
        const int begin = r.start * kVertexChunk;
        bool narrow = true;
        if (!snappedGiven) {
            // The caller's floats snapped where they are: no copy of them in double.
            FixedPoint* const out = work.snapped.data() + begin;
            uint64_t* const narrowOut = boxEightFits ? work.narrowPoints.data() + begin : nullptr;
            narrow = vertexFloats
                         ? snapPoints(vertexFloats + begin, out, narrowOut, end - begin)
                         : snapPoints(mesh.vertices.doubles() + begin, out, narrowOut, end - begin);
        } else if (boxEightFits) {
            // (drawMesh3d's vertices behind the near plane would otherwise take the whole mesh
            // off the 8-face paths.)
            for (int i = begin; i < end; i++)
                narrow &= isNarrowPoint(snapped[i]) || isUnusedPoint(snapped[i]);
        }
        if (!narrow)
            allNarrow.store(false, std::memory_order_relaxed);
        else if (snappedGiven && boxEightFits)  // while these vertices are in cache
            narrowPointWords(snapped + begin, work.narrowPoints.data() + begin, end - begin);
    });
    [[maybe_unused]] const bool boxEight = allNarrow.load();
#if OPENCV_SHADING_BOX_EIGHT
    // Whether a closed surface's small faces in face order are drawn as sample blocks
    // (paintSampleBlock): flat shaders (a pen for the face, float or 8-bit), 8-lane builds.
    constexpr bool kSampleBlocksBuilt =
        penDraws<typename Shaders::SmallShader, T>() && !Shaders::SmallShader::kReadsWeights &&
        kSmallLanes == 8;
    const bool sampleBlocksDrawn = kSampleBlocksBuilt && boxEight;
#else
    const bool sampleBlocksDrawn = false;
#endif

    timer.mark("snap");
    // Pass 1, parallel over chunks of faces: each face's sort key, the rows it may touch and
    // its area; per chunk, the range of the depths (for quantizing them below) and the faces and
    // area each band receives (for binning).
    // Each face's sort key: the given faceDepth, or from its vertices' depths, computed here:
    // their mean (the painter's order) or, depth-tested, the nearest (culled faces keep stale
    // keys, never used).
    std::vector<double>& depths = work.depths;
    depths.resize(byDepth && !byFaceDepth ? faceCount : 0);
    const double* const faceKeys = byFaceDepth ? mesh.faceDepth.data() : depths.data();
    std::vector<SampleBox>& boxes = work.boxes;
    boxes.resize(faceCount);
    work.clockwise.resize(faceCount);
    // Enough chunks to balance the threads, few enough to bound the per-chunk band tables.
    const int chunkCount = std::min((faceCount + 1023) / 1024, std::max(32, 4 * getNumThreads()));
    const int chunkFaces = chunkCount ? (faceCount + chunkCount - 1) / chunkCount : 0;
    const double inf = std::numeric_limits<double>::infinity();
    std::vector<std::pair<double, double>> chunkDepthRange(chunkCount, {inf, -inf});
    // Per chunk and band: after pass 1, the faces in the low 32 bits and those wound clockwise
    // in the high 32 (one add per face); then the chunk's first slot in the band's list.
    // uint64_t: a face on a tall canvas can cross thousands of bands.
    constexpr uint64_t kClockwiseOne = uint64_t(1) << 32;
    std::vector<uint64_t> binCursor(size_t(chunkCount) * bandCount, 0);
    std::vector<double> binArea(size_t(chunkCount) * bandCount, 0.0);
    auto forEachBand = [&](const SampleBox& b, auto&& fn) {
        if (b.rowBegin < b.rowEnd)
            for (int k = b.rowBegin >> bandShift; k <= (b.rowEnd - 1) >> bandShift; k++)
                fn(k);
    };
    // One loop per way of keying faces, with what it reads in locals: the loop then keeps its
    // state in registers, with no branch on the way.
    auto boxFaces = [&](int chunk, auto kByDepth, auto kByFaceDepth, auto kDepthTested) {
        const Size canvasSize = size;
        const int shift = bandShift, rowsPerBand = bandRows;
        const FixedPoint* const vertexAt = snapped;
        const double* const vertexDepth = mesh.depth.data();
        const float* const vertexDepthFloats = mesh.depthFloats;  // else vertexDepth
        auto depthOf = [vertexDepth, vertexDepthFloats](int v) {
            return vertexDepthFloats ? double(vertexDepthFloats[v]) : vertexDepth[v];
        };
        const double* const givenKey = mesh.faceDepth.data();
        double* const faceKey = depths.data();
        SampleBox* const faceBox = boxes.data();
        uint8_t* const faceClockwise = work.clockwise.data();
        double lo = inf, hi = -inf;  // over finite depths
        uint64_t* count = &binCursor[size_t(chunk) * bandCount];
        double* area = &binArea[size_t(chunk) * bandCount];
        const int end = std::min(faceCount, (chunk + 1) * chunkFaces);
        // A boxed face's share of each band it reaches: its count, winding and area. Consecutive
        // faces within one band (the common case) add up in registers, the same sums in the same
        // order, not through memory (a store and a load of the sum per face: the critical path
        // of the 8-face steps).
        int runBand = -1;
        uint64_t runCount = 0;
        double runArea = 0;
        auto endRun = [&] {
            if (runBand >= 0)
                count[runBand] += runCount, area[runBand] = runArea;
            runBand = -1;
        };
        auto countFace = [&](const SampleBox& box, double signedArea) {
            const double faceArea = std::abs(signedArea);
            const uint64_t counted = 1 + (signedArea > 0 ? kClockwiseOne : 0);  // y points down
            const int firstBand = box.rowBegin >> shift;
            if (firstBand == (box.rowEnd - 1) >> shift) {
                if (firstBand != runBand) {
                    endRun();
                    runBand = firstBand, runCount = 0, runArea = area[firstBand];
                }
                runCount += counted;
                runArea += faceArea;
                return;
            }
            endRun();
            const double areaPerRow = faceArea / (box.rowEnd - box.rowBegin);
            forEachBand(box, [&](int k) {
                count[k] += counted;
                const int inBand = std::min(box.rowEnd, (k + 1) * rowsPerBand) -
                                   std::max(box.rowBegin, k * rowsPerBand);
                area[k] += areaPerRow * inBand;
            });
        };
        auto boxFace = [&](int i) {
            const Vec3i& f = mesh.faces[i];
            SampleBox& box = faceBox[i];
            box.rowBegin = box.rowEnd = 0;  // culled
            if constexpr (decltype(kByDepth)::value) {
                double key;
                if constexpr (decltype(kByFaceDepth)::value) {
                    key = givenKey[i];
                } else {
                    const double d0 = depthOf(f[0]), d1 = depthOf(f[1]), d2 = depthOf(f[2]);
                    key = (d0 + d1 + d2) / 3.0;  // NaN if any is
                    if (decltype(kDepthTested)::value && !std::isnan(key))
                        key = std::min({d0, d1, d2});
                    faceKey[i] = key;
                }
                if (std::isnan(key))
                    return;  // no place in the order: not drawn
                if (std::abs(key) < inf) {
                    lo = std::min(lo, key);
                    hi = std::max(hi, key);
                }
            }
            const FixedPoint p[3] = {vertexAt[f[0]], vertexAt[f[1]], vertexAt[f[2]]};
            if (!triangleBox(p, canvasSize, box)) {
                box.rowBegin = box.rowEnd = 0;
                return;
            }
            // In pixels, for estimating each band's overdraw; the sign gives the winding.
            const double signedArea =
                (double(p[1].x - p[0].x) * double(p[2].y - p[0].y) -
                 double(p[2].x - p[0].x) * double(p[1].y - p[0].y)) *
                (0.5 / double(kSubpixelOne * kSubpixelOne));
            faceClockwise[i] = signedArea > 0;
            countFace(box, signedArea);
        };
        int i = chunk * chunkFaces;
#if OPENCV_SHADING_BOX_EIGHT
        if (boxEight) {
            // boxFace for 8 faces a step, the same keys, boxes and areas bit for bit (the same
            // IEEE operations in the same order, no FMA), in 32-bit lanes from the
            // coordinates' low words (every vertex is narrow).
            const int* const faceWords = reinterpret_cast<const int*>(mesh.faces.data());
            const long long* const pointPairs =
                reinterpret_cast<const long long*>(work.narrowPoints.data());
            const v_int32x8 laneBit(1, 2, 4, 8, 16, 32, 64, 128);
            const v_int32x8 one = v256_setall_s32(1);
            const v_float64x4 third = v256_setall_f64(3.0), infinity = v256_setall_f64(inf),
                              minusInfinity = v256_setall_f64(-inf);
            const v_float64x4 toPixels =
                v256_setall_f64(0.5 / double(kSubpixelOne * kSubpixelOne));
            v_float64x4 lowest = infinity, highest = minusInfinity;
            for (; i + 8 <= end; i += 8) {
                v_int32x8 v0, v1, v2;
                v_load_deinterleave(faceWords + 3 * size_t(i), v0, v1, v2);
                v_int32x8 x0, y0, x1, y1, x2, y2;
                gatherNarrowPoints(pointPairs, v0, x0, y0);
                gatherNarrowPoints(pointPairs, v1, x1, y1);
                gatherNarrowPoints(pointPairs, v2, x2, y2);
                int keyed = 0xff;  // bit j: face i + j has a key (not NaN)
                if constexpr (decltype(kByDepth)::value) {
                    int corner[3][8];
                    v_store(corner[0], v0), v_store(corner[1], v1), v_store(corner[2], v2);
                    for (int h = 0; h < 8; h += 4) {
                        v_float64x4 key;
                        if constexpr (decltype(kByFaceDepth)::value) {
                            key = v256_load(givenKey + i + h);
                        } else {
                            auto depthsAt = [&](const int* vertices) {
                                return vertexDepthFloats
                                           ? gatherFloatsAsDoubles(vertexDepthFloats, vertices)
                                           : gatherDoubles(vertexDepth, vertices);
                            };
                            const v_float64x4 d0 = depthsAt(corner[0] + h),
                                              d1 = depthsAt(corner[1] + h),
                                              d2 = depthsAt(corner[2] + h);
                            key = (d0 + d1 + d2) / third;  // NaN if any is
                            if (decltype(kDepthTested)::value)  // the mean stays where NaN
                                key = v_select(key == key, v_min(v_min(d0, d1), d2), key);
                            v_store(faceKey + i + h, key);
                        }
                        // (OpenCV's != is an ordered compare, false for NaN: hence ==.)
                        keyed &= ~((~v_signmask(key == key) & 0xf) << h);
                        const v_float64x4 finite = v_abs(key) < infinity;
                        lowest = v_min(lowest, v_select(finite, key, infinity));
                        highest = v_max(highest, v_select(finite, key, minusInfinity));
                    }
                }
                const v_int32x8 xs[3] = {x0, x1, x2}, ys[3] = {y0, y1, y2};
                const BoxLanes box = triangleBoxEight(xs, ys, canvasSize);
                const v_int32x8 rowBegin = box.rowBegin, rowEnd = box.rowEnd;
                const int drawn = v_signmask(box.boxed) & keyed;
                const v_int32x8 drawnMask = (v256_setall_s32(drawn) & laneBit) == laneBit;
                v_store_interleave(reinterpret_cast<int*>(faceBox + i), rowBegin & drawnMask,
                                   rowEnd & drawnMask, box.colFirst, box.colLast);
                if (!drawn)
                    continue;
                // The area as boxFace computes it, from the same exact differences.
                const v_int32x8 dx1 = x1 - x0, dy2 = y2 - y0, dx2 = x2 - x0, dy1 = y1 - y0;
                const v_float64x4 areaLow = (v_cvt_f64(dx1) * v_cvt_f64(dy2) -
                                             v_cvt_f64(dx2) * v_cvt_f64(dy1)) * toPixels;
                const v_float64x4 areaHigh = (v_cvt_f64_high(dx1) * v_cvt_f64_high(dy2) -
                                              v_cvt_f64_high(dx2) * v_cvt_f64_high(dy1)) *
                                             toPixels;
                const v_float64x4 zeroArea = v256_setzero_f64();
                const int clockwise = v_signmask(areaLow > zeroArea) |
                                      v_signmask(areaHigh > zeroArea) << 4;
                const uint64_t clockwiseBytes = kBitBytes.of[clockwise];
                std::memcpy(faceClockwise + i, &clockwiseBytes, sizeof(clockwiseBytes));
                // All eight within the band of the faces before them (a mesh's neighbours
                // mostly are): countFace's sums, added in a tree (they only estimate costs).
                const v_int32x8 inRun = v256_setall_s32(runBand);
                if (drawn == 0xff && v_check_all(((rowBegin >> shift) == inRun) &
                                                 (((rowEnd - one) >> shift) == inRun))) {
                    runCount += 8 + (uint64_t(__builtin_popcount(clockwise)) << 32);
                    runArea += v_reduce_sum(v_abs(areaLow) + v_abs(areaHigh));
                    continue;
                }
                double signedArea[8];
                v_store(signedArea, areaLow);
                v_store(signedArea + 4, areaHigh);
                for (int j = 0; j < 8; j++)
                    if (drawn >> j & 1)
                        countFace(faceBox[i + j], signedArea[j]);
            }
            double lows[4], highs[4];
            v_store(lows, lowest), v_store(highs, highest);
            for (int j = 0; j < 4; j++)
                lo = std::min(lo, lows[j]), hi = std::max(hi, highs[j]);
        }
#endif
        for (; i < end; i++)
            boxFace(i);
        endRun();
        chunkDepthRange[chunk] = {lo, hi};
    };
    parallel_for_(Range(0, chunkCount), [&](const Range& chunks) {
        using Yes = std::true_type;
        using No = std::false_type;
        for (int chunk = chunks.start; chunk < chunks.end; chunk++) {
            if (!byDepth)
                boxFaces(chunk, No(), No(), No());
            else if (byFaceDepth)
                boxFaces(chunk, Yes(), Yes(), No());
            else if (depthTested)
                boxFaces(chunk, Yes(), No(), Yes());
            else
                boxFaces(chunk, Yes(), No(), No());
        }
    });

    // Faces are sorted by 32-bit keys, their depths quantized linearly; faces sharing a key are
    // ordered exactly afterwards (refineEqualKeys).
    double minDepth = inf, maxDepth = -inf;
    for (const auto& range : chunkDepthRange) {
        minDepth = std::min(minDepth, range.first);
        maxDepth = std::max(maxDepth, range.second);
    }
    const double depthScale = maxDepth > minDepth ? double(UINT32_MAX) / (maxDepth - minDepth) : 0;
    auto quantizedKey = [&](int face) {
        return byDepth ? quantizeDepth(faceKeys[face], minDepth, depthScale) : uint32_t(0);
    };

    timer.mark("boxes");
    // Pass 2, parallel over the same chunks: the entries binned by band (a counting sort), each
    // band's list in decreasing face order.
    std::vector<size_t> bandStart(bandCount + 1, 0);
    std::vector<double> bandArea(bandCount, 0.0);  // covered samples, counted with overdraw
    std::vector<size_t> bandClockwise(bandCount, 0);
    for (int k = 0; k < bandCount; k++) {
        size_t next = bandStart[k];
        for (int c = chunkCount; c-- > 0;) {  // later chunks first: decreasing face order
            const uint64_t counts = binCursor[size_t(c) * bandCount + k];
            binCursor[size_t(c) * bandCount + k] = next;
            next += counts & (kClockwiseOne - 1);
            bandClockwise[k] += counts >> 32;
            bandArea[k] += binArea[size_t(c) * bandCount + k];
        }
        bandStart[k + 1] = next;
    }
    // A band is painted, without a coverage mask, when the samples it would shade more
    // than once (estimated from face areas) are fewer than this many per face: rewriting a
    // few pixels costs less than the mask's work on every span of small faces.
    constexpr double kOverdrawPerFacePainted = 32;
    // Small faces: at most this many samples each, on average over the band. A painted band
    // of small faces is drawn in face order, where each face's cost is mostly per face and
    // the sort's scattered reads are saved; one of bigger faces back to front, sorted, where
    // the depth test would cost more per sample than the sort does per face (the 2048 x
    // 2048 grid's 128-sample faces: 1.20-1.35x in face order). Also front to back: bands of
    // small faces wound both ways, at least a quarter of them each way. That is a closed
    // surface seen with its back faces, which are hidden: the coverage test skips them
    // whole, before any setup. (Big faces gain less: the mask's per-row work grows with
    // them.) Only while the band holds few enough faces that their boxes, keys and vertices
    // stay cached: in bigger bands, reading them in depth order (scattered) costs more than
    // drawing the hidden half in face order does. Closed surfaces in face order: the 49,408-
    // face sphere at 512 x 512 (4,900-7,800 faces a band) 0.81-0.88x the time, the million-face
    // sphere at 2048 x 2048 0.83-0.93x, the 10,000-face demo (700-2,900) 1.05-1.2x, and the
    // million-face torus of drawMesh3d in painter's order, whose tilted ring hides up to three
    // layers, 1.02-1.07x (history), and since the back faces are skipped where hidden
    // (nearWindingFirst), 0.74-0.84x. Where flat faces are drawn as sample blocks, every
    // closed surface's band is drawn in face order: the demo in flat 0.97-1.02x, median
    // 0.976 (in Gouraud, without the blocks, face order is still 1.02-1.06x).
    constexpr double kSmallFaceSamples = 32;
    constexpr size_t kCachedBandFaces = 4096;
    // A band's way of drawing, decided for the whole band (its parts draw as it does) from its
    // faces' count, area and winding.
    struct BandWay {
        bool smallFaces, inFaceOrder, backToFront;
        //! In face order, a closed surface's: the nearer winding first, then the other's faces
        //! that the depths drawn so far do not hide.
        bool nearWindingFirst;
    };
    auto bandWay = [&](int k) {
        const size_t faces = bandStart[k + 1] - bandStart[k];
        const int rows = std::min(size.height - k * bandRows, bandRows);
        const double overdraw = bandArea[k] - double(rows) * size.width;
        const size_t windingMinority = std::min(bandClockwise[k], faces - bandClockwise[k]);
        const bool smallFaces = bandArea[k] <= kSmallFaceSamples * double(faces);
        const bool bothWindings = 4 * windingMinority >= faces && smallFaces;
        const bool closedSurface =
            bothWindings && !sampleBlocksDrawn && faces <= kCachedBandFaces;
        const bool littleOverdraw = !depthTested && !options.frontToBack &&
                                    overdraw <= kOverdrawPerFacePainted * double(faces) &&
                                    !closedSurface;
        const bool inFaceOrder = littleOverdraw && smallFaces;
        return BandWay{smallFaces, inFaceOrder, littleOverdraw && !inFaceOrder,
                       inFaceOrder && bothWindings && byDepth};
    };
    // Bands drawn in face order read no sort key: where no band sorts, the entries go without
    // one (each face's key quantized and stored costs the million-face grid's binning ~17
    // instructions a face), and where every band is drawn in face order an entry is the face's
    // index alone, in 32 bits (binnedFaces): half the bytes binning writes and the bands read.
    bool allInFaceOrder = true;
    for (int k = 0; k < bandCount && allInFaceOrder; k++)
        allInFaceOrder = bandStart[k + 1] == bandStart[k] || bandWay(k).inFaceOrder;
    const bool anyBandSorts = byDepth && !allInFaceOrder;
    std::vector<uint64_t>& binned = work.binned;
    std::vector<uint32_t>& binnedFaces = work.binnedFaces;
    binned.resize(allInFaceOrder ? 0 : bandStart[bandCount]);
    binnedFaces.resize(allInFaceOrder ? bandStart[bandCount] : 0);
    auto binChunk = [&](int c, auto entries, auto kKeyed) {
        uint64_t* const cursor = &binCursor[size_t(c) * bandCount];
        const SampleBox* const boxOf = boxes.data();
        const int shift = bandShift;
        const int begin = c * chunkFaces;
        // Consecutive faces within one band (the common case) advance its cursor in a
        // register: through memory, a load and a store a face, it was the loop's critical path.
        int runBand = -1;
        uint64_t runCursor = 0;
        for (int i = std::min(faceCount, begin + chunkFaces); i-- > begin;) {
            const SampleBox& box = boxOf[i];
            if (box.rowBegin >= box.rowEnd)
                continue;  // culled: in no band
            using Entry = std::remove_pointer_t<decltype(entries)>;
            const Entry entry = Entry(bandEntry(kKeyed ? quantizedKey(i) : 0, i));
            const int first = box.rowBegin >> shift, last = (box.rowEnd - 1) >> shift;
            if (first == last) {
                if (first != runBand) {
                    if (runBand >= 0)
                        cursor[runBand] = runCursor;
                    runBand = first, runCursor = cursor[first];
                }
                entries[runCursor++] = entry;
                continue;
            }
            if (runBand >= 0)
                cursor[runBand] = runCursor, runBand = -1;
            for (int k = first; k <= last; k++)
                entries[cursor[k]++] = entry;
        }
        // (The last run's cursor is not stored back: no one reads the cursors after this pass.)
    };
    parallel_for_(Range(0, chunkCount), [&](const Range& chunks) {
        for (int c = chunks.start; c < chunks.end; c++) {
            if (allInFaceOrder)
                binChunk(c, binnedFaces.data(), std::false_type());
            else if (anyBandSorts)
                binChunk(c, binned.data(), std::true_type());
            else
                binChunk(c, binned.data(), std::false_type());
        }
    });

    timer.mark("binning");
    // Pass 3, parallel over bands: order the band's faces front to back, then draw them.
    uchar* const canvasData = canvas.data;
    const size_t canvasStep = canvas.step[0];
    const int width = size.width;
    const size_t rowBytes = size_t(width) * canvas.elemSize();
    // A canvas this big is not kept in the caches anyway: its front-to-back bands are drawn into
    // a scratch tile, which stays cached, and then streamed out, so that the canvas's lines are
    // written without first being read (half the memory traffic). Painted bands are not: drawn
    // back to front in slices kept in cache, or in face order, which writes a band's rows a few
    // at a time, they gained nothing from the tile (the copy cost what the reads did).
    constexpr size_t kStreamedCanvasBytes = size_t(16) << 20;
    const bool streamBands = background && rowBytes * size.height >= kStreamedCanvasBytes;
    // Each band's cost, estimated from its faces and their areas, shared by its quarters' rows.
    std::vector<double> quarterCost(size_t(bandCount) * BandPart::kQuarters);
    for (int k = 0; k < bandCount; k++) {
        const double cost =
            kBandCostPerFace * double(bandStart[k + 1] - bandStart[k]) + bandArea[k];
        const int rows = std::min(size.height - k * bandRows, bandRows);
        for (int q = 0; q < BandPart::kQuarters; q++) {
            const int quarterRows = bandRows / BandPart::kQuarters;
            const int inQuarter = std::clamp(rows - q * quarterRows, 0, quarterRows);
            quarterCost[size_t(k) * BandPart::kQuarters + q] = cost * inQuarter / rows;
        }
    }
    // The environment variable OPENCV_SHADING_SPLIT_BANDS=1 has every band drawn in parts (a
    // testing aid: the image must not change). Read per draw, so that a test can set it.
    const char* splitVariable = std::getenv("OPENCV_SHADING_SPLIT_BANDS");
    const bool splitAll = splitVariable && std::strcmp(splitVariable, "1") == 0;
    BandSchedule schedule(quarterCost, getNumThreads(), bandCount < 8 * getNumThreads(),
                          splitAll);
#if OPENCV_SHADING_STAGE_TIMES
    std::vector<std::pair<double, int>> workerTimes(schedule.workers(), {0.0, 0});
    const int64 bandsStart = getTickCount();
#endif
    parallel_for_(Range(0, schedule.workers()), [&](const Range& range) {
        // What the loop reads per face and per span, in locals: a variable captured by
        // reference is read again after every store that may alias it.
        const int columns = width;
        const SampleBox* const faceBox = boxes.data();
        const bool deferred = options.deferred;
        const size_t rowStep = canvasStep;
        uchar* const pixels = canvasData;
        const double* const keyOf = faceKeys;
        const Vec3i* const faceAt = mesh.faces.data();
        [[maybe_unused]] const uint64_t* const narrowWords = work.narrowPoints.data();
#if OPENCV_SHADING_STAGE_TIMES
        int workerBands = 0;
#endif
        // The thread's kept buffers, moved into locals: the compiler keeps a local's fields in
        // registers, which it cannot do for a thread_local's (every store might change them).
        BandWorkspace& threadBuffers = BandWorkspace::ofThisThread();
        CoverageBits coverage = std::move(threadBuffers.coverage);
        coverage.reset(bandRows, columns);
        std::vector<uint64_t> scratch = std::move(threadBuffers.scratch);
        std::vector<uchar> tile = std::move(threadBuffers.tile);
        std::vector<std::pair<double, uint64_t>> refineRun = std::move(threadBuffers.refineRun);
        ZBufferBlocks zbuffer = std::move(threadBuffers.zbuffer);
        std::vector<float> keptWeights = std::move(threadBuffers.keptWeights);
        std::vector<int> keptFaces = std::move(threadBuffers.keptFaces);
        std::vector<double> bandDepths = std::move(threadBuffers.bandDepths);
        std::vector<uint64_t> partEntries = std::move(threadBuffers.partEntries);
        std::vector<int> splitFaces = std::move(threadBuffers.splitFaces);
        int rowLeft[64];  // pixels of each band row not yet final
        // Whether this band's batches may go to paintTinyBlocks (set per band).
        [[maybe_unused]] bool tinyBlocksBand = false;
        // Whether paintSmallFaces draws its small faces by paintSampleBlock: while a closed
        // surface's band draws its nearer winding, or all of it again after a tie (the other
        // winding's spans check ties).
        [[maybe_unused]] bool sampleBlocks = false;
        // paintSampleBlock's bit 8 r + c: its offsets in bytes from the block's first sample,
        // in the band's depths and on the canvas.
        [[maybe_unused]] ptrdiff_t blockDepthOffset[64], blockPixelOffset[64];
        for (int bit = 0; bit < 64; bit++) {
            blockDepthOffset[bit] =
                (ptrdiff_t(bit >> 3) * columns + (bit & 7)) * ptrdiff_t(sizeof(double));
            blockPixelOffset[bit] = ptrdiff_t(bit >> 3) * ptrdiff_t(rowStep) +
                                    ptrdiff_t(bit & 7) * 3 * ptrdiff_t(sizeof(T));
        }
        struct BatchFace {
            TriangleSetup triangle;
            Shader shader;
            int face;
        };
        static_assert(std::is_trivially_destructible<BatchFace>::value,
                      "batch entries are overwritten in place, never destroyed");
        constexpr int kBatch = 32;
        constexpr size_t kBoxPrefetch = 16;  // entries ahead of the occlusion test
        // Entries ahead of the back-to-front slicing loop: a short loop, so farther ahead.
        constexpr size_t kSliceBoxPrefetch = 64;
        // Raw storage: the shaders have no default constructor and need none.
        alignas(BatchFace) unsigned char batchStorage[kBatch * sizeof(BatchFace)];
        BatchFace* const batch = reinterpret_cast<BatchFace*>(batchStorage);
        // Worker range.start's run, then what is left of the others' (all of them, where one
        // call gets several workers).
        for (BandPart part; (part = schedule.next(range.start)).band >= 0;) {
#if OPENCV_SHADING_STAGE_TIMES
            workerBands++;
#endif
            const int band = part.band;
            const int bandY0 = band * bandRows, bandY1 = std::min(size.height, bandY0 + bandRows);
            int y0 = bandY0, y1 = bandY1;
            if (!part.whole()) {
                constexpr int quarterRows = bandRows / BandPart::kQuarters;
                y0 = bandY0 + part.quarter * quarterRows;
                y1 = std::min(bandY1, y0 + part.quarters * quarterRows);
                if (y0 >= y1)  // the canvas's last band may end above the part
                    continue;
            }
            // Decreasing face order: the entries, or where all bands are in face order the faces.
            uint64_t* order = allInFaceOrder ? nullptr : binned.data() + bandStart[band];
            const uint32_t* faceList =
                allInFaceOrder ? binnedFaces.data() + bandStart[band] : nullptr;
            size_t orderSize = bandStart[band + 1] - bandStart[band];
            const BandWay way = bandWay(band);
            {
                // Faces of at most 5 samples on average (the million-face grid's 4.2; grid512's
                // 8 never fit the block). Not for a closed surface's band drawn a winding at a
                // time, whose second winding checks ties.
                constexpr double kTinyFaceSamples = 5;
                const size_t faces = bandStart[band + 1] - bandStart[band];
                tinyBlocksBand = way.inFaceOrder && byDepth && !way.nearWindingFirst &&
                                 bandArea[band] <= kTinyFaceSamples * double(faces);
            }
            sampleBlocks = false;  // set where this band paints with paintSpan
            [[maybe_unused]] const bool smallFaces = way.smallFaces;
            const bool inFaceOrder = way.inFaceOrder, backToFront = way.backToFront;
            if (!part.whole()) {
                // Part of a band: its own copy of the entries whose boxes reach its rows, as the
                // other parts may be drawn at the same time and the lists are sorted in place.
                partEntries.clear();
                for (size_t i = 0; i < orderSize; i++) {
                    const uint64_t entry = faceList ? uint64_t(faceList[i]) : order[i];
                    const SampleBox& box = faceBox[entryFace(entry)];
                    if (box.rowBegin < y1 && box.rowEnd > y0)
                        partEntries.push_back(entry);
                }
                order = partEntries.data();
                faceList = nullptr;
                orderSize = partEntries.size();
            }
            shaders.beginBand(y0, y1);
            // Front to back is the painter's order reversed: increasing mean depth, and among
            // equal means the later face first (the painter draws it last, on top).
            if (inFaceOrder) {
                // Drawn in face order with a depth test per sample (see below): no sort.
            } else if (byDepth && depthTested) {
                // The depth test decides every sample whatever the order: the order only lets
                // nearer faces hide farther ones before setup, for which 16 levels will do.
                // Coarse levels keep long runs of neighbouring faces (decreasing face order
                // within a level), whose vertices and canvas rows are then still in cache:
                // 16 levels instead of 256 took the million-face torus 2-6% less time.
                order = sortBandEntries(order, orderSize, scratch, 4);
            } else if (byDepth) {
                // Entries sharing a narrowed key have their exact depths gathered and compared
                // (refineEqualKeys), from all over the key array: in a band of tens of thousands
                // of faces, 16 bits leave many to compare, and a third radix pass costs less.
                constexpr size_t kWideKeyEntries = 8192;
                order = sortBandEntries(order, orderSize, scratch,
                                        orderSize > kWideKeyEntries ? 24 : 16);
                refineEqualKeys(order, orderSize, keyOf, refineRun);
            }

            // Sets up faces[0 .. count) into `batch`, returning how many cover something. Faces
            // are set up a batch at a time and then drawn, each step a loop over the batch, so
            // that the reads of faces, vertices and colours overlap instead of stalling in turn.
            auto prepareBatch = [&](const int* faces, int count) {
                Vec3i corners[kBatch];
                for (int i = 0; i < count; i++)
                    corners[i] = faceAt[faces[i]];
                FixedPoint points[kBatch][3];
                for (int i = 0; i < count; i++)
                    for (int j = 0; j < 3; j++) {
                        points[i][j] = snapped[corners[i][j]];
                        shaders.prefetchVertex(corners[i][j]);
                    }
                int prepared = 0;
                if constexpr (Shaders::kLightsFaces) {
                    // The faces that set up, then their colours together (lit in SIMD lanes),
                    // then their shaders.
                    TriangleSetup triangles[kBatch];
                    int vertexOrders[kBatch][3], setUp[kBatch];
                    // Zeroed: GCC 12 (the sanitizer build) cannot see that lightFaces reads only
                    // the first `prepared`, and warns.
                    int setUpFaces[kBatch] = {};
                    for (int i = 0; i < count; i++)
                        if (setupBoxedTriangle(points[i], faceBox[faces[i]], size,
                                               triangles[prepared], vertexOrders[prepared])) {
                            setUp[prepared] = i;
                            setUpFaces[prepared++] = faces[i];
                        }
                    float colors[kBatch][3];
                    shaders.lightFaces(setUpFaces, prepared, colors);
                    for (int j = 0; j < prepared; j++)
                        new (&batch[j]) BatchFace{
                            triangles[j],
                            shaders.make(triangles[j], vertexOrders[j], corners[setUp[j]],
                                         setUpFaces[j], colors[j]),
                            setUpFaces[j]};
                    return prepared;
                }
                for (int i = 0; i < count; i++) {
                    TriangleSetup triangle;
                    int vertexOrder[3];
                    if (!setupBoxedTriangle(points[i], faceBox[faces[i]], size, triangle,
                                            vertexOrder))
                        continue;
                    new (&batch[prepared++]) BatchFace{
                        triangle, shaders.make(triangle, vertexOrder, corners[i], faces[i]),
                        faces[i]};
                }
                return prepared;
            };
            int batchFaces[kBatch];
#if OPENCV_SHADING_BOX_EIGHT
            /* The tiny faces of a batch: their edge functions set up 8 at a time
            (smallEdgesEight), to be walked by walkSmallRows (walkSmall), and their shaders
            (Shaders::SmallShader) built without a TriangleSetup, from weights set up 8 at a time
            too (smallWeightsEight) where they read any; the others are set up as prepareBatch
            does. Only where shaders.smallShadersFit(). */
            using SmallShader = typename Shaders::SmallShader;
            struct SmallFaces {
                alignas(32) int32_t at0[3][kBatch], perColumn[3][kBatch], perRow[3][kBatch];
                //! The box in the band, from the vertices (triangleBoxEight): the bands read no
                //! boxes where all their faces are small (16 MB a million-face frame).
                alignas(32) int32_t firstColumn[kBatch], lastColumn[kBatch], firstRow[kBatch],
                    endRow[kBatch];
                Vec3i corners[kBatch];
                //! Shaders::kLightsFaces: every face's colour, lit together (lightFaces).
                float litColor[Shaders::kLightsFaces ? kBatch : 1][3];
                uint32_t small;  //!< bit i: face i is set up here
                // Built in place and never destroyed, which a trivial destructor allows.
                static_assert(std::is_trivially_destructible<SmallShader>::value,
                              "no destructor runs");
                alignas(SmallShader) unsigned char shaderStorage[kBatch * sizeof(SmallShader)];
                //! Small face i's shader.
                const SmallShader& shader(int i) const
                {
                    return reinterpret_cast<const SmallShader*>(shaderStorage)[i];
                }
                //! Face i's colour from lightFaces, or null.
                const float* lit(int i) const
                {
                    return Shaders::kLightsFaces ? litColor[i] : nullptr;
                }
            };
            // With mostTiny: returns false, having built no shader, where fewer than half of the
            // faces are tiny (see drawSmallFaces).
            auto setUpSmallFaces = [&](const int* faces, int count, SmallFaces& out,
                                       bool mostTiny) {
                alignas(32) int32_t x[3][kBatch], y[3][kBatch];
                // In locals: the loop's int32 stores to `out` might otherwise alias the
                // captured rows, which it would then reload every face.
                const int top = y0, bottom = y1;
                const Vec3i* const cornersOf = faceAt;
                // Each corner's x and y in one 8-byte word (every vertex is narrow where this
                // runs): half the bytes of its FixedPoint.
                const uint64_t* const pointWords = narrowWords;
                alignas(32) uint64_t words[3][kBatch];
                for (int i = 0; i < count; i++) {
                    out.corners[i] = cornersOf[faces[i]];
                    for (int j = 0; j < 3; j++) {
                        words[j][i] = pointWords[out.corners[i][j]];
                        shaders.prefetchVertex(out.corners[i][j]);
                    }
                }
                const int lanes = (count + 7) & ~7;
                for (int i = count; i < lanes; i++) {  // a zero area: not set up
                    for (int j = 0; j < 3; j++)
                        words[j][i] = 0;
                }
                out.small = 0;
                for (int g = 0; g < lanes; g += 8) {
                    v_int32x8 xs[3], ys[3];
                    for (int j = 0; j < 3; j++) {
                        // Words 0-3 and 4-7 as x0 x1 x4 x5 x2 x3 x6 x7 (and y), then in order.
                        const float* const pairs = reinterpret_cast<const float*>(words[j] + g);
                        const __m256 a = _mm256_load_ps(pairs), b = _mm256_load_ps(pairs + 8);
                        xs[j] = v_int32x8(_mm256_permute4x64_epi64(
                            _mm256_castps_si256(_mm256_shuffle_ps(a, b, 0x88)), 0xd8));
                        ys[j] = v_int32x8(_mm256_permute4x64_epi64(
                            _mm256_castps_si256(_mm256_shuffle_ps(a, b, 0xdd)), 0xd8));
                        v_store(x[j] + g, xs[j]);
                        v_store(y[j] + g, ys[j]);
                    }
                    const BoxLanes box = triangleBoxEight(xs, ys, size);
                    v_store(out.firstColumn + g, box.colFirst);
                    v_store(out.lastColumn + g, box.colLast);
                    v_store(out.firstRow + g, v_max(box.rowBegin, v256_setall_s32(top)));
                    v_store(out.endRow + g, v_min(box.rowEnd, v256_setall_s32(bottom)));
                    int32_t* const at[3] = {out.at0[0] + g, out.at0[1] + g, out.at0[2] + g};
                    int32_t* const column[3] = {out.perColumn[0] + g, out.perColumn[1] + g,
                                                out.perColumn[2] + g};
                    int32_t* const row[3] = {out.perRow[0] + g, out.perRow[1] + g,
                                             out.perRow[2] + g};
                    out.small |= uint32_t(smallEdgesEight(xs, ys, v256_load(out.firstColumn + g),
                                                          v256_load(out.firstRow + g), at,
                                                          column, row))
                                 << g;
                }
                if (mostTiny && 2 * __builtin_popcount(out.small) < count)
                    return false;
                if constexpr (Shaders::kLightsFaces)  // all of them: the others' too
                    shaders.lightFaces(faces, count, out.litColor);
                // The canonical vertices, weights' edges and 1 / twice the area.
                [[maybe_unused]] alignas(32) int32_t vertex[3][kBatch], weightAt[3][kBatch],
                    weightPerColumn[3][kBatch], weightPerRow[3][kBatch];
                [[maybe_unused]] alignas(32) double invArea2[kBatch];
                if constexpr (SmallShader::kReadsWeights) {
                    for (int g = 0; g < lanes; g += 8) {
                        const v_int32x8 xs[3] = {v256_load(x[0] + g), v256_load(x[1] + g),
                                                 v256_load(x[2] + g)};
                        const v_int32x8 ys[3] = {v256_load(y[0] + g), v256_load(y[1] + g),
                                                 v256_load(y[2] + g)};
                        auto lanesOf = [&](int32_t (&a)[3][kBatch]) {
                            return std::array<int32_t*, 3>{a[0] + g, a[1] + g, a[2] + g};
                        };
                        smallWeightsEight(xs, ys, v256_load(out.firstColumn + g),
                                          v256_load(out.firstRow + g), lanesOf(vertex).data(),
                                          lanesOf(weightAt).data(),
                                          lanesOf(weightPerColumn).data(),
                                          lanesOf(weightPerRow).data(), invArea2 + g);
                    }
                }
                // Their shaders, in a loop of their own: the vertices' loads and divisions of
                // several faces overlap.
                for (uint32_t left = out.small; left; left &= left - 1) {
                    const int i = __builtin_ctz(left);
                    SmallShader* const shader =
                        reinterpret_cast<SmallShader*>(out.shaderStorage) + i;
                    if constexpr (SmallShader::kReadsWeights) {
                        const SmallWeights w{
                            invArea2[i],
                            {weightAt[0][i], weightAt[1][i], weightAt[2][i]},
                            {weightPerColumn[0][i], weightPerColumn[1][i], weightPerColumn[2][i]},
                            {weightPerRow[0][i], weightPerRow[1][i], weightPerRow[2][i]},
                            out.firstColumn[i],
                            out.firstRow[i]};
                        const int canonical[3] = {vertex[0][i], vertex[1][i], vertex[2][i]};
                        const Vec3i& f = out.corners[i];
                        if constexpr (Shaders::kLightsFaces)
                            new (shader) SmallShader(
                                shaders.makeSmall(w, canonical, f, faces[i], out.lit(i)));
                        else
                            new (shader) SmallShader(shaders.makeSmall(w, canonical, f, faces[i]));
                    } else {
                        const TriangleSetup unread{};  // flat reads no setup
                        if constexpr (Shaders::kLightsFaces)
                            new (shader) SmallShader(shaders.make(unread, nullptr, out.corners[i],
                                                                  faces[i], out.lit(i)));
                        else
                            new (shader) SmallShader(shaders.make(unread, nullptr, out.corners[i],
                                                                  faces[i]));
                    }
                }
                return true;
            };
            // Face i of `sf` that is not small: its shader, once setUpOther set it up.
            auto makeOther = [&](const SmallFaces& sf, int i, int face, const TriangleSetup& t,
                                 const int vertexOrder[3]) {
                if constexpr (Shaders::kLightsFaces)
                    return shaders.make(t, vertexOrder, sf.corners[i], face, sf.lit(i));
                else
                    return shaders.make(t, vertexOrder, sf.corners[i], face);
            };
            // Sets up face i of `sf` that is not small, as prepareBatch does; false: it covers
            // nothing.
            auto setUpOther = [&](const SmallFaces& sf, int i, int face, TriangleSetup& triangle,
                                  int vertexOrder[3]) {
                // From the narrow words, as setUpSmallFaces reads them (the same values): those
                // are in cache, the FixedPoints not (read from those, this setup's share of the
                // demo's flat frames went from 5.2% to 7.0%).
                FixedPoint points[3];
                for (int j = 0; j < 3; j++) {
                    const uint64_t word = narrowWords[sf.corners[i][j]];
                    points[j] = {int32_t(uint32_t(word)), int32_t(uint32_t(word >> 32))};
                }
                return setupBoxedTriangle(points, faceBox[face], size, triangle, vertexOrder);
            };
            // Walks small face i of `sf` over its rows within [rowFirst, rowLast).
            auto walkSmall = [&](const SmallFaces& sf, int i, int rowFirst, int rowLast,
                                 auto& spanFn) {
                const int begin = std::max(sf.firstRow[i], rowFirst);
                const int end = std::min(sf.endRow[i], rowLast);
                if (begin >= end)
                    return;
                int32_t faceAt0[3], faceColumn[3], faceRow[3];
                for (int e = 0; e < 3; e++) {
                    faceColumn[e] = sf.perColumn[e][i], faceRow[e] = sf.perRow[e][i];
                    faceAt0[e] = sf.at0[e][i] + faceRow[e] * (begin - sf.firstRow[i]);
                }
                const unsigned onCanvas =
                    (1u << std::min(kSmallColumns, columns - sf.firstColumn[i])) - 1;
                walkSmallRows<1>(begin, end, sf.firstColumn[i], onCanvas, faceAt0, faceColumn,
                                 faceRow, spanFn);
            };
            /* paintSmallFaces for a batch of depth-tested faces of a pen shader (flat or
            Gouraud, on a float or 8-bit canvas), all small and within 4 x 4 samples
            in the band (a million-face grid's): their samples from one block test of 8 faces at
            once (tinyBlockSamplesEight), then each sample tested and stored as paintSpan's tiny
            spans do, with no walk of rows and no spans: about 60 instructions a face fewer on
            biggrid2048. A Gouraud face's pen starts at each row's first sample, the span's
            first sample in the walk, so the colours are the walk's. False, having drawn
            nothing, where a box is bigger, a face is not small (a zero area, or a big face that
            the canvas clips to a small box) or a shader has no pen; paintSmallFaces then
            sets the batch up again (with the setup shared, the spheres' walk in paintSmallFaces
            took 5-6% longer: the same instructions, the code's layout). The boxes' sizes come
            from that setup, not from the stored boxes. */
            auto paintTinyBlocks = [&](const int* faces, int count) __attribute__((noinline)) {
                constexpr bool kTinyBlocks = penDraws<SmallShader, T>();
                if constexpr (!kTinyBlocks) {
                    (void)faces, (void)count;
                    return false;
                } else {
                    SmallFaces sf;
                    setUpSmallFaces(faces, count, sf, false);
                    alignas(32) int32_t columnCount[kBatch], rowCount[kBatch];
                    for (int i = 0; i < count; i++) {
                        columnCount[i] = sf.lastColumn[i] - sf.firstColumn[i] + 1;
                        rowCount[i] = sf.endRow[i] - sf.firstRow[i];
                        if (columnCount[i] > 4 || rowCount[i] > 4)
                            return false;
                    }
                    if (sf.small != uint32_t(rowsBelow(count)))
                        return false;
                    for (int i = 0; i < count; i++)
                        if (!sf.shader(i).penFits())
                            return false;
                    for (int i = count; i < ((count + 7) & ~7); i++)
                        columnCount[i] = rowCount[i] = 0;
                    alignas(32) int32_t block[kBatch];         // bits 4 r + c: the samples
                    alignas(32) int32_t nearestIndex[kBatch];  // the block's first depth
                    const v_int32x8 bandTop = v256_setall_s32(y0);
                    const v_int32x8 rowLength = v256_setall_s32(columns);
                    for (int g = 0; g < count; g += 8) {
                        auto lanes = [g](const int32_t (&a)[3][kBatch]) {
                            return std::array<const int32_t*, 3>{a[0] + g, a[1] + g, a[2] + g};
                        };
                        const v_int32x8 rows = v256_load(rowCount + g);
                        const v_int32x8 cols = v256_load(columnCount + g);
                        v_store(block + g, tinyBlockSamplesEight(
                                               lanes(sf.at0).data(), lanes(sf.perColumn).data(),
                                               lanes(sf.perRow).data(), rows, cols,
                                               tinyBlockFitsEight(rows, cols)));
                        v_store(nearestIndex + g,
                                (v256_load(sf.firstRow + g) - bandTop) * rowLength +
                                    v256_load(sf.firstColumn + g));
                    }
                    // Bit 4 r + c's offsets in bytes from the block's first sample, in the
                    // band's depths and on the canvas: each sample's addresses are then a
                    // base register plus one of these.
                    ptrdiff_t depthOffset[16], pixelOffset[16];
                    for (int bit = 0; bit < 16; bit++) {
                        depthOffset[bit] = (ptrdiff_t(bit >> 2) * columns + (bit & 3)) *
                                           ptrdiff_t(sizeof(double));
                        pixelOffset[bit] = ptrdiff_t(bit >> 2) * ptrdiff_t(rowStep) +
                                           ptrdiff_t(bit & 3) * 3 * ptrdiff_t(sizeof(T));
                    }
                    double* const nearestDepths = bandDepths.data();
                    const double* const faceKey = keyOf;
                    uchar* const canvasAt = pixels;
                    const size_t stepBytes = rowStep;
                    for (int i = 0; i < count; i++) {
                        const int firstColumn = sf.firstColumn[i];
                        putBlockSamples<4, SmallShader::kReadsWeights, T>(
                            uint32_t(block[i]), sf.shader(i), sf.firstRow[i], firstColumn,
                            faceKey[faces[i]],
                            inOneRegister(
                                reinterpret_cast<uchar*>(nearestDepths + nearestIndex[i])),
                            inOneRegister(canvasAt + size_t(sf.firstRow[i]) * stepBytes +
                                          size_t(firstColumn) * 3 * sizeof(T)),
                            depthOffset, pixelOffset, depthOffset[4], pixelOffset[4]);
                    }
                    return true;
                }
            };
            /* Draws faces[0 .. count) in face order, each span by paintSpan: the tiny faces by
            setUpSmallFaces and walkSmall, the others as prepareBatch and walkTriangle do. Out of
            line: inlined, it cost the band loop's other paths 2-3%. (Gouraud's tiny faces lost
            7-18% on the grids here while they kept the one-face setup for their shaders; with
            smallWeightsEight they gain 20%.) */
            /* A small face of `sf` (at most 8 columns) that spans at most 8 rows in the band,
            drawn as paintSpan would draw its walk's spans: its samples found row by row with
            one 8-lane test each, as walkSmallRows finds them, into one mask of 8 x 8 bits, then
            tested and stored one at a time (putBlockSamples). One loop over the samples instead
            of a span a row: the spans' lengths, 1 to 6 samples on the million-face sphere, are
            not predictable. */
            auto paintSampleBlock = [&](const SmallFaces& sf, int i, double depth) {
                if constexpr (kSampleBlocksBuilt) {
                    if (!sf.shader(i).penFits())
                        return false;
                    const int firstRow = sf.firstRow[i], firstColumn = sf.firstColumn[i];
                    SmallLanes at[3], step[3];
                    for (int e = 0; e < 3; e++) {
                        at[e] = smallLanesRamp(sf.at0[e][i], sf.perColumn[e][i]);
                        step[e] = smallLanesAll(sf.perRow[e][i]);
                    }
                    const SmallLanes zero = smallLanesAll(0);
                    uint64_t samples = 0;
                    for (int r = 0, rows = sf.endRow[i] - firstRow; r < rows; r++) {
                        samples |= uint64_t(unsigned(v_signmask((at[0] > zero) & (at[1] > zero) &
                                                                (at[2] > zero))))
                                   << (8 * r);
                        for (int e = 0; e < 3; e++)
                            at[e] += step[e];
                    }
                    const uint64_t onCanvas =
                        (uint64_t(1) << std::min(8, columns - firstColumn)) - 1;
                    putBlockSamples<8, SmallShader::kReadsWeights, T>(
                        samples & onCanvas * 0x0101010101010101u, sf.shader(i), firstRow,
                        firstColumn, depth,
                        reinterpret_cast<uchar*>(bandDepths.data() +
                                                 size_t(firstRow - y0) * columns + firstColumn),
                        pixels + size_t(firstRow) * rowStep + size_t(firstColumn) * 3 * sizeof(T),
                        blockDepthOffset, blockPixelOffset, blockDepthOffset[8],
                        blockPixelOffset[8]);
                    return true;
                } else {
                    (void)sf, (void)i, (void)depth;
                    return false;
                }
            };
            auto paintSmallFaces = [&](const int* faces, int count,
                                       const auto& paintSpanGiven) __attribute__((noinline)) {
                if (tinyBlocksBand && paintTinyBlocks(faces, count))
                    return;
                const auto paintSpan = paintSpanGiven;  // a copy kept in registers
                SmallFaces sf;
                setUpSmallFaces(faces, count, sf, false);
                const TriangleSetup unread{};  // the shader reads no setup
                const bool blocks = sampleBlocks && byDepth;
                for (int i = 0; i < count; i++) {
                    const int face = faces[i];
                    const double depth = byDepth ? keyOf[face] : 0.0;
                    if (sf.small >> i & 1) {
                        // walkSmall without its step to a later first row, which face order
                        // never needs (biggrid2048 1.011-1.021 through walkSmall).
                        if (sf.firstRow[i] >= sf.endRow[i])
                            continue;
                        const SmallShader& shader = sf.shader(i);
                        if (blocks && sf.endRow[i] - sf.firstRow[i] <= 8 &&
                            paintSampleBlock(sf, i, depth))
                            continue;
                        const int32_t faceAt0[3] = {sf.at0[0][i], sf.at0[1][i], sf.at0[2][i]};
                        const int32_t faceColumn[3] = {sf.perColumn[0][i], sf.perColumn[1][i],
                                                       sf.perColumn[2][i]};
                        const int32_t faceRow[3] = {sf.perRow[0][i], sf.perRow[1][i],
                                                    sf.perRow[2][i]};
                        auto span = [&](int row, int xBegin, int xEnd) {
                            paintSpan(unread, shader, depth, row, xBegin, xEnd);
                        };
                        const unsigned onCanvas =
                            (1u << std::min(kSmallColumns, columns - sf.firstColumn[i])) - 1;
                        walkSmallRows<1>(sf.firstRow[i], sf.endRow[i], sf.firstColumn[i],
                                         onCanvas, faceAt0, faceColumn, faceRow, span);
                        continue;
                    }
                    TriangleSetup triangle;
                    int vertexOrder[3];
                    if (!setUpOther(sf, i, face, triangle, vertexOrder))
                        continue;
                    const Shader shader = makeOther(sf, i, face, triangle, vertexOrder);
                    walkTriangle(triangle, y0, y1, columns, [&](int row, int xBegin, int xEnd) {
                        paintSpan(triangle, shader, depth, row, xBegin, xEnd);
                    });
                }
            };
            /* Draws faces[0 .. count) in turn by drawFace (the claims of a front-to-back band,
            or the depth tests of a z-buffered one): as paintSmallFaces, with each face's walk
            handed to drawFace. False, having drawn nothing, where fewer than half of them are
            tiny: prepareBatch's loops over the batch overlap the bigger faces' reads. */
            auto drawSmallFaces = [&](const int* faces, int count,
                                      auto& drawFace) __attribute__((noinline)) {
                SmallFaces sf;
                if (!setUpSmallFaces(faces, count, sf, true))
                    return false;
                // The others first, each into its batch slot, in a loop of their own: their
                // setups and colours' loads overlap, as in prepareBatch.
                uint32_t others = 0;  // bit i: face i is set up in batch[i]
                for (uint32_t left = ~sf.small & uint32_t(rowsBelow(count)); left;
                     left &= left - 1) {
                    const int i = __builtin_ctz(left);
                    TriangleSetup triangle;
                    int vertexOrder[3];
                    if (!setUpOther(sf, i, faces[i], triangle, vertexOrder))
                        continue;
                    new (&batch[i]) BatchFace{
                        triangle, makeOther(sf, i, faces[i], triangle, vertexOrder), faces[i]};
                    others |= 1u << i;
                }
                const TriangleSetup unread{};  // the shader reads no setup
                for (int i = 0; i < count; i++) {
                    if (sf.small >> i & 1) {
                        drawFace(faces[i], unread, sf.shader(i),
                                 [&](int rowFirst, int rowLast, auto& spanFn) {
                            walkSmall(sf, i, rowFirst, rowLast, spanFn);
                        });
                    } else if (others >> i & 1) {
                        const BatchFace& bf = batch[i];
                        drawFace(bf.face, bf.triangle, bf.shader,
                                 [&](int rowFirst, int rowLast, auto& spanFn) {
                            walkTriangle(bf.triangle, rowFirst, rowLast, columns, spanFn);
                        });
                    }
                }
                return true;
            };
#endif
            /* Draws faces[0 .. count) in turn by drawFace, as drawSmallFaces does: through it
            where the band's faces are small, else each face set up by prepareBatch and walked by
            walkTriangle. */
            auto drawBatch = [&](const int* faces, int count, auto& drawFace) {
#if OPENCV_SHADING_BOX_EIGHT
                if (boxEight && smallFaces && shaders.smallShadersFit() &&
                    drawSmallFaces(faces, count, drawFace))
                    return;
#endif
                const int batchSize = prepareBatch(faces, count);
                for (int i = 0; i < batchSize; i++) {
                    const BatchFace& bf = batch[i];
                    drawFace(bf.face, bf.triangle, bf.shader,
                             [&](int rowFirst, int rowLast, auto& spanFn) {
                        walkTriangle(bf.triangle, rowFirst, rowLast, columns, spanFn);
                    });
                }
            };

            if constexpr (Shaders::kZBuffer) {
                if (depthTested) {
                    // Nearest faces first; each tests its samples against (depth, face) kept.
                    if (background)  // a cleared canvas: the band's rows first
                        for (int y = y0; y < y1; y++)
                            fillPixels(reinterpret_cast<T*>(pixels + size_t(y) * rowStep),
                                       0, columns, background->val);
                    zbuffer.reset(y1 - y0, columns);
                    if (deferred)
                        keptWeights.resize(size_t(y1 - y0) * columns * 2);
                    for (size_t next = 0; next < orderSize;) {
                        int count = 0;
                        for (; next < orderSize && count < kBatch; next++) {
                            if (next + kBoxPrefetch < orderSize) {
                                const int ahead = entryFace(order[next + kBoxPrefetch]);
                                __builtin_prefetch(&faceBox[ahead]);
                                __builtin_prefetch(&keyOf[ahead]);
                            }
                            const int face = entryFace(order[next]);
                            const SampleBox& box = faceBox[face];
                            // Its nearest vertex, less float rounding: no sample is nearer.
                            const float nearest = float(keyOf[face]) * (1.f - 1e-6f);
                            if (!zbuffer.hidden(std::max(box.rowBegin, y0) - y0,
                                                std::min(box.rowEnd, y1) - y0, box.colFirst,
                                                box.colLast, nearest)) {
                                __builtin_prefetch(&faceAt[face]);  // read by prepareBatch
                                batchFaces[count++] = face;
                            }
                        }
                        // A set-up face: its samples, each tested against the buffer.
                        auto depthTestFace = [&](int face, const TriangleSetup& triangle,
                                                 const auto& shader, auto&& walk) {
                            auto span = [&](int y, int xBegin, int xEnd) {
                                const int r = y - y0;
                                T* row = reinterpret_cast<T*>(pixels + size_t(y) * rowStep);
                                float* weights = deferred
                                                     ? keptWeights.data() + size_t(r) * columns * 2
                                                     : nullptr;
                                shader.depthTest(triangle, row, y, xBegin, xEnd, face,
                                                 zbuffer.keptRow(r), weights,
                                                 zbuffer.coveredRow(r), zbuffer.boundRow(r));
                            };
                            walk(y0, y1, span);
                        };
                        drawBatch(batchFaces, count, depthTestFace);
                    }
                    if (deferred)
                        for (int y = y0; y < y1; y++)
                            shaders.shadeKeptRow(
                                reinterpret_cast<T*>(pixels + size_t(y) * rowStep), y,
                                zbuffer.keptRow(y - y0),
                                keptWeights.data() + size_t(y - y0) * columns * 2,
                                zbuffer.coveredRow(y - y0), columns);
                    continue;
                }
            }
            if (inFaceOrder) {
                // Little overdraw: no sort and no coverage bookkeeping. Background first, then
                // every face in face order, each sample taking a face at least as near as the
                // nearest drawn there so far (takeNearerOrEqual): the painter's image, since the
                // nearest face wins and, among equally near ones, the last. Faces are read in
                // the order the arrays hold them, which the memory system streams, instead of
                // from all over them in depth order, and a mesh's neighbouring faces, mostly
                // neighbours in the arrays too, write the canvas and the depths a few rows at a
                // time. (Drawing tall bands 16 rows at a time, each slice visiting the band's
                // faces, took 6-11% longer on the million-face grid.)
                // With depths, the background goes where no face took the sample, after the
                // faces (paintBackground): a covered pixel is then written once, by its face
                // (biggrid2048 0.94-0.98x the time in flat and Gouraud), where the band's rows
                // hold more than 1 MB, which a core's cache does not keep from the fill to the
                // faces (grid512's 384 KB: 1.02-1.06x in Gouraud with the background last). Not
                // on a closed surface's band, whose rings cross the band in curves: its faces'
                // stores then find the canvas lines out of cache (bigsphere2048 1.05-1.10x);
                // the background's fill brings them in.
                constexpr size_t kBackgroundLastBytes = size_t(1) << 20;
                const bool backgroundLast = background && byDepth && !way.nearWindingFirst &&
                                            size_t(y1 - y0) * columns * 3 * sizeof(T) >
                                                kBackgroundLastBytes;
                auto clearBand = [&] {
                    if (background && !backgroundLast)
                        for (int y = y0; y < y1; y++)
                            fillPixels(canvas.ptr<T>(y), 0, columns, background->val);
                    if (byDepth) {
                        // Seven past the last row: hiddenByNearer reads eight at a box's start,
                        // and a wider box's four a step up to three past its end.
                        bandDepths.resize(size_t(y1 - y0) * columns + 7);
                        std::fill(bandDepths.begin(), bandDepths.end(), kUntouchedDepth);
                    }
                };
                auto paintBackground = [&] {
                    if (backgroundLast)
                        for (int y = y0; y < y1; y++)
                            paintUntouched(canvas.ptr<T>(y),
                                           bandDepths.data() + size_t(y - y0) * columns, columns,
                                           background->val);
                };
                clearBand();
                // A face's span: the samples that take it (all of them without depths).
                // Its values captured by copy: through references, each span reloaded them
                // after every store, which may alias them.
                auto paintSpan = [pixels, rowStep, byDepth, y0, columns,
                                  depths = bandDepths.data()](const TriangleSetup& t,
                                                              const auto& shader, double depth,
                                                              int y, int xBegin, int xEnd) {
                    T* row = reinterpret_cast<T*>(pixels + size_t(y) * rowStep);
                    if (!byDepth) {  // face order is the painter's
                        shader(t, row, y, xBegin, xBegin, xEnd);
                        return;
                    }
                    using FaceShader = std::decay_t<decltype(shader)>;
                    if constexpr (penDraws<FaceShader, T>()) {
                        // A tiny face's span (1.75 samples on the million-face grid): each
                        // sample tested and stored alone, without finding runs first.
                        if (xEnd - xBegin <= 4 && shader.penFits()) {
                            const auto pen = shader.pen(t, y, xBegin);
                            double* const nearest = depths + size_t(y - y0) * columns;
                            // Without a branch: where a closed surface's faces overlap, which
                            // samples take a face is not predictable. A sample that does not
                            // take it stores into these instead.
                            double discardedDepth;
                            T discardedPixel[3];
                            for (int x = xBegin; x < xEnd; x++) {
                                const bool takes = !(nearest[x] < depth);
                                *(takes ? nearest + x : &discardedDepth) = depth;
                                pen.put(takes ? row + 3 * x : discardedPixel, x);
                            }
                            return;
                        }
                    }
                    takeNearerOrEqual(depths + size_t(y - y0) * columns, xBegin, xEnd,
                                      depth, [&](int a, int b) {
                        shader(t, row, y, xBegin, a, b);
                    });
                };
                // Draws faces[0 .. count) in turn, each span by paintSpanFn.
                auto paintBatch = [&](const int* faces, int count, const auto& paintSpanFn) {
#if OPENCV_SHADING_BOX_EIGHT
                    if (boxEight && shaders.smallShadersFit()) {
                        paintSmallFaces(faces, count, paintSpanFn);
                        return;
                    }
#endif
                    const int batchSize = prepareBatch(faces, count);
                    for (int i = 0; i < batchSize; i++) {
                        const BatchFace& bf = batch[i];
                        const double depth = byDepth ? keyOf[bf.face] : 0.0;
                        walkTriangle(bf.triangle, y0, y1, columns,
                                     [&](int y, int xBegin, int xEnd) {
                            paintSpanFn(bf.triangle, bf.shader, depth, y, xBegin, xEnd);
                        });
                    }
                };
                // Draws the faces faceAtIndex(0 .. total) that `keep` keeps, in that order, a
                // batch at a time; stops early where stop() says so after a batch.
                auto paintFaces = [&](size_t total, auto&& faceAtIndex, auto&& keep,
                                      const auto& paintSpanFn, auto&& stop) {
                    for (size_t j = 0; j < total;) {
                        int count = 0;
                        for (; j < total && count < kBatch; j++) {
                            const int face = faceAtIndex(j);
                            if (keep(face))
                                batchFaces[count++] = face;
                        }
                        paintBatch(batchFaces, count, paintSpanFn);
                        if (stop())
                            return;
                    }
                };
                auto always = [](int) { return true; };
                auto never = [] { return false; };
                auto inFaceOrderAt = [&](size_t j) {  // entries are in decreasing face order
                    return faceList ? int(faceList[orderSize - 1 - j])
                                    : entryFace(order[orderSize - 1 - j]);
                };
                // Where faces never overlap (a grid), the walk's span lengths repeat and it is
                // the cheaper way (grid512 flat 1.02-1.05x through the sample blocks).
                sampleBlocks = way.nearWindingFirst;
                if (!way.nearWindingFirst) {
                    paintFaces(orderSize, inFaceOrderAt, always, paintSpan, never);
                    paintBackground();
                    continue;
                }
                /* A closed surface's band: half of its faces, turned away, are hidden by the
                other half. Since the nearest face wins each sample whatever the order (among
                equally near ones the last, which only ties need), the faces of the nearer
                winding (by mean depth) are drawn first, then each face of the other winding
                whose box holds a sample no nearer face has taken yet (exact: every sample of a
                skipped face is already nearer). Where one of those meets a sample of equal
                depth, the order matters: the band is drawn again, all of it in face order. */
                splitFaces.resize(orderSize);
                // The count and sums in registers, without a branch on the winding: indexed by
                // it, they went through memory, a store and a reload per face.
                size_t clockwise = 0;
                double depthSum[2] = {0, 0};  // counterclockwise, clockwise
                {
                    const uint8_t* const isClockwise = work.clockwise.data();
                    const double* const faceKey = keyOf;
                    int* const split = splitFaces.data();
                    for (size_t j = 0; j < orderSize; j++) {
                        // Counterclockwise faces from the list's start, clockwise from its end,
                        // each in face order.
                        const int face = inFaceOrderAt(j);
                        const bool c = isClockwise[face] != 0;
                        const double key = faceKey[face];
                        depthSum[0] += c ? 0.0 : key;
                        depthSum[1] += c ? key : 0.0;
                        split[c ? orderSize - 1 - clockwise : j - clockwise] = face;
                        clockwise += c;
                    }
                }
                const size_t inClass[2] = {orderSize - clockwise, clockwise};
                // Comparing the means (false where a sum is not finite: any order is exact).
                const int nearClass =
                    depthSum[1] * double(inClass[0]) < depthSum[0] * double(inClass[1]) ? 1 : 0;
                auto classFaceAt = [&](int c) {
                    const int* const faces = splitFaces.data();
                    const size_t last = orderSize - 1;
                    return [faces, last, c](size_t j) { return faces[c ? last - j : j]; };
                };
                paintFaces(inClass[nearClass], classFaceAt(nearClass), always, paintSpan, never);
                const double* const nearest = bandDepths.data();
                // Whether every sample of face's box (in the band) is nearer than its depth.
                auto hiddenByNearer = [&](int face) {
                    const SampleBox& box = faceBox[face];
                    const double depth = keyOf[face];
                    const int r0 = std::max(box.rowBegin, y0), r1 = std::min(box.rowEnd, y1);
                    const int boxColumns = box.colLast - box.colFirst + 1;
                    if (unsigned(boxColumns - 1) < 8u) {
                        // Four or eight samples a row, with no early exit: most boxes tested
                        // are hidden, so read whole.
                        unsigned notNearer = 0;
                        const double* row = nearest + size_t(r0 - y0) * columns + box.colFirst;
                        if (boxColumns <= 4) {
                            for (int y = r0; y < r1; y++, row += columns)
                                notNearer |= notNearerFour(row, depth);
                        } else {
                            for (int y = r0; y < r1; y++, row += columns)
                                notNearer |= notNearerFour(row, depth) |
                                             notNearerFour(row + 4, depth) << 4;
                        }
                        return (notNearer & ((1u << boxColumns) - 1)) == 0;
                    }
                    // Wider boxes (the demo's, a sixth of its flat frame one sample at a time):
                    // four samples a step, a row at a time, the last step masked to the box.
                    const int whole = boxColumns & ~3;
                    const unsigned lastSteps = (1u << (boxColumns - whole)) - 1;
                    const double* row = nearest + size_t(r0 - y0) * columns + box.colFirst;
                    for (int y = r0; y < r1; y++, row += columns) {
                        unsigned notNearer = notNearerFour(row + whole, depth) & lastSteps;
                        for (int x = 0; x < whole; x += 4)
                            notNearer |= notNearerFour(row + x, depth);
                        if (notNearer)
                            return false;
                    }
                    return true;
                };
                sampleBlocks = false;
                bool tied = false;
                auto paintSpanTieChecked = [paintSpan, &tied, nearest, y0, columns](
                                               const TriangleSetup& t, const auto& shader,
                                               double depth, int y, int xBegin, int xEnd) {
                    const double* const row = nearest + size_t(y - y0) * columns;
                    bool tie = false;
                    for (int x = xBegin; x < xEnd; x++)
                        tie |= row[x] == depth;
                    tied |= tie;
                    paintSpan(t, shader, depth, y, xBegin, xEnd);
                };
                paintFaces(inClass[1 - nearClass], classFaceAt(1 - nearClass),
                           [&](int face) { return !hiddenByNearer(face); }, paintSpanTieChecked,
                           [&] { return tied; });
                if (tied) {
                    clearBand();
                    sampleBlocks = true;
                    paintFaces(orderSize, inFaceOrderAt, always, paintSpan, never);
                }
                continue;
            }

            if (backToFront) {
                // Little overdraw and big faces: the painter's way. Background first, then
                // every face back to front, overwriting; no coverage bookkeeping. A slice of
                // rows at a time, so that what is overwritten is still in cache. The entries'
                // sort keys, no longer needed, become the slices each face's box reaches.
                const bool sliced = y1 - y0 > paintRows;
                if (sliced)
                    for (size_t i = 0; i < orderSize; i++) {
                        if (i + kSliceBoxPrefetch < orderSize)
                            __builtin_prefetch(&faceBox[entryFace(order[i + kSliceBoxPrefetch])]);
                        const int face = entryFace(order[i]);
                        const SampleBox& box = faceBox[face];
                        const int first = (std::max(box.rowBegin, y0) - y0) >> paintShift;
                        const int last = (std::min(box.rowEnd, y1) - 1 - y0) >> paintShift;
                        const uint32_t slices = (2u << last) - (1u << first);
                        order[i] = uint64_t(slices) << 32 | uint32_t(face);
                    }
                for (int s0 = y0, slice = 0; s0 < y1; s0 += paintRows, slice++) {
                    const int s1 = std::min(y1, s0 + paintRows);
                    if (background)
                        for (int y = s0; y < s1; y++)
                            fillPixels(canvas.ptr<T>(y), 0, columns, background->val);
                    for (size_t next = orderSize; next > 0;) {
                        int count = 0;
                        for (; next > 0 && count < kBatch; next--)
                            if (!sliced || (order[next - 1] >> (32 + slice) & 1)) {
                                // Faces in depth order, from all over the arrays: read by
                                // prepareBatch once the batch is full.
                                const int face = entryFace(order[next - 1]);
                                __builtin_prefetch(&faceBox[face]);
                                __builtin_prefetch(&faceAt[face]);
                                batchFaces[count++] = face;
                            }
                        const int batchSize = prepareBatch(batchFaces, count);
                        for (int i = 0; i < batchSize; i++) {
                            const BatchFace& bf = batch[i];
                            walkTriangle(bf.triangle, s0, s1, columns,
                                         [&](int y, int xBegin, int xEnd) {
                                T* row = reinterpret_cast<T*>(pixels + size_t(y) * rowStep);
                                bf.shader(bf.triangle, row, y, xBegin, xBegin, xEnd);
                            });
                        }
                    }
                }
                continue;
            }

            // Front to back with a coverage mask: each pixel is written once, by its first
            // (frontmost) face, and faces behind finished rows are skipped unread.
            coverage.clear();
            if constexpr (Shaders::kZBuffer)
                if (deferred) {
                    keptFaces.resize(size_t(bandRows) * columns);
                    keptWeights.resize(size_t(bandRows) * columns * 2);
                }
            uchar* bandData = pixels + size_t(y0) * rowStep;  // row y0
            size_t bandStep = rowStep;
            // The background first, under the faces: the fill brings the band's lines into
            // cache for the faces' runs, and no pass at the end looks for the samples no face
            // claimed (that pass's stores found the lines gone again: the demo 0.92-0.94x the
            // time at one thread, random512 0.92-0.95x, random1024 0.89-0.91x). In a streamed
            // band's tile, only where its faces cover it a few layers deep on average: where
            // they cover it all, the fill is a wasted write of the tile (random2048, 13 layers,
            // 1.00-1.03x with it; sphere2048, 2, 0.94-0.96x).
            constexpr double kTileFillLayers = 4;
            const bool backgroundFirst =
                background &&
                (!streamBands ||
                 bandArea[band] <= kTileFillLayers * double(bandY1 - bandY0) * columns);
            if (streamBands) {
                tile.resize(size_t(bandRows) * rowBytes);
                bandData = tile.data();
                bandStep = rowBytes;
            }
            if (backgroundFirst) {
                for (int y = y0; y < y1; y++)
                    fillPixels(reinterpret_cast<T*>(bandData + size_t(y - y0) * bandStep), 0,
                               columns, background->val);
            } else if (!streamBands) {
                // Visible runs land all over the band's rows: asking for all of its lines now
                // lets the memory system fetch them in parallel, not one store miss at a time.
                for (int y = y0; y < y1; y++)
                    prefetchBytes(pixels + size_t(y) * rowStep, rowBytes);
            }
            std::fill(rowLeft, rowLeft + bandRows, columns);
            uint64_t fullRows = 0;  // bit r: row y0 + r is final everywhere
            const uint64_t allRows = rowsBelow(y1 - y0);
            // The rows of `box` within the band, as bits from y0, less the rows that are final
            // everywhere and (with maskTest) those whose part of the box is final already.
            // kAny: only whether some row is left matters.
            auto visibleRows = [&](const SampleBox& box, uint64_t& visible, bool maskTest,
                                   auto kAny) {
                const int r0 = std::max(box.rowBegin, y0) - y0, r1 = std::min(box.rowEnd, y1) - y0;
                visible = (rowsBelow(r1) & ~rowsBelow(r0)) & ~fullRows;
                if (visible && maskTest)
                    visible &= ~(coverage.finalRows<decltype(kAny)::value>(
                                     r0, r1, box.colFirst, box.colLast)
                                 << r0);
                return visible != 0;
            };
            for (size_t next = 0; next < orderSize && fullRows != allRows;) {
                int count = 0;
                for (; next < orderSize && count < kBatch; next++) {
                    // Faces come in depth order, their boxes from all over the array.
                    if (next + kBoxPrefetch < orderSize)
                        __builtin_prefetch(&faceBox[entryFace(order[next + kBoxPrefetch])]);
                    const int face = entryFace(order[next]);
                    uint64_t anyRows;  // a face whose box is final is skipped unread
                    if (visibleRows(faceBox[face], anyRows, true, std::true_type())) {
                        __builtin_prefetch(&faceAt[face]);  // read by prepareBatch
                        batchFaces[count++] = face;
                    }
                }
                // Draws a set-up face: its rows that are not final, each span claiming what is
                // not final yet.
                auto claimFace = [&](int face, const TriangleSetup& triangle, const auto& shader,
                                     auto&& walk) {
                    // Small faces (a box within two mask words and 16 rows) are not tested
                    // again: walking them costs about what the test does, and their claims skip
                    // what is final. A bigger face may be hidden by the batch's earlier faces.
                    const SampleBox& box = faceBox[face];
                    const bool retest = box.colLast - box.colFirst >= 64 ||
                                        box.rowEnd - box.rowBegin > 16;
                    uint64_t rowsToDraw;
                    if (!visibleRows(box, rowsToDraw, retest, std::false_type()))  // hidden now
                        return;
                    const int firstRow = y0 + __builtin_ctzll(rowsToDraw);
                    const int lastRow = y0 + 63 - __builtin_clzll(rowsToDraw);
                    // Shades run [a, b) of span [xBegin, ...) on row y (r from y0).
                    const auto shadeRun = [&](int y, int r, T* row, int xBegin, int a, int b) {
                        (void)face, (void)r;  // read by the z-buffer's shaders only
                        if constexpr (Shaders::kZBuffer) {
                            if (deferred) {  // shaded below, a batch at a time
                                shader.keep(triangle, y, a, b, face,
                                            keptFaces.data() + size_t(r) * columns,
                                            keptWeights.data() + size_t(r) * columns * 2);
                                return;
                            }
                        }
                        if constexpr (std::is_same<Shader, GouraudShader<T>>::value ||
                                      std::is_same<Shader, FlatShader<T>>::value)
                            shader.template shadeRun<true>(triangle, row, y, xBegin, a, b);
                        else
                            shader(triangle, row, y, xBegin, a, b);
                    };
                    auto span = [&](int y, int xBegin, int xEnd) {
                        const int r = y - y0;
                        if (!(rowsToDraw >> r & 1))
                            return;
                        T* row = reinterpret_cast<T*>(bandData + size_t(r) * bandStep);
                        // A small callback (the face's part by reference): GCC stores its
                        // captures before the claim's fast paths, on every span.
                        rowLeft[r] -= coverage.claim(
                            r, xBegin, xEnd, [&shadeRun, y, r, row, xBegin](int a, int b) {
                                shadeRun(y, r, row, xBegin, a, b);
                            });
                        if (rowLeft[r] == 0)
                            fullRows |= uint64_t(1) << r;
                    };
                    walk(firstRow, lastRow + 1, span);
                };
                drawBatch(batchFaces, count, claimFace);
            }
            if constexpr (Shaders::kZBuffer)
                if (deferred)
                    for (int y = y0; y < y1; y++)
                        shaders.shadeKeptRow(
                            reinterpret_cast<T*>(bandData + size_t(y - y0) * bandStep), y,
                            keptFaces.data() + size_t(y - y0) * columns,
                            keptWeights.data() + size_t(y - y0) * columns * 2,
                            coverage.row(y - y0), columns);
            if (background && !backgroundFirst) {  // where no face drew
                for (int y = y0; y < y1; y++) {
                    T* row = reinterpret_cast<T*>(bandData + size_t(y - y0) * bandStep);
                    // Claiming the whole row visits exactly what no face covered.
                    coverage.claim(y - y0, 0, columns, [&](int a, int b) {
                        fillPixels(row, a, b, background->val);
                    });
                }
            }
            if (streamBands)
                for (int y = y0; y < y1; y++)
                    streamBytes(pixels + size_t(y) * rowStep,
                                bandData + size_t(y - y0) * bandStep, rowBytes);
        }
        if (streamBands)
            streamingStoresDone();
        threadBuffers = BandWorkspace{std::move(coverage), std::move(scratch),
                                      std::move(refineRun), std::move(tile),
                                      std::move(zbuffer), std::move(keptWeights),
                                      std::move(keptFaces), std::move(bandDepths),
                                      std::move(partEntries), std::move(splitFaces)};
        if (threadBuffers.capacityBytes() > MeshWorkspace::kKeepBytes)
            threadBuffers = BandWorkspace();
#if OPENCV_SHADING_STAGE_TIMES
        workerTimes[range.start] = {
            double(getTickCount() - bandsStart) * 1000.0 / getTickFrequency(), workerBands};
#endif
    });
#if OPENCV_SHADING_STAGE_TIMES
    // When each worker finished, from the pass's start: how evenly the bands were shared.
    for (size_t w = 0; w < workerTimes.size(); w++)
        timer.note(format("worker%zu %.3f ms (%d bands), ", w, workerTimes[w].first,
                          workerTimes[w].second));
#endif
    timer.mark("bands");
    if (work.capacityBytes() > MeshWorkspace::kKeepBytes)
        work = MeshWorkspace();
}

OPENCV_SHADING_ISA_END
}  // namespace detail
}  // namespace shading
}  // namespace cv

#endif  // OPENCV_SHADING_MESH_HPP
