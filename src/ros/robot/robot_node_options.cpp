// A robot node's options: what it reads from its private parameters and how they are checked.
#include <memory>
#include <sstream>
#include <string>

#include "swarm_transport/ros/common/params.h"
#include "swarm_transport/ros/robot/hardware_transport.h"
#include "swarm_transport/ros/robot/own_topics_transport.h"
#include "swarm_transport/ros/robot/robot_node.h"

namespace swarm_transport {

std::string RobotNodeOptions::Validate() const {
  std::ostringstream os;
  if (id < 0 || id > 65535) {
    os << "~id must be set to an integer in [0, 65535] but is " << id;
  } else if (hardware && clock != core::Clock::kRealtime) {
    os << "~hardware needs ~clock realtime (a robot on hardware ticks on the wall clock)";
  } else if (hardware && comm != core::Comm::kLocal) {
    os << "~hardware needs ~comm local (its own radio decides whom it hears)";
  }
  return os.str();
}

bool RobotNode::Initialize() {
  RobotNodeOptions options;
  std::string error;
  if (!ReadPrivate(private_nh_, "id", &options.id, &error) ||
      !ReadPrivate(private_nh_, "clock", &options.clock, &error) ||
      !ReadPrivate(private_nh_, "comm", &options.comm, &error) ||
      !ReadPrivate(private_nh_, "diagnostics", &options.diagnostics, &error) ||
      !ReadPrivate(private_nh_, "hardware", &options.hardware, &error)) {
    ROS_FATAL("robot: invalid parameters: %s", error.c_str());
    return false;
  }
  if (!options.hardware) {
    return Initialize(options, std::make_unique<OwnTopicsTransport>(options.clock));
  }
  core::HardwareOptions hardware;
  if (!ReadHardwareOptions(private_nh_, &hardware, &error)) {
    ROS_FATAL("robot: invalid parameters: %s", error.c_str());
    return false;
  }
  return Initialize(options, std::make_unique<HardwareTransport>(hardware));
}

}  // namespace swarm_transport
