// Missions [SPEC 6]: the order, its validation, and its phases.
#ifndef SWARM_TRANSPORT_CORE_MISSION_H_
#define SWARM_TRANSPORT_CORE_MISSION_H_

#include <cstddef>
#include <cstdint>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "swarm_transport/core/geometry.h"
#include "swarm_transport/core/path_planner.h"

namespace swarm_transport {
namespace core {

// Phases, numbered as a status message carries them.
enum class MissionPhase : std::uint8_t {
  kQueued = 0,
  kGathering = 1,
  kLoading = 2,
  kTransport = 3,
  kUnloading = 4,
  kDone = 5,
  kAborted = 6,
  kRejected = 7,
};
// How many phases there are: a status value from here on is none.
constexpr std::size_t kPhaseCount = 8;
const char* PhaseName(MissionPhase phase);

// Signal values (LOADED, UNLOADED).
enum class MissionEventKind : std::uint8_t { kLoaded = 1, kUnloaded = 2 };

// A mission order as the robots and the dispatcher hold it (an order, validated).
struct MissionSpec {
  std::uint16_t id = 0;
  // Assigned robot ids as sent: robot_ids if non-empty, else [from, to).
  std::uint16_t range_from = 0;
  std::uint16_t range_to = 0;
  std::vector<std::uint16_t> robot_ids;
  int leader_number = 0;
  Vec2 object_centre;
  Vec2 object_size;
  Vec2 target;
  std::uint8_t transport_mode = 0;
  // (ext) > 0 with no range and no ids: the dispatcher picks this many robots
  // (PickRobotsByCount) and sends the order with their ids and robot_count 0.
  std::uint16_t robot_count = 0;
  // (ext) Statist as dispatcher (SPEC 9.4, core/recruit.h): with robot_count and no robots
  // named, the dispatcher places a statist at the object and the first robot_count idle robots
  // to enter the object take the mission; the order then goes out with their ids.
  bool recruit = false;
  // (ext) If non-empty, the leaders (exactly leader_number assigned ids, in any order) instead of
  // the lowest leader_number assigned ids; the dispatcher fills it for a count-only mission
  // (PickRobotsByCount: the robots at the front of the object toward the target).
  std::vector<std::uint16_t> leader_ids;
  // Finite-ness of every float of the original message (a NaN cannot live in a Vec2 check).
  bool all_finite = true;

