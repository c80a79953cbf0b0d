#!/usr/bin/env python3
"""Runs in a robot host's network namespace of test/across_hosts_hardware.test: writes every
robot's own /flock/position as it arrives here, one line '<wall> <robot_id> <x> <y> <angle>'
(the floats as sent), to OUT. Run in two namespaces, the same announcement's two arrival times
are its delay between them (the namespaces share this machine's clock; Robot_Position carries no
stamp of its own). Stops on SIGINT.
usage: across_hosts_probe.py OUT"""

import sys
import threading
import time

import rospy
from swarm_transport.msg import Robot_Position


def main():
    out = open(sys.argv[1], 'w')
    lock = threading.Lock()  # a callback thread per publisher
    rospy.init_node('probe', anonymous=True)

    def on_position(msg):
        if msg.type == Robot_Position.TYPE_PHYSICAL and msg.sub_id == 0:
            with lock:
                out.write('%.6f %d %r %r %r\n' % (time.time(), msg.robot_id, msg.pos_x,
                                                  msg.pos_y, msg.angle))

    rospy.Subscriber('/flock/position', Robot_Position, on_position, queue_size=10000,
                     tcp_nodelay=True)
    rospy.spin()
    with lock:
        out.close()


if __name__ == '__main__':
    main()
