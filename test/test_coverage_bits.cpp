// This file is part of opencv_shading. License: Apache-2.0.
//
// The front-to-back bands' coverage bits (internal): the occlusion test CoverageBits::finalRows
// against a plain per-pixel record of what the claims marked final, with claims and tests
// interleaved at random, so that the words the test remembers as final (for big boxes) are
// reused after the coverage has grown; and the background that face-order bands paint last.
#include "../modules/shading/src/mesh.hpp"

#include <gtest/gtest.h>

#include <opencv2/core.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

using cv::shading::detail::CoverageBits;

namespace {

//! The bits of rows [rowBegin, rowEnd) whose pixels [colFirst, colLast] are all in `final`.
uint64_t finalRowsOf(const std::vector<std::vector<bool>>& final, int rowBegin, int rowEnd,
                     int colFirst, int colLast)
{
    uint64_t rows = 0;
    for (int r = rowBegin; r < rowEnd; r++) {
        bool all = true;
        for (int x = colFirst; x <= colLast; x++)
            all = all && final[r][x];
        if (all)
            rows |= uint64_t(1) << (r - rowBegin);
    }
    return rows;
}

void checkRandomClaimsAndTests(int width, uint64_t seed)
{
    constexpr int kRows = 64;
    CoverageBits coverage;
    coverage.reset(kRows, width);
    cv::RNG rng(seed);
    for (int band = 0; band < 3; band++) {  // clear() forgets what the tests remembered
        coverage.clear();
        std::vector<std::vector<bool>> final(kRows, std::vector<bool>(width, false));
        for (int step = 0; step < 3000; step++) {
            if (rng.uniform(0, 3) == 0) {  // a claim; long spans, so rows fill up
                const int row = rng.uniform(0, kRows);
                const int a = rng.uniform(0, width);
                const int b = std::min(width, a + 1 + rng.uniform(0, width / 2));
                int newly = 0;
                for (int x = a; x < b; x++)
                    newly += final[row][x] ? 0 : 1;
                std::vector<bool> reported(width, false);
                const int claimed = coverage.claim(row, a, b, [&](int runBegin, int runEnd) {
                    for (int x = runBegin; x < runEnd; x++)
                        reported[x] = true;
                });
                ASSERT_EQ(claimed, newly);
                for (int x = 0; x < width; x++)
                    ASSERT_EQ(bool(reported[x]), x >= a && x < b && !final[row][x]) << x;
                for (int x = a; x < b; x++)
                    final[row][x] = true;
                continue;
            }
            // A box: tall and wide ones too, as the faces of a big random mesh have.
            const int rowBegin = rng.uniform(0, kRows);
            const int rowEnd = std::min(kRows, rowBegin + 1 + rng.uniform(0, kRows));
            const int colFirst = rng.uniform(0, width);
            const int colLast = std::min(width - 1, colFirst + rng.uniform(0, width));
            const uint64_t expected = finalRowsOf(final, rowBegin, rowEnd, colFirst, colLast);
            ASSERT_EQ(coverage.finalRows<false>(rowBegin, rowEnd, colFirst, colLast), expected)
                << "rows " << rowBegin << "-" << rowEnd << ", columns " << colFirst << "-"
                << colLast << ", step " << step;
            // Stopping at an open row: only final rows reported, and all of them when no row
            // is open.
            const uint64_t boxRows = rowEnd - rowBegin >= 64
                                         ? ~uint64_t(0)
                                         : (uint64_t(1) << (rowEnd - rowBegin)) - 1;
            const uint64_t untilOpen =
                coverage.finalRows<true>(rowBegin, rowEnd, colFirst, colLast);
            ASSERT_EQ(untilOpen & ~expected, 0u) << "step " << step;
            ASSERT_EQ(untilOpen == boxRows, expected == boxRows) << "step " << step;
        }
    }
}

TEST(CoverageBits, FinalRowsMatchPerPixelRecordNarrow)
{
    checkRandomClaimsAndTests(70, 1);  // two words, the second partial
}

TEST(CoverageBits, FinalRowsMatchPerPixelRecordWide)
{
    checkRandomClaimsAndTests(300, 2);  // five words: boxes over three and more
}

TEST(CoverageBits, FinalRowsOfHiddenBoxAfterGrowth)
{
    // A box over four words and all 64 rows: open, then final once the last word fills; the
    // words seen final before (remembered) and after must agree.
    CoverageBits coverage;
    coverage.reset(64, 256);
    coverage.clear();
    auto none = [](int, int) {};
    for (int r = 0; r < 64; r++)
        coverage.claim(r, 0, 200, none);
    EXPECT_EQ(coverage.finalRows<true>(0, 64, 10, 250) == ~uint64_t(0), false);
    EXPECT_EQ(coverage.finalRows<false>(0, 64, 10, 250), 0u);
    EXPECT_EQ(coverage.finalRows<false>(0, 64, 10, 199), ~uint64_t(0));
    for (int r = 0; r < 64; r += 2)
        coverage.claim(r, 200, 256, none);
    EXPECT_EQ(coverage.finalRows<false>(0, 64, 10, 250), 0x5555555555555555u);
    for (int r = 1; r < 64; r += 2)
        coverage.claim(r, 200, 256, none);
    EXPECT_EQ(coverage.finalRows<false>(0, 64, 10, 250), ~uint64_t(0));
    EXPECT_EQ(coverage.finalRows<true>(3, 40, 70, 255), (uint64_t(1) << 37) - 1);
}

}  // namespace

