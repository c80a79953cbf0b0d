#!/usr/bin/env python3
"""docs/hardware.md against the stand-in: with the page's launch lines up (hardware_launch.test),
the page's checks before a mission hold - every robot's odometry arrives at its rate, the core
lists every robot on /flock/world_poses, each robot's state says it is listed - a leader-only
mission given with the page's `rosservice call` ends DONE with its leader at the target, and a
robot whose link is lost (its process killed) leaves /flock/world_poses."""
import math
import subprocess
import time
import unittest

import rospy
import rostest
from swarm_transport.msg import Mission_Status, Robot_Positions


def run(cmd, timeout=30):
    return subprocess.run(cmd, shell=True, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                          universal_newlines=True, timeout=timeout)


class HardwareLaunch(unittest.TestCase):

    @classmethod
    def setUpClass(cls):
        rospy.init_node('hardware_launch_test')
        cls.robots = rospy.get_param('~robots')
        cls.timeout = rospy.get_param('~timeout_s')
        cls.positions = None
        cls.statuses = []
        rospy.Subscriber('/flock/world_poses', Robot_Positions, cls._positions)
        rospy.Subscriber('/flock/mission/status', Mission_Status, cls.statuses.append)

    @classmethod
    def _positions(cls, msg):
        cls.positions = msg

    def wait_for(self, cond, what):
        deadline = time.time() + self.timeout
        while time.time() < deadline and not rospy.is_shutdown():
            if cond():
                return
            time.sleep(0.1)
        self.fail('no %s within %.0f s' % (what, self.timeout))

    def ids(self):
        return sorted(r.robot_id for r in self.positions.robots) if self.positions else []

    def test_1_checks_before_a_mission(self):
        # rostopic hz robot_<id>/odom: the base's odometry at its rate
        rate = rospy.get_param('~odom_rate_hz') * rospy.get_param('~min_rate_share')
        for rid in range(self.robots):
            out = run('timeout 4 rostopic hz -w 50 /robot_%d/odom' % rid).stdout
            rates = [float(line.split(':')[1]) for line in out.splitlines()
                     if line.strip().startswith('average rate:')]
            self.assertTrue(rates and rates[-1] >= rate, 'robot %d odom: %s' % (rid, out))
        # rostopic echo -n 1 /flock/world_poses: the core lists every robot
        self.wait_for(lambda: self.ids() == list(range(self.robots)), 'robot on /flock/world_poses')
        out = run('rostopic echo -n 1 /flock/world_poses').stdout
        self.assertIn('robot_id: %d' % (self.robots - 1), out)
        # rosservice call /robot_<id>/robot/state: listed, ticking
        for rid in range(self.robots):
            out = run('rosservice call /robot_%d/robot/state' % rid).stdout
            self.assertIn('listed: True', out)
            self.assertNotIn('ticks: 0\n', out)
            out = run('rosservice call /robot_%d/robot/describe' % rid).stdout
            self.assertIn('id=%d ticks=' % rid, out)
        # freeze every robot, then release them (the start of a run)
        run("rostopic pub -1 /flock/freeze swarm_transport/Robot_Freeze "
            "'{robot_index_from: 0, robot_index_to: 25}'")
        self.wait_for(lambda: 'frozen: True' in run('rosservice call /robot_0/robot/state').stdout,
                      'frozen robot 0')
        run("rostopic pub -1 /flock/continue swarm_transport/Robot_Continue "
            "'{robot_index_from: 0, robot_index_to: 25}'")
        self.wait_for(lambda: 'frozen: False' in run('rosservice call /robot_0/robot/state').stdout,
                      'released robot 0')

    def test_2_a_leader_only_mission_ends_done_at_its_target(self):
        self.wait_for(lambda: self.ids() == list(range(self.robots)), 'robot on /flock/world_poses')
        me = [r for r in self.positions.robots if r.robot_id == 0][0]
        tx, ty = min(me.pos_x + 1.5, 9.0), min(me.pos_y + 1.5, 9.0)
        out = run('rosservice call /mission_dispatcher/submit "{mission: {mission_id: 3, '
                  'robot_index_from: 0, robot_index_to: 1, leader_number: 1, target_x: %.2f, '
                  'target_y: %.2f}}"' % (tx, ty)).stdout
        self.assertIn('code: 0', out)
        self.wait_for(lambda: any(s.mission_id == 3 and s.state == Mission_Status.DONE
                                  for s in self.statuses), 'DONE of mission 3')
        me = [r for r in self.positions.robots if r.robot_id == 0][0]
        self.assertLess(math.hypot(me.pos_x - tx, me.pos_y - ty),
                        rospy.get_param('~goal_tolerance_m'))

    def test_3_a_lost_link_leaves_the_swarm(self):
        self.wait_for(lambda: 1 in self.ids(), 'robot 1 on /flock/world_poses')
        run('rosnode kill /robot_1/robot')
        self.wait_for(lambda: 1 not in self.ids(), 'robot 1 leaving /flock/world_poses')


if __name__ == '__main__':
    rostest.rosrun('swarm_transport', 'hardware_launch', HardwareLaunch)
