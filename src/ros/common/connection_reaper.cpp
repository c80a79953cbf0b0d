#include "swarm_transport/ros/common/connection_reaper.h"

#include <ros/connection.h>
#include <ros/connection_manager.h>
#include <ros/console.h>
#include <ros/poll_manager.h>

#include <atomic>
#include <chrono>
#include <cstdlib>
#include <cstring>

namespace swarm_transport {
namespace {

// ConnectionManager's set and its mutex are private and it offers no way to walk them. An
// explicit instantiation may name private members ([temp.explicit]: access checking does not
// apply to its arguments): MemberOf<Tag> hands out the member pointer it was instantiated
// with, typed by Tag.
template <typename Tag, typename Tag::Type Member>
struct Expose {
  friend typename Tag::Type MemberOf(Tag) { return Member; }
};
struct ConnectionsTag {
  using Type = ros::S_Connection ros::ConnectionManager::*;
  friend Type MemberOf(ConnectionsTag);
};
struct ConnectionsMutexTag {
  using Type = boost::mutex ros::ConnectionManager::*;
  friend Type MemberOf(ConnectionsMutexTag);
};
template struct Expose<ConnectionsTag, &ros::ConnectionManager::connections_>;
template struct Expose<ConnectionsMutexTag, &ros::ConnectionManager::connections_mutex_>;

constexpr auto kPeriod = std::chrono::seconds(1);

std::atomic<std::uint64_t> reaped{0};

// Calls f(the manager's set) under the manager's own lock.
template <typename F>
void WithConnections(F f) {
  ros::ConnectionManager& manager = *ros::ConnectionManager::instance();
  boost::mutex::scoped_lock lock(manager.*MemberOf(ConnectionsMutexTag()));
  f(manager.*MemberOf(ConnectionsTag()));
}

// Runs in roscpp's poll thread, between its rounds (as removeDroppedConnections does).
void Reap() {
  static std::chrono::steady_clock::time_point next;  // the poll thread's only
  const auto now = std::chrono::steady_clock::now();
  if (now < next) return;
  next = now + kPeriod;
  // Declared before the lock is taken, so destroyed after it is released, as roscpp destroys
  // the ones it removes.
  ros::V_Connection gone;
  WithConnections([&gone](ros::S_Connection& connections) {
    for (auto it = connections.begin(); it != connections.end();) {
      if ((*it)->isDropped()) {
        gone.push_back(*it);
        it = connections.erase(it);
      } else {
        ++it;
      }
    }
  });
  reaped.fetch_add(gone.size(), std::memory_order_relaxed);
}

}  // namespace

ConnectionReaper::ConnectionReaper() {
  const char* off = std::getenv(kOffVariable);
  if (off != nullptr && std::strcmp(off, "off") == 0) {
    ROS_WARN("%s=off: roscpp's dropped connections are not reaped", kOffVariable);
    return;
  }
  listener_ = ros::PollManager::instance()->addPollThreadListener(&Reap);
}

ConnectionReaper::~ConnectionReaper() {
  if (listener_.connected()) ros::PollManager::instance()->removePollThreadListener(listener_);
}

HeldConnections ConnectionReaper::Held() {
  HeldConnections held;
  WithConnections([&held](const ros::S_Connection& connections) {
    for (const ros::ConnectionPtr& connection : connections) {
      ++held.held;
      if (connection->isDropped()) ++held.dropped;
    }
  });
  return held;
}

std::uint64_t ConnectionReaper::Reaped() { return reaped.load(std::memory_order_relaxed); }

}  // namespace swarm_transport
