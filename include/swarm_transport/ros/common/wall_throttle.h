// One throttle for repeated warnings, on the wall clock. ROS's ROS_*_THROTTLE macros use
// ros::Time, which stands still at 0 under use_sim_time before the first /clock (lock-step runs,
// rosbag replays): then the first warning is the only one ever logged. A WarnThrottle per kind of
// warning lets one line through per period of wall time and counts the ones it held back, so that
// a line can say "and N more".
#ifndef SWARM_TRANSPORT_ROS_WALL_THROTTLE_H_
#define SWARM_TRANSPORT_ROS_WALL_THROTTLE_H_

#include <ros/time.h>

#include <cstdint>
#include <string>

namespace swarm_transport {

class WarnThrottle {
 public:
  // The period every node uses unless it has a reason for another (wall s).
  static constexpr double kDefaultPeriodS = 5.0;

  explicit WarnThrottle(double period_s = kDefaultPeriodS) : period_s_(period_s) {}

  // True at the first call and then when at least period_s of wall time passed since the last
  // true; a false counts as one held back.
  bool Due() { return Due(ros::WallTime::now()); }
  // The same at a given wall time (tests).
  bool Due(ros::WallTime now);

  // How many calls returned false between the last true and the one before it (0 before the
  // first true): what the line logged at the last true may add as "and N more".
  std::uint64_t suppressed() const { return suppressed_; }
  // The tail of that line: "" when none was held back, else e.g. " (and 3 more <what> since the
  // last such line)".
  std::string AndMore(const std::string& what) const;
  double period_s() const { return period_s_; }

 private:
  double period_s_;
  bool started_ = false;
  ros::WallTime last_;
  std::uint64_t held_back_ = 0;   // since the last true
  std::uint64_t suppressed_ = 0;  // held back before the last true
};

}  // namespace swarm_transport

#endif  // SWARM_TRANSPORT_ROS_WALL_THROTTLE_H_
