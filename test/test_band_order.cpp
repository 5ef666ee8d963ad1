// This file is part of opencv_shading. License: Apache-2.0.
//
// A band's painter's order (internal): sortBandEntries on narrowed keys, then refineEqualKeys,
// give exactly the front-to-back order, nearer mean depth first and among equal depths the later
// face first, whatever the key width: checked against std::sort on the exact depths.
#include "../modules/shading/src/mesh.hpp"

#include <gtest/gtest.h>

#include <opencv2/core.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <utility>
#include <vector>

namespace {

using namespace cv::shading::detail;

// Depths drawn so that a key width sees both ties and near-ties: a few equal values, values
// closer than a 16-bit level, values spread over the whole range and, with `outlier`, one far
// value that crowds all the others into a few levels.
std::vector<double> crowdedDepths(cv::RNG& rng, int count, bool outlier)
{
    std::vector<double> depth(count);
    for (double& d : depth) {
        switch (rng.uniform(0, 4)) {
        case 0: d = double(rng.uniform(0, 5)); break;                // exact ties
        case 1: d = 1.0 + rng.uniform(0, 1000) * 1e-9; break;        // within one level
        case 2: d = rng.uniform(-3.0, 3.0); break;                   // spread
        default: d = 2.0 + rng.uniform(0, 40) * std::ldexp(1.0, -30); // near-ties
        }
    }
    if (outlier)
        depth[rng.uniform(0, count)] = 1e6;
    return depth;
}

// The band pass's order of `depth`'s faces, from a list in decreasing face order (as binning
// writes it).
std::vector<int> bandOrder(const std::vector<double>& depth, int keyBits)
{
    const auto [lo, hi] = std::minmax_element(depth.begin(), depth.end());
    const double scale = *hi > *lo ? double(UINT32_MAX) / (*hi - *lo) : 0;
    std::vector<uint64_t> entries;
    for (int face = int(depth.size()); face-- > 0;)
        entries.push_back(bandEntry(quantizeDepth(depth[face], *lo, scale), face));
    std::vector<uint64_t> scratch;
    std::vector<std::pair<double, uint64_t>> run;
    uint64_t* sorted = sortBandEntries(entries.data(), entries.size(), scratch, keyBits);
    refineEqualKeys(sorted, entries.size(), depth.data(), run);
    std::vector<int> order;
    for (size_t i = 0; i < entries.size(); i++)
        order.push_back(entryFace(sorted[i]));
    return order;
}

}  // namespace

TEST(BandOrder, FrontToBackForEveryKeyWidth)
{
    cv::RNG rng(20261125);
    for (int count : { 2, 7, 300, 9000, 40000 })
        for (bool outlier : { false, true }) {
            const std::vector<double> depth = crowdedDepths(rng, count, outlier);
            std::vector<int> expected(count);
            for (int i = 0; i < count; i++)
                expected[i] = i;
            std::sort(expected.begin(), expected.end(), [&](int a, int b) {
                return depth[a] < depth[b] || (depth[a] == depth[b] && a > b);
            });
            for (int keyBits : { 8, 16, 24 })
                EXPECT_EQ(bandOrder(depth, keyBits), expected)
                    << count << " faces, " << keyBits << "-bit keys, outlier " << outlier;
        }
}
