#!/usr/bin/env python3
"""PyBullet 3.2.7 doing the simulator's work, for the side-by-side benchmark (docs/benchmarks.md).

Same URDF (xacro-expanded, package:// paths made absolute), same world geometry (the .world's
static boxes, cylinders and spheres plus a ground plane), a 1 ms step with 20 solver iterations,
the same controller targets (rear wheels by velocity with force 10, hinges by position) and the
same sensor schedule: rayTestBatch of 1081 rays every 40 ms; getCameraImage with ER_TINY_RENDERER
at 800x800 every 1/30 s and at 640x480 every 1/20 s, the latter turned into a point cloud with
numpy. Prints one JSON object (rtf, wall, counts) on stdout.

    pybullet_bench.py --urdf robot.urdf --world racetrack.world --sensors lidar,camera,depth --duration 20
"""
import argparse
import json
import math
import os
import sys
import time
import xml.etree.ElementTree as ET

import numpy as np
import pybullet as p

STEP = 0.001
LIDAR = dict(samples=1081, min_angle=-2.3561944902, max_angle=2.3561944902, min_range=0.1,
             max_range=10.0, z_offset=0.0124, period=1.0 / 40.0, link="lidar")
CAMERA = dict(width=800, height=800, hfov=1.3962634, near=0.02, far=300.0, period=1.0 / 30.0,
              link="camera")
DEPTH = dict(width=640, height=480, hfov=1.0466666666666666, near=0.05, far=8.0, period=1.0 / 20.0,
             link="real_sense")
EYE_OFFSET = 0.02
SENSORS = ("lidar", "camera", "depth")


def parse_pose(text):
    v = [float(x) for x in (text or "").split()] if text else []
    v += [0.0] * (6 - len(v))
    return np.array(v[:3]), p.getQuaternionFromEuler(v[3:6])


def compose(a, b):
    pos, orn = p.multiplyTransforms(a[0], a[1], b[0], b[1])
    return np.array(pos), orn


def world_shapes(world_file):
    """(kind, size, position, orientation, collide) of every box/cylinder/sphere of the world's models."""
    root = ET.parse(world_file).getroot()
    shapes = []
    for model in root.iter("model"):
        X_WM = parse_pose(model.findtext("pose"))
        for link in model.findall("link"):
            X_WL = compose(X_WM, parse_pose(link.findtext("pose")))
            for tag, collide in (("collision", True), ("visual", False)):
                for g in link.findall(tag):
                    X_WG = compose(X_WL, parse_pose(g.findtext("pose")))
                    geom = g.find("geometry")
                    if geom is None:
                        continue
                    for kind in ("box", "cylinder", "sphere"):
                        e = geom.find(kind)
                        if e is None:
                            continue
                        if kind == "box":
                            size = [float(x) for x in e.findtext("size").split()]
                        elif kind == "cylinder":
                            size = [float(e.findtext("radius")), float(e.findtext("length"))]
                        else:
                            size = [float(e.findtext("radius"))]
                        shapes.append((kind, size, X_WG[0], X_WG[1], collide))
    return shapes


def add_world(world_file):
    # PyBullet has no visual plane: the ground is drawn as a 100 m square, 1 cm thick.
    plane = p.createCollisionShape(p.GEOM_PLANE)
    ground = p.createVisualShape(p.GEOM_BOX, halfExtents=[50, 50, 0.005], visualFramePosition=[0, 0, -0.005],
                                 rgbaColor=[0.8, 0.8, 0.8, 1])
    p.createMultiBody(0, plane, ground, [0, 0, 0])
    if not world_file:
        return 0
    n = 0
    for kind, size, pos, orn, collide in world_shapes(world_file):
        # SDF lists collision and visual separately: one body each (collision-only bodies are
        # not drawn, visual-only bodies do not collide), as in our simulator.
        col = vis = -1
        if kind == "box":
            half = [s / 2 for s in size]
            if collide:
                col = p.createCollisionShape(p.GEOM_BOX, halfExtents=half)
            else:
                vis = p.createVisualShape(p.GEOM_BOX, halfExtents=half, rgbaColor=[0.8, 0.2, 0.2, 1])
        elif kind == "cylinder":
            if collide:
                col = p.createCollisionShape(p.GEOM_CYLINDER, radius=size[0], height=size[1])
            else:
                vis = p.createVisualShape(p.GEOM_CYLINDER, radius=size[0], length=size[1],
                                          rgbaColor=[1, 0.5, 0, 1])
        else:
            if collide:
                col = p.createCollisionShape(p.GEOM_SPHERE, radius=size[0])
            else:
                vis = p.createVisualShape(p.GEOM_SPHERE, radius=size[0])
        p.createMultiBody(0, col, vis, list(pos), list(orn))
        n += 1
    return n


