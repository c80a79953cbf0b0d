// What the mission agent's tests share: a pose and the phase names of an outbox.
#ifndef SWARM_TRANSPORT_TEST_CORE_MISSION_AGENT_FIXTURE_H_
#define SWARM_TRANSPORT_TEST_CORE_MISSION_AGENT_FIXTURE_H_

#include <string>
#include <vector>

#include "swarm_transport/core/mission_agent.h"

namespace swarm_transport {
namespace core {
namespace fixtures {

inline Pose2 PoseAt(double x, double y) { return Pose2{{x, y}, Angle(0.0)}; }

inline std::vector<std::string> Phases(const MissionOutbox& out) {
  std::vector<std::string> names;
  for (const StatusReport& r : out.statuses) names.push_back(PhaseName(r.phase));
  return names;
}

}  // namespace fixtures
}  // namespace core
}  // namespace swarm_transport

#endif  // SWARM_TRANSPORT_TEST_CORE_MISSION_AGENT_FIXTURE_H_
