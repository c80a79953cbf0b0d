// The deployment modes a node is started in, as types instead of strings.
#ifndef SWARM_TRANSPORT_CORE_MODES_H_
#define SWARM_TRANSPORT_CORE_MODES_H_

#include <cstdint>
#include <string>

namespace swarm_transport {
namespace core {

// realtime: each robot ticks on its own wall timer; lockstep: one tick per radio round of the
// simulator, which waits for every answer.
enum class Clock : std::uint8_t { kRealtime, kLockstep };
// local: a robot flocks on the radio's in-range list (SPEC 7); broadcast: on every robot's
// /flock/position (the thesis's all-to-all wiring, for comparison benchmarks).
enum class Comm : std::uint8_t { kLocal, kBroadcast };
// Where the simulator puts its initial robots: seeded random non-overlapping poses, a grid in
// the bottom-left corner, or the lines of a placement file.
enum class Placement : std::uint8_t { kRandom, kCorner, kFile };
// Where the robots run (swarm.launch deploy:=...): a process each, all in one robot_host, all in
// one robot_host that also runs the simulator (direct links), or on other machines.
enum class Deploy : std::uint8_t { kProcess, kHost, kHostSim, kNone };

// False (and `out` untouched) for a name that is none of the modes.
bool ParseClock(const std::string& name, Clock* out);
bool ParseComm(const std::string& name, Comm* out);
bool ParsePlacement(const std::string& name, Placement* out);
bool ParseDeploy(const std::string& name, Deploy* out);
const char* ClockName(Clock clock);
const char* CommName(Comm comm);
const char* PlacementName(Placement placement);
const char* DeployName(Deploy deploy);

}  // namespace core
}  // namespace swarm_transport

#endif  // SWARM_TRANSPORT_CORE_MODES_H_
