#include "swarm_transport/core/modes.h"

namespace swarm_transport {
namespace core {

bool ParseClock(const std::string& name, Clock* out) {
  if (name == "realtime") {
    *out = Clock::kRealtime;
  } else if (name == "lockstep") {
    *out = Clock::kLockstep;
  } else {
    return false;
  }
  return true;
}

bool ParseComm(const std::string& name, Comm* out) {
  if (name == "local") {
    *out = Comm::kLocal;
  } else if (name == "broadcast") {
    *out = Comm::kBroadcast;
  } else {
    return false;
  }
  return true;
}

bool ParsePlacement(const std::string& name, Placement* out) {
  if (name == "random") {
    *out = Placement::kRandom;
  } else if (name == "corner") {
    *out = Placement::kCorner;
  } else if (name == "file") {
    *out = Placement::kFile;
  } else {
    return false;
  }
  return true;
}

bool ParseDeploy(const std::string& name, Deploy* out) {
  if (name == "process") {
    *out = Deploy::kProcess;
  } else if (name == "host") {
    *out = Deploy::kHost;
  } else if (name == "host_sim") {
    *out = Deploy::kHostSim;
  } else if (name == "none") {
    *out = Deploy::kNone;
  } else {
    return false;
  }
  return true;
}

const char* ClockName(Clock clock) { return clock == Clock::kLockstep ? "lockstep" : "realtime"; }

const char* CommName(Comm comm) { return comm == Comm::kBroadcast ? "broadcast" : "local"; }

const char* PlacementName(Placement placement) {
  switch (placement) {
    case Placement::kCorner:
      return "corner";
    case Placement::kFile:
      return "file";
    default:
      return "random";
  }
}

const char* DeployName(Deploy deploy) {
  switch (deploy) {
    case Deploy::kHost:
      return "host";
    case Deploy::kHostSim:
      return "host_sim";
    case Deploy::kNone:
      return "none";
    default:
      return "process";
  }
}

}  // namespace core
}  // namespace swarm_transport
