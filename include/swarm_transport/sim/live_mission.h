// What the simulator knows of a live mission: who is in it and where its object is. The radio
// gives its members their mission channel; the visuals draw its object, target and leaders.
#ifndef SWARM_TRANSPORT_SIM_LIVE_MISSION_H_
#define SWARM_TRANSPORT_SIM_LIVE_MISSION_H_

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "swarm_transport/core/geometry.h"
#include "swarm_transport/core/mission.h"
#include "swarm_transport/sim/world2d.h"

namespace swarm_transport {
namespace sim {

struct LiveMission {
  std::vector<std::uint16_t> members;  // ascending
  std::vector<std::uint16_t> leaders;  // highlighted in rviz
  core::Vec2 object_position;
  core::Vec2 object_size;  // 0 x 0: a leader-only mission
  core::Vec2 target;
  int phase = -1;  // the last phase its robots reported (status value); -1: none yet
};

// By mission id.
using LiveMissions = std::map<std::uint16_t, LiveMission>;

// Enters an order the robots act on: validated as the robots and the dispatcher validate it
// (against `world`'s robots and the live missions), so the mission channel and the markers
// exist exactly for the missions the robots take. Empty when entered, else why not.
std::string RegisterMission(const core::MissionSpec& spec, const World2D& world,
                            LiveMissions* missions);

// A first leader's object update: moves a live mission's object when `centre` is finite and
// inside `world`'s arena. False when it changed nothing (unknown mission, bad position).
bool UpdateMissionObject(std::uint16_t mission_id, core::Vec2 centre, const World2D& world,
                         LiveMissions* missions);

}  // namespace sim
}  // namespace swarm_transport

#endif  // SWARM_TRANSPORT_SIM_LIVE_MISSION_H_
