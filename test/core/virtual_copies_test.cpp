// Virtual leaders (SPEC 9.2): the copies a leader announces are neighbours of its hearers'
// flocking (core::NeighbourhoodOf expands them where it links the robot), and they travel on
// its own position - in its answer in lock-step, on its /flock/position in real time - to the
// robots that hear it: one position, not one per copy (sim::LockstepEngine).
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "fixtures.h"
#include "swarm_transport/core/flocking.h"
#include "swarm_transport/sim/lockstep_engine.h"

namespace swarm_transport {
namespace core {
namespace {

constexpr double kTolerance = 1e-9;

using fixtures::Quiet;
using fixtures::Robot;

// The perceiving robot.
constexpr auto At = fixtures::PerceptionAt;

double Heading(Angle a) { return Angle::SignedDifference(a, Angle(0)); }

// Virtual leaders (SPEC 9.2): the copies a robot announced with its position are neighbours of
// type 1 at its pose, sub_id 1..copies, wherever the robot is one (in range, hop by hop, its
// group admitting it), and nowhere else.
TEST(NeighbourhoodTest, AnnouncedCopiesAreNeighboursWhereTheirRobotIs) {
  Perception in = At(1.0, 5.0, 0.0);
  Neighbour leader = Robot(2, 1.9, 5.0, 45.0);
  leader.copies = 3;
  Neighbour far = Robot(4, 3.7, 5.0);  // linked through 3 only
  far.copies = 2;
  in.others = {leader, Robot(3, 2.8, 5.0), far};
  const std::vector<Neighbour> chain = NeighbourhoodOf(in, Quiet());
  ASSERT_EQ(chain.size(), 9u);  // itself, 2 + 3 copies, 3, 4 + 2 copies
  int copies_of_2 = 0;
  for (const Neighbour& n : chain) {
    if (n.type != 1) continue;
    EXPECT_EQ(n.copies, 0) << "a copy announces nothing";
    if (n.id != 2) continue;
    ++copies_of_2;
    EXPECT_EQ(n.sub_id, copies_of_2);
    EXPECT_DOUBLE_EQ(n.position.x, 1.9);
    EXPECT_DOUBLE_EQ(n.heading.degrees(), 45.0);
  }
  EXPECT_EQ(copies_of_2, 3);
  EXPECT_EQ(NeighbourhoodSize(chain), 4) << "copies are nobody to count";
  // A disc: 3, 4 and 4's copies are out of range.
  FlockingParams disc = Quiet();
  disc.neighbourhood = Neighbourhood::kDisc;
  EXPECT_EQ(NeighbourhoodOf(in, disc).size(), 5u);
  // Its group does not admit 2: neither it nor its copies (nor 3 and 4, linked through it).
  in.group.ids = {2};
  EXPECT_EQ(NeighbourhoodOf(in, Quiet()).size(), 1u);
  // A statist's copies field means nothing.
  in.group.ids.clear();
  Neighbour statist = Robot(7, 9.0, 9.0, 0.0, 2);
  statist.copies = 5;
  in.others = {statist};
  EXPECT_EQ(NeighbourhoodOf(in, Quiet()).size(), 2u);
}

// Alignment and cohesion with announced copies are those with as many explicit copies (type 1
// positions, as a robot would hear them one by one).
TEST(DesiredHeadingTest, AnnouncedCopiesWeighAsExplicitCopies) {
  Perception announced = At(5.0, 5.0, 90.0);
  Perception explicit_copies = announced;
  Neighbour leader = Robot(2, 5.5, 5.2, 0.0);
  announced.others = {Robot(3, 4.6, 5.0, 90.0)};
  explicit_copies.others = announced.others;
  explicit_copies.others.push_back(leader);
  for (std::uint8_t k = 1; k <= 4; ++k) {
    Neighbour copy = leader;
    copy.type = 1;
    copy.sub_id = k;
    explicit_copies.others.push_back(copy);
  }
  leader.copies = 4;
  announced.others.push_back(leader);
  FlockingParams p = Quiet();
  p.cohesion = 0.5;
  Rng a(1, 1);
  Rng b(1, 1);
  bool fleeing = false;
  int size_a = 0;
  int size_b = 0;
  const Angle with_field = DesiredHeading(announced, p, a, &fleeing, &size_a);
  const Angle with_copies = DesiredHeading(explicit_copies, p, b, &fleeing, &size_b);
  EXPECT_NEAR(Heading(with_field), Heading(with_copies), kTolerance);
  EXPECT_EQ(size_a, 3);
  EXPECT_EQ(size_b, 3);
  // And they do weigh: without them the wish differs.
  announced.others.back().copies = 0;
  Rng c(1, 1);
  EXPECT_GT(std::abs(Heading(DesiredHeading(announced, p, c, &fleeing)) - Heading(with_field)),
            5.0);
}

}  // namespace
}  // namespace core

namespace sim {
namespace {

// Robots 0 and 1 within range of each other, robot 2 far away.
class LockstepEngineCopiesTest : public ::testing::Test {
 protected:
  LockstepEngineCopiesTest() : world_(WorldParams()), radio_(Range(), &rng_) {
    std::string error;
    EXPECT_TRUE(world_.Spawn(0, {{1.0, 5.0}, core::Angle(0)}, &error)) << error;
    EXPECT_TRUE(world_.Spawn(1, {{1.5, 5.0}, core::Angle(90)}, &error)) << error;
    EXPECT_TRUE(world_.Spawn(2, {{8.0, 5.0}, core::Angle(0)}, &error)) << error;
  }
  static RadioParams Range() {
    RadioParams p;
    p.range_m = 1.0;
    return p;
  }
  // Round `tick` of robot `index`: the positions it hears in range.
  std::vector<core::Position> Hears(std::uint64_t tick, std::size_t index,
                                    const RelayedPositions* relayed = nullptr) {
    engine_.BeginRound(tick, 0.1 * static_cast<double>(tick), relayed, {});
    core::Round round;
    for (std::size_t i = 0; i <= index; ++i) engine_.Round(i, false, &round);
    engine_.EndRound();
    return round.robots;
  }
  void Answer(std::uint16_t id, std::uint8_t copies) {
    LockstepEngine::Answers answers(1);
    answers[0].first = id;
    answers[0].second.copies = copies;
    engine_.TakeAnswers(&answers, nullptr);
  }

