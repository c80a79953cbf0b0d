// Typed, validated swarm configuration and its one loader (from the /swarm parameter
// namespace, or from a YAML file turned into the same XmlRpc dictionary).
#ifndef SWARM_TRANSPORT_ROS_PARAMS_H_
#define SWARM_TRANSPORT_ROS_PARAMS_H_

#include <ros/node_handle.h>
#include <xmlrpcpp/XmlRpcValue.h>

#include <cstdint>
#include <string>
#include <vector>

#include "swarm_transport/core/flocking.h"
#include "swarm_transport/core/leader.h"
#include "swarm_transport/core/modes.h"
#include "swarm_transport/core/transport.h"

namespace swarm_transport {

// Everything in the shared /swarm namespace (config/*.yaml): behaviour, clock, zones.
struct SwarmConfig {
  core::FlockingParams flocking;
  core::LeaderParams leader;
  core::TransportParams transport;
  double tick_period_s = 0.1;            // one tick (lock-step: simulated; real time: wall)
  std::uint64_t seed = 1;                // base seed of every robot's generator
  std::vector<core::Zone> danger_zones;  // static danger zones
  double loaded_delay_s = 2.0;           // dispatcher: LOADED this long after LOADING (<0: wait)
  double unloaded_delay_s = 2.0;         // dispatcher: UNLOADED this long after UNLOADING
  int object_update_ticks = 1;           // first leader publishes Update_Object every N ticks
  // The radio passes positions on hop by hop this many hops for a chain neighbourhood (1: only
  // robots in range are heard; mission peers are always heard over the mission channel).
  int chain_hops = 16;

  // Empty when valid, else one sentence naming the bad key.
  std::string Validate() const;
};

// Fills `config` from a dictionary holding the /swarm keys. Missing keys keep their defaults;
// a key of the wrong type or an invalid value is an error (`error` names it, config untouched).
bool ConfigFromXmlRpc(XmlRpc::XmlRpcValue& dict, SwarmConfig* config, std::string* error);

// Reads a whole YAML file into the XmlRpc dictionary ROS would make of it with rosparam load.
bool XmlRpcFromYamlFile(const std::string& path, XmlRpc::XmlRpcValue* out, std::string* error);

// Optional private parameters of a node: a missing key keeps `value`; a value of the wrong
// type (or a non-finite number) is an error naming the key, e.g. "~sample_period_s must be a
// number". Integers are accepted where a number is expected.
bool ReadPrivate(const ros::NodeHandle& nh, const std::string& key, double* value,
                 std::string* error);
bool ReadPrivate(const ros::NodeHandle& nh, const std::string& key, int* value, std::string* error);
bool ReadPrivate(const ros::NodeHandle& nh, const std::string& key, bool* value,
                 std::string* error);
bool ReadPrivate(const ros::NodeHandle& nh, const std::string& key, std::string* value,
                 std::string* error);

// ~clock (realtime | lockstep) and ~comm (local | broadcast): a missing key keeps `value`; any
// other name is an error naming the key and the accepted values.
bool ReadPrivate(const ros::NodeHandle& nh, const std::string& key, core::Clock* value,
                 std::string* error);
bool ReadPrivate(const ros::NodeHandle& nh, const std::string& key, core::Comm* value,
                 std::string* error);

// Parses one zone dictionary {shape: rect|circle, x, y, size_x, size_y | radius}.
bool ZoneFromXmlRpc(XmlRpc::XmlRpcValue& value, int id, core::Zone* zone, std::string* error);

}  // namespace swarm_transport

#endif  // SWARM_TRANSPORT_ROS_PARAMS_H_
