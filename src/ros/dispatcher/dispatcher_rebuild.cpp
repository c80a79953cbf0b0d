#include "swarm_transport/ros/dispatcher/dispatcher_rebuild.h"

#include <algorithm>
#include <optional>
#include <string>

#include "swarm_transport/ros/common/conversions.h"
#include "swarm_transport/ros/common/graph.h"
#include "swarm_transport/ros/common/mission_resend.h"
#include "swarm_transport/ros/common/names.h"
#include "swarm_transport/ros/dispatcher/dispatcher_options.h"

namespace swarm_transport {
namespace {

// How long (wall) a restart takes re-sent statuses before anything else, and how often it asks
// again meanwhile (a first leader whose connection came late answers the next request).
constexpr double kRebuildWaitS = 1.5;
constexpr double kRequestPeriodS = 0.5;
// ... and longer, up to this, until every first leader's /flock/mission/resent is connected to
// it and it to every robot's request subscription (the master asked every kConnectedPollS):
// an answer sent before that connection is lost (seen in restart.test, 2026-11-28: 1 of 3
// missions rebuilt after 1.5 s).
constexpr double kRebuildMaxS = 5.0;
constexpr double kConnectedPollS = 0.1;
constexpr double kPollS = 0.005;
constexpr std::uint32_t kResentQueue = 1000;
constexpr double kAskAgainS = 1.0;

}  // namespace

DispatcherRebuild::DispatcherRebuild(ros::NodeHandle nh, core::DispatcherPolicy* policy,
                                     const char* node)
    : nh_(nh), policy_(policy), node_(node) {}

void DispatcherRebuild::Request() {
  ++request_.request;
  request_pub_.publish(request_);
}

void DispatcherRebuild::Run() {
  ros::NodeHandle resent_nh(nh_);
  resent_nh.setCallbackQueue(&resent_queue_);
  resent_sub_ =
      resent_nh.subscribe(names::kMissionResent, kResentQueue, &DispatcherRebuild::OnResent, this);
  request_pub_ = nh_.advertise<Mission_Resend_Request>(names::kMissionResendRequest, 1, true);
  request_.requester = ros::this_node::getName();
  const ros::WallTime start = ros::WallTime::now();
  const ros::WallTime latest = start + ros::WallDuration(kRebuildMaxS);
  ros::WallTime until = start + ros::WallDuration(kRebuildWaitS);
  ros::WallTime next_request = start;
  ros::WallTime next_check = start;
  bool connected = false;
  while (ros::ok()) {
    const ros::WallTime now = ros::WallTime::now();
    if (!connected && now >= next_check) {
      TopicNodeCounts graph;
      connected = QueryTopicNodeCounts(&graph) && graph.AllConnected(resent_sub_) &&
                  graph.AllConnected(request_pub_);
      next_check = now + ros::WallDuration(kConnectedPollS);
      if (connected) {  // one more request, answered over connections that all exist now
        next_request = now;
        until = std::max(until, now + ros::WallDuration(kRequestPeriodS));
      }
    }
    if (now >= (connected ? until : latest)) break;
    if (now >= next_request) {
      Request();
      next_request = now + ros::WallDuration(kRequestPeriodS);
    }
    resent_queue_.callAvailable(ros::WallDuration(kPollS));
  }
  if (!connected) {
    ROS_WARN(
        "%s: restarted: not every robot's /flock/mission/resent and request subscription is "
        "connected after %.1f s; a mission whose answer is lost is asked for again when its "
        "progress is heard",
        node_, kRebuildMaxS);
  }
  ROS_INFO(
      "%s: restarted: %d live mission(s) rebuilt from the first leaders' re-sent statuses (%zu "
      "known, %.1f s); orders, submissions and statuses held meanwhile are taken now",
      node_, policy_->book().LiveCount(), policy_->book().entries().size(),
      (ros::WallTime::now() - start).toSec());
  resent_timer_ = nh_.createWallTimer(ros::WallDuration(0.1), [this](const ros::WallTimerEvent&) {
    resent_queue_.callAvailable();
  });
}

void DispatcherRebuild::OnResent(const ros::MessageEvent<Mission_Resent const>& event) {
  const Mission_Resent& msg = *event.getMessage();
  const std::string problem = StatusProblem(msg.status);
  std::optional<core::MissionSpec> order;
  if (msg.has_order && msg.order.mission_id == msg.status.mission_id) {
    order = ToMissionSpec(msg.order);
  }
  // Only a robot of the mission may re-send its status (its order names them).
  const core::MissionBook::Entry* entry = policy_->book().Find(msg.status.mission_id);
  const core::MissionSpec* spec = entry != nullptr && entry->has_spec ? &entry->spec
                                  : order                             ? &*order
                                                                      : nullptr;
  if (!problem.empty() || !core::MayReport(spec, SenderOf(event.getPublisherName()))) {
    if (foreign_warning_.Due()) {
      ROS_WARN("%s: ignored a re-sent status of mission %u from %s: %s%s", node_,
               msg.status.mission_id, event.getPublisherName().c_str(),
               problem.empty() ? "only the mission's robots may send it" : problem.c_str(),
               foreign_warning_.AndMore("such reports").c_str());
    }
    return;
  }
  policy_->OnResent(ToMissionReport(msg.status), order ? &*order : nullptr,
                    event.getPublisherName());
}

void DispatcherRebuild::AskAgain(std::uint16_t mission_id) {
  if (ros::WallTime::now() < next_ask_) return;
  next_ask_ = ros::WallTime::now() + ros::WallDuration(kAskAgainS);
  Request();
  ROS_INFO(
      "%s: heard of live mission %u, which it has not rebuilt: asks the first leaders to "
      "re-send their statuses again (request %u)",
      node_, mission_id, request_.request);
}

}  // namespace swarm_transport
