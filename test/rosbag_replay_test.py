#!/usr/bin/env python3
"""rosbag record and replay (issue 13): a short lock-step run with a transport mission is
recorded (swarm.launch record:=true) while the recorder computes its metrics live; the bag is
then played into a recorder alone (replay.launch), which must write the same swarm counts and
mission rows as the live one."""

import os
import shutil
import sys
import tempfile
import unittest

import rospy
import rostest
from swarm_transport.msg import New_Mission

import swarm_testing as st


def g(key):
    return rospy.get_param('~' + key)


def read(path):
    with open(path) as f:
        return f.read()


class RosbagReplay(unittest.TestCase):

    def test_a_replayed_run_gives_the_live_metrics(self):
        tmp = tempfile.mkdtemp(prefix='rosbag_replay_')
        self.addCleanup(shutil.rmtree, tmp, True)
        bag = os.path.join(tmp, 'run.bag')
        timeout = g('timeout_s')
        status = st.StatusLog()
        pub = rospy.Publisher('/flock/mission/new', New_Mission, queue_size=10)
        live = st.launch_swarm(robots=g('robots'), seed=g('seed'), lockstep=True,
                               max_ticks=g('ticks'), recorder=True, record_dir=tmp,
                               run_name='live', record=True, bag=bag)
        try:
            order = st.mission(5, 0, 4, 1, (7.0, 7.0, 1.0, 1.0), (4.0, 7.0))
            self.assertEqual(st.submit_before_first_tick(pub, order, timeout), '')
            log = st.PositionLog()
            self.assertTrue(log.wait_tick(g('ticks'), timeout), 'the run did not reach its end')
            log.close()
            self.assertEqual(status.states(5)[-1], 'DONE', status.states(5))
        finally:
            live.shutdown()  # the recorder writes its files, rosbag closes the bag
        self.assertTrue(st.wait_for(lambda: os.path.exists(bag), timeout), os.listdir(tmp))
        # The bag's stamps are simulated time (lock-step): play it faster than recorded.
        replay = st.launch_file('replay.launch', bag=bag, record_dir=tmp, run_name='replay',
                                seed=g('seed'), rate=g('replay_rate'))
        try:
            # The launch ends when the bag is played out (the player is required).
            self.assertTrue(st.wait_for(lambda: replay.pm.is_shutdown, timeout),
                            'the replay did not end')
        finally:
            replay.shutdown()
        for name in ('swarm_count.csv', 'missions.csv'):
            a = read(os.path.join(tmp, 'live', name))
            b = read(os.path.join(tmp, 'replay', name))
            self.assertGreater(len(a.splitlines()), 1, '%s has no rows' % name)
            self.assertEqual(a, b, '%s differs between the live run and its replay' % name)


if __name__ == '__main__':
    rospy.init_node('rosbag_replay_test')
    rostest.rosrun('swarm_transport', 'rosbag_replay', RosbagReplay, sys.argv)
