#!/usr/bin/env python3
"""Runs inside the core network namespace of test/across_hosts.test: prints every
/flock/mission/status of mission `id` as 'STATUS <state> <tick> <reason>' and, once it ended,
the XML-RPC URI of every node as 'NODE <name> <uri>'; exits 0 when the mission ended DONE, 1
when it ended otherwise, 2 on timeout.
usage: across_hosts_watch.py MISSION_ID TIMEOUT_S"""

import sys
import time

import rosgraph
import rosnode
import rospy
from swarm_transport.msg import Mission_Status

NAMES = {0: 'QUEUED', 1: 'GATHERING', 2: 'LOADING', 3: 'TRANSPORT', 4: 'UNLOADING', 5: 'DONE',
         6: 'ABORTED', 7: 'REJECTED'}


def main():
    mission_id, timeout_s = int(sys.argv[1]), float(sys.argv[2])
    rospy.init_node('across_hosts_watch', disable_signals=True)
    final = []

    def on_status(msg):
        if msg.mission_id != mission_id:
            return
        print('STATUS %s %d %s' % (NAMES.get(msg.state, msg.state), msg.tick, msg.reason),
              flush=True)
        if msg.state in (5, 6, 7):
            final.append(msg.state)

    rospy.Subscriber('/flock/mission/status', Mission_Status, on_status, queue_size=1000)
    deadline = time.monotonic() + timeout_s
    while not final and time.monotonic() < deadline:
        time.sleep(0.05)
    master = rosgraph.Master('/across_hosts_watch')
    for name in sorted(rosnode.get_node_names()):
        try:
            print('NODE %s %s' % (name, rosnode.get_api_uri(master, name, skip_cache=True)),
                  flush=True)
        except Exception as e:  # noqa: BLE001 - a node that just went away
            print('NODE %s ? (%s)' % (name, e), flush=True)
    if not final:
        return 2
    return 0 if final[0] == 5 else 1


if __name__ == '__main__':
    sys.exit(main())
