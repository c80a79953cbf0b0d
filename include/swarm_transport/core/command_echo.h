// Real time with the simulator: whether a robot's newest round already shows its last command.
#ifndef SWARM_TRANSPORT_CORE_COMMAND_ECHO_H_
#define SWARM_TRANSPORT_CORE_COMMAND_ECHO_H_

#include <cstdint>

#include "swarm_transport/core/kinematics.h"

namespace swarm_transport {
namespace core {

// The simulator turns a command's turn at once when the command arrives (World2D::SetCommand),
// then drives it for one tick. In real time a round may be made before the robot's last command
// arrived - a robot that ticks just before the simulator steps, or a late robot or simulator -
// and then shows the pose before that turn. A robot that planned from it would turn the same turn
// again when both commands arrive: with every command one round late its heading never settles
// (the error of tick k+1 is that of k minus that of k-1, an undamped swing), and a leader ends in
// the arena's corners. CommandEcho tells from the heading which pose a round shows: the one its
// last command started from (not applied yet) or the one after its turn; in the first case the
// robot plans from where that command will take it (TurnThenDrive).
class CommandEcho {
 public:
  // A turn smaller than this (deg) tells nothing apart from noise: the round is taken as it is.
  static constexpr double kMinTurnDeg = 2.0;

  // The pose to plan from, given the own pose of a round newer than the last command.
  Pose2 PlanFrom(const Pose2& round_pose);
  // The command sent after planning from `planned_from`, driven for `duration_s`.
  void Sent(const Pose2& planned_from, const Velocity& command, double duration_s);
  // No command is pending (it stood, or its rounds stopped): the next round is taken as it is.
  void Forget() { pending_ = false; }
  // Rounds that did not show the last command yet.
  std::uint64_t unseen() const { return unseen_; }

 private:
  bool pending_ = false;
  Pose2 from_;
  Velocity command_;
  double duration_s_ = 0.0;
  std::uint64_t unseen_ = 0;
};

}  // namespace core
}  // namespace swarm_transport

#endif  // SWARM_TRANSPORT_CORE_COMMAND_ECHO_H_
