#include "swarm_transport/core/robot_session.h"

#include <type_traits>
#include <utility>
#include <variant>

namespace swarm_transport {
namespace core {
namespace {

bool SameOrder(const MissionSpec& a, const MissionSpec& b) {
  const auto same = [](Vec2 p, Vec2 q) { return p.x == q.x && p.y == q.y; };
  return a.id == b.id && a.Assigned() == b.Assigned() && a.Leaders() == b.Leaders() &&
         same(a.object_centre, b.object_centre) && same(a.object_size, b.object_size) &&
         same(a.target, b.target) && a.transport_mode == b.transport_mode;
}

}  // namespace

RobotSession::RobotSession(std::uint16_t id, const SwarmConfig& config) : brain_(id, config) {}

RobotSession::Taken RobotSession::Take(const MissionMessage& message, const Sender& from,
                                       const std::set<std::uint16_t>& known_robots) {
  using Say = Taken::Say;
  Taken out;
  out.kind = KindName(message);
  const std::uint16_t mission_id = MissionIdOf(message);
  if (const auto* order = std::get_if<MissionSpec>(&message)) {
    if (!MayOrder(brain_.admission(), from)) {
      // Not admitted (yet): the dispatcher answers it, and publishes it when it admits it.
      out.say = Say::kDebug;
      out.why = "order " + std::to_string(mission_id) +
                " not from the dispatcher; waiting for its verdict";
      return out;
    }
    MissionTaken taken;
    out.why = brain_.Take(message, known_robots, &taken);
    if (out.why.empty()) {
      if (taken.first_leader) {
        // Its answers (or its mission topics) carry the statuses.
        statuses_.Queue(taken.queued);
        out.first_leader = true;
      }
      return out;
    }
    out.why = "order " + std::to_string(mission_id) + ": " + out.why;
    // Only the robots concerned say so, so that one bad order does not log N lines. The order
    // it holds, again, is routine: the dispatcher sends the QUEUED ones to a robot as it
    // connects, which may be just after it published one of them to everybody.
    const MissionSpec* held = brain_.missions().Find(mission_id);
    if (held != nullptr && SameOrder(*held, *order)) {
      out.say = Say::kDebug;
    } else {
      out.say = order->Assigns(id()) || id() == 0 ? Say::kWarn : Say::kNothing;
    }
    return out;
  }
  const bool reported = std::holds_alternative<ObjectUpdate>(message) ||
                        std::holds_alternative<ObjectDelete>(message) ||
                        std::holds_alternative<PhaseStatus>(message);
  if (reported && !MayReport(brain_.missions().Find(mission_id), from)) {
    out.say = Say::kWarn;
    out.why = out.kind + " of mission " + std::to_string(mission_id) +
              ": not from one of its robots or the dispatcher";
    return out;
  }
  out.why = brain_.Take(message, known_robots);
  if (out.why.empty()) return out;
  if (std::holds_alternative<ObjectUpdate>(message) || std::holds_alternative<Signal>(message)) {
    // For a mission it does not hold, routine: an object update of another's mission, or a
    // LOADED / UNLOADED the dispatcher re-sends while its view of the mission lags its end (real
    // time: MissionBook::Owed). For one it holds, bad input: a non-finite, out-of-arena or
    // implausible update, or a signal in the wrong phase.
    out.say = brain_.missions().Find(mission_id) == nullptr ? Say::kDebug : Say::kWarn;
  } else if (std::holds_alternative<ObjectDelete>(message)) {
    out.say = Say::kDebug;
  } else {
    out.say = Say::kWarn;
  }
  return out;
}

void RobotSession::TakeRelayed(const Round& round, const std::set<std::uint16_t>& known_robots,
                               std::vector<Taken>* refused) {
  // The relay passed on only what counts.
  const Sender relay{SenderKind::kRelay, 0};
  for (const MissionMessage& m : round.messages) {
    Taken taken = Take(m, relay, known_robots);
    if (!taken.why.empty() && refused != nullptr) refused->push_back(std::move(taken));
  }
}

RobotSession::Taken RobotSession::TakeTuning(const std::optional<TuningGeneration>& tuning,
                                             std::uint64_t tick) {
  Taken out;
  out.kind = "flocking tuning";
  if (!tuning) return out;
  const TuningGeneration& t = *tuning;
  if (t.generation == tuning_generation_ || t.generation == refused_generation_) return out;
  const std::string why = brain_.OnTuning(t.tuning);
  if (!why.empty()) {
    refused_generation_ = t.generation;
    out.say = Taken::Say::kWarn;
    out.why = "flocking tuning " + std::to_string(t.generation) + ": " + why;
    return out;
  }
  tuning_generation_ = t.generation;
  tuning_tick_ = tick;
  return out;
}

RobotSession::Step RobotSession::Tick(Perception in, std::uint64_t tick, double sim_time,
                                      bool ready) {
  Step step;
  step.brain = brain_.Tick(std::move(in), tick, ready);
  std::vector<StatusReport> progress;
  statuses_.Sequence(ready, &step.brain.outbox.statuses, &progress);
  step.answer.tick = tick;
  step.answer.sim_time = sim_time;
  step.answer.command = step.brain.command;
  step.answer.copies = step.brain.copies;
  FillAnswer(step.brain.outbox, std::move(progress), &step.answer);
  return step;
}

}  // namespace core
}  // namespace swarm_transport
