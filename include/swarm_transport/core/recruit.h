// Statist as dispatcher [SPEC 9.4, T5.5.4]: a recruiting mission names no robots; a statist at
// its object's centre pulls the standby swarm, and the first idle robots to enter the object
// take the mission until enough are inside. Pure bookkeeping: who entered first, when enough.
#ifndef SWARM_TRANSPORT_CORE_RECRUIT_H_
#define SWARM_TRANSPORT_CORE_RECRUIT_H_

#include <cstdint>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "swarm_transport/core/geometry.h"
#include "swarm_transport/core/mission.h"

namespace swarm_transport {
namespace core {

// Empty when a recruiting order (`recruit`, robot_count N > 0) is acceptable, else the reason:
// it names robots besides (a range, ids or leader_ids), is leader-only, has leader_number outside
// [1, N], N above the `idle` robots, or fails ValidateMission as an order of N of them would
// (object or target outside the arena, a live id, ...).
std::string ValidateRecruit(const MissionSpec& spec, const std::set<std::uint16_t>& idle,
                            const MissionContext& context);

// Which idle robots entered a recruiting mission's object, in the order they entered.
class RecruitWatch {
 public:
  explicit RecruitWatch(const MissionSpec& spec);

  // One tick's positions of the robots that may still be recruited (idle, physical). A robot
  // inside the object that was not inside at the previous observation joins the queue (several
  // in one tick: ascending id); one that left it, or is no longer listed, leaves the queue.
  // True once robot_count robots are inside.
  bool Observe(const std::map<std::uint16_t, Vec2>& idle);
  bool Enough() const { return inside_.size() >= count_; }
  // The first robot_count robots to enter, in order of entry (fewer until Enough()).
  std::vector<std::uint16_t> Recruits() const;
  // Robots inside now, in order of entry.
  const std::vector<std::uint16_t>& inside() const { return inside_; }

 private:
  Shape object_;
  std::size_t count_;
  std::vector<std::uint16_t> inside_;
};

// The order a recruiting mission becomes: `recruits` as its robot_ids (the leaders, as for
// every order, are the lowest leader_number of them), robot_count 0, recruit false.
MissionSpec RecruitedOrder(MissionSpec spec, const std::vector<std::uint16_t>& recruits);

}  // namespace core
}  // namespace swarm_transport

#endif  // SWARM_TRANSPORT_CORE_RECRUIT_H_
