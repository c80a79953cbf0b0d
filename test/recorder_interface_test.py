#!/usr/bin/env python3
"""The recorder's interface (issue 10, item 6), the test playing the simulator and a mission's
first leader: one /flock/stats message per sample period of simulated time (the frames' own
sim_time, not a clock), with the robots, swarm count and largest swarm of that frame; a frame
with a NaN robot is counted without it (and the recorder goes on); live_missions follows a
mission's order and its DONE."""

import sys
import threading
import time
import unittest

import rospy
import rostest
from swarm_transport.msg import Mission_Status, New_Mission, Robot_Position, Robot_Positions, Swarm_Stats

import swarm_testing as st


def g(key):
    return rospy.get_param('~' + key)


class RecorderInterface(unittest.TestCase):

    def test_samples_counts_and_missions(self):
        lock = threading.Lock()
        stats = []

        def on_stats(msg):
            with lock:
                stats.append(msg)
        sub = rospy.Subscriber('/flock/stats', Swarm_Stats, on_stats, queue_size=100)
        frames = rospy.Publisher('/flock/world_poses', Robot_Positions, queue_size=100)
        orders = rospy.Publisher('/flock/mission/new', New_Mission, queue_size=10, latch=True)
        phases = rospy.Publisher('/flock/mission/status', Mission_Status, queue_size=10)
        timeout = g('timeout_s')
        for pub in (frames, orders, phases):
            self.assertTrue(st.wait_connected(pub, timeout), pub.name)
        self.assertTrue(st.wait_for(lambda: sub.get_num_connections() > 0, timeout))
        period = g('sample_period_s')
        tick_s = 0.1
        # Robots 0-2 in a chain 0.5 m apart, robot 3 far away: 2 swarms, the largest of 3.
        line = [(1.0, 1.0), (1.5, 1.0), (2.0, 1.0), (8.0, 8.0)]

        def frame(tick, nan=False):
            msg = Robot_Positions(tick=tick, sim_time=tick * tick_s)
            msg.robots = [Robot_Position(robot_id=i, pos_x=x, pos_y=y) for i, (x, y) in
                          enumerate(line)]
            if nan:
                msg.robots[3].pos_x = float('nan')
            frames.publish(msg)
        ticks_per_sample = int(round(period / tick_s))
        order = st.mission(3, 0, 3, 1, (1.5, 1.0, 2.0, 2.0), (5.0, 5.0))
        for tick in range(0, 3 * ticks_per_sample + 1):
            if tick == 5:
                orders.publish(order)
            if tick == ticks_per_sample + 5:
                phases.publish(Mission_Status(mission_id=3, state=Mission_Status.DONE,
                                              tick=tick, robots_assigned=3,
                                              object_position_x=5.0, object_position_y=5.0))
            frame(tick, nan=(tick == 2 * ticks_per_sample))
            # Paced like a simulator: the order and its DONE (other topics, other connections)
            # reach the recorder before the frames of the next sample.
            time.sleep(0.002)
        # One more sample as a sentinel: its stats come after every earlier one (one publisher,
        # one connection, in order), an unwanted extra sample included.
        sentinel = 4 * ticks_per_sample
        for tick in range(3 * ticks_per_sample + 1, sentinel + 1):
            frame(tick)
            time.sleep(0.002)
        self.assertTrue(st.wait_for(lambda: any(s.tick == sentinel for s in list(stats)),
                                    timeout), stats)
        with lock:
            got = [s for s in stats if s.tick != sentinel]
        self.assertEqual([s.tick for s in got], [k * ticks_per_sample for k in range(4)])
        normal = [s for s in got if s.tick != 2 * ticks_per_sample]
        for s in normal:
            self.assertEqual((s.robots, s.swarm_count, s.largest_swarm), (4, 2, 3), s)
        nan = [s for s in got if s.tick == 2 * ticks_per_sample][0]
        self.assertEqual((nan.robots, nan.swarm_count, nan.largest_swarm), (3, 1, 3), nan)
        # The order arrived after the first sample, its DONE after the second.
        self.assertEqual([s.live_missions for s in got], [0, 1, 0, 0])


if __name__ == '__main__':
    rospy.init_node('recorder_interface_test')
    rostest.rosrun('swarm_transport', 'recorder_interface', RecorderInterface, sys.argv)
