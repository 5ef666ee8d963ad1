// This file is part of opencv_shading. License: Apache-2.0.
//
// The band pass's schedule (internal): every quarter of every band is handed out exactly once,
// whatever the threads do; a worker's own run is consecutive bands of about its share of the
// cost, and where bands are few, runs end within bands and thieves take parts of them.
#include "../modules/shading/src/mesh.hpp"

#include <gtest/gtest.h>

#include <initializer_list>
#include <string>
#include <thread>
#include <utility>
#include <vector>

using cv::shading::detail::BandPart;
using cv::shading::detail::BandSchedule;

namespace {

//! Each band's cost shared by its four quarters, as the band pass does.
std::vector<double> quartersOf(const std::vector<double>& bandCost)
{
    std::vector<double> quarters;
    for (double cost : bandCost)
        quarters.insert(quarters.end(), BandPart::kQuarters, cost / BandPart::kQuarters);
    return quarters;
}

//! `bands` bands of cost 1, in quarters.
std::vector<double> equalBands(int bands)
{
    return quartersOf(std::vector<double>(bands, 1.0));
}

//! next(w) as "band" (whole), "band.q" (quarter q) or "band.q-r" (quarters q to r), or "none".
std::string nextOf(BandSchedule& schedule, int w)
{
    const BandPart part = schedule.next(w);
    if (part.band < 0)
        return "none";
    std::string text = std::to_string(part.band);
    if (!part.whole())
        text += "." + std::to_string(part.quarter);
    if (!part.whole() && part.quarters > 1)
        text += "-" + std::to_string(part.quarter + part.quarters - 1);
    return text;
}

//! Expects each (worker, part) in turn, as nextOf writes it.
void expectTakes(BandSchedule& schedule, std::initializer_list<std::pair<int, const char*>> takes)
{
    for (const auto& take : takes)
        EXPECT_EQ(nextOf(schedule, take.first), take.second) << "worker " << take.first;
}

}  // namespace

TEST(BandSchedule, OwnRunsAreConsecutiveSharesOfTheCost)
{
    // Costs 10 x 1, then 1 x 10: two workers split them 10 | 1 by cost, not 5.5 | 5.5 by count.
    std::vector<double> cost(10, 1.0);
    cost.push_back(10.0);
    BandSchedule schedule(quartersOf(cost), 2, false);
    ASSERT_EQ(schedule.workers(), 2);
    for (int band = 0; band < 10; band++)
        EXPECT_EQ(nextOf(schedule, 0), std::to_string(band));  // worker 0's run, in order
    EXPECT_EQ(nextOf(schedule, 0), "10");  // then stolen, whole, from worker 1's
    EXPECT_EQ(nextOf(schedule, 0), "none");
    EXPECT_EQ(nextOf(schedule, 1), "none");
}

TEST(BandSchedule, AThiefTakesFromTheFarEndOfTheLongestRun)
{
    BandSchedule schedule(equalBands(12), 3, false);  // runs 0-3, 4-7, 8-11
    EXPECT_EQ(nextOf(schedule, 1), "4");
    for (const char* band : {"8", "9", "10", "11"})
        EXPECT_EQ(nextOf(schedule, 2), band);
    EXPECT_EQ(nextOf(schedule, 2), "3");  // run 0 has 4 left, run 1 three
    EXPECT_EQ(nextOf(schedule, 0), "0");
}

TEST(BandSchedule, WithPartsRunsEndWithinABand)
{
    // Costs 1, 2, 1: each worker's share is 2, so run 0 is band 0 and band 1's upper half.
    BandSchedule schedule(quartersOf({1.0, 2.0, 1.0}), 2);
    // Worker 1 starts with the rest of band 1. Its last band is its run's last, and no other
    // run has a band left: it takes it in halves.
    expectTakes(schedule, {{0, "0"}, {1, "1.2-3"}, {0, "1.0-1"}, {1, "2.0-1"}, {1, "2.2-3"},
                           {1, "none"}, {0, "none"}});
}

TEST(BandSchedule, ThievesTakeHalfBands)
{
    BandSchedule schedule(equalBands(4), 2);  // runs 0-1, 2-3
    // Worker 1's last band is whole (run 0 still has two). Then it takes the far halves of run
    // 0's last band.
    expectTakes(schedule, {{1, "2"}, {1, "3"}, {1, "1.2-3"}, {0, "0"}, {1, "1.0-1"}, {0, "none"},
                           {1, "none"}});
}

