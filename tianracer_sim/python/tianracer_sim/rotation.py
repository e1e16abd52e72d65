"""Rotations as ROS messages carry them (REP-103), for the tests and scripts: yaw from a
quaternion, a quaternion from roll, pitch and yaw."""
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
