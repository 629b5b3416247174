// Remapped ids of other networks' nodes (asebaswitch's rule: keep the id
// unless it clashes) and the duplicate filter of QoS 1 deliveries.

#include <gtest/gtest.h>

#include "tools/mqtt/remote_nodes.hpp"

namespace
{

using namespace aseba::mqtt;

TEST(RemoteNodeIds, KeepsFreeIdsAndRemapsClashes)
{
    RemoteNodeIds ids;
    std::set<uint16_t> local = { 1, 2 };
    EXPECT_EQ(ids.id_for("b", 5, local), 5); // free: kept
    EXPECT_EQ(ids.id_for("b", 1, local), 3); // clashes with ours: lowest free
    EXPECT_EQ(ids.id_for("c", 5, local), 4); // taken by b's 5
    EXPECT_EQ(ids.id_for("b", 1, local), 3); // stable
    EXPECT_EQ(ids.id_for("b", 0, local), 0); // a host stays a host
    EXPECT_TRUE(ids.is_remote(3));
    EXPECT_FALSE(ids.is_remote(1));
    // A node of ours takes 3: b's 1 moves.
    local.insert(3);
    uint16_t moved = ids.id_for("b", 1, local);
    EXPECT_TRUE(local.count(moved) == 0 && moved != 5 && moved != 4) << moved;
}

TEST(DuplicateFilter, EachEventOnce)
{
    DuplicateFilter filter;
    EXPECT_FALSE(filter.seen_before("s", 1));
    EXPECT_TRUE(filter.seen_before("s", 1));
    EXPECT_FALSE(filter.seen_before("s", 3));
    EXPECT_FALSE(filter.seen_before("s", 2)); // late, not a copy
    EXPECT_TRUE(filter.seen_before("s", 2));
    EXPECT_FALSE(filter.seen_before("t", 1)); // another session
    EXPECT_FALSE(filter.seen_before("s", 1000));
    EXPECT_TRUE(filter.seen_before("s", 3)); // beyond the window: refused
    EXPECT_FALSE(filter.seen_before("s", 999));
}

} // namespace
