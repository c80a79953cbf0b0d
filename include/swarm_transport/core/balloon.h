// Balloon dispersion [SPEC 9.5, T5.5.5]: a standby robot's virtual size grows like a balloon in
// a sack of balloons all pumped at once, until it touches others or borders at points that
// enclose it (at least three, with no free side left); while it is not enclosed, its flight
// reflex pushes it off whatever its balloon touches. Pure: everything comes in as arguments.
#ifndef SWARM_TRANSPORT_CORE_BALLOON_H_
#define SWARM_TRANSPORT_CORE_BALLOON_H_

#include <cstdint>
#include <string>
#include <vector>

#include "swarm_transport/core/flocking.h"
#include "swarm_transport/core/geometry.h"
#include "swarm_transport/core/random.h"

namespace swarm_transport {
namespace core {

// How a robot on no mission behaves: flock (the thesis's flocking step, the default) or balloon
// (it spreads over the arena, out of the way).
enum class StandbyMode { kFlock, kBalloon };
// "flock" / "balloon"; false for anything else.
bool ParseStandbyMode(const std::string& name, StandbyMode* out);
const char* StandbyModeName(StandbyMode mode);

struct BalloonParams {
  // The balloon's radius grows by this much per tick while it is not enclosed (m, > 0).
  double growth_m_per_tick = 0.02;

  // Empty when valid, else one sentence naming the bad field.
  std::string Validate() const;
};

// Something a balloon can touch: it touches when its radius reaches `distance_m`, and the push
// it then gets points along `away` (a unit vector from the contact towards the robot).
struct BalloonContact {
  double distance_m = 0.0;
  Vec2 away;
};

// Every contact of a robot, nearest first: each other physical robot heard within local range
// at half the distance to it (its own balloon is estimated to meet this one halfway: a
// Voronoi-like rule), the four borders of the arena, and each danger zone that applies to it
// (the nearest point of its shape; inverted zones are not borders of a standby robot).
std::vector<BalloonContact> BalloonContacts(const Perception& in, const FlockingParams& p);
// The same with `borders` (an axis-aligned rectangle) in place of the arena's, and the danger
// zones only when `zones` (BalloonContacts(in, p) is this with the arena [0, world_size_m]^2
// and zones).
std::vector<BalloonContact> BalloonContacts(const Perception& in, const FlockingParams& p,
                                            const Rect& borders, bool zones);

// True when the contacts within `radius_m` enclose the robot: they leave no free side, i.e.
// every open half-plane of directions holds one of them (at least three are needed).
bool BalloonEnclosed(const std::vector<BalloonContact>& contacts, double radius_m);

// One tick of growth: an enclosed balloon keeps its radius, any other grows by
// growth_m_per_tick; never beyond half the local range (it cannot feel farther) nor below the
// robot's radius.
double GrowBalloon(double radius_m, const std::vector<BalloonContact>& contacts,
                   const FlockingParams& p, const BalloonParams& bp);

// The push off the contacts a balloon of `radius_m` overlaps: the sum of (radius - distance) x
// away over them (metres; zero when it overlaps nothing or the overlaps cancel).
Vec2 BalloonPush(const std::vector<BalloonContact>& contacts, double radius_m);

// A standby robot's tick in balloon mode. `radius_m` is its balloon, kept by the caller between
// ticks (start at robot_radius_m); it grows first, then the robot drives along the push by up
// to its speed (at most the push's length), swerving up to 90 degrees around robots in the way,
// else standing. A robot in a forbidden place flees as in FlockingStep. Draws exactly one
// free-will sample from `rng`, like FlockingStep, so that the random sequence does not depend on
// the mode.
MoveDecision BalloonStep(const Perception& in, const FlockingParams& p, const BalloonParams& bp,
                         Rng& rng, double duration_s, double* radius_m);

// (ext, SPEC 9.5) How a transport mission's robots spend LOADING: none (they stand, frozen, as
// in the thesis) or balloon (the first leader holds the freeze back for loading_spread_ticks
// while every mission robot spreads under the object by LoadingBalloonStep: even spacing before
// the transport).
enum class LoadingSpread { kNone, kBalloon };
// "none" / "balloon"; false for anything else.
bool ParseLoadingSpread(const std::string& name, LoadingSpread* out);
const char* LoadingSpreadName(LoadingSpread spread);

// A mission robot's tick of balloon spreading under its object while LOADING: BalloonStep with
// the object's rectangle `object` as its borders and only its mission peers (`peers`, ids
// ascending) as the others; no danger zones. A move must end inside `object` (else it stands):
// it never leaves the object. A standing robot with `face` set turns to `course` (a leader
// showing its way). Draws exactly one free-will sample from `rng`, like CarryStep.
MoveDecision LoadingBalloonStep(const Perception& in, const FlockingParams& p,
                                const BalloonParams& bp, const Rect& object,
                                const std::vector<std::uint16_t>& peers, bool face, Angle course,
                                Rng& rng, double duration_s, double* radius_m);

}  // namespace core
}  // namespace swarm_transport

#endif  // SWARM_TRANSPORT_CORE_BALLOON_H_
