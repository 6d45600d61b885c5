// How the ranks split a round of work items, and the one-process Ranks.
#include "distributed/ranks.h"

#include <gtest/gtest.h>

#include <cstdlib>

namespace wp {
namespace {

TEST(ShareOf, SplitsARoundInContiguousSharesInRankOrder) {
    for (const ItemRange round : {ItemRange{0, 7}, ItemRange{1000, 1003}, ItemRange{5, 6}, ItemRange{0, 1u << 20}}) {
        for (int ranks : {1, 2, 3, 4, 7}) {
            SCOPED_TRACE(testing::Message() << round.begin << ":" << round.end << " on " << ranks);
            std::uint64_t at = round.begin, smallest = UINT64_MAX, largest = 0;
            for (int rank = 0; rank < ranks; ++rank) {
                const ItemRange share = share_of(round, rank, ranks);
                EXPECT_EQ(share.begin, at);
                EXPECT_LE(share.begin, share.end);
                at = share.end;
                smallest = std::min(smallest, share.size());
                largest = std::max(largest, share.size());
            }
            EXPECT_EQ(at, round.end);
            EXPECT_LE(largest - smallest, 1u);
        }
    }
}

TEST(ShareOf, DoesNotOverflowOnTheLargestRounds) {
    const ItemRange round{1, UINT64_MAX};
    EXPECT_EQ(share_of(round, 1, 2).begin, 1 + (UINT64_MAX - 1) / 2);
    EXPECT_EQ(share_of(round, 2, 3).end, UINT64_MAX);
}

TEST(SingleProcess, IsRankZeroOfOneAndKeepsItsValues) {
    SingleProcess one;
    EXPECT_EQ(one.rank(), 0);
    EXPECT_EQ(one.size(), 1);
    EXPECT_TRUE(one.is_root());
    EXPECT_TRUE(one.any(true));
    EXPECT_FALSE(one.any(false));
    EXPECT_EQ(one.gather({3, 4}), (std::vector<std::uint64_t>{3, 4}));
    int value = 5;
    one.broadcast(value);
    EXPECT_EQ(value, 5);
}

TEST(JoinRanks, IsOneProcessWithoutALauncher) {
    for (const char* variable : {"OMPI_COMM_WORLD_SIZE", "PMIX_SIZE", "PMI_SIZE", "PMIX_RANK", "PMI_RANK"})
        unsetenv(variable);
    const std::unique_ptr<Ranks> ranks = join_ranks();
    EXPECT_EQ(ranks->size(), 1);
    EXPECT_NE(dynamic_cast<SingleProcess*>(ranks.get()), nullptr);
}

}  // namespace
}  // namespace wp
