// A robot's lock-step round and its answer [SPEC 7], as the core holds them: what the simulator
// (or the batch runs) hands one robot for one tick, and what the robot says back. The ROS side
// carries them as messages (a round on robot_<id>/neighbors, an answer on robot_<id>/answer)
// and only converts (ros/common/conversions.h); in one process they pass as they are.
//
// Positions and reports have the precision their messages carry (float, headings in degrees
// [0, 360)), so that a round or an answer handed over in-process and one that crossed a topic
// give every reader the same values.
#ifndef SWARM_TRANSPORT_CORE_ROUND_H_
#define SWARM_TRANSPORT_CORE_ROUND_H_

#include <cstdint>
#include <optional>
#include <vector>

#include "swarm_transport/core/flocking.h"
#include "swarm_transport/core/kinematics.h"
#include "swarm_transport/core/mission_agent.h"
#include "swarm_transport/core/mission_book.h"
#include "swarm_transport/core/mission_message.h"
#include "swarm_transport/core/run_metrics.h"
#include "swarm_transport/core/swarm_config.h"

namespace swarm_transport {
namespace core {

// `v` at the precision its message carries (float32).
double AsSent(double v);

// A robot's position as it broadcasts it after each move [thesis 5.2], or as the radio relays
// it: a robot, a leader's virtual copy or a statist.
struct Position {
  enum Type : std::uint8_t { kPhysical = 0, kVirtual = 1, kStatist = 2 };
  std::uint16_t robot_id = 0;
  std::uint8_t sub_id = 0;  // copy index, 0 for the robot itself
  std::uint8_t type = kPhysical;
  float x = 0.0f;  // m, arena frame
  float y = 0.0f;
  float angle_deg = 0.0f;  // [0, 360)
  // A robot's own position only: the virtual copies (type 1, sub_id 1..copies) it announces at
  // this pose with it (SPEC 9.2: a leader's stacking) - one message, expanded by its hearers'
  // flocking rule (NeighbourhoodOf).
  std::uint8_t copies = 0;
};
// The position of robot `id` at `pose`.
Position PositionOf(std::uint16_t id, const Pose2& pose, std::uint8_t sub_id = 0,
                    std::uint8_t type = Position::kPhysical);
bool IsFinite(const Position& p);
Neighbour NeighbourOf(const Position& p);

// A robot's own pose in its round (its odometry): theta in radians, (-pi, pi].
struct OwnPose {
  float x = 0.0f;
  float y = 0.0f;
  float theta = 0.0f;
  float linear_velocity = 0.0f;   // m/s
  float angular_velocity = 0.0f;  // rad/s
};
OwnPose OwnPoseOf(const Pose2& pose, const Velocity& velocity);
Pose2 Pose2Of(const OwnPose& pose);

// The swarm's live flocking tuning (issue 13): generation `generation`, first carried in round
// `tick`.
struct TuningGeneration {
  std::uint32_t generation = 0;
  std::uint64_t tick = 0;
  FlockingTuning tuning;
};

// What the radio delivers to one robot for one tick; in lock-step each round is one tick.
struct Round {
  std::uint64_t tick = 0;
  double sim_time = 0.0;  // s, simulated time of the tick
  OwnPose pose;
  std::vector<Position> robots;         // heard in range (robots, copies, statists)
  std::vector<Position> relayed;        // beyond range, passed on hop by hop
  std::vector<Position> mission_peers;  // members of its live missions, wherever they are
  // Lock-step: the mission messages of the previous tick (and, for a robot that has just
  // connected, the standing orders with their phases), in the order a robot takes them
  // (core::MissionMessage's alternatives; within a kind, as relayed).
  std::vector<MissionMessage> messages;
  std::optional<TuningGeneration> tuning;  // once a tuning was made live
};
// What robot `id` perceives of a round when it listens to the radio: its own pose, then the
// robots in range, those relayed hop by hop and its mission peers; a non-finite one is dropped.
Perception PerceptionOf(std::uint16_t id, const Round& round);

// A robot's whole answer to one round: its command and every mission message it sends in that
// tick (a first leader's).
struct Answer {
  std::uint64_t tick = 0;  // the tick answered
  double sim_time = 0.0;   // its simulated time (the statuses' stamp in lock-step)
  // Any non-finite value: the robot stands (CommandOf).
  Velocity command;
  // Object updates, freezes, continues, object deletes, in that order.
  std::vector<MissionMessage> messages;
  std::vector<StatusReport> statuses;  // phase reports
  std::vector<StatusReport> progress;  // reports within a phase (observers only)
  // Virtual copies it announces at its new pose (SPEC 9.2; lock-step: heard from the next round
  // on, with its position).
  std::uint8_t copies = 0;
  bool Says() const { return !messages.empty() || !statuses.empty() || !progress.empty(); }
};
// The command an answer drives: a non-finite one stands (zero velocity).
Velocity CommandOf(const Answer& answer);
// A first leader's outbox as an answer's messages and statuses (already sequenced; `progress`
// the repeats), at the precision their messages carry.
void FillAnswer(const MissionOutbox& outbox, std::vector<StatusReport> progress, Answer* answer);
// A status report of tick `tick` as the dispatcher books it.
MissionReport ReportOf(const StatusReport& status, std::uint64_t tick);

// The recorder's frame of a round's positions: the physical robots by id (a duplicate id once);
// `bad` counts those with a non-finite position (left out).
MetricsFrame FrameOf(std::uint64_t tick, double sim_time, const std::vector<Position>& positions,
                     std::size_t* bad);

}  // namespace core
}  // namespace swarm_transport

#endif  // SWARM_TRANSPORT_CORE_ROUND_H_
