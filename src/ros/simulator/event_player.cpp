#include "swarm_transport/ros/simulator/event_player.h"

#include <utility>

#include "swarm_transport/Mission_Event.h"
#include "swarm_transport/Robot_Continue.h"
#include "swarm_transport/Robot_Freeze.h"
#include "swarm_transport/Robot_Position.h"
#include "swarm_transport/Update_Object.h"
#include "swarm_transport/core/angle.h"
#include "swarm_transport/ros/common/names.h"

namespace swarm_transport {

EventPlayer::EventPlayer(std::vector<TimedEvent> events, LockstepSession* session,
                         RobotRoster* roster, MissionMirror* missions)
    : schedule_(std::move(events)), session_(session), roster_(roster), missions_(missions) {}

void EventPlayer::Connect(ros::NodeHandle nh, std::uint32_t queue) {
  if (session_) return;
  // Real time: a timed event goes out as this node's message (robots take it as relayed).
  freeze_pub_ = nh.advertise<Robot_Freeze>(names::kFreeze, queue);
  continue_pub_ = nh.advertise<Robot_Continue>(names::kContinue, queue);
  update_pub_ = nh.advertise<Update_Object>(names::kObjectUpdate, queue);
  signal_pub_ = nh.advertise<Mission_Event>(names::kMissionEvent, queue);
}

template <typename M>
void EventPlayer::Send(const M& msg, const ros::Publisher& pub) {
  if (session_) {
    session_->Inject(msg);
  } else {
    pub.publish(msg);
  }
}

void EventPlayer::ApplyDue(std::uint64_t tick) {
  for (const TimedEvent& e : schedule_.Due(tick)) {
    switch (e.kind) {
      case TimedEvent::Kind::kFreeze: {
        Robot_Freeze msg;
        msg.robot_index_from = e.from;
        msg.robot_index_to = e.to;
        Send(msg, freeze_pub_);
        break;
      }
      case TimedEvent::Kind::kContinue: {
        Robot_Continue msg;
        msg.robot_index_from = e.from;
        msg.robot_index_to = e.to;
        Send(msg, continue_pub_);
        break;
      }
      case TimedEvent::Kind::kObjectUpdate: {
        Update_Object msg;
        msg.mission_id = e.mission;
        msg.object_position_x = static_cast<float>(e.x);
        msg.object_position_y = static_cast<float>(e.y);
        missions_->UpdateObject(e.mission, {e.x, e.y});
        Send(msg, update_pub_);
        break;
      }
      case TimedEvent::Kind::kSignal: {
        Mission_Event msg;
        msg.mission_id = e.mission;
        msg.event = e.signal;
        msg.not_before_tick = e.tick;
        Send(msg, signal_pub_);
        break;
      }
      case TimedEvent::Kind::kKill:
        roster_->KillByEvent(e.robot);
        break;
      case TimedEvent::Kind::kSpawn:
        roster_->Spawn(e.robot, {{e.x, e.y}, core::Angle(e.theta_deg)});
        break;
      case TimedEvent::Kind::kStatist: {
        Robot_Position statist;
        statist.robot_id = e.robot;
        statist.sub_id = e.sub_id;
        statist.type = Robot_Position::TYPE_STATIST;
        statist.pos_x = static_cast<float>(e.x);
        statist.pos_y = static_cast<float>(e.y);
        roster_->relayed().Take(statist);
        break;
      }
      case TimedEvent::Kind::kRemoveStatist:
        roster_->relayed().Erase(e.robot, e.sub_id);
        break;
    }
  }
}

}  // namespace swarm_transport
