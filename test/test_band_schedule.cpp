// This file is part of opencv_shading. License: Apache-2.0.
//
// The band pass's schedule (internal): every row of every band is handed out exactly once,
// whatever the threads do; a worker's own run is consecutive whole bands of about its share of
// the cost, and thieves take half bands where bands are few.
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

//! next(w) as "band" (whole), "band.0" / "band.1" (upper / lower half) or "none".
std::string nextOf(BandSchedule& schedule, int w)
{
    const BandPart part = schedule.next(w);
    if (part.band < 0)
        return "none";
    return std::to_string(part.band) + (part.half < 0 ? "" : "." + std::to_string(part.half));
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
    BandSchedule schedule(cost, 2, false);
    ASSERT_EQ(schedule.workers(), 2);
    for (int band = 0; band < 10; band++)
        EXPECT_EQ(nextOf(schedule, 0), std::to_string(band));  // worker 0's run, in order
    EXPECT_EQ(nextOf(schedule, 0), "10");  // then stolen, whole, from worker 1's
    EXPECT_EQ(nextOf(schedule, 0), "none");
    EXPECT_EQ(nextOf(schedule, 1), "none");
}

TEST(BandSchedule, AThiefTakesFromTheFarEndOfTheLongestRun)
{
    BandSchedule schedule(std::vector<double>(12, 1.0), 3, false);  // runs 0-3, 4-7, 8-11
    EXPECT_EQ(nextOf(schedule, 1), "4");
    for (const char* band : {"8", "9", "10", "11"})
        EXPECT_EQ(nextOf(schedule, 2), band);
    EXPECT_EQ(nextOf(schedule, 2), "3");  // run 0 has 4 left, run 1 three
    EXPECT_EQ(nextOf(schedule, 0), "0");
}

TEST(BandSchedule, ThievesTakeHalfBandsAndOwnersTheRest)
{
    BandSchedule schedule(std::vector<double>(4, 1.0), 2);  // runs 0-1, 2-3; halves
    // Worker 1's last band is whole (run 0 still has two); then it takes the far half of run
    // 0's last band. No other run has a band left: worker 0 takes its last one in halves.
    expectTakes(schedule, {{1, "2"}, {1, "3"}, {1, "1.1"}, {0, "0.0"}, {1, "1.0"}, {0, "0.1"},
                           {0, "none"}, {1, "none"}});
}

TEST(BandSchedule, AnOwnersLastBandIsWholeWhileAnotherRunHasBands)
{
    BandSchedule schedule(std::vector<double>(4, 1.0), 2);
    expectTakes(schedule, {{0, "0"}, {0, "1"}, {1, "2"}, {1, "3.0"}, {0, "3.1"}});
}

TEST(BandSchedule, OnlyHalves)
{
    BandSchedule schedule(std::vector<double>(2, 1.0), 1, true, true);
    for (const char* part : {"0.0", "0.1", "1.0", "1.1", "none"})
        EXPECT_EQ(nextOf(schedule, 0), part);
}

TEST(BandSchedule, FewerBandsThanThreadsAndNone)
{
    BandSchedule three(std::vector<double>(3, 1.0), 8, false);
    EXPECT_EQ(three.workers(), 3);
    BandSchedule none(std::vector<double>(), 4);
    EXPECT_EQ(none.workers(), 1);
    EXPECT_EQ(none.next(0).band, -1);
}

TEST(BandSchedule, WorkersBeyondTheBandsTakeHalves)
{
    BandSchedule schedule(std::vector<double>(2, 1.0), 8);  // runs 0 and 1; halves
    ASSERT_EQ(schedule.workers(), 4);                        // one per half band
    // Workers 2 and 3 have no run: each takes the far half of the run with the most left.
    expectTakes(schedule, {{2, "0.1"}, {3, "1.1"}, {0, "0.0"}, {1, "1.0"}, {0, "none"},
                           {1, "none"}, {2, "none"}, {3, "none"}});
}

TEST(BandSchedule, EveryHalfOnceUnderConcurrentTakers)
{
    for (int round = 0; round < 30; round++) {
        const int bands = 500 + round, workers = 4;
        std::vector<double> cost(bands);
        for (int k = 0; k < bands; k++)
            cost[k] = double((k * 7919) % 13);  // zero costs too
        // Whole bands only, halves for thieves, halves for all.
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
        std::vector<int> times(2 * bands, 0);  // per half band
        for (const auto& list : taken)
            for (const BandPart& part : list) {
                ASSERT_GE(part.band, 0);
                ASSERT_LT(part.band, bands);
                ASSERT_GE(part.half, -1);
                ASSERT_LE(part.half, 1);
                if (round % 3 == 0) {
                    ASSERT_EQ(part.half, -1);
                }
                for (int h = 0; h < 2; h++)
                    times[2 * part.band + h] += part.half < 0 || part.half == h;
            }
        for (int k = 0; k < 2 * bands; k++)
            EXPECT_EQ(times[k], 1) << "half band " << k << " round " << round;
    }
}
