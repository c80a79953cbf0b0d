// A robot's side of the missions [SPEC 5, 6]: which missions it knows, which zones they make
// for it, its role this tick, and - as a mission's first leader - the phase machine.
#ifndef SWARM_TRANSPORT_CORE_MISSION_AGENT_H_
#define SWARM_TRANSPORT_CORE_MISSION_AGENT_H_

#include <cstdint>
#include <deque>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "swarm_transport/core/assignment.h"
#include "swarm_transport/core/balloon.h"
#include "swarm_transport/core/flocking.h"
#include "swarm_transport/core/gather_route.h"
#include "swarm_transport/core/leader.h"
#include "swarm_transport/core/mission.h"
#include "swarm_transport/core/transport.h"

namespace swarm_transport {
namespace core {

// Parameters of the robot-side mission logic.
struct MissionAgentParams {
  double goal_tolerance_m = 0.05;  // object centre (or leader) at the target within this
  int object_update_ticks = 1;     // first leader publishes an object update every N ticks
  int progress_every_ticks = 50;   // first leader repeats its status with progress every N
  std::uint64_t phase_timeout_ticks = 20000;  // a phase that lasts longer aborts the mission
  TransportParams transport;                  // gathering and carrying (leaders bound or not)
  double local_range_m = 1.0;  // the flocking's: whether the gathered group is one chain
  // A plausible object update: inside the arena [0, world_size_m]^2, and no farther from the
  // last known centre than the object's robots can carry it in the ticks since (issue 11).
  double world_size_m = 11.088889;
  double speed_m_per_tick = 0.1;  // the robots' top speed: the object moves no faster
  // A member of a running transport mission not heard for this many ticks is lost for the
  // mission (its radio is silent: a dead, hung or deleted robot) [SPEC 9.7]. Every member is
  // heard every tick over the mission channel while it answers its ticks, so every member
  // loses it at the same tick. The mission goes on without it: its leaders are the first
  // leader_number assigned robots not lost in MissionSpec::LeadOrder (its leader_ids first, if
  // named; a lost leader is replaced by the next assigned robot, a lost first leader by the
  // first of them in that order, which announces itself with a status),
  // and it ends ABORTED when fewer robots than leaders are left. Until it is lost a silent
  // member counts where it was last heard; in transport the object is re-anchored when one is
  // lost, so that it does not jump. Robots take it from /swarm/lost_after_s.
  std::uint64_t lost_after_ticks = 20;
  // Whether a robot's peers go on hearing it while it misses its ticks (its process hung or
  // starved of CPU). False where its radio falls silent with it: in lock-step (the simulator
  // makes a robot that does not answer quiet) and wherever a robot announces its own position
  // (hardware, broadcast comm); then a robot whose ticks jumped by more than lost_after_ticks
  // was lost for the others, and counts itself lost too, so that it does not lead beside the
  // one promoted in its place. True in a real-time simulation, where the simulator relays every
  // connected robot's pose from its world whatever its process does: its peers never lost it,
  // and it goes on as before (counting itself lost there left its mission without a first
  // leader until the dispatcher aborted it as silent: issue 29). Either way a robot named lost
  // in its first leader's status counts itself lost (OnStatus).
  bool heard_while_hung = false;
  // A running transport with fewer robots left than this (and always with fewer than its
  // leaders) ends ABORTED naming the lost robots (SPEC 9.7, /swarm/mission_min_robots; 0: the
  // leaders' number).
  int min_robots = 0;
  // Paths around danger (SPEC 9.8): the static danger zones, and how far a transport's object
  // centre keeps from them (half its diagonal plus route_clearance_m). The leaders steer for
  // each waypoint in turn and pass it within waypoint_reach_m.
  std::vector<Zone> static_zones;
  double waypoint_reach_m = 0.3;
  // Planned gathering (transport.gather_planner): a robot within this distance of another's
  // straight path blocks it (the flocking's minimum separation).
  double corridor_m = 0.11;
  // (ext, SPEC 9.5) Balloon spreading under the object while LOADING: the first leader sends
  // the freeze loading_spread_ticks after LOADING began (not at once) and starts the transport
  // no earlier than the tick after it; until the freeze the robots spread (RobotBrain).
  LoadingSpread loading_spread = LoadingSpread::kNone;
  int loading_spread_ticks = 10;
};

// How far an object may move in `ticks` ticks when its robots drive at most `speed_m_per_tick`:
// twice that distance plus two ticks' worth (the centroid of robots that each move at most the
// speed moves at most the speed; the rest is slack for rounding, a tick's lag and real-time
// jitter, where two updates may arrive between two of a robot's ticks).
double MaxObjectStep(std::uint64_t ticks, double speed_m_per_tick);
// The nearest centre to `centre` at which an object of `size` lies inside the arena
// [0, world_size_m]^2 (an axis the object does not fit in keeps its coordinate; world_size_m
// <= 0: no arena, `centre` itself).
Vec2 InsideArena(Vec2 centre, Vec2 size, double world_size_m);

// A status report the first leader publishes.
struct StatusReport {
  std::uint16_t mission_id = 0;
  MissionPhase phase = MissionPhase::kQueued;
  std::string reason;
  std::uint16_t assigned = 0;
  std::uint16_t inside = 0;
  Vec2 object;
  double distance_to_target = 0.0;
  // The robots of the mission its first leader counts lost (ascending): the others learn them
  // from it (MissionAgent::OnStatus).
  std::vector<std::uint16_t> lost;
};

// Messages the robot must publish after this tick (only a first leader fills them).
struct MissionOutbox {
  std::vector<std::pair<std::uint16_t, std::uint16_t>> freeze;  // [from, to) runs
  std::vector<std::pair<std::uint16_t, std::uint16_t>> resume;  // Continue runs
  std::optional<std::pair<std::uint16_t, Vec2>> update_object;  // mission id, centre
  std::optional<std::uint16_t> delete_object;                   // mission id
  std::vector<StatusReport> statuses;
  bool empty() const {
    return freeze.empty() && resume.empty() && !update_object && !delete_object && statuses.empty();
  }
};

// Which of a first leader's statuses go out as phase reports: a taken order's QUEUED first (once
// the leader can publish, or together with its first other status), then each phase once; a
// repeat of the phase it last reported for a mission is a progress report. The robot node and
// the in-process batch runner both use it, so observers see the same sequence.
class StatusSequencer {
 public:
  // The QUEUED of an order just taken.
  void Queue(const StatusReport& queued) { queued_.push_back(queued); }
  // Splits a tick's `statuses` in place: the phase reports stay, repeats move to `progress`.
  // `ready`: the leader's mission publishers are connected.
  void Sequence(bool ready, std::vector<StatusReport>* statuses,
                std::vector<StatusReport>* progress);

