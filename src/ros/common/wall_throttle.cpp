#include "swarm_transport/ros/common/wall_throttle.h"

namespace swarm_transport {

bool WarnThrottle::Due(ros::WallTime now) {
  if (started_ && (now - last_).toSec() < period_s_) {
    ++held_back_;
    return false;
  }
  started_ = true;
  last_ = now;
  suppressed_ = held_back_;
  held_back_ = 0;
  return true;
}

std::string WarnThrottle::AndMore(const std::string& what) const {
  if (suppressed_ == 0) return "";
  return " (and " + std::to_string(suppressed_) + " more " + what + " since the last such line)";
}

}  // namespace swarm_transport
