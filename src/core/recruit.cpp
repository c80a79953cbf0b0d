#include "swarm_transport/core/recruit.h"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <sstream>

namespace swarm_transport {
namespace core {

std::string ValidateRecruit(const MissionSpec& spec, const std::set<std::uint16_t>& idle,
                            const MissionContext& context) {
  std::ostringstream os;
  const std::size_t count = spec.robot_count;
  if (!spec.all_finite) {
    os << "a field is not a finite number (NaN or inf)";
  } else if (count == 0) {
    os << "recruit needs robot_count > 0 (how many robots the statist gathers)";
  } else if (!spec.robot_ids.empty() || spec.range_from < spec.range_to) {
    os << "recruit names no robots: give robot_count without a robot range or robot_ids";
  } else if (!spec.leader_ids.empty()) {
    os << "recruit names no robots: give it without leader_ids (the lowest leader_number of the "
          "recruits lead)";
  } else if (spec.LeaderOnly()) {
    os << "recruit needs an object (object size > 0): the robots are those that enter it";
  } else if (spec.leader_number < 1 || static_cast<std::size_t>(spec.leader_number) > count) {
    os << "leader_number " << spec.leader_number << " must be in [1, robot_count " << count << "]";
  } else if (count > idle.size()) {
    os << "recruit of robot_count " << count << " but only " << idle.size() << " robots are idle";
  }
  if (os.tellp() > 0) return os.str();
  // The rest as for an order naming `count` of them (arena, target, mode, live id).
  MissionSpec probe = spec;
  probe.recruit = false;
  probe.robot_count = 0;
  probe.robot_ids.assign(idle.begin(), std::next(idle.begin(), static_cast<long>(count)));
  return ValidateMission(probe, context);
}

RecruitWatch::RecruitWatch(const MissionSpec& spec)
    : object_(spec.ObjectAt(spec.object_centre)), count_(spec.robot_count) {}

bool RecruitWatch::Observe(const std::map<std::uint16_t, Vec2>& idle) {
  std::set<std::uint16_t> now;
  for (const auto& kv : idle) {
    const Vec2& p = kv.second;
    if (std::isfinite(p.x) && std::isfinite(p.y) && object_.Contains(p)) now.insert(kv.first);
  }
  // Those that left (or are no longer idle) leave the queue; the order of the rest holds.
  inside_.erase(std::remove_if(inside_.begin(), inside_.end(),
                               [&now](std::uint16_t id) { return now.count(id) == 0; }),
                inside_.end());
  const std::set<std::uint16_t> before(inside_.begin(), inside_.end());
  for (std::uint16_t id : now) {  // ascending
    if (before.count(id) == 0) inside_.push_back(id);
  }
  return Enough();
}

std::vector<std::uint16_t> RecruitWatch::Recruits() const {
  const std::size_t n = std::min(count_, inside_.size());
  return {inside_.begin(), inside_.begin() + static_cast<long>(n)};
}

MissionSpec RecruitedOrder(MissionSpec spec, const std::vector<std::uint16_t>& recruits) {
  spec.robot_ids = recruits;
  std::sort(spec.robot_ids.begin(), spec.robot_ids.end());
  spec.robot_count = 0;
  spec.recruit = false;
  return spec;
}

}  // namespace core
}  // namespace swarm_transport
