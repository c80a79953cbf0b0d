// New_Mission as any publisher may send it, through both admission paths: the robot's (message
// -> core, ValidateMission, the mission agent, ticks) and the dispatcher's (MissionBook Submit,
// then statuses of it). No crash, no sanitizer report; an accepted order is valid, and a
// robot's command stays finite on finite positions.
#include <cmath>
#include <map>

#include "fuzz_common.h"
#include "swarm_transport/Mission_Status.h"
#include "swarm_transport/core/assignment.h"
#include "swarm_transport/core/mission_book.h"
#include "swarm_transport/core/recruit.h"
#include "swarm_transport/core/robot_brain.h"
#include "swarm_transport/ros/common/conversions.h"

using namespace swarm_transport;  // NOLINT

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  FuzzedDataProvider in(data, size);
  const core::SwarmConfig config;
  const std::set<std::uint16_t> known = fuzz::KnownRobots(25);

  core::MissionBookParams book_params;
  book_params.world_size_m = config.flocking.world_size_m;
  book_params.tick_period_s = config.tick_period_s;
  core::MissionBook book(book_params);
  core::RobotBrain first(0, config);
  core::RobotBrain member(1, config);

  const int orders = in.ConsumeIntegralInRange<int>(1, 4);
  for (int k = 0; k < orders && in.remaining_bytes() > 0; ++k) {
    New_Mission msg = fuzz::AnyOrder(&in);
    msg.recruit = in.ConsumeBool();
    if (in.ConsumeBool()) {  // (ext) leaders named: any ids, duplicates, unassigned ones
      const int named = in.ConsumeIntegralInRange<int>(1, 4);
      for (int i = 0; i < named; ++i) {
        msg.leader_ids.push_back(in.ConsumeIntegralInRange<std::uint16_t>(0, 40));
      }
    }
    const core::MissionSpec spec = ToMissionSpec(msg);
    // The dispatcher's pick of a count-only order (robot_count): all or nothing.
    std::map<std::uint16_t, core::PlannerRobot> idle;
    const int candidates = in.ConsumeIntegralInRange<int>(0, 25);
    for (int r = 0; r < candidates; ++r) {
      idle[static_cast<std::uint16_t>(r)] = {{fuzz::AnyFloat(&in), fuzz::AnyFloat(&in)},
                                             core::Angle(fuzz::AnyFloat(&in))};
    }
    core::MissionSpec picked = spec;
    if (core::PickRobotsByCount(&picked, idle, core::SelectionParams()).empty()) {
      fuzz::Require(picked.robot_ids.size() == spec.robot_count && picked.robot_count == 0);
      // Its leaders: leader_number of the picked robots (none named when it is out of range).
      const bool named = spec.leader_number >= 1 && spec.leader_number <= spec.robot_count;
      fuzz::Require(picked.leader_ids.size() ==
                    (named ? static_cast<std::size_t>(spec.leader_number) : 0u));
      for (std::uint16_t id : picked.leader_ids) fuzz::Require(picked.Assigns(id));
    } else {
      fuzz::Require(picked.robot_ids == spec.robot_ids && picked.robot_count == spec.robot_count &&
                    picked.leader_ids == spec.leader_ids);
    }
    // The dispatcher's recruit (statist as dispatcher): once enough are inside, the order it
    // sends names them and is valid.
    core::MissionContext recruit_context;
    recruit_context.world_size_m = config.flocking.world_size_m;
    recruit_context.known_robots = known;
    std::set<std::uint16_t> idle_ids;
    std::map<std::uint16_t, core::Vec2> idle_at;
    for (const auto& kv : idle) {
      idle_ids.insert(kv.first);
      idle_at[kv.first] = kv.second.position;
    }
    if (spec.recruit && core::ValidateRecruit(spec, idle_ids, recruit_context).empty()) {
      core::RecruitWatch watch(spec);
      if (watch.Observe(idle_at)) {
        const core::MissionSpec order = core::RecruitedOrder(spec, watch.Recruits());
        fuzz::Require(order.robot_ids.size() == spec.robot_count);
        fuzz::Require(core::ValidateMission(order, recruit_context).empty());
      }
    }
    // The dispatcher.
    const core::MissionBook::Verdict verdict =
        book.Submit(spec, "fuzz", in.ConsumeBool(), in.ConsumeBool(), known, 1.0 * k);
    if (verdict.accepted) {
      core::MissionContext context;
      context.world_size_m = config.flocking.world_size_m;
      context.known_robots = known;
      fuzz::Require(core::ValidateMission(verdict.spec, context).empty());
    }
    // The robots.
    core::MissionTaken taken;
    first.Take(spec, known, &taken);
    member.Take(spec, known, &taken);
    // A status of it from anyone.
    Mission_Status status;
    status.mission_id = msg.mission_id;
    status.state = in.ConsumeIntegralInRange<std::uint8_t>(0, 9);
    status.tick = in.ConsumeIntegral<std::uint64_t>();
    status.robots_assigned = in.ConsumeIntegral<std::uint16_t>();
    status.robots_inside = in.ConsumeIntegral<std::uint16_t>();
    status.object_position_x = fuzz::AnyFloat(&in);
    status.object_position_y = fuzz::AnyFloat(&in);
    status.distance_to_target = fuzz::AnyFloat(&in);
    if (status.state < 8 && std::isfinite(status.distance_to_target)) {
      book.OnStatus(ToMissionReport(status), 1.0 * k);
    }
    member.Take(
        core::PhaseStatus{status.mission_id, static_cast<core::MissionPhase>(status.state), {}});
  }
  // A few ticks of both robots on finite positions.
  for (std::uint64_t tick = 0; tick < 3; ++tick) {
    for (core::RobotBrain* brain : {&first, &member}) {
      core::Perception p;
      p.self.position = {in.ConsumeFloatingPointInRange<double>(0.1, 11.0),
                         in.ConsumeFloatingPointInRange<double>(0.1, 11.0)};
      core::Neighbour other;
      other.id = brain == &first ? 1 : 0;
      other.position = {in.ConsumeFloatingPointInRange<double>(0.1, 11.0),
                        in.ConsumeFloatingPointInRange<double>(0.1, 11.0)};
      p.others.push_back(other);
      const core::BrainTick step = brain->Tick(p, tick, true);
      fuzz::Require(std::isfinite(step.command.linear) && std::isfinite(step.command.angular));
    }
  }
  book.Table(3.0);
  return 0;
}
