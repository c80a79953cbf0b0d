// The master watch (ros/common/master_watch.h) asks the master for its pid with a deadline: a
// master that accepts the connection but never answers (stopped, hung, or still starting on its
// port) does not hold it. roscpp's own calls to the master (ros::master::execute) wait for as long
// as such a connection stays open.
#include "swarm_transport/ros/common/master_watch.h"

#include <arpa/inet.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <ros/init.h>
#include <ros/master.h>
#include <sys/socket.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <future>
#include <optional>
#include <string>

namespace swarm_transport {
namespace {

// A TCP port on loopback that takes connections (the kernel completes them: listen) and never
// reads or answers.
class SilentMaster {
 public:
  SilentMaster() {
    fd_ = ::socket(AF_INET, SOCK_STREAM, 0);
    sockaddr_in addr{};
    addr.sin_family = AF_INET;
    addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    addr.sin_port = 0;
    socklen_t len = sizeof(addr);
    ok_ = fd_ >= 0 && ::bind(fd_, reinterpret_cast<sockaddr*>(&addr), sizeof(addr)) == 0 &&
          ::listen(fd_, 16) == 0 &&
          ::getsockname(fd_, reinterpret_cast<sockaddr*>(&addr), &len) == 0;
    port_ = ntohs(addr.sin_port);
  }
  ~SilentMaster() {
    if (fd_ >= 0) ::close(fd_);
  }
  bool ok() const { return ok_; }
  std::string uri() const { return "http://127.0.0.1:" + std::to_string(port_) + "/"; }

 private:
  int fd_ = -1;
  int port_ = 0;
  bool ok_ = false;
};

TEST(MasterWatchTest, AMasterThatNeverAnswersDoesNotHoldTheWatch) {
  SilentMaster master;
  ASSERT_TRUE(master.ok());
  ros::M_string remappings;
  remappings["__master"] = master.uri();
  // Not started (no NodeHandle): nothing contacts the master but the watch.
  ros::init(remappings, "master_watch_test", ros::init_options::NoSigintHandler);
  ASSERT_EQ(ros::master::getPort(), std::stoi(master.uri().substr(17)));
  // Constructed, the watch asks the master's pid once (without ros::init its thread stops at
  // once: ROS is not ok).
  auto watched = std::async(std::launch::async, [] {
    MasterWatch watch(60.0);
    return watch.restarted();
  });
  // Each call ends after 2 s; 30 s is far beyond that. A watch held for good would hold this
  // test too (the future's destructor waits): it fails the whole binary instead.
  if (watched.wait_for(std::chrono::seconds(30)) != std::future_status::ready) {
    std::fprintf(stderr,
                 "MasterWatchTest: the watch still waits for a master that never "
                 "answers after 30 s\n");
    std::fflush(stderr);
    std::_Exit(1);
  }
  EXPECT_FALSE(watched.get());
}

// One look at the master, by hand: a master with another pid restarted; after it was down, or at
// its first answer when it did not answer as the watch began, it must still know this node (a
// master that came back in between knows nothing: once its first answer was taken for the
// first contact, and the restart went unnoticed); no answer to that question is no answer.
TEST(MasterWatchTest, EachLookAtTheMasterIsJudgedByItsPidAndWhetherItKnowsThisNode) {
  using Look = MasterWatch::Look;
  int asked = 0;
  const auto answer = [&asked](std::optional<bool> known) {
    return [&asked, known] {
      ++asked;
      return known;
    };
  };
  int pid = 100;
  EXPECT_EQ(MasterWatch::Judge(&pid, 100, false, answer(false)), Look::kUp);
  EXPECT_EQ(asked, 0);  // a steady master is asked only its pid
  EXPECT_EQ(MasterWatch::Judge(&pid, 0, false, answer(true)), Look::kUnreachable);
  EXPECT_EQ(MasterWatch::Judge(&pid, 101, false, answer(true)), Look::kRestarted);
  EXPECT_EQ(MasterWatch::Judge(&pid, 101, true, answer(true)), Look::kRestarted);
  EXPECT_EQ(MasterWatch::Judge(&pid, 100, true, answer(true)), Look::kReachableAgain);
  EXPECT_EQ(MasterWatch::Judge(&pid, 100, true, answer(false)), Look::kRestarted);
  EXPECT_EQ(MasterWatch::Judge(&pid, 100, true, answer(std::nullopt)), Look::kUnreachable);
  EXPECT_EQ(pid, 100);
  // No pid when the watch began: the first answer is taken only from a master that knows it.
  int unknown = 0;
  EXPECT_EQ(MasterWatch::Judge(&unknown, 0, false, answer(true)), Look::kUnreachable);
  EXPECT_EQ(MasterWatch::Judge(&unknown, 200, true, answer(false)), Look::kRestarted);
  EXPECT_EQ(unknown, 0);
  EXPECT_EQ(MasterWatch::Judge(&unknown, 200, true, answer(std::nullopt)), Look::kUnreachable);
  EXPECT_EQ(unknown, 0);
  EXPECT_EQ(MasterWatch::Judge(&unknown, 200, false, answer(true)), Look::kUp);
  EXPECT_EQ(unknown, 200);
  asked = 0;
  EXPECT_EQ(MasterWatch::Judge(&unknown, 200, false, answer(false)), Look::kUp);
  EXPECT_EQ(asked, 0);
}

}  // namespace
}  // namespace swarm_transport
