#include "swarm_transport/core/mission.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace swarm_transport {
namespace core {

const char* PhaseName(MissionPhase phase) {
  switch (phase) {
    case MissionPhase::kQueued:
      return "QUEUED";
    case MissionPhase::kGathering:
      return "GATHERING";
    case MissionPhase::kLoading:
      return "LOADING";
    case MissionPhase::kTransport:
      return "TRANSPORT";
    case MissionPhase::kUnloading:
      return "UNLOADING";
    case MissionPhase::kDone:
      return "DONE";
    case MissionPhase::kAborted:
      return "ABORTED";
    case MissionPhase::kRejected:
      return "REJECTED";
  }
  return "UNKNOWN";
}

std::vector<std::uint16_t> MissionSpec::Assigned() const {
  std::vector<std::uint16_t> ids;
  if (!robot_ids.empty()) {
    ids = robot_ids;
  } else {
    for (std::uint32_t i = range_from; i < range_to; ++i)
      ids.push_back(static_cast<std::uint16_t>(i));
  }
  std::sort(ids.begin(), ids.end());
  ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
  return ids;
}

bool MissionSpec::Assigns(std::uint16_t robot) const {
  if (!robot_ids.empty()) {
    return std::find(robot_ids.begin(), robot_ids.end(), robot) != robot_ids.end();
  }
  return range_from <= robot && robot < range_to;
}

std::vector<std::uint16_t> MissionSpec::Leaders() const {
  if (!leader_ids.empty()) {
    std::vector<std::uint16_t> ids = leader_ids;
    std::sort(ids.begin(), ids.end());
    ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
    return ids;
  }
  std::vector<std::uint16_t> ids = Assigned();
  if (leader_number >= 0 && static_cast<std::size_t>(leader_number) < ids.size()) {
    ids.resize(static_cast<std::size_t>(leader_number));
  }
  return ids;
}

bool MissionSpec::IsLeader(std::uint16_t robot) const {
  const std::vector<std::uint16_t> leaders = Leaders();
  return std::find(leaders.begin(), leaders.end(), robot) != leaders.end();
}

std::uint16_t MissionSpec::FirstLeader() const {
  const std::vector<std::uint16_t> ids = leader_ids.empty() ? Assigned() : Leaders();
  return ids.empty() ? 0 : ids.front();
}

std::vector<std::uint16_t> MissionSpec::LeadOrder() const {
  std::vector<std::uint16_t> order = Assigned();
  if (leader_ids.empty()) return order;
  const std::vector<std::uint16_t> leaders = Leaders();
  std::stable_partition(order.begin(), order.end(), [&leaders](std::uint16_t id) {
    return std::binary_search(leaders.begin(), leaders.end(), id);
  });
  return order;
}

bool MissionSpec::LeaderOnly() const { return object_size.x == 0.0 && object_size.y == 0.0; }

Shape MissionSpec::ObjectAt(Vec2 centre) const { return Shape::FromRect(centre, object_size); }

std::vector<std::pair<std::uint16_t, std::uint16_t>> MissionSpec::AssignedRuns() const {
  std::vector<std::pair<std::uint16_t, std::uint16_t>> runs;
  for (std::uint16_t id : Assigned()) {
    if (!runs.empty() && runs.back().second == id) {
      ++runs.back().second;
    } else {
      runs.emplace_back(id, static_cast<std::uint16_t>(id + 1));
    }
  }
  return runs;
}

namespace {

// Why leader_ids, when given, does not name leader_number distinct assigned robots; empty if it
// does or is empty (the lowest leader_number assigned ids lead).
std::string LeaderIdsProblem(const MissionSpec& m, const std::vector<std::uint16_t>& assigned) {
  if (m.leader_ids.empty()) return "";
  std::ostringstream os;
  std::set<std::uint16_t> seen;
  for (std::uint16_t id : m.leader_ids) {
    if (!seen.insert(id).second) {
      os << "leader_ids names robot " << id << " twice";
      return os.str();
    }
    if (!std::binary_search(assigned.begin(), assigned.end(), id)) {
      os << "leader_ids names robot " << id << ", which the mission does not assign";
      return os.str();
    }
  }
  if (m.leader_ids.size() != static_cast<std::size_t>(m.leader_number)) {
    os << "leader_ids names " << m.leader_ids.size() << " robots but leader_number is "
       << m.leader_number;
  }
  return os.str();
}

}  // namespace

std::string ValidateMission(const MissionSpec& m, const MissionContext& ctx) {
  std::ostringstream os;
  const auto inside = [&ctx](Vec2 p) {
    return p.x >= 0.0 && p.y >= 0.0 && p.x <= ctx.world_size_m && p.y <= ctx.world_size_m;
  };
  const std::vector<std::uint16_t> assigned = m.Assigned();
  const std::string leader_ids_problem = LeaderIdsProblem(m, assigned);
  if (!m.all_finite) {
    os << "a field is not a finite number (NaN or inf)";
  } else if (m.recruit) {
    os << "recruit needs the mission dispatcher to gather the robots with a statist";
  } else if (m.robot_count > 0 && (!m.robot_ids.empty() || m.range_from < m.range_to)) {
    os << "robot_count " << m.robot_count
       << " is given besides a robot range or robot_ids (give one of them)";
  } else if (m.robot_count > 0) {
    os << "robot_count " << m.robot_count
       << " needs the mission dispatcher to pick the robots (no range or robot_ids given)";
  } else if (m.robot_ids.empty() && m.range_from >= m.range_to) {
    os << "robot range [" << m.range_from << ", " << m.range_to
       << ") is empty or inverted (from must be < to)";
  } else if (m.leader_number < 1) {
    os << "leader_number must be >= 1";
  } else if (static_cast<std::size_t>(m.leader_number) > assigned.size()) {
    os << "leader_number " << m.leader_number << " is larger than the group of " << assigned.size()
       << " robots";
  } else if (!leader_ids_problem.empty()) {
    os << leader_ids_problem;
  } else if (m.transport_mode > 1) {
    os << "transport_mode must be 0 (swarm) or 1 (formation) but is "
       << static_cast<int>(m.transport_mode);
  } else if (!m.LeaderOnly() && (!(m.object_size.x > 0.0) || !(m.object_size.y > 0.0))) {
    os << "object size must be > 0 on both axes (0 x 0 means a leader-only mission)";
  } else if (!m.LeaderOnly() &&
             (m.object_size.x > ctx.world_size_m || m.object_size.y > ctx.world_size_m)) {
    os << "object size " << m.object_size.x << " x " << m.object_size.y
       << " is larger than the arena (" << ctx.world_size_m << " m)";
  } else if (m.LeaderOnly() && assigned.size() != static_cast<std::size_t>(m.leader_number)) {
    os << "a leader-only mission (object size 0 x 0) must assign exactly its leaders";
  } else if (!m.LeaderOnly() && !inside(m.object_centre)) {
    os << "object centre (" << m.object_centre.x << ", " << m.object_centre.y
       << ") is outside the arena";
  } else if (!inside(m.target)) {
    os << "target (" << m.target.x << ", " << m.target.y << ") is outside the arena [0, "
       << ctx.world_size_m << "]";
  } else if (ctx.live_missions.count(m.id) > 0) {
    os << "mission_id " << m.id << " is already live";
  } else if (!ctx.Known().empty()) {
    for (std::uint16_t id : assigned) {
      if (ctx.Known().count(id) == 0) {
        os << "robot " << id << " is unknown";
        break;
      }
    }
  }
  return os.str();
}

std::uint64_t SignalTick(std::uint64_t phase_tick, double delay_s, double tick_period_s) {
  return phase_tick + static_cast<std::uint64_t>(std::ceil(delay_s / tick_period_s - 1e-9));
}

std::optional<std::vector<Vec2>> ObjectRoute(const MissionSpec& mission,
                                             const std::vector<Zone>& zones, double world_size_m) {
  if (zones.empty() || mission.LeaderOnly()) return std::vector<Vec2>{mission.target};
  PathParams p;
  p.world_size_m = world_size_m;
  p.clearance_m = 0.5 * std::hypot(mission.object_size.x, mission.object_size.y) + kRouteClearanceM;
  return PlanPath(mission.object_centre, mission.target, zones, p);
}

std::string AdmitMission(const MissionSpec& mission, const MissionContext& context) {
  std::string reason = ValidateMission(mission, context);
  if (!reason.empty()) return reason;
  if (!context.static_zones.empty() && !mission.LeaderOnly() &&
      !ObjectRoute(mission, context.static_zones, context.world_size_m)) {
    return "no route for the object around the danger zones (SPEC 9.8): the target is "
           "walled off or the object does not fit through";
  }
  const std::size_t live = context.live_missions.size();
  if (context.max_live_missions > 0 &&
      live >= static_cast<std::size_t>(context.max_live_missions)) {
    return "too many live missions (" + std::to_string(live) + ", max_live_missions " +
           std::to_string(context.max_live_missions) + ")";
  }
  return "";
}

bool ParseAdmission(const std::string& name, Admission* out) {
  if (name == "dispatcher") {
    *out = Admission::kDispatcher;
  } else if (name == "robots") {
    *out = Admission::kRobots;
  } else {
    return false;
  }
  return true;
}

const char* AdmissionName(Admission admission) {
  return admission == Admission::kDispatcher ? "dispatcher" : "robots";
}

bool MayOrder(Admission admission, const Sender& sender) {
  if (admission == Admission::kRobots) return true;
  return sender.kind == SenderKind::kDispatcher || sender.kind == SenderKind::kRelay;
}

bool MayReport(const MissionSpec* mission, const Sender& sender) {
  switch (sender.kind) {
    case SenderKind::kDispatcher:
    case SenderKind::kRelay:
      return true;
    case SenderKind::kRobot:
      return mission == nullptr || mission->Assigns(sender.robot_id);
    case SenderKind::kOther:
      break;
  }
  return false;
}

}  // namespace core
}  // namespace swarm_transport
