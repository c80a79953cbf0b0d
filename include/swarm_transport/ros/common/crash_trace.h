// A node that dies of a fatal signal (SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGABRT) writes its
// name, the signal and the call stack to stderr first, then dies of the same signal (its exit
// status, and so roslaunch's "exit code -11", unchanged). roslaunch keeps stderr in the node's
// log: a crash in a soak or in CI leaves where it happened, not only that it happened.
#ifndef SWARM_TRANSPORT_ROS_COMMON_CRASH_TRACE_H
#define SWARM_TRANSPORT_ROS_COMMON_CRASH_TRACE_H

namespace swarm_transport {

// Installs the handlers; `node` (kept, not copied: a string literal) names the node in the
// message. Call once, early in main.
void InstallCrashTrace(const char* node);

}  // namespace swarm_transport

#endif  // SWARM_TRANSPORT_ROS_COMMON_CRASH_TRACE_H
