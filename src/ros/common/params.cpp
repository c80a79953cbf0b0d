#include "swarm_transport/ros/common/params.h"

#include <yaml-cpp/yaml.h>

#include <cmath>
#include <sstream>

namespace swarm_transport {
namespace {

const char* TypeName(XmlRpc::XmlRpcValue::Type type) {
  switch (type) {
    case XmlRpc::XmlRpcValue::TypeInvalid:
      return "empty";
    case XmlRpc::XmlRpcValue::TypeBoolean:
      return "a bool";
    case XmlRpc::XmlRpcValue::TypeInt:
      return "an integer";
    case XmlRpc::XmlRpcValue::TypeDouble:
      return "a double";
    case XmlRpc::XmlRpcValue::TypeString:
      return "a string";
    case XmlRpc::XmlRpcValue::TypeDateTime:
      return "a date";
    case XmlRpc::XmlRpcValue::TypeBase64:
      return "binary data";
    case XmlRpc::XmlRpcValue::TypeArray:
      return "a list";
    case XmlRpc::XmlRpcValue::TypeStruct:
      return "a dictionary";
  }
  return "of an unknown type";
}

bool ReadDouble(XmlRpc::XmlRpcValue& dict, const char* key, double* out, std::string* error) {
  if (!dict.hasMember(key)) return true;
  std::string why;
  if (!XmlRpcNumber(dict[key], out, &why)) {
    *error = std::string("parameter '") + key + "' " + why;
    return false;
  }
  return true;
}

bool ReadInt(XmlRpc::XmlRpcValue& dict, const char* key, int* out, std::string* error) {
  if (!dict.hasMember(key)) return true;
  if (dict[key].getType() != XmlRpc::XmlRpcValue::TypeInt) {
    *error = std::string("parameter '") + key + "' must be an integer";
    return false;
  }
  *out = static_cast<int>(dict[key]);
  return true;
}

bool ReadBool(XmlRpc::XmlRpcValue& dict, const char* key, bool* out, std::string* error) {
  if (!dict.hasMember(key)) return true;
  if (dict[key].getType() != XmlRpc::XmlRpcValue::TypeBoolean) {
    *error = std::string("parameter '") + key + "' must be true or false";
    return false;
  }
  *out = static_cast<bool>(dict[key]);
  return true;
}

// A string key whose value `parse` accepts; `allowed` names the accepted values.
template <typename T, typename Parse>
bool ReadChoice(XmlRpc::XmlRpcValue& dict, const char* key, const char* allowed, T* out,
                std::string* error, Parse parse) {
  if (!dict.hasMember(key)) return true;
  if (dict[key].getType() != XmlRpc::XmlRpcValue::TypeString ||
      !parse(static_cast<std::string>(dict[key]), out)) {
    *error = std::string("parameter '") + key + "' must be " + allowed;
    return false;
  }
  return true;
}

XmlRpc::XmlRpcValue FromYaml(const YAML::Node& node) {
  XmlRpc::XmlRpcValue v;
  if (node.IsMap()) {
    v.begin();  // makes v a struct even when the map is empty
    for (const auto& kv : node) v[kv.first.as<std::string>()] = FromYaml(kv.second);
    if (node.size() == 0) v = XmlRpc::XmlRpcValue();
  } else if (node.IsSequence()) {
    v.setSize(static_cast<int>(node.size()));
    for (std::size_t i = 0; i < node.size(); ++i) v[static_cast<int>(i)] = FromYaml(node[i]);
  } else if (node.IsScalar()) {
    const std::string s = node.Scalar();
    int i = 0;
    double d = 0.0;
    bool b = false;
    if (node.Tag() != "!" && YAML::convert<int>::decode(node, i) &&
        s.find_first_of(".eE") == std::string::npos) {
      v = i;
    } else if (node.Tag() != "!" && YAML::convert<double>::decode(node, d)) {
      v = d;
    } else if (node.Tag() != "!" && YAML::convert<bool>::decode(node, b)) {
      v = b;
    } else {
      v = s;
    }
  }
  return v;
}

}  // namespace

bool XmlRpcNumber(const XmlRpc::XmlRpcValue& value, double* out, std::string* why) {
  double number = NAN;
  if (value.getType() == XmlRpc::XmlRpcValue::TypeDouble) {
    number = static_cast<const double&>(value);
  } else if (value.getType() == XmlRpc::XmlRpcValue::TypeInt) {
    number = static_cast<const int&>(value);
  } else {
    if (why != nullptr) *why = std::string("must be a number but is ") + TypeName(value.getType());
    return false;
  }
  if (!std::isfinite(number)) {
    if (why != nullptr) {
      *why = std::string("must be finite but is ") + (std::isnan(number) ? "nan"
                                                      : number > 0.0     ? "inf"
                                                                         : "-inf");
    }
    return false;
  }
  *out = number;
  return true;
}

bool ZoneFromXmlRpc(XmlRpc::XmlRpcValue& value, int id, core::Zone* zone, std::string* error) {
  if (value.getType() != XmlRpc::XmlRpcValue::TypeStruct || !value.hasMember("shape") ||
      value["shape"].getType() != XmlRpc::XmlRpcValue::TypeString) {
    *error = "a zone must be a dictionary with a 'shape' of rect or circle";
    return false;
  }
  const std::string shape = static_cast<std::string>(value["shape"]);
  double x = NAN, y = NAN;
  if (!value.hasMember("x") || !value.hasMember("y") || !XmlRpcNumber(value["x"], &x) ||
      !XmlRpcNumber(value["y"], &y)) {
    *error = "a zone needs finite numbers x and y (its centre, m)";
    return false;
  }
  core::Zone z;
  z.id = id;
  if (shape == "rect") {
    double sx = NAN, sy = NAN;
    if (!value.hasMember("size_x") || !value.hasMember("size_y") ||
        !XmlRpcNumber(value["size_x"], &sx) || !XmlRpcNumber(value["size_y"], &sy) || !(sx > 0.0) ||
        !(sy > 0.0)) {
      *error = "a rect zone needs size_x > 0 and size_y > 0 (m)";
      return false;
    }
    z.shape = core::Shape::FromRect({x, y}, {sx, sy});
  } else if (shape == "circle") {
    double r = NAN;
    if (!value.hasMember("radius") || !XmlRpcNumber(value["radius"], &r) || !(r > 0.0)) {
      *error = "a circle zone needs radius > 0 (m)";
      return false;
    }
    z.shape = core::Shape::FromCircle({x, y}, r);
  } else {
    *error = "zone shape must be rect or circle but is '" + shape + "'";
    return false;
  }
  *zone = z;
  return true;
}

bool ConfigFromXmlRpc(XmlRpc::XmlRpcValue& dict, SwarmConfig* config, std::string* error) {
  if (dict.getType() != XmlRpc::XmlRpcValue::TypeStruct) {
    *error = "the swarm configuration must be a dictionary";
    return false;
  }
  SwarmConfig c = *config;
  core::FlockingParams& f = c.flocking;
  int seed = static_cast<int>(c.seed);
  bool ok =
      ReadDouble(dict, "local_range_m", &f.local_range_m, error) &&
      ReadDouble(dict, "speed_m_per_tick", &f.speed_m_per_tick, error) &&
      ReadDouble(dict, "free_will_deg", &f.free_will_deg, error) &&
      ReadDouble(dict, "cohesion", &f.cohesion, error) &&
      ReadDouble(dict, "robot_radius_m", &f.robot_radius_m, error) &&
      ReadDouble(dict, "collision_margin", &f.collision_margin, error) &&
      ReadDouble(dict, "world_size_m", &f.world_size_m, error) &&
      ReadDouble(dict, "speed_reduction", &f.speed_reduction, error) &&
      ReadInt(dict, "speed_retries", &f.speed_retries, error) &&
      ReadBool(dict, "check_path", &f.check_path, error) &&
      ReadDouble(dict, "zone_margin_m", &f.zone_margin_m, error) &&
      ReadDouble(dict, "goal_tolerance_m", &c.leader.goal_tolerance_m, error) &&
      ReadDouble(dict, "leader_wait_fraction", &c.leader.wait_fraction, error) &&
      ReadBool(dict, "leader_keep_flock", &c.leader.keep_flock, error) &&
      ReadBool(dict, "leader_wait_behind", &c.leader.wait_behind, error) &&
      ReadBool(dict, "leader_wait_evaluated_angles", &c.leader.wait_evaluated_angles, error) &&
      ReadBool(dict, "leader_give_up_beyond_range", &c.leader.give_up_beyond_range, error) &&
      ReadBool(dict, "leader_centroid_with_self", &c.leader.centroid_with_self, error) &&
      ReadBool(dict, "leader_check_collisions", &c.leader.check_collisions, error) &&
      ReadInt(dict, "leader_swerve_after_blocked_ticks", &c.leader.swerve_after_blocked_ticks,
              error) &&
      ReadInt(dict, "leader_virtual_copies", &c.leader.virtual_copies, error) &&
      ReadDouble(dict, "tick_period_s", &c.tick_period_s, error) &&
      ReadInt(dict, "seed", &seed, error) &&
      ReadDouble(dict, "loaded_delay_s", &c.loaded_delay_s, error) &&
      ReadDouble(dict, "unloaded_delay_s", &c.unloaded_delay_s, error) &&
      ReadInt(dict, "object_update_ticks", &c.object_update_ticks, error) &&
      ReadChoice(dict, "neighbourhood", "chain or disc", &f.neighbourhood, error,
                 core::ParseNeighbourhood) &&
      ReadInt(dict, "chain_hops", &c.chain_hops, error) &&
      ReadDouble(dict, "lost_after_s", &c.lost_after_s, error) &&
      ReadChoice(dict, "mission_admission", "dispatcher or robots", &c.admission, error,
                 core::ParseAdmission) &&
      ReadInt(dict, "max_live_missions", &c.max_live_missions, error) &&
      ReadInt(dict, "mission_min_robots", &c.mission_min_robots, error) &&
      ReadChoice(dict, "gathering", "hold or fill", &c.transport.gathering, error,
                 core::ParseGatherMode) &&
      ReadChoice(dict, "gather_planner",
                 "nearest, selection_matrix, optimal, bottleneck or row_minimum",
                 &c.transport.gather_planner, error, core::ParseGatherPlanner) &&
      ReadInt(dict, "replan_period", &c.transport.replan_period_ticks, error) &&
      ReadDouble(dict, "planner_turn_deg_per_tick", &c.transport.planner_turn_deg_per_tick,
                 error) &&
      ReadBool(dict, "leaders_bound", &c.transport.leaders_bound, error) &&
      ReadDouble(dict, "approach_radius_m", &c.transport.approach_radius_m, error) &&
      ReadDouble(dict, "leader_reach_m", &c.transport.leader_reach_m, error) &&
      ReadBool(dict, "object_at_centroid", &c.transport.object_at_centroid, error) &&
      ReadInt(dict, "transport_leader_weight", &c.transport.transport_leader_weight, error) &&
      ReadBool(dict, "leaders_face_course", &c.transport.leaders_face_course, error) &&
      ReadBool(dict, "gather_one_chain", &c.transport.gather_one_chain, error) &&
      ReadDouble(dict, "formation_speed_fraction", &c.transport.formation_speed_fraction, error) &&
      ReadChoice(dict, "standby", "flock or balloon", &c.standby, error, core::ParseStandbyMode) &&
      ReadDouble(dict, "balloon_growth_m_per_tick", &c.balloon.growth_m_per_tick, error) &&
      ReadChoice(dict, "loading_spread", "none or balloon", &c.loading_spread, error,
                 core::ParseLoadingSpread) &&
      ReadInt(dict, "loading_spread_ticks", &c.loading_spread_ticks, error);
  if (!ok) return false;
  if (seed < 0) {
    *error = "parameter 'seed' must be >= 0";
    return false;
  }
  c.seed = static_cast<std::uint64_t>(seed);
  if (dict.hasMember("danger_zones")) {
    XmlRpc::XmlRpcValue& zones = dict["danger_zones"];
    c.danger_zones.clear();
    if (zones.getType() != XmlRpc::XmlRpcValue::TypeArray) {
      *error = "parameter 'danger_zones' must be a list";
      return false;
    }
    for (int i = 0; i < zones.size(); ++i) {
      core::Zone z;
      if (!ZoneFromXmlRpc(zones[i], -(i + 1), &z, error)) {
        *error = "danger_zones[" + std::to_string(i) + "]: " + *error;
        return false;
      }
      c.danger_zones.push_back(z);
    }
  }
  const std::string invalid = c.Validate();
  if (!invalid.empty()) {
    *error = invalid;
    return false;
  }
  *config = c;
  return true;
}

bool XmlRpcFromYamlText(const std::string& text, XmlRpc::XmlRpcValue* out, std::string* error) {
  try {
    *out = FromYaml(YAML::Load(text));
  } catch (const YAML::Exception& e) {
    *error = e.what();
    return false;
  }
  return true;
}

bool XmlRpcFromYamlFile(const std::string& path, XmlRpc::XmlRpcValue* out, std::string* error) {
  try {
    *out = FromYaml(YAML::LoadFile(path));
  } catch (const YAML::Exception& e) {
    *error = path + ": " + e.what();
    return false;
  }
  return true;
}

namespace {

// Reads `key` when present; `convert` takes the XmlRpc value and says whether it fits.
template <typename T, typename Convert>
bool ReadPrivateAs(const ros::NodeHandle& nh, const std::string& key, const char* what, T* value,
                   std::string* error, Convert convert) {
  XmlRpc::XmlRpcValue v;
  if (!nh.getParam(key, v)) return true;
  T converted;
  if (!convert(v, &converted)) {
    *error = "~" + key + " must be " + what;
    return false;
  }
  *value = converted;
  return true;
}

}  // namespace

bool ReadPrivate(const ros::NodeHandle& nh, const std::string& key, double* value,
                 std::string* error) {
  return ReadPrivateAs(nh, key, "a finite number", value, error,
                       [](XmlRpc::XmlRpcValue& v, double* out) { return XmlRpcNumber(v, out); });
}

bool ReadPrivate(const ros::NodeHandle& nh, const std::string& key, int* value,
                 std::string* error) {
  return ReadPrivateAs(nh, key, "an integer", value, error, [](XmlRpc::XmlRpcValue& v, int* out) {
    if (v.getType() != XmlRpc::XmlRpcValue::TypeInt) return false;
    *out = static_cast<int>(v);
    return true;
  });
}

bool ReadPrivate(const ros::NodeHandle& nh, const std::string& key, bool* value,
                 std::string* error) {
  return ReadPrivateAs(nh, key, "true or false", value, error,
                       [](XmlRpc::XmlRpcValue& v, bool* out) {
                         if (v.getType() != XmlRpc::XmlRpcValue::TypeBoolean) return false;
                         *out = static_cast<bool>(v);
                         return true;
                       });
}

bool ReadPrivate(const ros::NodeHandle& nh, const std::string& key, std::string* value,
                 std::string* error) {
  return ReadPrivateAs(nh, key, "a string", value, error,
                       [](XmlRpc::XmlRpcValue& v, std::string* out) {
                         if (v.getType() != XmlRpc::XmlRpcValue::TypeString) return false;
                         *out = static_cast<std::string>(v);
                         return true;
                       });
}

namespace {

// A private string parameter that must name one of a few modes.
template <typename Mode, typename Parse>
bool ReadPrivateMode(const ros::NodeHandle& nh, const std::string& key, const char* allowed,
                     Mode* value, std::string* error, Parse parse) {
  std::string name;
  if (!nh.hasParam(key)) return true;
  if (!ReadPrivate(nh, key, &name, error)) return false;
  if (!parse(name, value)) {
    *error = "~" + key + " must be " + allowed + " but is '" + name + "'";
    return false;
  }
  return true;
}

}  // namespace

bool ReadPrivate(const ros::NodeHandle& nh, const std::string& key, core::Clock* value,
                 std::string* error) {
  return ReadPrivateMode(nh, key, "'realtime' or 'lockstep'", value, error, core::ParseClock);
}

bool ReadPrivate(const ros::NodeHandle& nh, const std::string& key, core::Comm* value,
                 std::string* error) {
  return ReadPrivateMode(nh, key, "'local' or 'broadcast'", value, error, core::ParseComm);
}

bool ReadPrivate(const ros::NodeHandle& nh, const std::string& key, core::Placement* value,
                 std::string* error) {
  return ReadPrivateMode(nh, key, "'random', 'corner' or 'file'", value, error,
                         core::ParsePlacement);
}

bool ReadPrivate(const ros::NodeHandle& nh, const std::string& key, core::Deploy* value,
                 std::string* error) {
  return ReadPrivateMode(nh, key, "'process', 'host', 'host_sim' or 'none'", value, error,
                         core::ParseDeploy);
}

}  // namespace swarm_transport