  World2D world_;
  core::Rng rng_{1, 0};
  Radio radio_;
  LiveMissions missions_;
  LockstepEngine engine_{&world_, &radio_, &missions_};
};

TEST_F(LockstepEngineCopiesTest, AnAnswersCopiesTravelOnItsRobotsPositionFromTheNextRound) {
  std::vector<core::Position> heard = Hears(0, 0);
  ASSERT_EQ(heard.size(), 1u);
  EXPECT_EQ(heard[0].robot_id, 1);
  EXPECT_EQ(heard[0].copies, 0);
  Answer(1, 3);
  heard = Hears(1, 0);
  ASSERT_EQ(heard.size(), 1u) << "one position for the robot and its copies";
  EXPECT_EQ(heard[0].copies, 3);
  EXPECT_EQ(heard[0].type, core::Position::kPhysical);
  EXPECT_EQ(engine_.truth()[1].copies, 3);  // /flock/world_poses shows them too
  EXPECT_EQ(engine_.truth()[0].copies, 0);
  // Its own round: robot 0 without copies; the far robot hears nobody.
  heard = Hears(2, 1);
  ASSERT_EQ(heard.size(), 1u);
  EXPECT_EQ(heard[0].robot_id, 0);
  EXPECT_EQ(heard[0].copies, 0);
  EXPECT_TRUE(Hears(3, 2).empty());
  // An answer without copies ends them.
  Answer(1, 0);
  heard = Hears(4, 0);
  ASSERT_EQ(heard.size(), 1u);
  EXPECT_EQ(heard[0].copies, 0);
}

TEST_F(LockstepEngineCopiesTest, CopiesAnnouncedOnAPositionTravelInRealTime) {
  RelayedPositions relayed;
  core::Position own = core::PositionOf(1, {{1.5, 5.0}, core::Angle(90)});
  own.copies = 2;
  EXPECT_EQ(relayed.Take(own), "");
  EXPECT_EQ(relayed.size(), 0u) << "a robot's own position is no relayed position";
  std::vector<core::Position> heard = Hears(0, 0, &relayed);
  ASSERT_EQ(heard.size(), 1u);
  EXPECT_EQ(heard[0].copies, 2);
  own.copies = 0;
  EXPECT_EQ(relayed.Take(own), "");
  EXPECT_EQ(Hears(1, 0, &relayed)[0].copies, 0);
  own.copies = 5;
  EXPECT_EQ(relayed.Take(own), "");
  relayed.EraseCopiesOf(1);  // killed
  EXPECT_EQ(Hears(2, 0, &relayed)[0].copies, 0);
}

}  // namespace
}  // namespace sim
}  // namespace swarm_transport
