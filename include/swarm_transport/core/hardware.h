// A robot on real hardware (robot.launch hardware:=true, docs/hardware.md): its options, the
// speed limits of its base and the watch over the age of its pose. Pure (no ROS, no clock): the
// hardware transport (ros/robot/hardware_transport.h) reads the options and asks these.
#ifndef SWARM_TRANSPORT_CORE_HARDWARE_H_
#define SWARM_TRANSPORT_CORE_HARDWARE_H_

#include <cstdint>
#include <string>

#include "swarm_transport/core/kinematics.h"

namespace swarm_transport {
namespace core {

// Where a hardware robot takes its pose from: nav_msgs/Odometry on its `odom` topic, or a tf
// lookup of its base frame in a shared fixed frame.
enum class PoseSource : std::uint8_t { kOdom, kTf };
// False (and `out` untouched) for a name that is neither "odom" nor "tf".
bool ParsePoseSource(const std::string& name, PoseSource* out);
const char* PoseSourceName(PoseSource source);

// A hardware robot's private parameters (~pose_source, ...). Frame names follow REP 105.
struct HardwareOptions {
  PoseSource pose_source = PoseSource::kOdom;
  std::string odom_topic = "odom";       // relative: in the robot's namespace
  std::string fixed_frame = "map";       // tf: the shared frame (the arena's)
  std::string base_frame = "base_link";  // tf: this robot's base (robot.launch prefixes it)
  double max_linear_m_s = 1.0;           // |linear| of a command at most this
  double max_angular_rad_s = 31.415927;  // |angular| at most this (a half turn per 0.1 s tick)
  double pose_timeout_s = 0.5;           // a pose older than this stops the robot
  double heard_timeout_s = 0.5;          // another robot's position older than this is not heard
  double radio_loss = 0.0;               // /swarm/radio_loss: drop probability, [0, 1]
  // Empty when valid, else one sentence naming the first bad parameter and its range.
  std::string Validate() const;
};

// `command` within the limits: each part clamped to [-max, max] on its own; a non-finite part
// stands (0).
Velocity LimitSpeed(const Velocity& command, double max_linear_m_s, double max_angular_rad_s);

// Whether a robot's pose is fresh enough to move on: a pose stamped more than `timeout_s` before
// now (or none yet) is stale. It reports each change once, so a node says it once.
class PoseWatch {
 public:
  explicit PoseWatch(double timeout_s) : timeout_s_(timeout_s) {}
  enum class Change : std::uint8_t { kNone, kStale, kFresh };
  // The newest pose's stamp (s; the same clock as Check's `now_s`).
  void Took(double stamp_s);
  // At `now_s`: is the pose fresh, and did that change since the last check? The first check
  // with no pose yet reports kStale once; a pose stamped in the future counts as fresh.
  bool Check(double now_s, Change* change);
  // The age of the newest pose at `now_s` (infinity: none yet).
  double AgeS(double now_s) const;

 private:
  double timeout_s_;
  bool has_pose_ = false;
  double stamp_s_ = 0.0;
  bool fresh_ = true;  // as last reported (starts fresh so a first stale check is reported)
};

}  // namespace core
}  // namespace swarm_transport

#endif  // SWARM_TRANSPORT_CORE_HARDWARE_H_
