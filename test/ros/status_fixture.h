// A Mission_Status for the ROS glue tests: mission `mission` in state `state`, nothing else set.
#ifndef SWARM_TRANSPORT_TEST_ROS_STATUS_FIXTURE_H_
#define SWARM_TRANSPORT_TEST_ROS_STATUS_FIXTURE_H_

#include <cstdint>

#include "swarm_transport/Mission_Status.h"

namespace swarm_transport {
namespace fixtures {

inline Mission_Status Status(std::uint16_t mission, std::uint8_t state) {
  Mission_Status s;
  s.mission_id = mission;
  s.state = state;
  return s;
}

}  // namespace fixtures
}  // namespace swarm_transport

#endif  // SWARM_TRANSPORT_TEST_ROS_STATUS_FIXTURE_H_
