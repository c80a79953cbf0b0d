#!/usr/bin/env python3
"""Runs inside the core network namespace of test/across_hosts_hardware.test, on the hardware
deployment: waits until the positions node hears every robot (/flock/world_poses), submits
the missions it is given one after the other (each once the one before ended and every robot
is heard again), and, with --partition, takes that veth of the core down for --down-s from the
first mission's TRANSPORT on. It prints, with wall times:
  READY <wall>                               every robot heard (again)
  SUBMIT <id> <code> <wall> <message>        the dispatcher's answer
  STATUS <id> <state> <tick> <wall> <reason> /flock/mission/status
  PROGRESS <id> <state> <wall> <reason>      /flock/mission/progress, when its reason changes
  DOWN <wall> / UP <wall>                    the partition
  HEARD <wall> <ids,...>                     the robots on /flock/world_poses, when they change
  STATS <line>                               each robot's last ~diagnostics line at the end
Exits 0 when every mission ended (DONE, ABORTED or REJECTED), 2 on timeout.
usage: across_hosts_hw_watch.py --robots N --timeout S --mission ID,FROM,TO,LEADERS,OBJ,TX,TY
       [--mission ...] [--partition DEV --down-s S]   (OBJ: x:y:w:h or - for leader-only)"""

import argparse
import subprocess
import sys
import threading
import time

import rospy
from std_msgs.msg import String
from swarm_transport.msg import Mission_Status, New_Mission, Robot_Positions
from swarm_transport.srv import Submit_Mission

NAMES = {0: 'QUEUED', 1: 'GATHERING', 2: 'LOADING', 3: 'TRANSPORT', 4: 'UNLOADING', 5: 'DONE',
         6: 'ABORTED', 7: 'REJECTED'}
FINAL = (5, 6, 7)


def say(text):
    sys.stdout.write(text + '\n')
    sys.stdout.flush()


def order(spec):
    mid, lo, hi, leaders, obj, tx, ty = spec.split(',')
    m = New_Mission(mission_id=int(mid), robot_index_from=int(lo), robot_index_to=int(hi),
                    leader_number=int(leaders), target_x=float(tx), target_y=float(ty))
    if obj != '-':
        m.object_position_x, m.object_position_y, m.object_size_x, m.object_size_y = (
            float(v) for v in obj.split(':'))
    return m


def main():
    p = argparse.ArgumentParser()
    p.add_argument('--robots', type=int, required=True)
    p.add_argument('--timeout', type=float, required=True)
    p.add_argument('--mission', action='append', default=[])
    p.add_argument('--partition', default='')
    p.add_argument('--down-s', type=float, default=3.0)
    a = p.parse_args()
    rospy.init_node('across_hosts_watch', disable_signals=True)
    lock = threading.Lock()
    final, phases, listed, stats, reasons = {}, {}, [set()], {}, {}

    def on_status(msg):
        say('STATUS %d %s %d %.3f %s' % (msg.mission_id, NAMES.get(msg.state, msg.state),
                                         msg.tick, time.time(), msg.reason))
        with lock:
            phases.setdefault(msg.mission_id, []).append(msg.state)
            if msg.state in FINAL:
                final.setdefault(msg.mission_id, msg.state)

    def on_progress(msg):
        if reasons.get(msg.mission_id) != msg.reason:
            reasons[msg.mission_id] = msg.reason
            say('PROGRESS %d %s %.3f %s' % (msg.mission_id, NAMES.get(msg.state, msg.state),
                                            time.time(), msg.reason))

    def on_heard(msg):
        ids = set(r.robot_id for r in msg.robots if r.type == 0)
        if ids != listed[0]:
            listed[0] = ids
            say('HEARD %.3f %s' % (time.time(), ','.join(str(i) for i in sorted(ids))))

    def on_stats(msg):
        for line in msg.data.splitlines():
            stats[line.split()[0]] = line

    rospy.Subscriber('/flock/mission/status', Mission_Status, on_status, queue_size=1000)
    rospy.Subscriber('/flock/mission/progress', Mission_Status, on_progress, queue_size=1000)
    rospy.Subscriber('/flock/world_poses', Robot_Positions, on_heard, queue_size=10)
    rospy.Subscriber('/flock/robot_stats', String, on_stats, queue_size=1000)
    deadline = time.monotonic() + a.timeout

    def wait(cond):
        while not cond() and time.monotonic() < deadline:
            time.sleep(0.05)
        return cond()

    rospy.wait_for_service('/mission_dispatcher/submit', timeout=a.timeout)
    submit = rospy.ServiceProxy('/mission_dispatcher/submit', Submit_Mission)
    ok = True
    for k, spec in enumerate(a.mission):
        m = order(spec)
        if not wait(lambda: len(listed[0]) == a.robots):
            ok = False
            break
        say('READY %.3f' % time.time())
        time.sleep(2.0)  # every robot has heard every other
        res = submit(mission=m)
        say('SUBMIT %d %d %.3f %s' % (m.mission_id, res.code, time.time(), res.message))
        if k == 0 and a.partition:
            if wait(lambda: 3 in phases.get(m.mission_id, [])):
                subprocess.run(['ip', 'link', 'set', a.partition, 'down'], check=True)
                say('DOWN %.3f' % time.time())
                time.sleep(a.down_s)
                subprocess.run(['ip', 'link', 'set', a.partition, 'up'], check=True)
                say('UP %.3f' % time.time())
        if not wait(lambda: m.mission_id in final):
            ok = False
            break
    time.sleep(1.5)  # the last statistics lines
    for key in sorted(stats):
        say('STATS %s' % stats[key])
    return 0 if ok else 2


if __name__ == '__main__':
    sys.exit(main())
