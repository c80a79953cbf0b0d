"""What robots say of themselves, for a failed test's message and the soak's log of a hung
mission: where each stands (one /flock/world_poses) and its ~describe, asked without letting
a stopped robot hold the caller."""

import threading


def ask_describe(node, timeout=2.0):
    """`node`'s ~describe (e.g. node '/robot_3/robot'), or why there is none. A stopped process
    accepts the call and never answers: the call runs in a thread of its own, given `timeout`."""
    import rospy
    from std_srvs.srv import Trigger
    said = ['no answer within %.0f s' % timeout]

    def ask():
        try:
            said[0] = rospy.ServiceProxy(node + '/describe', Trigger)().message
        except Exception as e:  # noqa: BLE001 - dead, restarting or never there: say so
            said[0] = 'no answer (%s)' % type(e).__name__

    asking = threading.Thread(target=ask, daemon=True)
    asking.start()
    asking.join(timeout)
    return said[0]


def world_poses(timeout=2.0):
    """{robot id: Robot_Position} of one /flock/world_poses message (physical robots only);
    raises what rospy raises when none comes within `timeout`."""
    import rospy
    from swarm_transport.msg import Robot_Positions
    world = rospy.wait_for_message('/flock/world_poses', Robot_Positions, timeout=timeout)
    return {p.robot_id: p for p in world.robots if p.sub_id == 0}


def pose_text(p):
    return '(%.2f, %.2f, %.0f deg)' % (p.pos_x, p.pos_y, p.angle)


def describe_robots(robot_ids, timeout=2.0):
    """One line per robot: where it stands and what it says of itself."""
    try:
        poses = world_poses(timeout)
    except Exception:  # noqa: BLE001 - a stopped simulator: every robot is unlisted
        poses = {}
    return '\n'.join('robot %d at %s: %s' % (
        rid, pose_text(poses[rid]) if rid in poses else '(not listed)',
        ask_describe('/robot_%d/robot' % rid, timeout)) for rid in robot_ids)
