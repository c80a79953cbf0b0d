#include <yaml-cpp/yaml.h>

#include <string>

#include "swarm_transport/ros/engine/batch_run.h"

namespace swarm_transport {
namespace {

template <typename T>
bool Get(const YAML::Node& root, const char* key, T* value, std::string* error,
         bool required = true) {
  const YAML::Node node = root[key];
  if (!node || node.IsNull()) {
    if (required) *error = std::string("job: '") + key + "' is missing";
    return !required;
  }
  try {
    *value = node.as<T>();
  } catch (const YAML::Exception&) {
    *error = std::string("job: '") + key + "' has the wrong type";
    return false;
  }
  return true;
}

}  // namespace

bool ReadBatchJob(const std::string& path, BatchJob* job, std::string* error) {
  YAML::Node root;
  try {
    root = YAML::LoadFile(path);
  } catch (const YAML::Exception& e) {
    *error = path + ": " + e.what();
    return false;
  }
  if (!root.IsMap()) {
    *error = path + ": not a JSON object";
    return false;
  }
  std::string placement = "random";
  long long max_ticks = 0;
  long long seed = 1;
  if (!Get(root, "kind", &job->kind, error) || !Get(root, "setting", &job->setting, error) ||
      !Get(root, "run", &job->run, error) || !Get(root, "seed", &seed, error) ||
      !Get(root, "robots", &job->robots, error) || !Get(root, "max_ticks", &max_ticks, error) ||
      !Get(root, "config_path", &job->config_path, error) ||
      !Get(root, "run_dir", &job->run_dir, error) ||
      !Get(root, "record_dir", &job->record_dir, error) ||
      !Get(root, "run_name", &job->run_name, error) || !Get(root, "placement", &placement, error) ||
      !Get(root, "placement_file", &job->placement_file, error, false) ||
      !Get(root, "trace", &job->trace, error, false) ||
      !Get(root, "leader_id", &job->leader_id, error, false)) {
    *error = path + ": " + *error;
    return false;
  }
  job->seed = seed;
  if (max_ticks <= 0) {
    *error = path + ": 'max_ticks' must be > 0 (a batch run must end)";
    return false;
  }
  job->max_ticks = static_cast<std::uint64_t>(max_ticks);
  if (!core::ParsePlacement(placement, &job->placement)) {
    *error = path + ": 'placement' must be random, corner or file but is '" + placement + "'";
    return false;
  }
  if (job->kind != "flocking" && job->kind != "transport" && job->kind != "leader") {
    *error = path + ": 'kind' must be flocking, transport or leader but is '" + job->kind + "'";
    return false;
  }
  const YAML::Node m = root["mission"];
  job->has_mission = job->kind != "flocking";
  if (!job->has_mission) return true;
  if (!m || !m.IsMap()) {
    *error = path + ": a " + job->kind + " run needs its 'mission'";
    return false;
  }
  try {
    New_Mission& msg = job->mission;
    msg.mission_id = static_cast<std::uint16_t>(m["id"].as<int>());
    msg.target_x = static_cast<float>(m["target"][0].as<double>());
    msg.target_y = static_cast<float>(m["target"][1].as<double>());
    msg.transport_mode = static_cast<std::uint8_t>(m["mode"] ? m["mode"].as<int>() : 0);
    if (job->kind == "leader") {
      if (job->leader_id < 0) {
        *error = path + ": a leader run needs its 'leader_id'";
        return false;
      }
      msg.robot_index_from = static_cast<std::uint16_t>(job->leader_id);
      msg.robot_index_to = static_cast<std::uint16_t>(job->leader_id + 1);
      msg.leader_number = 1;
    } else {
      // (ext) count: the dispatcher picks that many robots (robot_count, no range); else the
      // robots [0, group).
      msg.robot_count = static_cast<std::uint16_t>(m["count"] ? m["count"].as<int>() : 0);
      msg.robot_index_from = 0;
      msg.robot_index_to =
          msg.robot_count > 0
              ? 0
              : static_cast<std::uint16_t>(m["group"] ? m["group"].as<int>() : job->robots);
      msg.leader_number = static_cast<std::uint16_t>(m["leaders"].as<int>());
      msg.object_position_x = static_cast<float>(m["object"][0].as<double>());
      msg.object_position_y = static_cast<float>(m["object"][1].as<double>());
      msg.object_size_x = static_cast<float>(m["object"][2].as<double>());
      msg.object_size_y = static_cast<float>(m["object"][3].as<double>());
    }
  } catch (const YAML::Exception& e) {
    *error = path + ": 'mission' is malformed: " + e.what();
    return false;
  }
  return true;
}

void MergeParams(const XmlRpc::XmlRpcValue& over, XmlRpc::XmlRpcValue* base) {
  XmlRpc::XmlRpcValue& b = *base;
  if (over.getType() != XmlRpc::XmlRpcValue::TypeStruct ||
      b.getType() != XmlRpc::XmlRpcValue::TypeStruct) {
    b = over;
    return;
  }
  XmlRpc::XmlRpcValue& o = const_cast<XmlRpc::XmlRpcValue&>(over);  // no const iteration
  for (auto it = o.begin(); it != o.end(); ++it) {
    if (it->second.getType() == XmlRpc::XmlRpcValue::TypeStruct && b.hasMember(it->first) &&
        b[it->first].getType() == XmlRpc::XmlRpcValue::TypeStruct) {
      MergeParams(it->second, &b[it->first]);
    } else {
      b[it->first] = it->second;
    }
  }
}

}  // namespace swarm_transport