// A face-order band paints the background after its faces, where a sample's depth is still
// kUntouchedDepth (mesh.hpp: paintUntouched, 4 depths a step): every pattern of taken and
// untouched samples in rows of 1 to 40 (runs starting and ending at every position within a
// step, whole rows of each), float and 8-bit rows, against a per-pixel loop; a taken sample at
// +inf or -inf is not untouched.
TEST(FaceOrderBackground, PaintsExactlyTheUntouchedSamples)
{
    using cv::shading::detail::kUntouchedDepth;
    using cv::shading::detail::paintUntouched;
    cv::RNG rng(7);
    const double inf = std::numeric_limits<double>::infinity();
    for (int trial = 0; trial < 4000; trial++) {
        const int columns = 1 + trial % 40;
        std::vector<double> depths(columns);
        const int kind = trial / 40 % 4;  // random, runs, all untouched, all taken
        bool untouched = rng.uniform(0, 2) != 0;
        for (int x = 0; x < columns; x++) {
            if (kind == 0)
                untouched = rng.uniform(0, 2) != 0;
            else if (kind == 1 && rng.uniform(0, 5) == 0)
                untouched = !untouched;
            const bool u = kind == 2 || (kind != 3 && untouched);
            const double taken[4] = {rng.uniform(-1.0, 1.0), inf, -inf, 0.0};
            depths[x] = u ? kUntouchedDepth : taken[rng.uniform(0, 4)];
        }
        const float colour[3] = {0.25f, -0.5f, 2.0f};
        const uchar bytes[3] = {7, 200, 31};
        std::vector<float> row(3 * columns + 1, -9.0f);  // one float past the row: untouched
        std::vector<uchar> rowBytes(3 * columns + 1, 99);
        paintUntouched(row.data(), depths.data(), columns, colour);
        paintUntouched(rowBytes.data(), depths.data(), columns, bytes);
        for (int x = 0; x < columns; x++)
            for (int k = 0; k < 3; k++) {
                const bool u = std::isnan(depths[x]);
                ASSERT_EQ(row[3 * x + k], u ? colour[k] : -9.0f)
                    << "float row of " << columns << ", sample " << x << ", trial " << trial;
                ASSERT_EQ(rowBytes[3 * x + k], u ? bytes[k] : 99)
                    << "8-bit row of " << columns << ", sample " << x << ", trial " << trial;
            }
        EXPECT_EQ(row[3 * columns], -9.0f);
        EXPECT_EQ(rowBytes[3 * columns], 99);
    }
}
