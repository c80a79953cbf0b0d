// Statist as dispatcher (SPEC 9.4): who entered the object first, when enough are inside, and
// the recruiting order's validation. Hand-built positions.
#include "swarm_transport/core/recruit.h"

#include <gtest/gtest.h>

#include <cmath>

namespace swarm_transport {
namespace core {
namespace {

// A 2 x 2 object at (5, 5) (inside: [4, 6] x [4, 6]), 3 robots, 1 leader.
MissionSpec Recruit(std::uint16_t count = 3, int leaders = 1) {
  MissionSpec spec;
  spec.id = 4;
  spec.recruit = true;
  spec.robot_count = count;
  spec.leader_number = leaders;
  spec.object_centre = {5.0, 5.0};
  spec.object_size = {2.0, 2.0};
  spec.target = {2.0, 2.0};
  return spec;
}

const Vec2 kIn{5.0, 5.0};
const Vec2 kOut{1.0, 1.0};

TEST(RecruitWatch, FirstToEnterInOrderTiesByIdUntilEnough) {
  RecruitWatch watch(Recruit(3));
  EXPECT_FALSE(watch.Observe({{1, kOut}, {2, kOut}, {7, kOut}, {9, kOut}}));
  EXPECT_FALSE(watch.Observe({{1, kOut}, {2, kOut}, {7, {4.5, 5.5}}, {9, kOut}}));
  // 2 and 9 enter in the same tick: ascending id.
  EXPECT_TRUE(watch.Observe({{1, kOut}, {2, kIn}, {7, {4.5, 5.5}}, {9, kIn}}));
  EXPECT_EQ(watch.Recruits(), (std::vector<std::uint16_t>{7, 2, 9}));
}

TEST(RecruitWatch, MoreThanEnoughTakesTheFirstOnes) {
  RecruitWatch watch(Recruit(2));
  watch.Observe({{5, kIn}});
  EXPECT_TRUE(watch.Observe({{1, kIn}, {3, kIn}, {5, kIn}}));
  EXPECT_EQ(watch.inside().size(), 3u);
  EXPECT_EQ(watch.Recruits(), (std::vector<std::uint16_t>{5, 1}));
}

TEST(RecruitWatch, ARobotThatLeavesLosesItsPlace) {
  RecruitWatch watch(Recruit(2));
  watch.Observe({{1, kIn}, {2, kOut}});
  watch.Observe({{1, kIn}, {2, kIn}, {3, kOut}});
  // ... but 1 drives out before a third comes: 2 is first now; 1 re-enters behind 3.
  EXPECT_TRUE(watch.Observe({{1, kOut}, {2, kIn}, {3, kIn}}));
  EXPECT_EQ(watch.Recruits(), (std::vector<std::uint16_t>{2, 3}));
  // A robot no longer listed (taken by another mission) leaves the queue too.
  EXPECT_TRUE(watch.Observe({{1, kIn}, {3, kIn}}));
  EXPECT_EQ(watch.inside(), (std::vector<std::uint16_t>{3, 1}));
}

TEST(RecruitWatch, NonFinitePositionsNeverCount) {
  RecruitWatch watch(Recruit(1));
  EXPECT_FALSE(watch.Observe({{1, {std::nan(""), 5.0}}}));
  EXPECT_TRUE(watch.Observe({{1, {5.0, 5.0}}}));
}

TEST(RecruitedOrder, NamesTheRecruitsAscendingAndIsNoLongerARecruit) {
  const MissionSpec order = RecruitedOrder(Recruit(3, 2), {7, 2, 9});
  EXPECT_EQ(order.robot_ids, (std::vector<std::uint16_t>{2, 7, 9}));
  EXPECT_EQ(order.robot_count, 0);
  EXPECT_FALSE(order.recruit);
  EXPECT_EQ(order.Leaders(), (std::vector<std::uint16_t>{2, 7}));
  MissionContext ctx;
  ctx.known_robots = {2, 7, 9};
  EXPECT_EQ(ValidateMission(order, ctx), "");
}

TEST(ValidateRecruit, AcceptsAndRejectsWithReasons) {
  MissionContext ctx;
  ctx.world_size_m = 10.0;
  const std::set<std::uint16_t> idle{0, 1, 2, 3};
  EXPECT_EQ(ValidateRecruit(Recruit(3), idle, ctx), "");
  EXPECT_EQ(ValidateRecruit(Recruit(5), idle, ctx),
            "recruit of robot_count 5 but only 4 robots are idle");
  EXPECT_NE(ValidateRecruit(Recruit(0), idle, ctx).find("robot_count > 0"), std::string::npos);
  EXPECT_NE(ValidateRecruit(Recruit(3, 4), idle, ctx).find("leader_number 4"), std::string::npos);
  MissionSpec outside = Recruit(3);
  outside.object_centre = {12.0, 5.0};
  EXPECT_NE(ValidateRecruit(outside, idle, ctx).find("outside the arena"), std::string::npos);
  MissionSpec named = Recruit(3);
  named.robot_ids = {1};
  EXPECT_NE(ValidateRecruit(named, idle, ctx).find("names no robots"), std::string::npos);
  MissionSpec named_leader = Recruit(3);
  named_leader.leader_ids = {1};
  EXPECT_NE(ValidateRecruit(named_leader, idle, ctx).find("without leader_ids"), std::string::npos);
  MissionSpec leader_only = Recruit(1);
  leader_only.object_size = {0.0, 0.0};
  EXPECT_NE(ValidateRecruit(leader_only, idle, ctx).find("needs an object"), std::string::npos);
  ctx.live_missions = {4};
  EXPECT_NE(ValidateRecruit(Recruit(3), idle, ctx).find("already live"), std::string::npos);
}

TEST(ValidateMission, ARecruitingOrderNeedsTheDispatcher) {
  EXPECT_NE(ValidateMission(Recruit(3), MissionContext()).find("dispatcher"), std::string::npos);
}

}  // namespace
}  // namespace core
}  // namespace swarm_transport
