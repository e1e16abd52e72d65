#!/usr/bin/env python3
"""PyBullet 3.2.7 doing the simulator's work, for the side-by-side benchmark (docs/benchmarks.md).

Same URDF (xacro-expanded, package:// paths made absolute), same world geometry (the .world's
boxes, cylinders and spheres plus a ground plane: static models static, the others free bodies
with the SDF's mass and inertia), a 1 ms step with 20 solver iterations, the same controller
targets (rear wheels by velocity with force 10, hinges by position) and the same sensor schedule:
rayTestBatch of 1081 rays every 40 ms (lidar) and of 16 x 1800 rays every 100 ms turned into the
velodyne plugin's cloud with numpy (lidar3d); getCameraImage with ER_TINY_RENDERER at 800x800
every 1/30 s and at 640x480 every 1/20 s, the latter turned into a point cloud with numpy. Prints
one JSON object (rtf, wall, counts, how many free models moved, each car's lap from its base
track: bench/lap.py) on stdout. --poses puts one car at each pose, each with its own sensors.

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

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import lap  # noqa: E402

STEP = 0.001
LIDAR = dict(samples=1081, min_angle=-2.3561944902, max_angle=2.3561944902, min_range=0.1,
             max_range=10.0, z_offset=0.0124, period=1.0 / 40.0, link="lidar")
CAMERA = dict(width=800, height=800, hfov=1.3962634, near=0.02, far=300.0, period=1.0 / 30.0,
              link="camera")
DEPTH = dict(width=640, height=480, hfov=1.0466666666666666, near=0.05, far=8.0, period=1.0 / 20.0,
             link="real_sense")
# bench/models/tianracer_lidar3d.xacro's velodyne: 16 rings over +-15 deg x 1800 beams over 360 deg
# (ray (j, i) at j * 1800 + i), 10 Hz, rays cast from range min to range max, the plugin's
# gaussianNoise added to each hit's range and the points kept strictly inside
# (max(min_range, range min), min(max_range, range max)), as our simulator's velodyne.
LIDAR3D = dict(samples=1800, min_angle=-3.14159265359, max_angle=3.13810199509, rings=16,
               min_vangle=-0.261799387799, max_vangle=0.261799387799, min_range=0.4, max_range=100.0,
               cloud_min_range=0.4, cloud_max_range=100.0, noise=0.008, z_offset=0.1, period=0.1, link="lidar")
# velodyne_gazebo_plugins' PointCloud2 point: x, y, z, intensity (FLOAT32 at 0, 4, 8, 16), ring
# (UINT16 at 20), 32 bytes.
VELODYNE_POINT = np.dtype(dict(names=["x", "y", "z", "intensity", "ring"],
                               formats=[np.float32, np.float32, np.float32, np.float32, np.uint16],
                               offsets=[0, 4, 8, 16, 20], itemsize=32))
EYE_OFFSET = 0.02
SENSORS = ("lidar", "lidar3d", "camera", "depth")
MOVED = 0.01  # m: a free model moved when its first link went farther than this from its start
TRACK_PERIOD = 0.02  # s: each car's base pose is sampled at ground truth odometry's 50 Hz


def parse_pose(text):
    v = [float(x) for x in (text or "").split()] if text else []
    v += [0.0] * (6 - len(v))
    return np.array(v[:3]), p.getQuaternionFromEuler(v[3:6])


def compose(a, b):
    pos, orn = p.multiplyTransforms(a[0], a[1], b[0], b[1])
    return np.array(pos), orn


def _is_static(model):
    return (model.findtext("static") or "").strip().lower() in ("true", "1")


def quat_from_matrix(R):
    """(x, y, z, w) of a rotation matrix."""
    t = np.trace(R)
    if t > 0:
        s = 2.0 * math.sqrt(t + 1.0)
        q = [(R[2, 1] - R[1, 2]) / s, (R[0, 2] - R[2, 0]) / s, (R[1, 0] - R[0, 1]) / s, 0.25 * s]
    else:
        i = int(np.argmax(np.diag(R)))
        j, k = (i + 1) % 3, (i + 2) % 3
        s = 2.0 * math.sqrt(1.0 + R[i, i] - R[j, j] - R[k, k])
        q = [0.0] * 4
        q[i] = 0.25 * s
        q[j] = (R[j, i] + R[i, j]) / s
        q[k] = (R[k, i] + R[i, k]) / s
        q[3] = (R[k, j] - R[j, k]) / s
    return tuple(q)


def link_inertial(link):
    """(mass, principal moments, X_LI) of a link's <inertial>, SDF's defaults (1 kg, unit
    inertia, the link frame) where absent. X_LI's axes are the principal axes: PyBullet takes a
    diagonal inertia only (changeDynamics' localInertiaDiagonal), so a full SDF tensor is
    diagonalised and the inertial frame turned onto its eigenvectors (the same body)."""
    e = link.find("inertial")
    mass, I, X_LI = 1.0, np.eye(3), (np.zeros(3), (0.0, 0.0, 0.0, 1.0))
    if e is not None:
        mass = float(e.findtext("mass") or 1.0)
        X_LI = parse_pose(e.findtext("pose"))
        i = e.find("inertia")
        if i is not None:
            def g(k, default):
                return float(i.findtext(k) or default)
            I = np.array([[g("ixx", 1), g("ixy", 0), g("ixz", 0)],
                          [g("ixy", 0), g("iyy", 1), g("iyz", 0)],
                          [g("ixz", 0), g("iyz", 0), g("izz", 1)]])
    moments, axes = np.linalg.eigh(I)
    if np.linalg.det(axes) < 0:
        axes[:, 2] = -axes[:, 2]
    return mass, moments, compose(X_LI, (np.zeros(3), quat_from_matrix(axes)))


def link_shapes(link):
    """(kind, size, X_LG, collide) of every box/cylinder/sphere collision and visual of a link."""
    shapes = []
    for tag, collide in (("collision", True), ("visual", False)):
        for g in link.findall(tag):
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
                shapes.append((kind, size, parse_pose(g.findtext("pose")), collide))
    return shapes


def world_models(world_file):
    """Every model of the world (nested ones as models of their own, named parent::child), as
    dict(name, static, links), each link dict(X_WL, inertial=(mass, moments, X_LI), shapes).
    A model is static with <static> true on it or on a model around it."""
    root = ET.parse(world_file).getroot()
    models = []

    def walk(model, X_WP, static, prefix):
        X_WM = compose(X_WP, parse_pose(model.findtext("pose")))
        static = static or _is_static(model)
        name = prefix + (model.get("name") or "")
        links = [dict(X_WL=compose(X_WM, parse_pose(link.findtext("pose"))), inertial=link_inertial(link),
                      shapes=link_shapes(link)) for link in model.findall("link")]
        models.append(dict(name=name, static=static, links=links))
        for sub in model.findall("model"):
            walk(sub, X_WM, static, name + "::")

    world_elems = [root] if root.tag == "world" else root.findall("world")
    for world in world_elems:
        for model in world.findall("model"):
            walk(model, (np.zeros(3), (0.0, 0.0, 0.0, 1.0)), False, "")
    return models


def _shape_args(kind, size):
    """createCollisionShapeArray / createVisualShapeArray entries of one shape."""
    if kind == "box":
        return p.GEOM_BOX, 0.0, [s / 2 for s in size], 0.0
    if kind == "cylinder":
        return p.GEOM_CYLINDER, size[0], [0.0, 0.0, 0.0], size[1]
    return p.GEOM_SPHERE, size[0], [0.0, 0.0, 0.0], 0.0


def add_static_shape(kind, size, X_WG, collide):
    # SDF lists collision and visual separately: one body each (collision-only bodies are
    # not drawn, visual-only bodies do not collide), as in our simulator.
    col = vis = -1
    pos, orn = X_WG
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
            vis = p.createVisualShape(p.GEOM_CYLINDER, radius=size[0], length=size[1], rgbaColor=[1, 0.5, 0, 1])
    else:
        if collide:
            col = p.createCollisionShape(p.GEOM_SPHERE, radius=size[0])
        else:
            vis = p.createVisualShape(p.GEOM_SPHERE, radius=size[0])
    p.createMultiBody(0, col, vis, list(pos), list(orn))


def add_free_link(link):
    """A moving link as one PyBullet body: its collisions and visuals together in the link frame,
    its SDF mass and inertia (inertial frame included). Sleeping is allowed, as Gazebo's
    auto-disable (on by default) and our simulator do for a model without joints."""
    arrays = {}
    for kind, size, (pos, orn), collide in link["shapes"]:
        a = arrays.setdefault(collide, dict(shapeTypes=[], radii=[], halfExtents=[], lengths=[], pos=[], orn=[]))
        t, r, h, length = _shape_args(kind, size)
        a["shapeTypes"].append(t)
        a["radii"].append(r)
        a["halfExtents"].append(h)
        a["lengths"].append(length)
        a["pos"].append(list(pos))
        a["orn"].append(list(orn))
    col = vis = -1
    if True in arrays:
        a = arrays[True]
        col = p.createCollisionShapeArray(a["shapeTypes"], radii=a["radii"], halfExtents=a["halfExtents"],
                                          lengths=a["lengths"], collisionFramePositions=a["pos"],
                                          collisionFrameOrientations=a["orn"])
    if False in arrays:
        a = arrays[False]
        vis = p.createVisualShapeArray(a["shapeTypes"], radii=a["radii"], halfExtents=a["halfExtents"],
                                       lengths=a["lengths"], visualFramePositions=a["pos"],
                                       visualFrameOrientations=a["orn"])
    mass, moments, (ipos, iorn) = link["inertial"]
    pos, orn = link["X_WL"]
    body = p.createMultiBody(mass, col, vis, list(pos), list(orn), baseInertialFramePosition=list(ipos),
                             baseInertialFrameOrientation=list(iorn))
    p.changeDynamics(body, -1, localInertiaDiagonal=list(moments),
                     activationState=p.ACTIVATION_STATE_ENABLE_SLEEPING)
    return body


def add_world(world_file):
    """Ground, then the world's models: a static model's shapes as static bodies; each link of a
    moving model as a free body (joints between a model's links are not modelled: the benchmark's
    worlds have none). Returns (shapes added, [(model name, its first link's body, start
    position)] of the moving models)."""
    # PyBullet has no visual plane: the ground is drawn as a 100 m square, 1 cm thick.
    plane = p.createCollisionShape(p.GEOM_PLANE)
    ground = p.createVisualShape(p.GEOM_BOX, halfExtents=[50, 50, 0.005], visualFramePosition=[0, 0, -0.005],
                                 rgbaColor=[0.8, 0.8, 0.8, 1])
    p.createMultiBody(0, plane, ground, [0, 0, 0])
    if not world_file:
        return 0, []
    n, free = 0, []
    for model in world_models(world_file):
        first = None
        for link in model["links"]:
            if not link["shapes"]:
                continue
            n += len(link["shapes"])
            if model["static"]:
                for kind, size, X_LG, collide in link["shapes"]:
                    add_static_shape(kind, size, compose(link["X_WL"], X_LG), collide)
            else:
                body = add_free_link(link)
                first = body if first is None else first
        if first is not None:
            free.append((model["name"], first, np.array(p.getBasePositionAndOrientation(first)[0])))
    return n, free


def load_robot(urdf, pose=(0.0, 0.0, 0.0)):
    x, y, yaw = pose
    orn = p.getQuaternionFromEuler([0.0, 0.0, yaw])
    robot = p.loadURDF(urdf, [x, y, 1.0], orn, flags=p.URDF_USE_INERTIA_FROM_FILE)
    # Wheels on the ground, as the simulator's z:=auto does.
    min_z = min(p.getAABB(robot, i)[0][2] for i in range(-1, p.getNumJoints(robot)))
    p.resetBasePositionAndOrientation(robot, [x, y, 1.0 - min_z + 1e-4], orn)
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


class Lidar3D:
    """The 16 x 1800 rays in rayTestBatch calls below MAX_RAY_INTERSECTION_BATCH_SIZE rays (16384
    in 3.2.7: more raise an error, and a batch of exactly that many returns one result fewer),
    then the velodyne plugin's cloud (noise, range window, points in the sensor frame with their
    ring) as the bytes its message carries."""

    def __init__(self, robot, link, seed=0):
        c = LIDAR3D
        self.robot, self.link = robot, link
        h = np.linspace(c["min_angle"], c["max_angle"], c["samples"])
        v = np.linspace(c["min_vangle"], c["max_vangle"], c["rings"])
        V, H = np.meshgrid(v, h, indexing="ij")  # ray (j, i) at j * samples + i
        self.dirs = np.stack([np.cos(V) * np.cos(H), np.cos(V) * np.sin(H), np.sin(V)], axis=-1).reshape(-1, 3)
        self.ring = np.repeat(np.arange(c["rings"], dtype=np.uint16), c["samples"])
        self.batch = p.MAX_RAY_INTERSECTION_BATCH_SIZE - 1
        self.rng = np.random.default_rng(seed)
        self.points = 0

    def scan(self):
        c = LIDAR3D
        pos, R = link_pose(self.robot, self.link)
        origin = pos + R[:, 2] * c["z_offset"]
        d = self.dirs @ R.T
        starts = (origin + d * c["min_range"]).tolist()
        ends = (origin + d * c["max_range"]).tolist()
        hits = []
        for k in range(0, len(starts), self.batch):
            hits += p.rayTestBatch(starts[k:k + self.batch], ends[k:k + self.batch])
        if len(hits) != len(starts):
            raise RuntimeError("rayTestBatch gave %d results for %d rays" % (len(hits), len(starts)))
        frac = np.array([h[2] if h[0] >= 0 else np.nan for h in hits])
        r = c["min_range"] + frac * (c["max_range"] - c["min_range"])
        r += self.rng.normal(0.0, c["noise"], r.shape)
        lo, hi = max(c["cloud_min_range"], c["min_range"]), min(c["cloud_max_range"], c["max_range"])
        keep = (r > lo) & (r < hi)  # NaN (no hit) compares false
        cloud = np.zeros(int(keep.sum()), dtype=VELODYNE_POINT)
        xyz = self.dirs[keep] * r[keep, None]
        cloud["x"], cloud["y"], cloud["z"] = xyz[:, 0], xyz[:, 1], xyz[:, 2]
        cloud["ring"] = self.ring[keep]
        self.points += len(cloud)
        return cloud.tobytes()


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


def run(urdf, world, kinds, duration, wheel_omega, steer, max_wall, poses=((0.0, 0.0, 0.0),)):
    p.connect(p.DIRECT)
    p.setGravity(0, 0, -9.8)
    p.setPhysicsEngineParameter(fixedTimeStep=STEP, numSolverIterations=20)
    n_world, free = add_world(world)
    robots, sensors, lidar3ds = [], [], []
    for pose in poses:
        robot, joints, links = load_robot(urdf, pose)
        robots.append(robot)
        for name, j in joints.items():
            if p.getJointInfo(robot, j)[2] != p.JOINT_FIXED:  # free joints: no default motor
                p.setJointMotorControl2(robot, j, p.VELOCITY_CONTROL, targetVelocity=0, force=0)
        for name in ("left_rear_wheel_joint", "right_rear_wheel_joint"):
            p.setJointMotorControl2(robot, joints[name], p.VELOCITY_CONTROL, targetVelocity=wheel_omega, force=10)
        for name in ("left_steering_hinge_joint", "right_steering_hinge_joint"):
            p.setJointMotorControl2(robot, joints[name], p.POSITION_CONTROL, targetPosition=steer, force=10)
        if "lidar" in kinds:
            sensors.append(["lidar", LIDAR["period"], Lidar(robot, links[LIDAR["link"]]).scan])
        if "lidar3d" in kinds:
            lidar3ds.append(Lidar3D(robot, links[LIDAR3D["link"]]))
            sensors.append(["lidar3d", LIDAR3D["period"], lidar3ds[-1].scan])
        if "camera" in kinds:
            sensors.append(["camera", CAMERA["period"], Camera(robot, links[CAMERA["link"]], CAMERA, False).render])
        if "depth" in kinds:
            sensors.append(["depth", DEPTH["period"], Camera(robot, links[DEPTH["link"]], DEPTH, True).render])
    counts = {s[0]: 0 for s in sensors}
    sensor_cpu = {s[0]: 0.0 for s in sensors}
    next_due = [0.0] * len(sensors)
    tracks = [[] for _ in robots]
    every = int(round(TRACK_PERIOD / STEP))
    steps = int(round(duration / STEP))
    cpu0, wall0 = time.process_time(), time.perf_counter()
    i = 0
    while i < steps:
        i += 1
        p.stepSimulation()
        t = i * STEP
        for k, (name, period, fn) in enumerate(sensors):
            if t + 1e-9 >= next_due[k]:
                next_due[k] += period
                c = time.process_time()
                fn()
                sensor_cpu[name] += time.process_time() - c
                counts[name] += 1
        if i % every == 0:
            for robot, track in zip(robots, tracks):
                pos, orn = p.getBasePositionAndOrientation(robot)
                track.append((t, pos[0], pos[1], lap.up_z(orn[0], orn[1])))
        # A wall-time cap (checked every 0.1 s of sim): the rate is measured over what ran.
        if max_wall and i % 100 == 0 and time.perf_counter() - wall0 > max_wall:
            break
    wall = time.perf_counter() - wall0
    cpu = time.process_time() - cpu0
    base, _ = p.getBasePositionAndOrientation(robots[0])
    moved = [name for name, body, start in free
             if np.linalg.norm(np.array(p.getBasePositionAndOrientation(body)[0]) - start) > MOVED]
    p.disconnect()
    laps = [lap.lap(tr) for tr in tracks]
    return dict(cars=len(robots), laps=laps, lap=lap.summary(laps), sensors=list(kinds), sim_seconds=i * STEP, requested_sim_seconds=steps * STEP, wall_seconds=wall,
                rtf=i * STEP / wall, cpu_seconds=cpu, cpu_cores=cpu / wall, counts=counts,
                sensor_cpu_ms_each={k: 1000 * v / max(1, counts[k]) for k, v in sensor_cpu.items()},
                world_shapes=n_world, final_base_xy=list(base[:2]), pybullet_version=p.getAPIVersion(),
                free_models=len(free), free_models_moved=len(moved), moved_threshold_m=MOVED,
                lidar3d_points_per_scan=(sum(x.points for x in lidar3ds) / max(1, counts["lidar3d"]))
                if "lidar3d" in kinds else None)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--urdf", required=True, help="URDF with absolute mesh paths")
    ap.add_argument("--world", default="", help="SDF .world (boxes, cylinders, spheres are used)")
    ap.add_argument("--sensors", default="", help="comma-separated subset of %s (default: none)" % ",".join(SENSORS))
    ap.add_argument("--duration", type=float, default=20.0, help="sim seconds")
    ap.add_argument("--wheel-omega", type=float, default=1.0 / 0.032, help="rear wheel rad/s")
    ap.add_argument("--steer", type=float, default=0.2, help="hinge angle, rad")
    ap.add_argument("--max-wall", type=float, default=0.0, help="stop after this many wall seconds (0: never)")
    ap.add_argument("--poses", default="0,0,0", help="one car per 'x,y,yaw' (space separated; default one at the origin)")
    a = ap.parse_args()
    kinds = [k for k in a.sensors.split(",") if k]
    for k in kinds:
        if k not in SENSORS:
            ap.error("unknown sensor '%s' (known: %s)" % (k, ", ".join(SENSORS)))
    try:
        poses = lap.parse_poses(a.poses)
    except ValueError as e:
        ap.error("--poses: %s" % e)
    res = run(a.urdf, a.world, kinds, a.duration, a.wheel_omega, a.steer, a.max_wall, poses)
    with open("/proc/self/status") as f:
        for line in f:
            if line.startswith("VmHWM:"):
                res["peak_rss_mb"] = int(line.split()[1]) / 1024.0
    json.dump(res, sys.stdout)
    print()


if __name__ == "__main__":
    main()
