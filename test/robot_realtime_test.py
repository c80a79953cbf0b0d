#!/usr/bin/env python3
"""The robot node's interface in real time (issue 10, item 8), the test playing the simulator
(its node is /simulator):
- the robot ticks on its own timeline: one robot_<id>/cmd_vel per tick period whether its rounds
  come at the same rate or four times as fast, each command finite; rounds with a non-finite own
  pose are refused: it does not move on its last good round again, and once that round is older
  than /swarm/lost_after_s it commands zero every tick;
- it acts on the latest round it got: the position it announces starts from that round's pose
  (advanced by its last command, which this simulator never shows);
- its own /flock/position goes out only while some node other than the simulator listens (here
  `rostopic echo`), and stops again when that observer leaves;
- a /flock/freeze and a /flock/continue (callbacks of its spinning thread while its ticks run in
  roscpp's receiving thread) take effect: zero commands and ~state frozen, then moving again.
Counts and typed fields only."""

import math
import os
import subprocess
import sys
import threading
import time
import unittest

import rospy
import rostest
from geometry_msgs.msg import Twist
from rosgraph_msgs.msg import Log
from swarm_transport.msg import (Neighbors, Robot_Continue, Robot_Freeze, Robot_Position,
                                 Robot_Positions)

import swarm_testing as st


def g(key):
    return rospy.get_param('~' + key)


