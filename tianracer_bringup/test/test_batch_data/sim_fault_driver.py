#!/usr/bin/env python3
"""A driver that breaks the simulator of its own run, to test how `batch` reports it: it drives
straight (one latched /cmd_vel), and at `_at` s of sim time it sends the run's simulator node
(the tianracer_sim_node process carrying this run's TIANRACER_BATCH_RUN token) `_fault`:
crash = SIGSEGV (the simulator crashes), hang = SIGSTOP (the simulator stops advancing)."""
import os
import signal
import sys

import rospy
from geometry_msgs.msg import Twist
from rosgraph_msgs.msg import Clock

TOKEN_VAR = 'TIANRACER_BATCH_RUN'


def simulator_pids(token):
    needle = ('%s=%s' % (TOKEN_VAR, token)).encode()
    out = []
    for entry in os.listdir('/proc'):
        if not entry.isdigit():
            continue
        try:
            with open('/proc/%s/environ' % entry, 'rb') as f:
                if needle not in f.read().split(b'\0'):
                    continue
            with open('/proc/%s/cmdline' % entry, 'rb') as f:
                argv0 = f.read().split(b'\0')[0]
        except OSError:
            continue
        if os.path.basename(argv0) == b'tianracer_sim_node':
            out.append(int(entry))
    return out


def main():
    rospy.init_node('sim_fault_driver')
    fault = rospy.get_param('~fault')
    at = float(rospy.get_param('~at', 1.0))
    sig = {'crash': signal.SIGSEGV, 'hang': signal.SIGSTOP}[fault]
    token = os.environ[TOKEN_VAR]
    done = []

    def on_clock(msg):
        if not done and msg.clock.to_sec() >= at:
            pids = simulator_pids(token)
            if len(pids) != 1:
                rospy.logfatal('expected one simulator of this run, found %s', pids)
                rospy.signal_shutdown('no simulator')
                return
            rospy.loginfo('sending %s to the simulator (pid %d) at %.3f s', sig.name, pids[0],
                          msg.clock.to_sec())
            os.kill(pids[0], sig)
            done.append(True)

    rospy.Subscriber('/clock', Clock, on_clock)
    pub = rospy.Publisher('/cmd_vel', Twist, queue_size=1, latch=True)
    cmd = Twist()
    cmd.linear.x = 0.5
    pub.publish(cmd)
    rospy.spin()
    return 0


if __name__ == '__main__':
    sys.exit(main())
