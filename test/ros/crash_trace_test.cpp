// InstallCrashTrace: a node that dies of a fatal signal says so on stderr with its call stack,
// and still dies of that signal.
#include "swarm_transport/ros/common/crash_trace.h"

#include <gtest/gtest.h>
#include <signal.h>

namespace swarm_transport {
namespace {

// Not inlined, so that it is a frame of its own (exported: the stack names it).
__attribute__((noinline)) void CrashHere(volatile int* where) { *where = 1; }

TEST(CrashTraceDeathTest, ASegfaultSaysWhereAndStillKillsBySigsegv) {
  ::testing::FLAGS_gtest_death_test_style = "threadsafe";
  EXPECT_EXIT(
      {
        InstallCrashTrace("crash_trace_test");
        CrashHere(nullptr);
      },
      ::testing::KilledBySignal(SIGSEGV),
      "crash_trace_test: fatal signal 11 \\(SIGSEGV\\), call stack:.*\\[0x[0-9a-f]+\\]");
}

TEST(CrashTraceDeathTest, AnAbortToo) {
  ::testing::FLAGS_gtest_death_test_style = "threadsafe";
  EXPECT_EXIT(
      {
        InstallCrashTrace("crash_trace_test");
        abort();
      },
      ::testing::KilledBySignal(SIGABRT), "crash_trace_test: fatal signal 6 \\(SIGABRT\\)");
}

TEST(CrashTraceDeathTest, WithoutASignalNothingIsWritten) {
  ::testing::FLAGS_gtest_death_test_style = "threadsafe";
  EXPECT_EXIT(
      {
        InstallCrashTrace("crash_trace_test");
        exit(3);
      },
      ::testing::ExitedWithCode(3), "^$");
}

}  // namespace
}  // namespace swarm_transport
