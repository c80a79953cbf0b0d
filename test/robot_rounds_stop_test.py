#!/usr/bin/env python3
"""A real-time robot whose radio rounds stop stands (issue 29): it must not act on its last
round again and again. A soak's robot that did (session 25, mission 96) turned the same turn
every tick, drove into the arena's corner and pulled its mission's object after it.

The test plays the simulator: rounds at 10 Hz, a pause longer than /swarm/lost_after_s, rounds
again. While rounds come, the robot commands moves and ticks; in the pause every command it sends
is zero and its tick count stands; once rounds return it moves and ticks again."""

import sys
import threading
import time
import unittest

import rospy
import rostest
from geometry_msgs.msg import Twist
from swarm_transport.msg import Neighbors, Robot_Position

import swarm_testing as st


def g(key):
    return rospy.get_param('~' + key)


class RoundsStop(unittest.TestCase):

    @classmethod
    def setUpClass(cls):
        cls.rid = g('robot_id')
        cls.timeout = g('timeout_s')
        cls.lock = threading.Lock()
        cls.commands = []  # (wall time, linear, angular)
        cls.sub = rospy.Subscriber('/robot_%d/cmd_vel' % cls.rid, Twist, cls.on_command,
                                   queue_size=100)
        # It joins the radio once it gave up waiting for a dispatcher (none here: 10 s).
        cls.rounds, cls.robots = st.play_simulator_for(cls.rid, 2, cls.timeout)
        cls.tick = 0

    @classmethod
    def on_command(cls, msg):
        with cls.lock:
            cls.commands.append((time.time(), msg.linear.x, msg.angular.z))

    def send_rounds(self, seconds):
        """Rounds at 10 Hz for `seconds`, the robot at (5, 5) with a peer 0.4 m ahead."""
        end = time.time() + seconds
        while time.time() < end and not rospy.is_shutdown():
            msg = Neighbors()
            msg.tick = type(self).tick
            msg.sim_time = 0.1 * msg.tick
            msg.pose.x, msg.pose.y, msg.pose.theta = 5.0, 5.0, 0.0
            msg.robots = [Robot_Position(robot_id=1, pos_x=5.4, pos_y=5.0)]
            self.rounds.publish(msg)
            type(self).tick += 1
            time.sleep(0.1)

    def commands_between(self, t0, t1):
        with self.lock:
            return [c for c in self.commands if t0 <= c[0] < t1]

    def ticks(self):
        return st.robot_state(self.rid, self.timeout).ticks

    def test_a_robot_without_rounds_stands_and_moves_again_when_they_return(self):
        lost_after = rospy.get_param('/swarm/lost_after_s')
        settle = g('settle_s')
        t0 = time.time()
        self.send_rounds(2.0)
        moving = self.commands_between(t0, time.time())
        self.assertTrue(any(abs(c[1]) > 1e-6 for c in moving),
                        'no move while rounds came: %s' % moving[-5:])
        # The pause: after lost_after_s (and settle_s for delivery) it sends only zero commands
        # and ticks no more.
        paused = time.time()
        time.sleep(lost_after + settle)
        ticks_before = self.ticks()
        quiet_from = time.time()
        time.sleep(g('pause_s'))
        quiet = self.commands_between(quiet_from, time.time())
        ticks_after = self.ticks()
        self.assertTrue(quiet, 'no command at all in the pause (it should say zero)')
        self.assertTrue(all(abs(c[1]) < 1e-9 and abs(c[2]) < 1e-9 for c in quiet),
                        'it moved on a stale round %.1f s after the last one: %s'
                        % (quiet[-1][0] - paused, quiet[-5:]))
        self.assertEqual(ticks_after, ticks_before, 'it ticked without rounds')
        # Its ~state says why: its round is old; its command reaches one node (this test).
        state = st.robot_state(self.rid, self.timeout)
        self.assertGreater(state.round_age_s, lost_after, state)
        self.assertEqual(state.command_listeners, 1, state)
        # Rounds again: it moves and ticks.
        back = time.time()
        self.send_rounds(2.0)
        again = self.commands_between(back, time.time())
        self.assertTrue(any(abs(c[1]) > 1e-6 for c in again),
                        'no move after rounds returned: %s' % again[-5:])
        self.assertGreater(self.ticks(), ticks_after)
        self.assertLess(st.robot_state(self.rid, self.timeout).round_age_s, lost_after)

    def test_b_one_round_one_move(self):
        # Rounds at a third of its rate: it moves once per round and waits for the next (a
        # second move from the same pose would turn the same turn again: the simulator turns at
        # once on receipt). Every round is fresh: no zero command of a stale round either.
        lost_after = rospy.get_param('/swarm/lost_after_s')
        gap = g('slow_round_gap_s')
        self.assertLess(gap, lost_after)
        self.send_rounds(1.0)
        waits_before = st.robot_state(self.rid, self.timeout).round_waits
        n = g('slow_rounds')
        t0 = time.time()
        for _ in range(n):
            self.send_rounds(0.05)  # one round
            time.sleep(gap - 0.1)
        time.sleep(0.2)
        moves = self.commands_between(t0, time.time())
        state = st.robot_state(self.rid, self.timeout)
        # At most one command per round; a starved robot may take two rounds in one tick.
        self.assertLessEqual(len(moves), n, 'commands for %d rounds: %s' % (n, moves))
        self.assertGreaterEqual(len(moves), n - g('slow_rounds_merged'),
                                'commands for %d rounds: %s' % (n, moves))
        self.assertTrue(all(abs(c[1]) > 1e-6 for c in moves), moves)
        self.assertGreater(state.round_waits, waits_before, state)


if __name__ == '__main__':
    rospy.init_node('robot_rounds_stop_test')
    rostest.rosrun('swarm_transport', 'robot_rounds_stop', RoundsStop, sys.argv)
