#include "swarm_transport/ros/robot/robot_session.h"

#include <type_traits>
#include <utility>
#include <variant>

#include "swarm_transport/ros/common/conversions.h"

namespace swarm_transport {

RobotSession::RobotSession(std::uint16_t id, const core::SwarmConfig& config)
    : brain_(id, config) {}

RobotSession::Taken RobotSession::Take(const core::MissionMessage& message,
                                       const core::Sender& from,
                                       const std::set<std::uint16_t>& known_robots) {
  using Say = Taken::Say;
  Taken out;
  out.kind = core::KindName(message);
  const std::uint16_t mission_id = core::MissionIdOf(message);
  if (const auto* order = std::get_if<core::MissionSpec>(&message)) {
    if (!core::MayOrder(brain_.admission(), from)) {
      // Not admitted (yet): the dispatcher answers it, and publishes it when it admits it.
      out.say = Say::kDebug;
      out.why = "New_Mission " + std::to_string(mission_id) +
                " not from the dispatcher; waiting for its verdict";
      return out;
    }
    core::MissionTaken taken;
    out.why = brain_.Take(message, known_robots, &taken);
    if (out.why.empty()) {
      if (taken.first_leader) {
        // Its answers (or its mission topics) carry the statuses.
        statuses_.Queue(taken.queued);
        out.first_leader = true;
      }
      return out;
    }
    out.why = "New_Mission " + std::to_string(mission_id) + ": " + out.why;
    // Only the robots concerned say so, so that one bad order does not log N lines.
    out.say = order->Assigns(id()) || id() == 0 ? Say::kWarn : Say::kNothing;
    return out;
  }
  const bool reported = std::holds_alternative<core::ObjectUpdate>(message) ||
                        std::holds_alternative<core::ObjectDelete>(message) ||
                        std::holds_alternative<core::PhaseStatus>(message);
  if (reported && !core::MayReport(brain_.missions().Find(mission_id), from)) {
    out.say = Say::kWarn;
    out.why = out.kind + " of mission " + std::to_string(mission_id) +
              ": not from one of its robots or the dispatcher";
    return out;
  }
  out.why = brain_.Take(message, known_robots);
  if (out.why.empty()) return out;
  if (std::holds_alternative<core::ObjectUpdate>(message)) {
    // An update for a mission it does not hold is routine; a non-finite, out-of-arena or
    // implausible one is bad input.
    out.say = brain_.missions().Find(mission_id) == nullptr ? Say::kDebug : Say::kWarn;
  } else if (std::holds_alternative<core::ObjectDelete>(message)) {
    out.say = Say::kDebug;
  } else {
    out.say = Say::kWarn;
  }
  return out;
}

void RobotSession::TakeRelayed(const Neighbors& round, const std::set<std::uint16_t>& known_robots,
                               std::vector<Taken>* refused) {
  // The relay passed on only what counts.
  const core::Sender relay{core::SenderKind::kRelay, 0};
  for (const core::MissionMessage& m : ToMissionMessages(round)) {
    Taken taken = Take(m, relay, known_robots);
    if (!taken.why.empty() && refused != nullptr) refused->push_back(std::move(taken));
  }
}

RobotSession::Taken RobotSession::TakeTuning(const Neighbors& round) {
  Taken out;
  out.kind = "Flocking_Tuning";
  if (round.tuning.empty()) return out;
  const Flocking_Tuning& t = round.tuning.front();
  if (t.generation == tuning_generation_ || t.generation == refused_generation_) return out;
  const std::string why = brain_.OnTuning(ToFlockingTuning(t));
  if (!why.empty()) {
    refused_generation_ = t.generation;
    out.say = Taken::Say::kWarn;
    out.why = "Flocking_Tuning " + std::to_string(t.generation) + ": " + why;
    return out;
  }
  tuning_generation_ = t.generation;
  tuning_tick_ = round.tick;
  return out;
}

RobotSession::Step RobotSession::Tick(core::Perception in, std::uint64_t tick,
                                      const ros::Time& stamp, bool ready) {
  Step step;
  step.brain = brain_.Tick(std::move(in), tick, ready);
  std::vector<core::StatusReport> progress;
  statuses_.Sequence(ready, &step.brain.outbox.statuses, &progress);
  step.answer = ToAnswerMessages(step.brain.outbox, progress, tick, stamp);
  step.answer.tick = tick;
  step.answer.command = ToTwist(step.brain.command);
  return step;
}

}  // namespace swarm_transport
