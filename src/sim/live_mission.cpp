#include "swarm_transport/sim/live_mission.h"

namespace swarm_transport {
namespace sim {

std::string RegisterMission(const core::MissionSpec& spec, const World2D& world,
                            LiveMissions* missions) {
  core::MissionContext context;
  context.world_size_m = world.params().world_size_m;
  for (const auto& entry : world.robots()) context.known_robots.insert(entry.first);
  for (const auto& entry : *missions) context.live_missions.insert(entry.first);
  const std::string why = core::ValidateMission(spec, context);
  if (!why.empty()) return why;
  LiveMission mission;
  mission.members = spec.Assigned();
  mission.leaders = spec.Leaders();
  mission.object_position = spec.object_centre;
  mission.object_size = spec.object_size;
  mission.target = spec.target;
  (*missions)[spec.id] = mission;
  return "";
}

bool UpdateMissionObject(std::uint16_t mission_id, core::Vec2 centre, const World2D& world,
                         LiveMissions* missions) {
  const auto it = missions->find(mission_id);
  const double size = world.params().world_size_m;
  // Negated comparisons: NaN is outside.
  if (it == missions->end() || !(centre.x >= 0.0 && centre.x <= size) ||
      !(centre.y >= 0.0 && centre.y <= size)) {
    return false;
  }
  it->second.object_position = centre;
  return true;
}

}  // namespace sim
}  // namespace swarm_transport
