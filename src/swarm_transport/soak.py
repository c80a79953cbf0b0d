"""scripts/soak (issue 29): a real-time swarm run for --minutes with about three transport
missions live at all times and faults drawn from --seed arriving while others are still being
handled: SIGKILL of a robot and its respawn (/kill, /spawn, robot.launch), SIGSTOP of a robot for
2 s, SIGKILL and restart of the dispatcher and of the recorder, a burst of radio loss (the
simulator's radio_loss, dynamic_reconfigure, for 10 s) and a flood of 500 invalid orders
(--faults: only some of these kinds).

It prints progress every --progress-s and ends with one line
  RESULT missions= done= aborted= unfinished= hung= lost_rows= duplicate_rows= crashes= rss_growth_pct=
         fd_growth= faults=
and writes soak.log (every fault and its effect), result.json and the recorder's files under
--out. Figures only: the exit status is 0 when the run itself worked (docs/reliability.md)."""

import argparse
import json
import os
import signal
import sys
import time

from swarm_transport import st_ros
from swarm_transport.soak_faults import ALL_KINDS, EXTRA_KINDS, KINDS


def parse_args(argv):
    p = argparse.ArgumentParser(prog='scripts/soak', description=__doc__,
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument('--minutes', type=float, default=60.0, help='faults and missions (default 60)')
    p.add_argument('--seed', type=int, default=1, help='placement, missions and faults')
    p.add_argument('--robots', type=int, default=25, help='robot processes (default 25)')
    p.add_argument('--deploy', choices=('process', 'host'), default='process')
    p.add_argument('--live', type=int, default=3, help='transport missions kept live (3)')
    p.add_argument('--mission-robots', type=int, default=6, help='robots per mission (6)')
    p.add_argument('--gap-s', type=float, nargs=2, default=(20.0, 50.0), metavar=('MIN', 'MAX'),
                   help='seconds between faults, drawn uniformly (20 50)')
    p.add_argument('--warmup-s', type=float, default=300.0,
                   help='memory and descriptors are compared from this age of a process on '
                        '(default 300; shorter soaks use a third of their length)')
    p.add_argument('--hung-s', type=float, default=240.0,
                   help='a live mission without progress (a new state, its object 5 cm nearer '
                        'the target, more robots inside) for this long is hung (240)')
    p.add_argument('--drain-s', type=float, default=120.0,
                   help='after the last fault, seconds for the live missions to end (120)')
    p.add_argument('--progress-s', type=float, default=30.0)
    p.add_argument('--out', default='', help='directory of the log, result and recorder files')
    p.add_argument('--hung-max', type=int, default=0,
                   help='--junit: the hung check fails above this many hung missions (0)')
    p.add_argument('--fd-growth-max', type=int, default=20,
                   help='--junit: the descriptors check fails when a long-lived node opened more '
                        'than this many descriptors after its warm-up (20: flat but for the ~5 '
                        'connections of a dispatcher or recorder restarting at a sample)')
    p.add_argument('--faults', default='',
                   help='the fault kinds to inject, comma-separated (default: all of %s); e.g. '
                        'robot_stop,radio_loss,flood for an hour without node restarts; also %s '
                        '(SIGKILL and respawn of the first leader of a mission in GATHERING, the '
                        'next one to gather if none is)'
                        % (', '.join(KINDS), ', '.join(EXTRA_KINDS)))
    p.add_argument('--first-fault-s', type=float, default=30.0,
                   help='seconds of missions before the first fault (30)')
    p.add_argument('--junit', default='',
                   help='also write the checks of a bounded soak (scripts/test) as JUnit XML: '
                        'no mission hung, no crash, no mission row lost or written twice, every '
                        'fault kind injected with its effect, missions DONE, descriptors flat')
    a = p.parse_args(argv)
    if not (a.minutes > 0 and a.robots >= a.mission_robots >= 2 and a.live >= 1
            and 0 < a.gap_s[0] <= a.gap_s[1]):
        p.error('need --minutes > 0, --robots >= --mission-robots >= 2, --live >= 1 and '
                '0 < gap MIN <= MAX')
    kinds = [k.strip() for k in a.faults.split(',')] if a.faults.strip() else list(KINDS)
    unknown = [k for k in kinds if k not in ALL_KINDS]
    if unknown or len(set(kinds)) != len(kinds):
        p.error('--faults %r: a comma-separated list of distinct kinds of %s%s'
                % (a.faults, ', '.join(ALL_KINDS),
                   ' (unknown: %s)' % ', '.join(repr(k) for k in unknown) if unknown else ''))
    a.faults = tuple(k for k in ALL_KINDS if k in kinds)  # the schedule's order is ALL_KINDS'
    a.warmup_s = min(a.warmup_s, a.minutes * 60.0 / 3.0)
    if not a.out:
        a.out = os.path.join(st_ros.WS, 'soak', 'seed%d-%d' % (a.seed, int(time.time())))
    a.out = os.path.abspath(a.out)
    if os.path.isdir(a.out) and os.listdir(a.out):
        p.error('--out %s is not empty: a soak counts the recorder rows of its own run only'
                % a.out)
    return a


def main(argv=None):
    a = parse_args(sys.argv[1:] if argv is None else argv)
    os.makedirs(a.out, exist_ok=True)
    out_log = open(os.path.join(a.out, 'soak.log'), 'w')
    t_start = time.time()

    def log(text):
        line = '[%7.1f s] %s' % (time.time() - t_start, text)
        out_log.write(line + '\n')
        out_log.flush()
        st_ros.log(line)

    from swarm_transport.soak_run import Run
    with st_ros.PrivateRos(log_dir=os.path.join(a.out, 'logs')) as ros:
        run = Run(a, ros, log)
        try:
            result = run.go()
        except Exception as e:  # noqa: BLE001 - the run broke: said, and a failed RESULT
            log('the soak itself failed: %r' % e)
            result = dict(run.result(), ok=False, error=repr(e))
        finally:
            run.stop()
    result['out'] = a.out
    with open(os.path.join(a.out, 'result.json'), 'w') as f:
        json.dump(result, f, indent=1, sort_keys=True)
    keys = ('missions', 'done', 'aborted', 'unfinished', 'hung', 'lost_rows', 'duplicate_rows', 'crashes',
            'rss_growth_pct', 'fd_growth', 'faults')
    line = 'RESULT ' + ' '.join('%s=%s' % (k, result[k]) for k in keys)
    out_log.write(line + '\n')
    out_log.close()
    print(line)
    if a.junit:
        failed = write_junit(a.junit, checks(result, a.hung_max, a.fd_growth_max))
        return 1 if failed or not result.get('ok') else 0
    return 0 if result.get('ok') else 1


def checks(result, hung_max=0, fd_growth_max=20):
    """(name, failure or '') of what a soak must show (issue 29); at most `hung_max` hung
    missions pass, and a node's descriptors may grow by `fd_growth_max` after its warm-up."""
    faults = result['fault_log']
    asked = sorted(result.get('fault_kinds') or KINDS)
    kinds = sorted(set(f['kind'] for f in faults))
    bad_effects = ['%s at %s s: %s' % (f['kind'], f['at_s'], f['effect'] or 'no effect read')
                   for f in faults if not f['effect'] or 'NOT back' in f['effect']
                   or 'does not answer' in f['effect'] or 'failed' in f['effect']]
    out = [
        ('soak_ran', '' if result.get('ok') else result.get('error', 'the soak failed')),
        ('no_mission_hung', '' if result['hung'] <= hung_max else
         '%d missions hung (at most %d allowed)' % (result['hung'], hung_max)),
        ('no_crash', '' if result['crashes'] == 0 else '%d nodes crashed' % result['crashes']),
        ('no_mission_row_lost', '' if result['lost_rows'] == 0 else
         '%d ended missions have no row in missions.csv' % result['lost_rows']),
        ('no_mission_row_twice', '' if result['duplicate_rows'] == 0 else
         '%d mission rows written twice' % result['duplicate_rows']),
        ('every_fault_kind_injected', '' if kinds == asked else
         'injected only %s of %s' % (', '.join(kinds), ', '.join(asked))),
        ('every_fault_had_its_effect', '; '.join(bad_effects)),
        ('missions_done', '' if result['done'] >= 1 else 'no mission ended DONE'),
        ('descriptors_flat', '' if result['fd_growth'] <= fd_growth_max else
         '%s opened %d descriptors after its warm-up (at most %d allowed)'
         % (result.get('fd_growth_node', '?'), result['fd_growth'], fd_growth_max)),
    ]
    return out


def write_junit(path, cases):
    from xml.sax.saxutils import quoteattr
    body = ''
    for name, failure in cases:
        inner = '<failure message=%s/>' % quoteattr(failure) if failure else ''
        body += '<testcase classname="soak" name="%s">%s</testcase>' % (name, inner)
    failed = sum(1 for _, f in cases if f)
    os.makedirs(os.path.dirname(os.path.abspath(path)), exist_ok=True)
    with open(path, 'w') as f:
        f.write('<?xml version="1.0" encoding="utf-8"?>\n<testsuite name="soak" tests="%d" '
                'failures="%d" errors="0">%s</testsuite>\n' % (len(cases), failed, body))
    return failed


if __name__ == '__main__':
    signal.signal(signal.SIGINT, signal.default_int_handler)
    sys.exit(main())
