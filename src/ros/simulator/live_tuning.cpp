#include "swarm_transport/ros/simulator/live_tuning.h"

#include "swarm_transport/ros/common/conversions.h"
#include "swarm_transport/ros/common/names.h"

namespace swarm_transport {

void LiveTuning::Connect(ros::NodeHandle nh, ros::NodeHandle private_nh, double radio_loss) {
  pub_ = nh.advertise<Flocking_Tuning>(names::kTuning, 1, true);
  server_ = std::make_unique<FlockingTuningServer>(private_nh, &relay_, radio_loss);
}

void LiveTuning::Shutdown() {
  server_.reset();
  pub_.shutdown();
}

std::optional<core::TuningGeneration> LiveTuning::BeginRound(std::uint64_t tick) {
  std::optional<core::TuningGeneration> tuned = relay_.BeginRound(tick);
  if (tuned) pub_.publish(ToTuningMsg(tuned->tuning, tuned->generation, tuned->tick));
  return tuned;
}

}  // namespace swarm_transport
