// The master watch (ros/master_watch.h) asks the master for its pid with a deadline: a master
// that accepts the connection but never answers (stopped, hung, or still starting on its port)
// does not hold it. roscpp's own calls to the master (ros::master::execute) wait for as long
// as such a connection stays open.
#include "swarm_transport/ros/master_watch.h"

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
    std::fprintf(stderr, "MasterWatchTest: the watch still waits for a master that never "
                         "answers after 30 s\n");
    std::fflush(stderr);
    std::_Exit(1);
  }
  EXPECT_FALSE(watched.get());
}

}  // namespace
}  // namespace swarm_transport