def load_robot(urdf):
    robot = p.loadURDF(urdf, [0, 0, 1.0], flags=p.URDF_USE_INERTIA_FROM_FILE)
    # Wheels on the ground, as the simulator's z:=auto does.
    min_z = min(p.getAABB(robot, i)[0][2] for i in range(-1, p.getNumJoints(robot)))
    p.resetBasePositionAndOrientation(robot, [0, 0, 1.0 - min_z + 1e-4], [0, 0, 0, 1])
    joints, links = {}, {}
    for j in range(p.getNumJoints(robot)):
        info = p.getJointInfo(robot, j)
        joints[info[1].decode()] = j
        links[info[12].decode()] = j
    return robot, joints, links


def link_pose(robot, link):
    s = p.getLinkState(robot, link, computeForwardKinematics=True)
    return np.array(s[4]), np.array(p.getMatrixFromQuaternion(s[5])).reshape(3, 3)


class Lidar:
    def __init__(self, robot, link):
        self.robot, self.link = robot, link
        a = np.linspace(LIDAR["min_angle"], LIDAR["max_angle"], LIDAR["samples"])
        self.dirs = np.stack([np.cos(a), np.sin(a), np.zeros_like(a)], axis=1)

    def scan(self):
        pos, R = link_pose(self.robot, self.link)
        origin = pos + R[:, 2] * LIDAR["z_offset"]
        d = self.dirs @ R.T
        hits = p.rayTestBatch((origin + d * LIDAR["min_range"]).tolist(),
                              (origin + d * LIDAR["max_range"]).tolist())
        return np.array([LIDAR["min_range"] + h[2] * (LIDAR["max_range"] - LIDAR["min_range"])
                         if h[0] >= 0 else math.inf for h in hits], dtype=np.float32)


class Camera:
    def __init__(self, robot, link, cfg, cloud):
        self.robot, self.link, self.cfg, self.cloud = robot, link, cfg, cloud
        w, h = cfg["width"], cfg["height"]
        self.vfov = 2 * math.atan(math.tan(cfg["hfov"] / 2) * h / w)
        self.proj = p.computeProjectionMatrixFOV(math.degrees(self.vfov), w / h, cfg["near"], cfg["far"])
        if cloud:
            fx = (w / 2) / math.tan(cfg["hfov"] / 2)
            u, v = np.meshgrid(np.arange(w) + 0.5 - w / 2, np.arange(h) + 0.5 - h / 2)
            self.rx, self.ry = (u / fx).astype(np.float32), (v / fx).astype(np.float32)

    def render(self):
        pos, R = link_pose(self.robot, self.link)
        forward, up = R[:, 0], R[:, 2]
        # TinyRenderer does not clip at the near plane and hangs (minutes per frame) on triangles
        # through the eye: the seed's real_sense origin lies on its own mesh. The eye moves 2 cm
        # forward, out of the camera's housing.
        pos = pos + forward * EYE_OFFSET
        view = p.computeViewMatrix(pos.tolist(), (pos + forward).tolist(), up.tolist())
        c = self.cfg
        _, _, rgba, depth, _ = p.getCameraImage(c["width"], c["height"], view, self.proj,
                                                renderer=p.ER_TINY_RENDERER)
        rgb = np.asarray(rgba, dtype=np.uint8).reshape(c["height"], c["width"], 4)[:, :, :3]
        if not self.cloud:
            return rgb
        zbuf = np.asarray(depth, dtype=np.float32).reshape(c["height"], c["width"])
        n, f = c["near"], c["far"]
        z = f * n / (f - (f - n) * zbuf)  # metric depth along the optical axis
        z[zbuf >= 1.0] = np.nan
        # Organized XYZRGB cloud in the optical frame (x right, y down, z forward).
        cloud = np.stack([self.rx * z, self.ry * z, z], axis=-1)
        colors = rgb.astype(np.uint32)
        packed = (colors[..., 0] << 16) | (colors[..., 1] << 8) | colors[..., 2]
        return cloud, packed


