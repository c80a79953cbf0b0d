"""Shared helpers of the scenario rostests: launch a swarm inside the test's master, follow
the aggregated /flock/positions stream, wait on conditions with timeouts (never fixed sleeps)."""

import math
import threading
import time

import rospkg
import rospy
import roslaunch
from swarm_transport.msg import Robot_Positions


def launch_swarm(**args):
    """Starts launch/swarm.launch with the given args in the running master; returns the
    parent (call .shutdown())."""
    path = rospkg.RosPack().get_path('swarm_transport') + '/launch/swarm.launch'
    cli = ['%s:=%s' % (k, str(v).lower() if isinstance(v, bool) else v) for k, v in args.items()]
    uuid = roslaunch.rlutil.get_or_generate_uuid(None, False)
    parent = roslaunch.parent.ROSLaunchParent(uuid, [(path, cli)], is_core=False)
    parent.start()
    return parent


class PositionLog(object):
    """Every /flock/positions message by tick (the simulator's ground truth)."""

    def __init__(self):
        self.lock = threading.Lock()
        self.by_tick = {}
        self.last = None
        self.sub = rospy.Subscriber('/flock/positions', Robot_Positions, self._cb,
                                    queue_size=10000, tcp_nodelay=True)

    def _cb(self, msg):
        with self.lock:
            self.by_tick[msg.tick] = {r.robot_id: (r.pos_x, r.pos_y, r.angle)
                                      for r in msg.robots if r.type == 0}
            self.last = msg

    def latest_tick(self):
        with self.lock:
            return -1 if self.last is None else self.last.tick

    def wait_tick(self, tick, timeout):
        deadline = time.time() + timeout
        while time.time() < deadline and not rospy.is_shutdown():
            if self.latest_tick() >= tick:
                return True
            time.sleep(0.01)
        return False

    def at(self, tick):
        with self.lock:
            return dict(self.by_tick.get(tick, {}))

    def ticks(self):
        with self.lock:
            return sorted(self.by_tick)

    def close(self):
        self.sub.unregister()


def wait_for(predicate, timeout, period=0.02):
    deadline = time.time() + timeout
    while time.time() < deadline and not rospy.is_shutdown():
        if predicate():
            return True
        time.sleep(period)
    return predicate()


def moved(a, b):
    return math.hypot(a[0] - b[0], a[1] - b[1])
