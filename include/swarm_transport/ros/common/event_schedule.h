// Timed events of a scenario (the simulator's ~events_file, issue 14): freeze / continue a
// range, kill / spawn a robot, move a mission's object, LOADED / UNLOADED - each at a stated
// tick, so that a lock-step run with events is the same on every machine.
#ifndef SWARM_TRANSPORT_ROS_EVENT_SCHEDULE_H_
#define SWARM_TRANSPORT_ROS_EVENT_SCHEDULE_H_

#include <xmlrpcpp/XmlRpcValue.h>

#include <cstdint>
#include <set>
#include <string>
#include <vector>

namespace swarm_transport {

struct TimedEvent {
  enum class Kind : std::uint8_t {
    kFreeze,
    kContinue,
    kKill,
    kSpawn,
    kObjectUpdate,
    kSignal,
    kStatist,        // a motionless virtual robot (SPEC 9.3) appears at (x, y): robot, sub_id
    kRemoveStatist,  // ... and goes
    kOdomStop,       // the hardware stand-in (bases) sends no odometry of `robot` for `ticks`
  };
  std::uint64_t tick = 0;
  Kind kind = Kind::kFreeze;
  std::uint16_t from = 0;  // freeze / continue: robots [from, to)
  std::uint16_t to = 0;
  std::uint16_t robot = 0;    // kill / spawn / statist
  std::uint8_t sub_id = 0;    // statist
  std::uint16_t mission = 0;  // object_update / signal
  double x = 0.0;             // spawn / object_update (m)
  double y = 0.0;
  double theta_deg = 0.0;   // spawn
  std::uint8_t signal = 0;  // Mission_Event::LOADED / UNLOADED
  std::uint64_t ticks = 0;  // odom_stop: how long
};

// Reads `events:` - a list of {tick, kind: freeze | continue | kill | spawn | object_update |
// signal | statist | remove_statist | odom_stop, and the kind's fields: from, to | robot |
// robot, x, y, theta_deg | mission, x, y | mission, event: LOADED | UNLOADED | robot, sub_id,
// x, y | robot, sub_id | robot, ticks}. False with `error` naming the entry and the key.
bool EventsFromXmlRpc(XmlRpc::XmlRpcValue& file, std::vector<TimedEvent>* events,
                      std::string* error);
bool ReadEventsFile(const std::string& path, std::vector<TimedEvent>* events, std::string* error);

// The physical robots in the world at `tick` as the events make them: `robots` (those of the
// run's first tick), then every spawn and kill due at or before `tick` in tick order (file order
// within a tick) - the robots a lock-step mission that starts at `tick` may name.
std::set<std::uint16_t> RobotsAt(std::set<std::uint16_t> robots,
                                 const std::vector<TimedEvent>& events, std::uint64_t tick);

// The events not yet due, by tick (file order within a tick).
class EventSchedule {
 public:
  explicit EventSchedule(std::vector<TimedEvent> events);
  // Removes and returns the events due at or before `tick`.
  std::vector<TimedEvent> Due(std::uint64_t tick);
  bool empty() const { return next_ == events_.size(); }

 private:
  std::vector<TimedEvent> events_;  // stably sorted by tick
  std::size_t next_ = 0;
};

}  // namespace swarm_transport

#endif  // SWARM_TRANSPORT_ROS_EVENT_SCHEDULE_H_