class RobotRealtime(unittest.TestCase):

    @classmethod
    def setUpClass(cls):
        cls.rid = g('robot_id')
        cls.timeout = g('timeout_s')
        cls.period = rospy.get_param('/swarm/tick_period_s')
        cls.speed = rospy.get_param('/swarm/speed_m_per_tick')
        cls.lock = threading.Lock()
        cls.commands = []   # (wall s, Twist)
        cls.positions = []  # (wall s, Robot_Position) of this robot
        cls.pose = (2.0, 2.0)
        cls.round_hz = 1.0 / cls.period
        cls.bad = False
        cls.tick = 0
        cls.stop = False
        rospy.Subscriber('/robot_%d/cmd_vel' % cls.rid, Twist, cls.on_command, queue_size=100)
        cls.position_sub = rospy.Subscriber('/flock/position', Robot_Position, cls.on_position,
                                            queue_size=100)
        cls.rounds = rospy.Publisher('/robot_%d/neighbors' % cls.rid, Neighbors, queue_size=10)
        cls.robots = rospy.Publisher('/flock/robots', Robot_Positions, queue_size=1, latch=True)
        cls.freeze = rospy.Publisher('/flock/freeze', Robot_Freeze, queue_size=10)
        cls.cont = rospy.Publisher('/flock/continue', Robot_Continue, queue_size=10)
        listed = Robot_Positions()
        listed.robots = [Robot_Position(robot_id=i, pos_x=1.0 + i, pos_y=1.0) for i in range(4)]
        cls.robots.publish(listed)
        for pub in (cls.rounds, cls.freeze, cls.cont):
            assert st.wait_connected(pub, cls.timeout), 'the robot never subscribed'
        assert st.wait_for(lambda: st.robot_state(cls.rid, cls.timeout).listed, cls.timeout)
        cls.sender = threading.Thread(target=cls.send_rounds)
        cls.sender.daemon = True
        cls.sender.start()
        assert st.wait_for(lambda: cls.commands, cls.timeout), 'no command'

    @classmethod
    def tearDownClass(cls):
        cls.stop = True
        cls.sender.join(5)

    @classmethod
    def send_rounds(cls):
        """The radio: rounds at round_hz with the pose the test sets (a neighbour beside it)."""
        start = time.time()
        while not cls.stop and not rospy.is_shutdown():
            with cls.lock:
                x, y = cls.pose
                hz = cls.round_hz
                if cls.bad:
                    x = float('nan')
            msg = Neighbors()
            msg.tick = cls.tick
            msg.sim_time = time.time() - start
            msg.pose.x, msg.pose.y, msg.pose.theta = x, y, 0.0
            msg.robots = [Robot_Position(robot_id=1, pos_x=x + 0.4, pos_y=y)]
            cls.rounds.publish(msg)
            cls.tick += 1
            time.sleep(1.0 / hz)

    @classmethod
    def on_command(cls, msg):
        with cls.lock:
            cls.commands.append((time.time(), msg))

    @classmethod
    def on_position(cls, msg):
        if msg.robot_id == cls.rid and msg.type == Robot_Position.TYPE_PHYSICAL:
            with cls.lock:
                cls.positions.append((time.time(), msg))

    def since(self, log, t0):
        with self.lock:
            return [m for t, m in log if t >= t0]

    def count_over_window(self):
        t0 = time.time()
        time.sleep(g('window_s'))
        got = self.since(self.commands, t0)
        for c in got:
            self.assertTrue(math.isfinite(c.linear.x) and math.isfinite(c.angular.z), c)
        return len(got)

    def assertTicksOwnPeriod(self, count, what):
        want = g('window_s') / self.period
        self.assertLessEqual(abs(count - want), g('tick_tolerance'),
                             '%s: %d commands in %.1f s, want %.0f' % (what, count,
                                                                       g('window_s'), want))

    def test_1_ticks_on_its_own_timeline(self):
        self.assertTicksOwnPeriod(self.count_over_window(), 'rounds at its rate')
        with self.lock:
            type(self).round_hz = 4.0 / self.period
            changed = type(self).tick
        # Rounds at the new rate have begun (the round under way waited at the old one).
        self.assertTrue(st.wait_for(lambda: type(self).tick >= changed + 2, self.timeout))
        self.assertTicksOwnPeriod(self.count_over_window(), 'rounds at 4x its rate')
        # Rounds with a NaN pose: it refuses them (it says so) and does not move on its last good
        # round again (one move per round); once that round is stale it commands zero.
        refusals = []
        log = rospy.Subscriber('/rosout', Log, lambda m: refusals.append(m.msg)
                               if 'non-finite own pose' in m.msg else None, queue_size=100)
        self.assertTrue(st.wait_hears(log, ['/robot_%d/robot' % self.rid], self.timeout))
        with self.lock:
            type(self).round_hz = 1.0 / self.period
            type(self).bad = True
        bad_from = time.time()
        time.sleep(g('window_s'))
        with self.lock:
            type(self).bad = False
            got = [(t - bad_from, c) for t, c in self.commands if t >= bad_from]
        # A good round may be under way when the bad ones begin: two periods for it.
        moved = [(round(t, 2), c.linear.x) for t, c in got
                 if t > 2 * self.period and abs(c.linear.x) > 1e-9]
        self.assertEqual(moved, [], 'it moved on rounds it refused (s after they began, speed)')
        lost_after = rospy.get_param('/swarm/lost_after_s')
        stands = [c for t, c in got if t > lost_after + 2 * self.period]
        self.assertTrue(stands, 'no zero command once its last good round was stale')
        self.assertTrue(all(abs(c.linear.x) < 1e-9 and abs(c.angular.z) < 1e-9 for c in stands))
        self.assertTrue(st.wait_for(lambda: refusals, self.timeout),
                        'the robot never said it refused a round with a NaN pose')
        log.unregister()

    def test_2_announces_its_position_only_while_observed(self):
        robot = '/robot_%d/robot' % self.rid
        # We would hear it announce, and it knows only the simulator listens.
        self.assertTrue(st.wait_hears(self.position_sub, [robot], self.timeout),
                        'not connected to the robot\'s /flock/position')
        self.assertTrue(st.wait_for(
            lambda: st.subscribers_of(robot, '/flock/position') == {'/simulator'}, self.timeout),
            st.subscribers_of(robot, '/flock/position'))
        t0 = time.time()
        time.sleep(2.0)  # the observed time: nothing may be announced meanwhile
        self.assertEqual(self.since(self.positions, t0), [],
                         'it announced its position with only the simulator listening')
        env = dict(os.environ)
        observer = subprocess.Popen(['rostopic', 'echo', '-n', '12', '/flock/position'],
                                    stdout=subprocess.PIPE, stderr=subprocess.DEVNULL,
                                    env=env, universal_newlines=True)
        try:
            # Teleported by its rounds to a new place: what it announces starts from there.
            with self.lock:
                type(self).pose = (5.0, 3.0)
            out, _ = observer.communicate(timeout=self.timeout)
        finally:
            if observer.poll() is None:
                observer.kill()
                observer.wait()
        self.assertGreaterEqual(out.count('robot_id: %d' % self.rid), 12, out[-500:])
        heard = self.since(self.positions, t0)
        self.assertGreater(len(heard), 0, 'the test heard no announced position')
        last = heard[-1]
        # This simulator executes no command: its rounds never show the last command's turn, so
        # the robot plans from where that command takes it (core::CommandEcho), one tick's drive
        # beyond the round's pose, and announces where its new command takes it from there.
        self.assertLessEqual(math.hypot(last.pos_x - 5.0, last.pos_y - 3.0),
                             2 * self.speed + g('position_tolerance_m'),
                             'announced (%.3f, %.3f), its round said (5, 3)'
                             % (last.pos_x, last.pos_y))
        # The observer's disconnection reached the robot: the simulator is its only listener.
        self.assertTrue(st.wait_for(
            lambda: st.subscribers_of(robot, '/flock/position') == {'/simulator'}, self.timeout),
            st.subscribers_of(robot, '/flock/position'))
        t1 = time.time()
        time.sleep(2.0)  # the observed time: nothing may be announced meanwhile
        self.assertEqual(self.since(self.positions, t1), [],
                         'it went on announcing its position after the observer left')

    def test_3_freeze_and_continue_from_the_topics(self):
        self.freeze.publish(Robot_Freeze(robot_index_from=self.rid, robot_index_to=self.rid + 1))
        self.assertTrue(st.wait_for(lambda: st.robot_state(self.rid, self.timeout).frozen,
                                    self.timeout), 'not frozen')
        # Commands of ticks before the freeze may still be on their way: the window starts at
        # the first zero command, after which (one connection, in order) all are of frozen ticks.
        with self.lock:
            seen = len(self.commands)
        self.assertTrue(st.wait_for(
            lambda: any(c.linear.x == 0.0 and c.angular.z == 0.0
                        for _, c in self.commands[seen:]), self.timeout), 'no zero command')
        with self.lock:
            t0 = next(t for t, c in self.commands[seen:]
                      if c.linear.x == 0.0 and c.angular.z == 0.0)
        time.sleep(1.0)  # the observed time: every command meanwhile must be zero
        frozen = self.since(self.commands, t0)
        self.assertGreater(len(frozen), 0)
        self.assertTrue(all(c.linear.x == 0.0 and c.angular.z == 0.0 for c in frozen),
                        'a frozen robot moved')
        self.cont.publish(Robot_Continue(robot_index_from=self.rid,
                                         robot_index_to=self.rid + 1))
        self.assertTrue(st.wait_for(lambda: not st.robot_state(self.rid, self.timeout).frozen,
                                    self.timeout), 'still frozen')
        t1 = time.time()
        self.assertTrue(st.wait_for(
            lambda: any(c.linear.x != 0.0 for c in self.since(self.commands, t1)),
            self.timeout), 'it did not move again')


if __name__ == '__main__':
    rospy.init_node('simulator')
    rostest.rosrun('swarm_transport', 'robot_realtime', RobotRealtime, sys.argv)
