#include "swarm_transport/core/round.h"

#include <algorithm>
#include <cmath>
#include <utility>

namespace swarm_transport {
namespace core {
double AsSent(double v) {
  // Through memory: g++ -O2 drops a double -> float -> double pair of conversions in registers.
  volatile float f = static_cast<float>(v);
  return f;
}

namespace {

StatusReport StatusAsSent(StatusReport r) {
  r.object = {AsSent(r.object.x), AsSent(r.object.y)};
  r.distance_to_target = AsSent(r.distance_to_target);
  return r;
}

}  // namespace

Position PositionOf(std::uint16_t id, const Pose2& pose, std::uint8_t sub_id, std::uint8_t type) {
  Position p;
  p.robot_id = id;
  p.sub_id = sub_id;
  p.type = type;
  p.x = static_cast<float>(pose.position.x);
  p.y = static_cast<float>(pose.position.y);
  p.angle_deg = static_cast<float>(pose.heading.degrees());
  // float rounding may turn 359.9999999 into 360.0f: keep the [0, 360) promise.
  if (p.angle_deg >= 360.0f) p.angle_deg = 0.0f;
  return p;
}

bool IsFinite(const Position& p) {
  return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.angle_deg);
}

Neighbour NeighbourOf(const Position& p) {
  Neighbour n;
  n.id = p.robot_id;
  n.sub_id = p.sub_id;
  n.type = p.type;
  n.position = {p.x, p.y};
  n.heading = Angle(p.angle_deg);
  n.copies = p.type == Position::kPhysical ? p.copies : 0;
  return n;
}

OwnPose OwnPoseOf(const Pose2& pose, const Velocity& velocity) {
  OwnPose p;
  p.x = static_cast<float>(pose.position.x);
  p.y = static_cast<float>(pose.position.y);
  double theta = pose.heading.radians();
  if (theta > M_PI) theta -= 2.0 * M_PI;
  p.theta = static_cast<float>(theta);
  p.linear_velocity = static_cast<float>(velocity.linear);
  p.angular_velocity = static_cast<float>(velocity.angular);
  return p;
}

Pose2 Pose2Of(const OwnPose& pose) {
  return Pose2{{pose.x, pose.y}, Angle::FromRadians(pose.theta)};
}

Perception PerceptionOf(std::uint16_t id, const Round& round) {
  Perception in;
  in.self_id = id;
  in.self = Pose2Of(round.pose);
  in.others.reserve(round.robots.size() + round.relayed.size() + round.mission_peers.size());
  // In range, then passed on hop by hop (a chain's far end), then the mission channel.
  for (const auto* list : {&round.robots, &round.relayed, &round.mission_peers}) {
    for (const Position& p : *list) {
      if (!IsFinite(p)) continue;
      in.others.push_back(NeighbourOf(p));
    }
  }
  return in;
}

Velocity CommandOf(const Answer& answer) {
  const Velocity& c = answer.command;
  return std::isfinite(c.linear) && std::isfinite(c.angular) ? c : Velocity();
}

void FillAnswer(const MissionOutbox& outbox, std::vector<StatusReport> progress, Answer* answer) {
  std::vector<MissionMessage>& out = answer->messages;
  if (outbox.update_object) {
    const Vec2& c = outbox.update_object->second;
    out.push_back(ObjectUpdate{outbox.update_object->first, {AsSent(c.x), AsSent(c.y)}});
  }
  for (const auto& run : outbox.freeze) out.push_back(Freeze{run.first, run.second});
  for (const auto& run : outbox.resume) out.push_back(Continue{run.first, run.second});
  if (outbox.delete_object) out.push_back(ObjectDelete{*outbox.delete_object});
  // Most answers report nothing: no call to reserve for them.
  if (!outbox.statuses.empty()) answer->statuses.reserve(outbox.statuses.size());
  for (const StatusReport& r : outbox.statuses) answer->statuses.push_back(StatusAsSent(r));
  if (!progress.empty()) answer->progress.reserve(progress.size());
  for (StatusReport& r : progress) answer->progress.push_back(StatusAsSent(std::move(r)));
}

MissionReport ReportOf(const StatusReport& status, std::uint64_t tick) {
  MissionReport r;
  r.mission_id = status.mission_id;
  r.phase = status.phase;
  r.reason = status.reason;
  r.tick = tick;
  r.robots_assigned = status.assigned;
  r.robots_inside = status.inside;
  r.distance_to_target_m = status.distance_to_target;
  return r;
}

MetricsFrame FrameOf(std::uint64_t tick, double sim_time, const std::vector<Position>& positions,
                     std::size_t* bad) {
  MetricsFrame frame;
  frame.tick = tick;
  frame.sim_time_s = sim_time;
  *bad = 0;
  // The simulator's frames: physical robots only, finite, in ascending id: straight into the
  // frame (what the general path below gives for them, without its list of a frame's size).
  frame.ids.reserve(positions.size());
  frame.positions.reserve(positions.size());
  for (const Position& p : positions) {
    if (p.type != Position::kPhysical || !std::isfinite(p.x) || !std::isfinite(p.y) ||
        (!frame.ids.empty() && frame.ids.back() >= p.robot_id)) {
      frame.ids.clear();
      frame.positions.clear();
      break;
    }
    frame.ids.push_back(p.robot_id);
    frame.positions.push_back(Vec2{p.x, p.y});
  }
  if (frame.ids.size() == positions.size()) return frame;
  std::vector<std::pair<std::uint16_t, Vec2>> robots;
  robots.reserve(positions.size());
  for (const Position& p : positions) {
    if (p.type != Position::kPhysical) continue;
    if (!std::isfinite(p.x) || !std::isfinite(p.y)) {
      ++*bad;
      continue;
    }
    robots.emplace_back(p.robot_id, Vec2{p.x, p.y});
  }
  const auto by_id = [](const auto& a, const auto& b) { return a.first < b.first; };
  // The simulator sends them in id order already.
  if (!std::is_sorted(robots.begin(), robots.end(), by_id)) {
    std::stable_sort(robots.begin(), robots.end(), by_id);
  }
  frame.ids.reserve(robots.size());
  frame.positions.reserve(robots.size());
  for (const auto& r : robots) {
    if (!frame.ids.empty() && frame.ids.back() == r.first) continue;  // a duplicate id
    frame.ids.push_back(r.first);
    frame.positions.push_back(r.second);
  }
  return frame;
}

}  // namespace core
}  // namespace swarm_transport
