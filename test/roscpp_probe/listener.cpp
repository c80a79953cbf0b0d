// scripts/roscpp_probe's plain roscpp node, long-lived: subscribes to /probe/t0 .. /probe/t<K-1>
// (std_msgs/String), or with "publisher" as its second argument publishes them at 10 Hz, and
// does nothing else - no code of swarm_transport. Its heap is what roscpp alone holds while
// the peer on the other end of those topics is killed and started again. With "trim" as its third
// argument it gives the C library's free heap back to the system once a second (malloc_trim), so
// that what stays is what roscpp still holds, not what the allocator keeps of what it freed.
#include <malloc.h>

#include <cstdlib>
#include <cstring>

#include "probe_topics.h"

int main(int argc, char** argv) {
  ros::init(argc, argv, "probe_listener");
  const int topics = argc > 1 ? std::atoi(argv[1]) : 1;
  ros::NodeHandle nh;
  ros::WallTimer trim;
  if (argc > 3 && std::strcmp(argv[3], "trim") == 0) {
    trim = nh.createWallTimer(ros::WallDuration(1.0),
                              [](const ros::WallTimerEvent&) { malloc_trim(0); });
  }
  return probe::Run(topics, argc > 2 && std::strcmp(argv[2], "publisher") == 0);
}
