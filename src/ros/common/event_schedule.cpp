#include "swarm_transport/ros/common/event_schedule.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <utility>

#include "swarm_transport/Mission_Event.h"
#include "swarm_transport/ros/common/params.h"

namespace swarm_transport {
namespace {

using XmlRpc::XmlRpcValue;

// `key` is present and holds a finite number (XmlRpcNumber).
bool Number(XmlRpcValue& e, const char* key, double* out) {
  return e.hasMember(key) && XmlRpcNumber(e[key], out);
}

bool Id(XmlRpcValue& e, const char* key, std::uint16_t* out) {
  if (!e.hasMember(key) || e[key].getType() != XmlRpcValue::TypeInt) return false;
  const int v = static_cast<int>(e[key]);
  if (v < 0 || v > 65535) return false;
  *out = static_cast<std::uint16_t>(v);
  return true;
}

bool EventFromXmlRpc(XmlRpcValue& e, TimedEvent* event, std::string* error) {
  static const std::map<std::string, std::pair<TimedEvent::Kind, std::set<std::string>>> kKinds = {
      {"freeze", {TimedEvent::Kind::kFreeze, {"from", "to"}}},
      {"continue", {TimedEvent::Kind::kContinue, {"from", "to"}}},
      {"kill", {TimedEvent::Kind::kKill, {"robot"}}},
      {"spawn", {TimedEvent::Kind::kSpawn, {"robot", "x", "y", "theta_deg"}}},
      {"object_update", {TimedEvent::Kind::kObjectUpdate, {"mission", "x", "y"}}},
      {"signal", {TimedEvent::Kind::kSignal, {"mission", "event"}}},
      {"statist", {TimedEvent::Kind::kStatist, {"robot", "sub_id", "x", "y"}}},
      {"remove_statist", {TimedEvent::Kind::kRemoveStatist, {"robot", "sub_id"}}},
      {"odom_stop", {TimedEvent::Kind::kOdomStop, {"robot", "ticks"}}}};
  if (e.getType() != XmlRpcValue::TypeStruct || !e.hasMember("kind") ||
      e["kind"].getType() != XmlRpcValue::TypeString ||
      kKinds.count(static_cast<std::string>(e["kind"])) == 0) {
    *error =
        "needs 'kind': freeze, continue, kill, spawn, object_update, signal, statist or "
        "remove_statist";
    return false;
  }
  const auto& kind = kKinds.at(static_cast<std::string>(e["kind"]));
  for (auto& kv : e) {
    if (kv.first != "tick" && kv.first != "kind" && kind.second.count(kv.first) == 0) {
      *error = "unknown key '" + kv.first + "' for a " + static_cast<std::string>(e["kind"]);
      return false;
    }
  }
  TimedEvent ev;
  ev.kind = kind.first;
  double tick = 0.0;
  if (!Number(e, "tick", &tick) || tick < 0.0 || std::floor(tick) != tick) {
    *error = "'tick' must be an integer >= 0";
    return false;
  }
  ev.tick = static_cast<std::uint64_t>(tick);
  bool ok = true;
  switch (ev.kind) {
    case TimedEvent::Kind::kFreeze:
    case TimedEvent::Kind::kContinue:
      ok = Id(e, "from", &ev.from) && Id(e, "to", &ev.to) && ev.from < ev.to;
      if (!ok) *error = "'from' and 'to' must be robot ids with from < to";
      break;
    case TimedEvent::Kind::kKill:
      ok = Id(e, "robot", &ev.robot);
      if (!ok) *error = "'robot' must be a robot id";
      break;
    case TimedEvent::Kind::kSpawn:
      ok = Id(e, "robot", &ev.robot) && Number(e, "x", &ev.x) && Number(e, "y", &ev.y) &&
           (!e.hasMember("theta_deg") || Number(e, "theta_deg", &ev.theta_deg));
      if (!ok) *error = "a spawn needs 'robot' and finite 'x', 'y' (and 'theta_deg')";
      break;
    case TimedEvent::Kind::kObjectUpdate:
      ok = Id(e, "mission", &ev.mission) && Number(e, "x", &ev.x) && Number(e, "y", &ev.y);
      if (!ok) *error = "an object_update needs 'mission' and finite 'x', 'y'";
      break;
    case TimedEvent::Kind::kStatist:
    case TimedEvent::Kind::kRemoveStatist: {
      std::uint16_t sub = 0;
      ok = Id(e, "robot", &ev.robot) && Id(e, "sub_id", &sub) && sub <= 255 &&
           (ev.kind == TimedEvent::Kind::kRemoveStatist ||
            (Number(e, "x", &ev.x) && Number(e, "y", &ev.y)));
      ev.sub_id = static_cast<std::uint8_t>(sub);
      if (!ok) *error = "a statist needs 'robot', 'sub_id' in [0, 255] (and finite 'x', 'y')";
      break;
    }
    case TimedEvent::Kind::kOdomStop: {
      double ticks = 0.0;
      ok = Id(e, "robot", &ev.robot) && Number(e, "ticks", &ticks) && ticks >= 1.0 &&
           std::floor(ticks) == ticks && ticks < 1e9;
      ev.ticks = ok ? static_cast<std::uint64_t>(ticks) : 0;
      if (!ok) *error = "an odom_stop needs 'robot' and 'ticks', an integer >= 1";
      break;
    }
    case TimedEvent::Kind::kSignal: {
      ok = Id(e, "mission", &ev.mission) && e.hasMember("event") &&
           e["event"].getType() == XmlRpcValue::TypeString;
      const std::string name = ok ? static_cast<std::string>(e["event"]) : "";
      ok = ok && (name == "LOADED" || name == "UNLOADED");
      ev.signal = name == "LOADED" ? Mission_Event::LOADED : Mission_Event::UNLOADED;
      if (!ok) *error = "a signal needs 'mission' and 'event': LOADED or UNLOADED";
      break;
    }
  }
  if (!ok) return false;
  *event = ev;
  return true;
}

}  // namespace

bool EventsFromXmlRpc(XmlRpcValue& file, std::vector<TimedEvent>* events, std::string* error) {
  if (file.getType() != XmlRpcValue::TypeStruct || !file.hasMember("events") ||
      file["events"].getType() != XmlRpcValue::TypeArray) {
    *error = "the file must hold a list under the key 'events'";
    return false;
  }
  std::vector<TimedEvent> out;
  for (int i = 0; i < file["events"].size(); ++i) {
    TimedEvent ev;
    std::string why;
    if (!EventFromXmlRpc(file["events"][i], &ev, &why)) {
      *error = "events[" + std::to_string(i) + "]: " + why;
      return false;
    }
    out.push_back(ev);
  }
  *events = std::move(out);
  return true;
}

bool ReadEventsFile(const std::string& path, std::vector<TimedEvent>* events, std::string* error) {
  XmlRpcValue file;
  if (!XmlRpcFromYamlFile(path, &file, error)) return false;
  if (!EventsFromXmlRpc(file, events, error)) {
    *error = path + ": " + *error;
    return false;
  }
  return true;
}

EventSchedule::EventSchedule(std::vector<TimedEvent> events) : events_(std::move(events)) {
  std::stable_sort(events_.begin(), events_.end(),
                   [](const TimedEvent& a, const TimedEvent& b) { return a.tick < b.tick; });
}

std::set<std::uint16_t> RobotsAt(std::set<std::uint16_t> robots,
                                 const std::vector<TimedEvent>& events, std::uint64_t tick) {
  EventSchedule schedule(events);
  for (const TimedEvent& e : schedule.Due(tick)) {
    if (e.kind == TimedEvent::Kind::kSpawn) robots.insert(e.robot);
    if (e.kind == TimedEvent::Kind::kKill) robots.erase(e.robot);
  }
  return robots;
}

std::vector<TimedEvent> EventSchedule::Due(std::uint64_t tick) {
  std::vector<TimedEvent> due;
  while (next_ < events_.size() && events_[next_].tick <= tick) due.push_back(events_[next_++]);
  return due;
}

}  // namespace swarm_transport
