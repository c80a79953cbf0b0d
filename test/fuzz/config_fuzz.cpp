// /swarm configuration as YAML text (what a user's config file or `rosparam set` gives): the one
// loader, the validator, and a robot built from a configuration that validated (a valid
// configuration must never crash a robot). Also placement files. No crash, no sanitizer report.
#include <cmath>
#include <string>
#include <vector>

#include "fuzz_common.h"
#include "swarm_transport/core/robot_brain.h"
#include "swarm_transport/ros/common/params.h"
#include "swarm_transport/sim/world2d.h"

using namespace swarm_transport;  // NOLINT

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  XmlRpc::XmlRpcValue dict;
  std::string error;
  if (XmlRpcFromYamlText(text, &dict, &error) &&
      dict.getType() == XmlRpc::XmlRpcValue::TypeStruct) {
    core::SwarmConfig config;
    if (ConfigFromXmlRpc(dict, &config, &error) && config.Validate().empty()) {
      core::RobotBrain brain(0, config);
      core::Perception p;
      p.self.position = {config.flocking.world_size_m / 2.0, config.flocking.world_size_m / 2.0};
      core::Neighbour other;
      other.id = 1;
      other.position = {p.self.position.x + 0.3, p.self.position.y};
      p.others.push_back(other);
      const core::BrainTick step = brain.Tick(p, 1, true);
      fuzz::Require(std::isfinite(step.command.linear) && std::isfinite(step.command.angular));
    }
  }
  std::vector<core::Pose2> poses;
  sim::ParsePlacement(text, &poses, &error);
  return 0;
}
