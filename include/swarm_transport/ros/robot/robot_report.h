// A robot's state as its ~state and ~describe services and its /diagnostics status say it.
#ifndef SWARM_TRANSPORT_ROS_ROBOT_REPORT_H_
#define SWARM_TRANSPORT_ROS_ROBOT_REPORT_H_

#include <cstdint>
#include <string>

#include "swarm_transport/Robot_State.h"
#include "swarm_transport/core/robot_session.h"
#include "swarm_transport/ros/common/diagnostics.h"

namespace swarm_transport {

// ~state: its state, typed (for tools and tests). `ticks`: the ticks it ran; `listed`: it is in
// the simulator's robot list.
Robot_State::Response StateOf(const core::RobotSession& session, std::uint64_t ticks, bool listed);
// ~describe: the same in one line for people.
std::string Describe(const Robot_State::Response& state);
// Its /diagnostics status at radio round `tick`.
void FillStatus(const Robot_State::Response& state, std::uint64_t tick, NodeStatus* status);

}  // namespace swarm_transport

#endif  // SWARM_TRANSPORT_ROS_ROBOT_REPORT_H_