def run(urdf, world, kinds, duration, wheel_omega, steer, max_wall):
    p.connect(p.DIRECT)
    p.setGravity(0, 0, -9.8)
    p.setPhysicsEngineParameter(fixedTimeStep=STEP, numSolverIterations=20)
    n_world = add_world(world)
    robot, joints, links = load_robot(urdf)
    for name, j in joints.items():
        if p.getJointInfo(robot, j)[2] != p.JOINT_FIXED:  # free joints: no default motor
            p.setJointMotorControl2(robot, j, p.VELOCITY_CONTROL, targetVelocity=0, force=0)
    for name in ("left_rear_wheel_joint", "right_rear_wheel_joint"):
        p.setJointMotorControl2(robot, joints[name], p.VELOCITY_CONTROL, targetVelocity=wheel_omega, force=10)
    for name in ("left_steering_hinge_joint", "right_steering_hinge_joint"):
        p.setJointMotorControl2(robot, joints[name], p.POSITION_CONTROL, targetPosition=steer, force=10)
    sensors = []
    if "lidar" in kinds:
        sensors.append(["lidar", LIDAR["period"], Lidar(robot, links[LIDAR["link"]]).scan])
    if "camera" in kinds:
        sensors.append(["camera", CAMERA["period"], Camera(robot, links[CAMERA["link"]], CAMERA, False).render])
    if "depth" in kinds:
        sensors.append(["depth", DEPTH["period"], Camera(robot, links[DEPTH["link"]], DEPTH, True).render])
    counts = {s[0]: 0 for s in sensors}
    sensor_cpu = {s[0]: 0.0 for s in sensors}
    next_due = {s[0]: 0.0 for s in sensors}
    steps = int(round(duration / STEP))
    cpu0, wall0 = time.process_time(), time.perf_counter()
    i = 0
    while i < steps:
        i += 1
        p.stepSimulation()
        t = i * STEP
        for name, period, fn in sensors:
            if t + 1e-9 >= next_due[name]:
                next_due[name] += period
                c = time.process_time()
                fn()
                sensor_cpu[name] += time.process_time() - c
                counts[name] += 1
        # A wall-time cap (checked every 0.1 s of sim): the rate is measured over what ran.
        if max_wall and i % 100 == 0 and time.perf_counter() - wall0 > max_wall:
            break
    wall = time.perf_counter() - wall0
    cpu = time.process_time() - cpu0
    base, _ = p.getBasePositionAndOrientation(robot)
    p.disconnect()
    return dict(sensors=list(kinds), sim_seconds=i * STEP, requested_sim_seconds=steps * STEP, wall_seconds=wall,
                rtf=i * STEP / wall, cpu_seconds=cpu, cpu_cores=cpu / wall, counts=counts,
                sensor_cpu_ms_each={k: 1000 * v / max(1, counts[k]) for k, v in sensor_cpu.items()},
                world_shapes=n_world, final_base_xy=list(base[:2]), pybullet_version=p.getAPIVersion())


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--urdf", required=True, help="URDF with absolute mesh paths")
    ap.add_argument("--world", default="", help="SDF .world (boxes, cylinders, spheres are used)")
    ap.add_argument("--sensors", default="", help="comma-separated subset of %s (default: none)" % ",".join(SENSORS))
    ap.add_argument("--duration", type=float, default=20.0, help="sim seconds")
    ap.add_argument("--wheel-omega", type=float, default=1.0 / 0.032, help="rear wheel rad/s")
    ap.add_argument("--steer", type=float, default=0.2, help="hinge angle, rad")
    ap.add_argument("--max-wall", type=float, default=0.0, help="stop after this many wall seconds (0: never)")
    a = ap.parse_args()
    kinds = [k for k in a.sensors.split(",") if k]
    for k in kinds:
        if k not in SENSORS:
            ap.error("unknown sensor '%s' (known: %s)" % (k, ", ".join(SENSORS)))
    res = run(a.urdf, a.world, kinds, a.duration, a.wheel_omega, a.steer, a.max_wall)
    with open("/proc/self/status") as f:
        for line in f:
            if line.startswith("VmHWM:"):
                res["peak_rss_mb"] = int(line.split()[1]) / 1024.0
    json.dump(res, sys.stdout)
    print()


if __name__ == "__main__":
    main()