  // Assigned ids, ascending, without duplicates.
  std::vector<std::uint16_t> Assigned() const;
  bool Assigns(std::uint16_t robot) const;
  // The first leader_number assigned ids, or leader_ids (ascending) when given; the first
  // leader is the lowest of them.
  std::vector<std::uint16_t> Leaders() const;
  bool IsLeader(std::uint16_t robot) const;
  std::uint16_t FirstLeader() const;
  // The order in which assigned robots lead: Leaders(), then the other assigned ids ascending (a
  // lost leader is replaced by the next one). Without leader_ids it is Assigned().
  std::vector<std::uint16_t> LeadOrder() const;
  // A leader-only mission [T5.3]: object size 0 x 0 (the target is the leader's goal).
  bool LeaderOnly() const;
  // The object as a shape at `centre` (a rectangle of object_size).
  Shape ObjectAt(Vec2 centre) const;
  // Maximal runs [from, to) covering Assigned(), for freeze / continue.
  std::vector<std::pair<std::uint16_t, std::uint16_t>> AssignedRuns() const;
};

// What a validator knows besides the mission itself.
struct MissionContext {
  double world_size_m = 11.088889;
  // Robots known to exist; empty = unknown (the check is skipped).
  std::set<std::uint16_t> known_robots;
  // When set, the robots known to exist instead of known_robots, not copied: every robot of a
  // swarm checks an order against the whole swarm's ids (a copy each was N^2 at N robots).
  const std::set<std::uint16_t>* known_robots_view = nullptr;
  const std::set<std::uint16_t>& Known() const {
    return known_robots_view != nullptr ? *known_robots_view : known_robots;
  }
  // Ids of live missions (neither DONE, ABORTED nor REJECTED).
  std::set<std::uint16_t> live_missions;
  // AdmitMission: at most this many live missions (0: no limit).
  int max_live_missions = 0;
  // The static danger zones: a transport must have a route around them (ObjectRoute).
  std::vector<Zone> static_zones;
};

// Empty when the mission is acceptable, else the reason (one sentence) [SPEC 10]: non-finite
// fields; from >= to (when robot_ids is empty); leader_number 0 or larger than the group;
// leader_ids (when given) not leader_number distinct assigned ids;
// transport: object size <= 0 on an axis (only 0 x 0 means leader-only); leader-only with more
// than leader_number robots; object centre or target outside the arena; duplicate live id;
// unknown robot id; transport_mode not 0 or 1.
std::string ValidateMission(const MissionSpec& mission, const MissionContext& context);

// The one admission decision (issue 11): ValidateMission, then the limit of live missions. The
// dispatcher decides with it; with no dispatcher (Admission::kRobots) every robot decides with
// it on its own table, so that robots and dispatcher cannot disagree.
std::string AdmitMission(const MissionSpec& mission, const MissionContext& context);

// Paths around danger (SPEC 9.8): the route of a transport mission's object around the static
// danger zones - waypoints with the target last, just the target when the straight line is
// clear - keeping the object's half diagonal plus kRouteClearanceM from every zone;
// std::nullopt when there is none (the order is refused). Every robot computes the same route
// from the same order and configuration.
constexpr double kRouteClearanceM = 0.1;
std::optional<std::vector<Vec2>> ObjectRoute(const MissionSpec& mission,
                                             const std::vector<Zone>& zones, double world_size_m);

// Who admits orders (/swarm/mission_admission): the dispatcher (robots act only on the orders it
// publishes; a hand-made order reaches them after it admitted it), or, with no dispatcher
// running, every robot itself with AdmitMission.
enum class Admission : std::uint8_t { kDispatcher, kRobots };
bool ParseAdmission(const std::string& name, Admission* out);
const char* AdmissionName(Admission admission);

// Who sent a mission message, as far as the transport tells. ROS 1 has no authentication: this
// keeps stray and hand-made messages out of a mission, not an attacker.
enum class SenderKind : std::uint8_t {
  kDispatcher,  // the mission dispatcher
  kRelay,       // the simulator's relay (lock-step) or a robot host: carries robots' messages
  kRobot,       // a robot's own node: `robot_id`
  kOther,       // anyone else (rostopic pub, a script, a recorder)
};
struct Sender {
  SenderKind kind = SenderKind::kOther;
  std::uint16_t robot_id = 0;
};

// Whether an order from `sender` counts: with admission by the dispatcher only the dispatcher's
// (and the relay's, which passed only those on); with admission by the robots anyone's.
bool MayOrder(Admission admission, const Sender& sender);
// Whether a status, object update or object delete from `sender` counts for a mission:
// only its first leader sends them, besides the dispatcher (REJECTED, ABORTED and the object of
// an aborted mission). A robot's node counts for a mission that assigns it (any of them: a
// promoted first leader is one of them); `mission` null (not known to the receiver) lets any
// robot's node count. The relay and robot hosts carry robots' messages and count; others not.
bool MayReport(const MissionSpec* mission, const Sender& sender);

// The tick a dispatcher's LOADED / UNLOADED takes effect: the tick the first leader reported
// LOADING / UNLOADING plus `delay_s` rounded up to whole ticks (stamped, so that the delay lands
// on the same tick however the processes are scheduled).
std::uint64_t SignalTick(std::uint64_t phase_tick, double delay_s, double tick_period_s);

}  // namespace core
}  // namespace swarm_transport

#endif  // SWARM_TRANSPORT_CORE_MISSION_H_
