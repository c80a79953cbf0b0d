#include "swarm_transport/ros/simulator/event_player.h"

#include <utility>
#include <variant>

#include "swarm_transport/core/angle.h"
#include "swarm_transport/core/round.h"
#include "swarm_transport/ros/common/conversions.h"
#include "swarm_transport/ros/common/names.h"

namespace swarm_transport {

EventPlayer::EventPlayer(std::vector<TimedEvent> events, LockstepSession* session,
                         RobotRoster* roster, MissionMirror* missions)
    : schedule_(std::move(events)), session_(session), roster_(roster), missions_(missions) {}

void EventPlayer::Connect(ros::NodeHandle nh, std::uint32_t queue) {
  if (session_) return;
  // Real time: a timed event goes out as this node's message (robots take it as relayed).
  freeze_pub_ = nh.advertise<MsgOf<core::Freeze>>(names::kFreeze, queue);
  continue_pub_ = nh.advertise<MsgOf<core::Continue>>(names::kContinue, queue);
  update_pub_ = nh.advertise<MsgOf<core::ObjectUpdate>>(names::kObjectUpdate, queue);
  signal_pub_ = nh.advertise<MsgOf<core::Signal>>(names::kMissionEvent, queue);
}

void EventPlayer::Send(const core::MissionMessage& message, const ros::Publisher& pub) {
  if (session_) {
    session_->Inject(message);
  } else {
    std::visit([&pub](const auto& m) { pub.publish(ToMsg(m)); }, message);
  }
}

void EventPlayer::ApplyDue(std::uint64_t tick) {
  for (const TimedEvent& e : schedule_.Due(tick)) {
    switch (e.kind) {
      case TimedEvent::Kind::kFreeze:
        Send(core::Freeze{e.from, e.to}, freeze_pub_);
        break;
      case TimedEvent::Kind::kContinue:
        Send(core::Continue{e.from, e.to}, continue_pub_);
        break;
      case TimedEvent::Kind::kObjectUpdate:
        missions_->UpdateObject(e.mission, {e.x, e.y});
        // At the precision its message carries.
        Send(core::ObjectUpdate{e.mission, {core::AsSent(e.x), core::AsSent(e.y)}}, update_pub_);
        break;
      case TimedEvent::Kind::kSignal:
        Send(core::Signal{e.mission, static_cast<core::MissionEventKind>(e.signal), e.tick},
             signal_pub_);
        break;
      case TimedEvent::Kind::kKill:
        roster_->KillByEvent(e.robot);
        break;
      case TimedEvent::Kind::kSpawn:
        roster_->Spawn(e.robot, {{e.x, e.y}, core::Angle(e.theta_deg)});
        break;
      case TimedEvent::Kind::kStatist: {
        core::Position statist;
        statist.robot_id = e.robot;
        statist.sub_id = e.sub_id;
        statist.type = core::Position::kStatist;
        statist.x = static_cast<float>(e.x);
        statist.y = static_cast<float>(e.y);
        roster_->relayed().Take(statist);
        break;
      }
      case TimedEvent::Kind::kRemoveStatist:
        roster_->relayed().Erase(e.robot, e.sub_id);
        break;
      case TimedEvent::Kind::kOdomStop:
        ROS_WARN(
            "simulator: tick %llu: an odom_stop is for the hardware stand-in (bases); the "
            "simulator has no odometry to stop",
            static_cast<unsigned long long>(tick));
        break;
    }
  }
}

}  // namespace swarm_transport
