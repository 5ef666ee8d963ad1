// This file is part of opencv_shading. License: Apache-2.0.
//
// The band pass's schedule (internal): every band is handed out exactly once, whatever the
// threads do, and a worker's own run is consecutive bands of about its share of the cost.
#include "../modules/shading/src/mesh.hpp"

#include <gtest/gtest.h>

#include <thread>
#include <vector>

using cv::shading::detail::BandSchedule;

TEST(BandSchedule, OwnRunsAreConsecutiveSharesOfTheCost)
{
    // Costs 10 x 1, then 1 x 10: two workers split them 10 | 1 by cost, not 5.5 | 5.5 by count.
    std::vector<double> cost(10, 1.0);
    cost.push_back(10.0);
    BandSchedule schedule(cost, 2);
    ASSERT_EQ(schedule.workers(), 2);
    for (int band = 0; band < 10; band++)
        EXPECT_EQ(schedule.next(0), band);  // worker 0's run, in order
    EXPECT_EQ(schedule.next(0), 10);          // then stolen from worker 1's
    EXPECT_EQ(schedule.next(0), -1);
    EXPECT_EQ(schedule.next(1), -1);
}

TEST(BandSchedule, AThiefTakesFromTheFarEndOfTheLongestRun)
{
    BandSchedule schedule(std::vector<double>(12, 1.0), 3);  // runs 0-3, 4-7, 8-11
    EXPECT_EQ(schedule.next(1), 4);
    EXPECT_EQ(schedule.next(2), 8);
    EXPECT_EQ(schedule.next(2), 9);
    EXPECT_EQ(schedule.next(2), 10);
    EXPECT_EQ(schedule.next(2), 11);
    EXPECT_EQ(schedule.next(2), 3);  // run 0 has 4 left, run 1 three
    EXPECT_EQ(schedule.next(0), 0);
}

TEST(BandSchedule, FewerBandsThanThreadsAndNone)
{
    BandSchedule three(std::vector<double>(3, 1.0), 8);
    EXPECT_EQ(three.workers(), 3);
    BandSchedule none(std::vector<double>(), 4);
    EXPECT_EQ(none.workers(), 1);
    EXPECT_EQ(none.next(0), -1);
}

TEST(BandSchedule, EveryBandOnceUnderConcurrentTakers)
{
    for (int round = 0; round < 20; round++) {
        const int bands = 500 + round, workers = 4;
        std::vector<double> cost(bands);
        for (int k = 0; k < bands; k++)
            cost[k] = double((k * 7919) % 13);  // zero costs too
        BandSchedule schedule(cost, workers);
        std::vector<std::vector<int>> taken(workers);
        std::vector<std::thread> threads;
        for (int w = 0; w < workers; w++)
            threads.emplace_back([&, w] {
                for (int band; (band = schedule.next(w)) >= 0;)
                    taken[w].push_back(band);
            });
        for (std::thread& t : threads)
            t.join();
        std::vector<int> times(bands, 0);
        for (const auto& list : taken)
            for (int band : list) {
                ASSERT_GE(band, 0);
                ASSERT_LT(band, bands);
                times[band]++;
            }
        for (int k = 0; k < bands; k++)
            EXPECT_EQ(times[k], 1) << "band " << k << " round " << round;
    }
}