TEST(BandSchedule, AThiefTakesAQuarterWhereARunEndsWithinAHalf)
{
    // Costs 1, 2: shares of 1.5, so run 0 is band 0 and band 1's first quarter.
    BandSchedule schedule(quartersOf({1.0, 2.0}), 2);
    // Worker 1's run is three quarters, taken at once. A half from the far end of run 0 would
    // cross its end: a quarter. Worker 0's last band is then taken in halves.
    expectTakes(schedule, {{1, "1.1-3"}, {1, "1.0"}, {0, "0.0-1"}, {1, "0.2-3"}, {0, "none"},
                           {1, "none"}});
}

TEST(BandSchedule, AnOwnersLastBandIsWholeWhileAnotherRunHasABand)
{
    BandSchedule schedule(equalBands(4), 2);
    expectTakes(schedule, {{0, "0"}, {0, "1"}, {1, "2"}, {1, "3.0-1"}, {0, "3.2-3"}, {1, "none"},
                           {0, "none"}});
}

TEST(BandSchedule, SplitAll)
{
    BandSchedule schedule(equalBands(4), 1, true, true);
    for (const char* part : {"0.0", "0.1-3", "1.0-1", "1.2-3", "2.0", "2.1", "2.2", "2.3",
                             "3.0", "3.1-3", "none"})
        EXPECT_EQ(nextOf(schedule, 0), part);
}

TEST(BandSchedule, FewerBandsThanThreadsAndNone)
{
    BandSchedule three(equalBands(3), 8, false);
    EXPECT_EQ(three.workers(), 3);
    BandSchedule none(std::vector<double>(), 4);
    EXPECT_EQ(none.workers(), 1);
    EXPECT_EQ(none.next(0).band, -1);
}

TEST(BandSchedule, WorkersBeyondTheBandsTakeParts)
{
    BandSchedule schedule(equalBands(2), 8);  // runs 0 and 1
    ASSERT_EQ(schedule.workers(), 4);          // one per half band
    // Workers 2 and 3 have no run: each takes the far half of the run with the most left.
    expectTakes(schedule, {{2, "0.2-3"}, {3, "1.2-3"}, {0, "0.0-1"}, {1, "1.0-1"}, {0, "none"},
                           {1, "none"}, {2, "none"}, {3, "none"}});
}

TEST(BandSchedule, EveryQuarterOnceUnderConcurrentTakers)
{
    for (int round = 0; round < 30; round++) {
        const int bands = 500 + round, workers = 4;
        std::vector<double> cost(size_t(bands) * BandPart::kQuarters);
        for (size_t q = 0; q < cost.size(); q++)
            cost[q] = double((q * 7919) % 13);  // zero costs too
        // Whole bands only, parts where they pay, every band in parts.
        BandSchedule schedule(cost, workers, round % 3 != 0, round % 3 == 2);
        std::vector<std::vector<BandPart>> taken(workers);
        std::vector<std::thread> threads;
        for (int w = 0; w < workers; w++)
            threads.emplace_back([&, w] {
                for (BandPart part; (part = schedule.next(w)).band >= 0;)
                    taken[w].push_back(part);
            });
        for (std::thread& t : threads)
            t.join();
        std::vector<int> times(cost.size(), 0);  // per quarter band
        for (const auto& list : taken)
            for (const BandPart& part : list) {
                ASSERT_GE(part.band, 0);
                ASSERT_LT(part.band, bands);
                ASSERT_GE(part.quarter, 0);
                ASSERT_GE(part.quarters, 1);
                ASSERT_LE(part.quarter + part.quarters, BandPart::kQuarters);
                if (round % 3 == 0) {
                    ASSERT_TRUE(part.whole());
                }
                for (int q = part.quarter; q < part.quarter + part.quarters; q++)
                    times[size_t(part.band) * BandPart::kQuarters + q]++;
            }
        for (size_t q = 0; q < times.size(); q++)
            EXPECT_EQ(times[q], 1) << "quarter band " << q << " round " << round;
    }
}
