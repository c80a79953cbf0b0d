// Works around a leak of roscpp 1.15 (Debian's 1.15.15, and ros_comm's noetic-devel): when a
// subscription's publisher dies, TransportPublisherLink::onRetryTimer reconnects every 0.1, 0.2,
// 0.4, ... s and, for each attempt, initialises the new Connection *before* handing it to
// ConnectionManager::addConnection. On loopback a refused connect fails at once: the poll thread
// drops the connection before it is added, the drop listener that would take it out again is
// not registered yet, and ConnectionManager keeps it - with its transport, header strings and
// signal slots - until the node exits. A long-lived node gains a few such connections per topic
// at every restart of a peer (issue 29: the soak's RSS growth; docs/reliability.md).
//
// A ConnectionReaper removes dropped connections from ConnectionManager's set in the poll
// thread, where roscpp removes the ones it knows dropped (removeDroppedConnections), at most
// once a second. Connections still in use elsewhere (a link's own pointer) live on; only the
// manager's reference goes.
#ifndef SWARM_TRANSPORT_ROS_COMMON_CONNECTION_REAPER_H
#define SWARM_TRANSPORT_ROS_COMMON_CONNECTION_REAPER_H

#include <boost/signals2/connection.hpp>
#include <cstddef>
#include <cstdint>

namespace swarm_transport {

struct HeldConnections {
  std::size_t held = 0;     // connections in roscpp's ConnectionManager
  std::size_t dropped = 0;  // of them already dropped (what roscpp would keep for ever)
};

class ConnectionReaper {
 public:
  // SWARM_TRANSPORT_CONNECTION_REAPER=off in a node's environment leaves roscpp as it is (to
  // measure the leak, or should a roscpp release fix it: scripts/respawn_probe --reaper off).
  static constexpr const char* kOffVariable = "SWARM_TRANSPORT_CONNECTION_REAPER";

  // Starts reaping; call after ros::init, once the node has a NodeHandle (roscpp started).
  ConnectionReaper();
  ~ConnectionReaper();
  ConnectionReaper(const ConnectionReaper&) = delete;
  ConnectionReaper& operator=(const ConnectionReaper&) = delete;

  // What roscpp's ConnectionManager holds now (locks its set briefly; any thread).
  static HeldConnections Held();
  // Dropped connections this process took out of the set so far (every reaper together).
  static std::uint64_t Reaped();

 private:
  boost::signals2::connection listener_;
};

}  // namespace swarm_transport

#endif  // SWARM_TRANSPORT_ROS_COMMON_CONNECTION_REAPER_H