 private:
  std::vector<StatusReport> queued_;
  std::map<std::uint16_t, MissionPhase> reported_;  // last phase reported per live mission
};

// How the robot behaves this tick.
struct MissionPlan {
  std::vector<Zone> zones;     // objects: safety for its active mission, danger for all others
  FlockGroup group;            // its swarm's candidates: its mission group, or all but others'
  std::optional<Carry> carry;  // a transport mission's robot: use CarryStep
  bool lead = false;           // a leader-only mission's leader: use LeaderStep
  bool keep_flock = false;     // leader-only missions wait for / give up on the swarm
  Vec2 goal;                   // leader's goal
  Angle steer;                 // leader's heading
  std::optional<std::uint16_t> active;  // the mission it works on, if any
};

// A plan of a planned gathering as one robot made it (transport.gather_planner not nearest):
// what the batch engine's plan metrics read (issue 27).
struct GatherPlanRecord {
  std::uint16_t mission_id = 0;
  std::uint64_t tick = 0;
  std::vector<PlannerRobot> robots;  // the mission's robots left, as heard
  std::vector<std::uint16_t> ids;    // their ids, in the same order
  std::vector<PlannerTarget> targets;
  SelectionParams params;
  SelectionPlan plan;
};

// The mission side of one robot. Pure: messages in, a plan and an outbox out.
class MissionAgent {
 public:
  MissionAgent(std::uint16_t self_id, const MissionAgentParams& params);

