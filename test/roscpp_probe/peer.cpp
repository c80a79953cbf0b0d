// scripts/roscpp_probe's peer: publishes /probe/t0 .. /probe/t<K-1> at 10 Hz (or, with
// "subscriber" as its second argument, subscribes to them) until it is killed; started again
// under the same node name, as a respawned robot or a restarted dispatcher is.
#include <cstdlib>
#include <cstring>

#include "probe_topics.h"

int main(int argc, char** argv) {
  ros::init(argc, argv, "probe_peer");
  const int topics = argc > 1 ? std::atoi(argv[1]) : 1;
  return probe::Run(topics, !(argc > 2 && std::strcmp(argv[2], "subscriber") == 0));
}
