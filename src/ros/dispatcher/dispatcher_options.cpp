#include "swarm_transport/ros/dispatcher/dispatcher_options.h"

#include <cmath>
#include <limits>
#include <set>
#include <sstream>

#include "swarm_transport/core/recruit.h"

namespace swarm_transport {
namespace {

using XmlRpc::XmlRpcValue;

// An integer in [lo, hi] or false.
bool AsInt(XmlRpcValue& v, int lo, int hi, int* out) {
  if (v.getType() != XmlRpcValue::TypeInt) return false;
  *out = static_cast<int>(v);
  return lo <= *out && *out <= hi;
}

// A list of exactly `n` finite numbers.
bool AsNumbers(XmlRpcValue& v, int n, std::vector<double>* out) {
  if (v.getType() != XmlRpcValue::TypeArray || v.size() != n) return false;
  out->assign(static_cast<std::size_t>(n), 0.0);
  for (int i = 0; i < n; ++i) {
    if (!XmlRpcNumber(v[i], &(*out)[static_cast<std::size_t>(i)])) return false;
  }
  return true;
}

// Reads one missions-file entry; `error` says which key is wrong.
bool MissionFromXmlRpc(XmlRpcValue& e, core::MissionSpec* spec, std::uint64_t* at_tick,
                       std::string* error) {
  static const std::set<std::string> kKeys = {"id",      "robots_from", "robots_to", "robot_ids",
                                              "leaders", "object",      "target",    "mode",
                                              "at_tick", "recruit"};
  if (e.getType() != XmlRpcValue::TypeStruct) {
    *error = "must be a dictionary";
    return false;
  }
  for (auto& kv : e) {
    if (kKeys.count(kv.first) == 0) {
      *error = "unknown key '" + kv.first +
               "' (known: id, robots_from, robots_to, robot_ids, leaders, object, target, mode, "
               "at_tick, recruit)";
      return false;
    }
  }
  core::MissionSpec m;
  int value = 0;
  if (e.hasMember("id")) {
    if (!AsInt(e["id"], 0, 65535, &value)) {
      *error = "'id' must be an integer in [0, 65535] (0 = next free id)";
      return false;
    }
    m.id = static_cast<std::uint16_t>(value);
  }
  const bool has_range = e.hasMember("robots_from") || e.hasMember("robots_to");
  const bool recruit = e.hasMember("recruit");
  if (recruit) {
    // Statist as dispatcher (SPEC 9.4): no robots named, the first N to enter the object.
    if (!AsInt(e["recruit"], 1, 65535, &value)) {
      *error = "'recruit' must be an integer in [1, 65535] (how many robots the statist gathers)";
      return false;
    }
    if (has_range || e.hasMember("robot_ids")) {
      *error = "'recruit' names no robots: give it without robots_from, robots_to or robot_ids";
      return false;
    }
    m.recruit = true;
    m.robot_count = static_cast<std::uint16_t>(value);
  } else if (has_range == e.hasMember("robot_ids")) {
    *error =
        "give either robots_from and robots_to (half-open range), robot_ids (a list) or recruit "
        "(a count)";
    return false;
  }
  if (has_range) {
    int from = 0, to = 0;
    if (!e.hasMember("robots_from") || !e.hasMember("robots_to") ||
        !AsInt(e["robots_from"], 0, 65535, &from) || !AsInt(e["robots_to"], 0, 65535, &to)) {
      *error = "'robots_from' and 'robots_to' must both be integers in [0, 65535]";
      return false;
    }
    m.range_from = static_cast<std::uint16_t>(from);
    m.range_to = static_cast<std::uint16_t>(to);
  } else if (!recruit) {
    XmlRpcValue& ids = e["robot_ids"];
    if (ids.getType() != XmlRpcValue::TypeArray || ids.size() == 0) {
      *error = "'robot_ids' must be a non-empty list of robot ids";
      return false;
    }
    for (int i = 0; i < ids.size(); ++i) {
      if (!AsInt(ids[i], 0, 65535, &value)) {
        *error = "'robot_ids' must hold integers in [0, 65535]";
        return false;
      }
      m.robot_ids.push_back(static_cast<std::uint16_t>(value));
    }
  }
  if (!e.hasMember("leaders") || !AsInt(e["leaders"], 1, 255, &m.leader_number)) {
    *error = "'leaders' must be an integer in [1, 255]";
    return false;
  }
  std::vector<double> v;
  if (!e.hasMember("target") || !AsNumbers(e["target"], 2, &v)) {
    *error = "'target' must be [x, y], finite numbers (m)";
    return false;
  }
  m.target = {v[0], v[1]};
  if (e.hasMember("object")) {
    if (!AsNumbers(e["object"], 4, &v)) {
      *error =
          "'object' must be [x, y, size_x, size_y], finite numbers (m), or left out for a "
          "leader-only mission";
      return false;
    }
    m.object_centre = {v[0], v[1]};
    m.object_size = {v[2], v[3]};
  } else {
    m.object_centre = m.target;  // leader-only: the position is ignored, keep it meaningful
  }
  if (e.hasMember("mode")) {
    XmlRpcValue& mode = e["mode"];
    if (mode.getType() == XmlRpcValue::TypeString) {
      const std::string name = static_cast<std::string>(mode);
      value = name == "swarm" ? 0 : name == "formation" ? 1 : -1;
    } else if (!AsInt(mode, 0, 1, &value)) {
      value = -1;
    }
    if (value < 0) {
      *error = "'mode' must be 0 (swarm) or 1 (formation)";
      return false;
    }
    m.transport_mode = static_cast<std::uint8_t>(value);
  }
  *at_tick = 0;
  if (e.hasMember("at_tick")) {
    if (!AsInt(e["at_tick"], 0, std::numeric_limits<int>::max(), &value)) {
      *error = "'at_tick' must be an integer >= 0 (0: ~start_delay_s)";
      return false;
    }
    *at_tick = static_cast<std::uint64_t>(value);
  }
  *spec = m;
  return true;
}

}  // namespace

std::string DispatcherOptions::Validate() const {
  std::ostringstream os;
  if (!std::isfinite(loaded_delay_s) || !std::isfinite(unloaded_delay_s)) {
    os << "loaded_delay_s and unloaded_delay_s must be finite (s; negative = never send)";
  } else if (!(start_delay_s >= 0.0) || !std::isfinite(start_delay_s)) {
    os << "~start_delay_s must be a finite number >= 0 (s) but is " << start_delay_s;
  } else if (max_live_missions < 1 || max_live_missions > 65535) {
    os << "~max_live_missions must be in [1, 65535] but is " << max_live_missions;
  } else if (silent_abort_ticks < 0) {
    os << "~silent_abort_ticks must be >= 0 (ticks; 0: never) but is " << silent_abort_ticks;
  }
  return os.str();
}

bool MissionsFromXmlRpc(XmlRpcValue& file, std::vector<core::MissionSpec>* missions,
                        std::string* error, std::vector<std::uint64_t>* at_ticks) {
  if (file.getType() != XmlRpcValue::TypeStruct || !file.hasMember("missions") ||
      file["missions"].getType() != XmlRpcValue::TypeArray) {
    *error = "the file must hold a list under the key 'missions'";
    return false;
  }
  XmlRpcValue& list = file["missions"];
  std::vector<core::MissionSpec> out;
  std::vector<std::uint64_t> ticks;
  for (int i = 0; i < list.size(); ++i) {
    core::MissionSpec spec;
    std::uint64_t at_tick = 0;
    std::string why;
    if (!MissionFromXmlRpc(list[i], &spec, &at_tick, &why)) {
      *error = "missions[" + std::to_string(i) + "]: " + why;
      return false;
    }
    out.push_back(spec);
    ticks.push_back(at_tick);
  }
  *missions = out;
  if (at_ticks != nullptr) *at_ticks = ticks;
  return true;
}

bool ReadMissionsFile(const std::string& path, double world_size_m,
                      std::vector<core::MissionSpec>* missions, std::string* error,
                      std::vector<std::uint64_t>* at_ticks) {
  XmlRpcValue file;
  if (!XmlRpcFromYamlFile(path, &file, error)) {
    *error = "~missions_file: " + *error;  // the reader names the path
    return false;
  }
  std::vector<core::MissionSpec> read;
  std::vector<std::uint64_t> ticks;
  if (!MissionsFromXmlRpc(file, &read, error, &ticks)) {
    *error = "~missions_file " + path + ": " + *error;
    return false;
  }
  core::MissionContext context;
  context.world_size_m = world_size_m;
  for (std::size_t i = 0; i < read.size(); ++i) {
    const core::MissionSpec& m = read[i];
    std::string reason;
    if (m.recruit) {
      // The robots are not known yet: the count is checked against the idle ones at its start.
      std::set<std::uint16_t> any;
      for (std::uint16_t id = 0; id < m.robot_count; ++id) any.insert(id);
      reason = core::ValidateRecruit(m, any, context);
    } else {
      reason = core::ValidateMission(m, context);
    }
    if (context.live_missions.count(m.id) > 0) {
      reason = "id " + std::to_string(m.id) + " appears twice in the file";
    }
    if (!reason.empty()) {
      *error = "~missions_file " + path + ": missions[" + std::to_string(i) + "]: " + reason;
      return false;
    }
    if (m.id != 0) context.live_missions.insert(m.id);
  }
  *missions = read;
  if (at_ticks != nullptr) *at_ticks = ticks;
  return true;
}

bool ReadDispatcherOptions(const ros::NodeHandle& nh, const ros::NodeHandle& p, SwarmConfig* config,
                           DispatcherOptions* options,
                           std::vector<core::MissionSpec>* file_missions, std::string* error,
                           std::vector<std::uint64_t>* file_ticks) {
  XmlRpcValue swarm;
  if (nh.getParam("/swarm", swarm) && !ConfigFromXmlRpc(swarm, config, error)) {
    *error = "/swarm: " + *error;
    return false;
  }
  *options = DispatcherOptionsOf(*config);
  if (!ReadPrivate(p, "loaded_delay_s", &options->loaded_delay_s, error) ||
      !ReadPrivate(p, "unloaded_delay_s", &options->unloaded_delay_s, error) ||
      !ReadPrivate(p, "missions_file", &options->missions_file, error) ||
      !ReadPrivate(p, "events_file", &options->events_file, error) ||
      !ReadPrivate(p, "start_delay_s", &options->start_delay_s, error) ||
      !ReadPrivate(p, "max_live_missions", &options->max_live_missions, error) ||
      !ReadPrivate(p, "silent_abort_ticks", &options->silent_abort_ticks, error)) {
    return false;
  }
  *error = options->Validate();
  if (!error->empty()) return false;
  options->events.clear();
  if (!options->events_file.empty() &&
      !ReadEventsFile(options->events_file, &options->events, error)) {
    *error = "~events_file " + options->events_file + ": " + *error;
    return false;
  }
  file_missions->clear();
  if (options->missions_file.empty()) return true;
  return ReadMissionsFile(options->missions_file, config->flocking.world_size_m, file_missions,
                          error, file_ticks);
}

DispatcherOptions DispatcherOptionsOf(const SwarmConfig& config) {
  DispatcherOptions options;
  options.loaded_delay_s = config.loaded_delay_s;
  options.unloaded_delay_s = config.unloaded_delay_s;
  options.max_live_missions = config.max_live_missions;
  return options;
}

core::MissionBookParams MissionBookParamsOf(const SwarmConfig& config,
                                            const DispatcherOptions& options) {
  core::MissionBookParams book;
  book.world_size_m = config.flocking.world_size_m;
  book.static_zones = config.danger_zones;
  book.tick_period_s = config.tick_period_s;
  book.loaded_delay_s = options.loaded_delay_s;
  book.unloaded_delay_s = options.unloaded_delay_s;
  book.max_live_missions = options.max_live_missions;
  book.silent_after_s =
      options.silent_abort_ticks > 0 ? options.silent_abort_ticks * config.tick_period_s : -1.0;
  return book;
}

core::DispatcherPolicyParams DispatcherPolicyParamsOf(const SwarmConfig& config,
                                                      const DispatcherOptions& options,
                                                      bool lockstep) {
  core::DispatcherPolicyParams params;
  params.book = MissionBookParamsOf(config, options);
  params.selection.speed_m = config.flocking.speed_m_per_tick;
  params.selection.turn_deg = config.transport.planner_turn_deg_per_tick;
  params.selection.corridor_m = config.flocking.MinSeparation();
  params.lockstep = lockstep;
  params.start_delay_s = options.start_delay_s;
  const std::vector<TimedEvent> events = options.events;
  params.robots_at = [events](const std::set<std::uint16_t>& now, std::uint64_t tick) {
    return RobotsAt(now, events, tick);
  };
  return params;
}

std::string DelayText(double s) {
  if (s < 0.0) return "on a signal only";
  std::ostringstream os;
  os << "after " << s << " s";
  return os.str();
}

std::string StatusProblem(const Mission_Status& status) {
  if (status.state >= core::kPhaseCount) return "unknown state " + std::to_string(status.state);
  if (!std::isfinite(status.object_position_x) || !std::isfinite(status.object_position_y) ||
      !std::isfinite(status.distance_to_target)) {
    return "a field is not finite";
  }
  return "";
}

std::map<std::uint16_t, core::PlannerRobot> SwarmOf(const std::vector<Robot_Position>& robots) {
  std::map<std::uint16_t, core::PlannerRobot> swarm;
  for (const Robot_Position& r : robots) {
    if (r.type == Robot_Position::TYPE_PHYSICAL) {
      swarm[r.robot_id] = {{r.pos_x, r.pos_y}, core::Angle(r.angle)};
    }
  }
  return swarm;
}

}  // namespace swarm_transport
