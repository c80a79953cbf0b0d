#include "swarm_transport/ros/common/crash_trace.h"

#include <execinfo.h>
#include <signal.h>
#include <unistd.h>

#include <cstring>
#include <initializer_list>

namespace swarm_transport {
namespace {

const char* g_node = "node";
constexpr int kMaxFrames = 64;

void Write(const char* text) {
  // write(2) only: what a signal handler may call.
  ssize_t ignored = ::write(STDERR_FILENO, text, std::strlen(text));
  (void)ignored;
}

void OnFatal(int sig) {
  char number[8];
  int n = sig, i = sizeof(number) - 1;
  number[i] = '\0';
  do {
    number[--i] = static_cast<char>('0' + n % 10);
    n /= 10;
  } while (n > 0 && i > 0);
  Write("\n");
  Write(g_node);
  Write(": fatal signal ");
  Write(number + i);
  Write(" (");
  Write(sig == SIGSEGV   ? "SIGSEGV"
        : sig == SIGBUS  ? "SIGBUS"
        : sig == SIGFPE  ? "SIGFPE"
        : sig == SIGILL  ? "SIGILL"
        : sig == SIGABRT ? "SIGABRT"
                         : "?");
  Write("), call stack:\n");
  void* frames[kMaxFrames];
  const int count = backtrace(frames, kMaxFrames);
  backtrace_symbols_fd(frames, count, STDERR_FILENO);
  // SA_RESETHAND put the default action back: the same signal ends the process as before.
  raise(sig);
}

}  // namespace

void InstallCrashTrace(const char* node) {
  g_node = node;
  // The first backtrace() loads libgcc (it allocates): here, not in the handler.
  void* warm[1];
  backtrace(warm, 1);
  struct sigaction action;
  std::memset(&action, 0, sizeof(action));
  action.sa_handler = &OnFatal;
  sigemptyset(&action.sa_mask);
  action.sa_flags = SA_RESETHAND | SA_NODEFER;
  for (int sig : {SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGABRT}) sigaction(sig, &action, nullptr);
}

}  // namespace swarm_transport