  // Inbox. Each returns false with a reason when the message is rejected (state unchanged).
  // `mission` must already have passed ValidateMission with LiveIds() in its context.
  bool OnNewMission(const MissionSpec& mission, std::string* why);
  // The last plan of a planned gathering this robot made, if any.
  const std::optional<GatherPlanRecord>& last_gather_plan() const { return last_gather_plan_; }
  bool OnObjectUpdate(std::uint16_t mission_id, Vec2 centre, std::string* why);
  bool OnObjectDelete(std::uint16_t mission_id, std::string* why);
  // The first leader acts on it at tick `not_before_tick` at the earliest (0: at once).
  bool OnEvent(std::uint16_t mission_id, MissionEventKind event, std::uint64_t not_before_tick,
               std::string* why);
  // A status published by a mission's first leader (how other members learn the phase), with
  // the robots it counts lost: they are lost for this robot too, itself included (a robot the
  // first leader no longer hears, or a first leader whose members promoted another in its place
  // while it heard them: every robot of a mission comes to agree on who is lost, so on who
  // leads it, and a lost robot never leads beside the one promoted in its place).
  void OnStatus(std::uint16_t mission_id, MissionPhase phase,
                const std::vector<std::uint16_t>& lost = {});
  // Where it runs (MissionAgentParams::heard_while_hung).
  void set_heard_while_hung(bool heard) { params_.heard_while_hung = heard; }
  // The swarm's local range and speed changed (a valid flocking tuning, issue 13).
  void Retune(double local_range_m, double speed_m_per_tick) {
    params_.local_range_m = local_range_m;
    params_.speed_m_per_tick = speed_m_per_tick;
  }

  // Missions this robot holds (not yet deleted).
  std::set<std::uint16_t> LiveIds() const;
  // The order of live mission `mission_id`, or nullptr.
  const MissionSpec* Find(std::uint16_t mission_id) const;
  // The phase this robot believes `mission_id` is in (kDone when unknown).
  MissionPhase PhaseOf(std::uint16_t mission_id) const;
  // True when this robot is the first leader of a live mission (it must be able to publish),
  // also when it was promoted because the first leader was lost.
  bool IsFirstLeaderOfAny() const;
  // The robots of live mission `mission_id` this robot counts as lost (empty when unknown).
  std::set<std::uint16_t> LostOf(std::uint16_t mission_id) const;

  // One tick: `self` is its pose, `heard` every robot it heard (in range, relayed and mission
  // peers). A transport mission's robots each compute its object's centre from the positions
  // they hear: fixed while gathering, in transport the offset at its start + the current
  // centroid of the mission's robots [T5.4, THESIS_CODE 2].
  // Fills `outbox` (first leader only) and returns how to move. A null `outbox` means the robot
  // cannot publish yet: a first leader's phase machine waits (its members gather anyway).
  MissionPlan Tick(const Pose2& self, const std::vector<Neighbour>& heard, std::uint64_t tick,
                   MissionOutbox* outbox);
  // After the move: a leader that arrived at its leader-only goal ends its mission.
  void LeaderArrived(std::uint16_t mission_id, MissionOutbox* outbox);

