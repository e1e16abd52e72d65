"""Rotations as ROS messages carry them (REP-103), for the tests and scripts: yaw from a
quaternion, a quaternion from roll, pitch and yaw, angles wrapped, and how a body moved in the
plane."""
import math


def yaw_from_quaternion(q):
    """Yaw (rad) of a quaternion with fields x, y, z, w (REP-103: about z, from x towards y)."""
    return math.atan2(2.0 * (q.w * q.z + q.x * q.y), 1.0 - 2.0 * (q.y * q.y + q.z * q.z))


def quaternion_from_rpy(roll, pitch, yaw):
    """(x, y, z, w) of R = Rz(yaw) Ry(pitch) Rx(roll), as URDF, tf and gazebo_ros spawn_model
    use it."""
    cr, sr = math.cos(roll / 2), math.sin(roll / 2)
    cp, sp = math.cos(pitch / 2), math.sin(pitch / 2)
    cy, sy = math.cos(yaw / 2), math.sin(yaw / 2)
    return (sr * cp * cy - cr * sp * sy,
            cr * sp * cy + sr * cp * sy,
            cr * cp * sy - sr * sp * cy,
            cr * cp * cy + sr * sp * sy)


def wrap_angle(a):
    """a wrapped into [-pi, pi]."""
    return math.atan2(math.sin(a), math.cos(a))


def planar_motion(poses):
    """Mean forward speed (along the heading) and yaw rate of [(t, Pose)] in time order."""
    path = turned = 0.0
    for (_, p0), (_, p1) in zip(poses, poses[1:]):
        yaw = yaw_from_quaternion(p0.orientation)
        dx, dy = p1.position.x - p0.position.x, p1.position.y - p0.position.y
        path += dx * math.cos(yaw) + dy * math.sin(yaw)
        turned += wrap_angle(yaw_from_quaternion(p1.orientation) - yaw)
    span = poses[-1][0] - poses[0][0]
    return path / span, turned / span
