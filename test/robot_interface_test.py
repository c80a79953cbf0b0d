#!/usr/bin/env python3
"""The robot node's interface in lock-step (issue 10, item 6), the test playing the simulator:
- one robot_<id>/answer per robot_<id>/neighbors round, naming the round's tick, with a
  finite command; a round with a non-finite own pose is refused (no answer), and the good
  round after it is answered (the refusal did not stop the robot);
- an order relayed in a round makes the robot (its first leader) say QUEUED and GATHERING in
  its answers, each once and in order;
- a relayed Robot_Freeze for it: ~state says frozen and its command is zero; a relayed freeze
  with an inverted range is refused (state unchanged), and the continue after it takes effect.
- in lock-step the robot takes its time from the rounds: it does not subscribe to /clock
  (robot.launch), and its statuses carry their round's sim_time.
Counts and typed fields only (no ~describe text)."""

import math
import sys
import threading
import unittest

import rospy
import rostest
from swarm_transport.msg import (Neighbors, Robot_Continue, Robot_Freeze, Robot_Position,
                                 Tick_Answer)

import swarm_testing as st


def g(key):
    return rospy.get_param('~' + key)


class RobotInterface(unittest.TestCase):

    @classmethod
    def setUpClass(cls):
        cls.rid = g('robot_id')
        cls.timeout = g('timeout_s')
        cls.lock = threading.Lock()
        cls.answers = []
        cls.sub = rospy.Subscriber('/robot_%d/answer' % cls.rid, Tick_Answer, cls.on_answer,
                                   queue_size=100)
        cls.rounds, cls.robots = st.play_simulator_for(cls.rid, 4, cls.timeout)
        cls.tick = 0

    @classmethod
    def on_answer(cls, msg):
        with cls.lock:
            cls.answers.append(msg)

    def round(self, x=2.0, y=2.0, **relayed):
        """Sends the next tick's round; returns the tick."""
        msg = Neighbors()
        msg.tick = type(self).tick
        msg.sim_time = 0.1 * msg.tick
        msg.pose.x, msg.pose.y, msg.pose.theta = x, y, 0.0
        msg.robots = [Robot_Position(robot_id=1, pos_x=x + 0.4, pos_y=y)]
        for key, value in relayed.items():
            setattr(msg, key, value)
        self.rounds.publish(msg)
        type(self).tick += 1
        return msg.tick

    def answers_to(self, tick):
        with self.lock:
            return [a for a in self.answers if a.tick == tick]

    def answered(self, tick):
        """Waits for the answer to round `tick` and checks it; then every answer the robot gave
        to an earlier round is here too (one publisher, one connection, in order), so each of
        those rounds must have had exactly one answer (or none: refused ones)."""
        self.assertTrue(st.wait_for(lambda: self.answers_to(tick), self.timeout),
                        'no answer to tick %d' % tick)
        with self.lock:
            counts = {}
            for a in self.answers:
                counts[a.tick] = counts.get(a.tick, 0) + 1
        twice = {t: n for t, n in counts.items() if n > 1 and t < tick}
        self.assertEqual(twice, {}, 'rounds answered more than once: %s' % twice)
        a = self.answers_to(tick)[0]
        self.assertTrue(math.isfinite(a.command.linear.x) and math.isfinite(a.command.angular.z))
        return a

    def tearDown(self):
        # A last round: its answer brings every earlier answer (a late second one included).
        self.answered(self.round())

    def test_1_one_answer_per_round_and_a_bad_round_is_refused(self):
        for _ in range(3):
            self.answered(self.round())
        bad = self.round(x=float('nan'))
        # The good round after it is answered: an answer to the bad one would be here already.
        self.answered(self.round())
        self.assertEqual(self.answers_to(bad), [], 'a round with a NaN pose was answered')

    def test_2_a_relayed_order_is_queued_and_gathered_once(self):
        order = st.mission(9, self.rid, self.rid + 2, 1, (6.0, 6.0, 1.0, 1.0), (3.0, 6.0))
        states = []
        for k in range(6):
            tick = self.round(missions=[order] if k == 0 else [])
            a = self.answered(tick)
            states += [s.state for s in a.statuses if s.mission_id == 9]
            for s in a.statuses:  # stamped with its round's simulated time, not a /clock
                self.assertAlmostEqual(s.stamp.to_sec(), 0.1 * tick, places=6)
        self.assertEqual(states[:2], [0, 1], states)  # QUEUED, GATHERING
        self.assertEqual(len(states), len(set(states)), 'a phase said twice: %s' % states)

    def test_3_freeze_continue_and_an_inverted_range(self):
        self.answered(self.round(freezes=[Robot_Freeze(robot_index_from=self.rid,
                                                       robot_index_to=self.rid + 1)]))
        self.assertTrue(st.robot_state(self.rid, self.timeout).frozen)
        a = self.answered(self.round())
        self.assertEqual((a.command.linear.x, a.command.angular.z), (0.0, 0.0))
        self.answered(self.round(continues=[Robot_Continue(robot_index_from=self.rid + 1,
                                                           robot_index_to=self.rid)]))
        self.assertTrue(st.robot_state(self.rid, self.timeout).frozen, 'an inverted range acted')
        self.answered(self.round(continues=[Robot_Continue(robot_index_from=self.rid,
                                                           robot_index_to=self.rid + 1)]))
        self.assertFalse(st.robot_state(self.rid, self.timeout).frozen)


    def test_4_no_clock_subscription_in_lock_step(self):
        import rosgraph
        _, subscribers, _ = rosgraph.Master('/robot_interface_test').getSystemState()
        on_clock = [nodes for topic, nodes in subscribers if topic == '/clock']
        robot = '/robot_%d/robot' % self.rid
        self.assertTrue(any(robot == n for _, nodes in subscribers for n in nodes),
                        'the robot subscribes to nothing?')
        self.assertNotIn(robot, on_clock[0] if on_clock else [], 'the robot hears /clock')

if __name__ == '__main__':
    rospy.init_node('robot_interface_test')
    rostest.rosrun('swarm_transport', 'robot_interface', RobotInterface, sys.argv)
