// Typed, validated swarm configuration and its one loader (from the /swarm parameter
// namespace, or from a YAML file turned into the same XmlRpc dictionary).
#ifndef SWARM_TRANSPORT_ROS_PARAMS_H_
#define SWARM_TRANSPORT_ROS_PARAMS_H_

#include <ros/node_handle.h>
#include <xmlrpcpp/XmlRpcValue.h>

#include <cstdint>
#include <string>
#include <vector>

#include "swarm_transport/core/modes.h"
#include "swarm_transport/core/swarm_config.h"

namespace swarm_transport {

// The shared configuration is the core's (core/swarm_config.h); this file loads it.
using core::SwarmConfig;

// The one reader of a number in an XmlRpc value (a parameter or a YAML file turned into XmlRpc):
// an int or a double (`x: 7` comes as an int and means 7.0) that is finite. Anything else - a
// string, a bool, a list, NaN or an infinity (`.nan`, `.inf` in YAML) - is refused: false,
// `out` untouched and, when `why` is given, the reason, e.g. "must be a number but is a
// string" or "must be finite but is nan" (the caller puts the key's name in front).
bool XmlRpcNumber(const XmlRpc::XmlRpcValue& value, double* out, std::string* why = nullptr);

// Fills `config` from a dictionary holding the /swarm keys. Missing keys keep their defaults;
// a key of the wrong type or an invalid value is an error (`error` names it, config untouched).
bool ConfigFromXmlRpc(XmlRpc::XmlRpcValue& dict, SwarmConfig* config, std::string* error);

// Reads a whole YAML file into the XmlRpc dictionary ROS would make of it with rosparam load.
bool XmlRpcFromYamlFile(const std::string& path, XmlRpc::XmlRpcValue* out, std::string* error);
// The same from YAML text (tests, fuzzing).
bool XmlRpcFromYamlText(const std::string& text, XmlRpc::XmlRpcValue* out, std::string* error);

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
// ~placement (random | corner | file) and ~deploy (process | host | host_sim | none), the same
// way.
bool ReadPrivate(const ros::NodeHandle& nh, const std::string& key, core::Placement* value,
                 std::string* error);
bool ReadPrivate(const ros::NodeHandle& nh, const std::string& key, core::Deploy* value,
                 std::string* error);

// Parses one zone dictionary {shape: rect|circle, x, y, size_x, size_y | radius}.
bool ZoneFromXmlRpc(XmlRpc::XmlRpcValue& value, int id, core::Zone* zone, std::string* error);

}  // namespace swarm_transport

#endif  // SWARM_TRANSPORT_ROS_PARAMS_H_