 private:
  // What every robot knows of a live mission.
  struct Live {
    MissionSpec spec;
    Vec2 centre;
    std::uint64_t centre_tick = 0;               // the tick `centre` was last set at
    MissionPhase phase = MissionPhase::kQueued;  // as known by this robot
    std::uint64_t phase_tick = 0;                // first-leader: tick the phase began
    bool phase_started = false;
    bool anchored = false;  // transport began for this robot: `offset`, `place` are set
    Vec2 offset;            // centre - centroid of the mission's robots at transport start
    Vec2 place;             // formation: this robot's position - centre at transport start
    std::uint64_t transport_ticks = 0;
    bool loaded = false;    // first-leader: LOADED arrived during LOADING
    bool unloaded = false;  // first-leader: UNLOADED arrived during UNLOADING
    // first-leader, loading_spread balloon: the tick the freeze goes out, and whether it did
    std::uint64_t spread_end_tick = 0;
    bool spread_frozen = false;
    std::uint64_t signal_tick = 0;                      // ... and takes effect at this tick
    bool self_arrived = false;                          // this leader reached its leader-only goal
    std::map<std::uint16_t, std::uint64_t> heard_tick;  // each member's last tick heard
    std::map<std::uint16_t, Vec2> last_seen;            // ... and where
    std::set<std::uint16_t> lost;                       // members lost for the mission (for good)
    bool reanchor = false;  // a member was lost in transport: anchor the object anew
    // Transport, not its first leader: the first leader's object of an update taken since the
    // last tick, and this robot's centroid of the mission's robots at its last tick.
    std::optional<Vec2> leader_centre;
    std::optional<Vec2> last_centroid;
    std::uint64_t first_since = 0;  // tick it became first leader by promotion (0: none)
    bool promoted = false;          // it leads as first leader because the first leader was lost
    bool announced = false;         // ... and said so
    std::size_t lost_told = 0;      // first-leader: lost robots it has named in a report so far
    bool lost_heard = false;        // a status named robots lost since its last tick
    std::vector<Vec2> route;        // transport: the object's waypoints, the target last
    std::size_t leg = 0;            // ... the one it heads for now
    std::optional<Vec2> slot;       // planned gathering: its own slot under the object
    GatherWay way;                  // gathering: its way to its goal around danger zones
    bool way_planned = false;       // ... planned (once per goal: each slot plan, or the centre)
  };
  // Of a live mission, with its lost robots: the robots left (ascending), its leaders now (the
  // first leader_number of them in MissionSpec::LeadOrder) and its first leader now (the first
  // of them; 0 when none is left).
  std::vector<std::uint16_t> Left(const Live& live) const;
  std::vector<std::uint16_t> LeadersNow(const Live& live) const;
  bool LeadsFirst(const Live& live) const;
  // Heartbeats of the active transport mission at `tick`: who was heard, who is lost now.
  // True when a member was lost this tick.
  bool Heartbeats(Live* live, const std::vector<Neighbour>& heard, std::uint64_t tick);
  // Where a transport mission's robots are, as this robot hears them.
  struct Group {
    std::map<std::uint16_t, Vec2> where;  // itself and every assigned robot heard
    Vec2 centroid;
    std::uint16_t inside = 0;           // of them inside the object at its current centre
    bool OneChain(double range) const;  // every robot linked to every other within range
  };
  void Drop(std::uint16_t mission_id);
  // Planned gathering: this robot's slot by transport.gather_planner over the mission's robots
  // left (itself, those heard, the others where last heard), as every member computes it; a
  // robot whose way to the object is routed around danger zones as RoutedForPlanner sees it.
  // `record` receives the plan as made (robots, slots, parameters, result; rounds 0: none).
  std::optional<Vec2> PlanSlot(const Live& live, const Pose2& self,
                               const std::vector<Neighbour>& heard, GatherPlanRecord* record) const;
  // A gathering robot's goal this tick (mission_agent_gather.cpp): its slot when the mission
  // plans its gathering (planned at its first gathering tick, every replan_period ticks and at
  // once when a member was lost: `lost_now`), and the next waypoint of its way around the
  // static danger zones while its goal is not in clear sight. Fills carry->slot and carry->via.
  void Gather(Live* live, const Pose2& self, const std::vector<Neighbour>& heard,
              std::uint64_t tick, bool lost_now, Carry* carry);
  PathParams GatherPathParams() const;
  Group Locate(const Live& live, const Pose2& self, const std::vector<Neighbour>& heard) const;
  // A member of a transport mission: moves the object with its robots once transport began.
  void UpdateCentre(Live* live, const Pose2& self, Group* group) const;
  void RunFirstLeader(Live* live, const Pose2& self, const Group& group, std::uint64_t tick,
                      MissionOutbox* outbox);
  StatusReport Report(const Live& live, std::uint16_t inside) const;
  void EnterPhase(Live* live, MissionPhase phase, std::uint64_t tick, std::uint16_t inside,
                  MissionOutbox* outbox);

  std::uint16_t self_id_;
  std::uint64_t tick_ = 0;  // the last tick run: relayed messages belong to the next one
  MissionAgentParams params_;
  std::map<std::uint16_t, Live> live_;
  std::deque<std::uint16_t> queue_;  // this robot's own missions, FIFO [T6.4]
  std::optional<GatherPlanRecord> last_gather_plan_;
};

}  // namespace core
}  // namespace swarm_transport

#endif  // SWARM_TRANSPORT_CORE_MISSION_AGENT_H_
