#include <algorithm>
#include <map>
#include <utility>

#include "swarm_transport/core/assignment.h"
#include "swarm_transport/core/gather_route.h"
#include "swarm_transport/core/mission_agent.h"

// A gathering member's goal: its slot by the mission's plan, and its way there around the static
// danger zones (the mission's tick: mission_agent_tick.cpp).

namespace swarm_transport {
namespace core {
namespace {

// Every member plans on what it hears as /flock/position carries it (float32), its own pose
// included, so that all members compute the same plan.
PlannerRobot AsHeard(Vec2 position, Angle heading) {
  PlannerRobot robot;
  robot.position = {static_cast<float>(position.x), static_cast<float>(position.y)};
  robot.heading = Angle(static_cast<float>(heading.degrees()));
  return robot;
}

// Whether a mission's robots gather to planned slots: gather_planner not nearest, or the order
// names its leaders (leader_ids: the dispatcher's pick of a count-only order, whose leaders must
// take the front; issue 27, item 6).
bool PlansGathering(const TransportParams& tp, const MissionSpec& spec) {
  return tp.gather_planner != GatherPlanner::kNearest || !spec.leader_ids.empty();
}

}  // namespace

std::optional<Vec2> MissionAgent::PlanSlot(const Live& live, const Pose2& self,
                                           const std::vector<Neighbour>& heard,
                                           GatherPlanRecord* record) const {
  std::map<std::uint16_t, PlannerRobot> known;
  known.emplace(self_id_, AsHeard(self.position, self.heading));
  for (const Neighbour& n : heard) {
    if (n.type == 0 && live.spec.Assigns(n.id)) known.emplace(n.id, AsHeard(n.position, n.heading));
  }
  for (const auto& kv : live.last_seen) known.emplace(kv.first, AsHeard(kv.second, Angle(0.0)));
  std::vector<PlannerRobot> robots;
  std::vector<std::uint16_t> ids;
  int self_index = -1;
  for (std::uint16_t id : Left(live)) {
    const auto it = known.find(id);
    if (it == known.end()) continue;
    if (id == self_id_) self_index = static_cast<int>(robots.size());
    robots.push_back(it->second);
    ids.push_back(id);
  }
  if (self_index < 0) return std::nullopt;
  // Around danger zones each robot's time counts along its way to the object (issue 27, item 7).
  if (!params_.static_zones.empty()) {
    const PathParams way = GatherPathParams();
    for (PlannerRobot& r : robots) r = RoutedForPlanner(r, live.centre, params_.static_zones, way);
  }
  const std::vector<Vec2> slots = SlotsIn(live.spec.ObjectAt(live.centre), robots.size());
  if (slots.empty()) return std::nullopt;
  std::vector<PlannerTarget> targets;
  for (const Vec2& s : slots) targets.push_back({s, 0.0});
  SelectionParams sp;
  sp.speed_m = params_.speed_m_per_tick;
  sp.turn_deg = params_.transport.planner_turn_deg_per_tick;
  sp.corridor_m = params_.corridor_m;
  // A mission that names its leaders (the dispatcher's count-only pick, issue 27) is planned
  // even with gather_planner nearest (by the selection matrix, which picked them), its leaders
  // onto the front slots toward the target.
  const GatherPlanner planner = params_.transport.gather_planner == GatherPlanner::kNearest
                                    ? GatherPlanner::kSelectionMatrix
                                    : params_.transport.gather_planner;
  const Planner plan_by = [planner](const std::vector<PlannerRobot>& r,
                                    const std::vector<PlannerTarget>& t, const SelectionParams& p) {
    return planner == GatherPlanner::kSelectionMatrix ? PlanSelection(r, t, p)
           : planner == GatherPlanner::kRowMinimum
               ? PlanRowMinimum(r, t, p)
               : PlanOptimal(r, t, p, planner == GatherPlanner::kBottleneck);
  };
  SelectionPlan plan;
  if (live.spec.leader_ids.empty()) {
    plan = plan_by(robots, targets, sp);
  } else {
    const std::vector<std::uint16_t> leaders = LeadersNow(live);
    std::vector<bool> is_leader;
    for (std::uint16_t id : ids) {
      is_leader.push_back(std::find(leaders.begin(), leaders.end(), id) != leaders.end());
    }
    plan = PlanLeadersInFront(robots, is_leader, targets, live.centre,
                              live.spec.target - live.centre, sp, plan_by);
  }
  record->robots = robots;
  record->ids = ids;
  record->targets = targets;
  record->params = sp;
  record->plan = plan;
  const int slot = plan.target_of[static_cast<std::size_t>(self_index)];
  if (slot < 0) return std::nullopt;
  return slots[static_cast<std::size_t>(slot)];
}

PathParams MissionAgent::GatherPathParams() const {
  PathParams p;
  p.world_size_m = params_.world_size_m;
  // A robot's centre keeps the flocking's minimum separation from a zone: its body stays out.
  p.clearance_m = params_.corridor_m;
  return p;
}

void MissionAgent::Gather(Live* live, const Pose2& self, const std::vector<Neighbour>& heard,
                          std::uint64_t tick, bool lost_now, Carry* carry) {
  const MissionSpec& spec = live->spec;
  // The way is planned anew with each slot plan (or once, for the object's centre).
  bool new_goal = !live->way_planned;
  if (PlansGathering(params_.transport, spec)) {
    // Planned at its first gathering tick, then every replan_period ticks and at once when a
    // member was lost (on the same ticks for every member: they lose it at the same tick).
    const std::uint64_t period = static_cast<std::uint64_t>(params_.transport.replan_period_ticks);
    if (!live->slot || ((tick % period == 0 || lost_now) && !carry->loading)) {
      GatherPlanRecord record;
      record.mission_id = spec.id;
      record.tick = tick;
      live->slot = PlanSlot(*live, self, heard, &record);
      if (record.plan.rounds > 0) last_gather_plan_ = std::move(record);
      new_goal = true;
    }
    carry->slot = live->slot;
  }
  if (params_.static_zones.empty() || carry->loading) return;
  const PathParams way = GatherPathParams();
  if (new_goal) {
    live->way =
        PlanGatherWay(self.position, carry->slot.value_or(live->centre), params_.static_zones, way);
    live->way_planned = true;
  }
  carry->via = live->way.Next(self.position, params_.static_zones, way, 2.0 * params_.corridor_m);
}

}  // namespace core
}  // namespace swarm_transport
