// An informed leader [SPEC 5, T5.3, T7.3]: heads for its goal without swerving.
#ifndef SWARM_TRANSPORT_CORE_LEADER_H_
#define SWARM_TRANSPORT_CORE_LEADER_H_

#include <cstdint>
#include <string>

#include "swarm_transport/core/flocking.h"

namespace swarm_transport {
namespace core {

// Leader parameters.
struct LeaderParams {
  double goal_tolerance_m = 0.05;  // within this of the goal the leader is done
  double wait_fraction = 0.5;      // wait while the swarm centroid is farther than this * range
  bool keep_flock = true;          // wait for / give up on the swarm (leader-only missions)
  bool wait_behind = true;         // wait only while that centroid is behind (more than 90 deg off
                                   // the course), as the thesis's leader code meant to (its
                                   // arithmetic: wait_evaluated_angles)
  // Decide "behind" with the angle arithmetic of the thesis's evaluated §7.3 leader code
  // (RobotSwarms 68b2ba6, robot/nodes/Leader.cpp 76-81 with basics/Angle.h
  // normalizeToCircularAngle): r = fmod(bearing to the centroid in (-180, 180] - course in
  // [0, 360), 360), a negative r turned into 360 - r, and it waits only for 90 < r < 270. On a
  // course of 45 deg that is a centroid bearing of 135-180 deg (behind on the left); a swarm
  // straight behind it or behind on its right never holds it. Replaces wait_behind's test.
  bool wait_evaluated_angles = false;
  // Give up (go on alone, never wait again) once the centroid of its swarm is farther than the
  // local range, as the thesis's text says of its final §7.3 leader ("gibt auf, wenn der
  // Schwarm-Mittelpunkt die eigene lokale Reichweite ganz verlassen hat") and SPEC 5. false:
  // only once no robot of its swarm is left in range (its chain broke off), as the evaluated
  // §7.3 leader code, which had no give-up (RobotSwarms 68b2ba6 Leader.cpp 73-86). Measured
  // (leader_group_cohesion, 240 runs): with true a chain of 15-25 passive robots, wider than
  // the range, is given up at every cohesion (25 passive at 40 %: 1.5 of 25 arrive, against
  // 13.2 with false), so the text's "only at 40 % do the values stay high" is lost.
  bool give_up_beyond_range = false;
  // The centroid it waits for counts the leader itself once beside its swarm, as the evaluated
  // §7.3 leader code did (RobotSwarms 68b2ba6, robot/nodes/Leader.cpp 74-75: flockCentre over
  // findFlock of its own pose, flock/Statistics.h 58-65, which keeps its own entry): the wait
  // starts when the swarm's own centroid is (n + 1) / n times wait_fraction * range away (n
  // robots in its swarm). false: the swarm's robots only.
  bool centroid_with_self = false;
  // Test its own move against the other robots (slow down, then stand when blocked) [T5.3,
  // T6.3]. false: drive the course at full speed through them, the simulator pushing the
  // overlapping robots apart afterwards, as the evaluated §7.3 leader code did (RobotSwarms
  // 68b2ba6 Leader.cpp 93 with robot_system/RobotPilot.h move(): no legality test for the
  // leader, antiBump after the move). The arena border and zones still hold it.
  bool check_collisions = true;
  // (ext) After this many blocked ticks in a row the leader swerves like any robot (SPEC 4
  // step 5) until its course is free again; 0: never (the thesis: two leaders heading for each
  // other's side then stand for good).
  int swerve_after_blocked_ticks = 0;
  // (ext, SPEC 9.2) Virtual leaders and stacking: while it leads a leader-only mission a leader
  // announces virtual_copies - 1 copies (type 1) at its pose with its position, and its
  // hearers count each as a neighbour (alignment and cohesion): it weighs virtual_copies times
  // in their flocking. 1: only itself (the thesis). At most 255.
  int virtual_copies = 1;
  std::string Validate() const;
};

// What a leader remembers between ticks.
struct LeaderMemory {
  bool gave_up = false;                // its swarm (or its centroid) left its range: it goes on
                                       // alone
  std::uint64_t blocked_waits = 0;     // ticks it stood because every speed collided
  std::uint64_t blocked_in_a_row = 0;  // blocked ticks since it last drove its course
  std::uint64_t swarm_waits = 0;       // ticks it stood waiting for its swarm
};

// Result of one leader tick.
struct LeaderDecision {
  MoveDecision move;
  bool arrived = false;  // within goal_tolerance: the caller reverts to normal behaviour
};

// One leader tick towards `goal` along `steer` (for a leader-only mission the bearing self ->
// goal; in transport the bearing object centre -> target). Never swerves: tries `steer` at
// full speed, then at reduced speeds; stands otherwise (a blocked wait). With keep_flock, the
// swarm is the physical neighbours in range (itself excluded): none left, or with
// give_up_beyond_range their centroid farther than the range -> gave_up; centroid
// farther than wait_fraction * range (and, with wait_behind, more than 90 deg off `steer`) ->
// stand (a swarm wait). `rng` is advanced exactly as
// FlockingStep advances it, so switching roles keeps the random sequence aligned.
LeaderDecision LeaderStep(const Perception& in, const FlockingParams& p, const LeaderParams& lp,
                          Vec2 goal, Angle steer, Rng& rng, double duration_s,
                          LeaderMemory* memory);

}  // namespace core
}  // namespace swarm_transport

#endif  // SWARM_TRANSPORT_CORE_LEADER_H_
