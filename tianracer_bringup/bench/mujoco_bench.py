#!/usr/bin/env python3
"""MuJoCo (PyPI mujoco) doing the simulator's work, for the side-by-side benchmark
(docs/benchmarks.md), with pybullet_bench.py's command line and JSON output.

The same URDF (xacro-expanded, package:// paths made absolute) read by MuJoCo's own URDF import
(MjSpec.from_file: collision meshes as their convex hulls for contacts, visuals dropped, links
joined by fixed joints fused into their parent), a free joint added to its root, each car
attached at its --poses pose with its wheels on the ground; the world's boxes, cylinders and
spheres and a ground plane (static models as world geoms, the others free bodies with the SDF's
mass, inertia and inertial frame, and sleeping allowed); a 1 ms step (MuJoCo's defaults
otherwise: Newton solver, pyramidal friction cones, soft contacts, with the implicitfast
integrator that MuJoCo recommends for velocity actuators); the same controller targets as pybullet_bench.py and our
simulator: the rear wheels by velocity actuators (force limit 10, as PyBullet's motor), the
steering hinges by position actuators with the seed's PID gains (p 20, d 0.2) and the URDF's
effort limit 10; the lidar's 1081 rays every 25 ms by mj_multiRay from the hokuyo's origin,
its own car's body left out. Each car's base track gives its lap (bench/lap.py): speed, turn
radius, flipped. Prints one JSON object on stdout.

    mujoco_bench.py --urdf robot.urdf --world racetrack.world --sensors lidar --duration 20
"""
import argparse
import json
import math
import os
import sys
import time
import xml.etree.ElementTree as ET

import mujoco
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import lap  # noqa: E402

STEP = 0.001
LIDAR = dict(samples=1081, min_angle=-2.3561944902, max_angle=2.3561944902, min_range=0.1,
             max_range=10.0, z_offset=0.0124, period=1.0 / 40.0, link="lidar")
SENSORS = ("lidar",)
MOVED = 0.01  # m: a free model moved when its first link went farther than this from its start
TRACK_PERIOD = 0.02  # s: each car's base pose is sampled at ground truth odometry's 50 Hz
WHEELS = ("left_rear_wheel_joint", "right_rear_wheel_joint")
HINGES = ("left_steering_hinge_joint", "right_steering_hinge_joint")
# The seed's steering controllers (tianracer_control.yaml: effort PID p 20, d 0.2) and the
# force PyBullet's velocity motor is given (pybullet_bench.py).
HINGE_KP, HINGE_KD, WHEEL_FORCE = 20.0, 0.2, 10.0
# A velocity actuator is a damper towards the target: stiff enough that the wheel holds its
# speed (the error is torque / kv) without the implicit integrator needing more.
WHEEL_KV = 10.0


def quat_from_rpy(rpy):
    """(w, x, y, z) of SDF's roll, pitch, yaw (about the fixed x, y, z axes, in that order)."""
    q = np.zeros(4)
    mujoco.mju_euler2Quat(q, np.asarray(rpy, dtype=float), "XYZ")
    return q


def parse_pose(text):
    v = [float(x) for x in (text or "").split()] if text else []
    v += [0.0] * (6 - len(v))
    return np.array(v[:3]), quat_from_rpy(v[3:6])


def compose(a, b):
    """X_AC of X_AB, X_BC as (position, (w, x, y, z))."""
    pos = np.zeros(3)
    mujoco.mju_rotVecQuat(pos, b[0], a[1])
    q = np.zeros(4)
    mujoco.mju_mulQuat(q, a[1], b[1])
    return a[0] + pos, q


def link_inertial(link):
    """(mass, full inertia [ixx iyy izz ixy ixz iyz], X_LI) of a link's <inertial>, SDF's
    defaults (1 kg, unit inertia, the link frame) where absent."""
    e = link.find("inertial")
    mass, full, X_LI = 1.0, [1.0, 1.0, 1.0, 0.0, 0.0, 0.0], (np.zeros(3), np.array([1.0, 0, 0, 0]))
    if e is not None:
        mass = float(e.findtext("mass") or 1.0)
        X_LI = parse_pose(e.findtext("pose"))
        i = e.find("inertia")
        if i is not None:
            full = [float(i.findtext(k) or d) for k, d in
                    (("ixx", 1), ("iyy", 1), ("izz", 1), ("ixy", 0), ("ixz", 0), ("iyz", 0))]
    return mass, full, X_LI


def link_shapes(link):
    """(kind, size, X_LG) of every box/cylinder/sphere collision of a link (MuJoCo needs no
    visuals: nothing here is drawn)."""
    shapes = []
    for g in link.findall("collision"):
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
            shapes.append((kind, size, parse_pose(g.findtext("pose"))))
    return shapes


def world_models(world_file):
    """Every model of the world as pybullet_bench.world_models reads it (nested models as models
    of their own; static when it or a model around it says so): dict(name, static, links), each
    link dict(X_WL, inertial, shapes)."""
    root = ET.parse(world_file).getroot()
    models = []

    def walk(model, X_WP, static, prefix):
        X_WM = compose(X_WP, parse_pose(model.findtext("pose")))
        static = static or (model.findtext("static") or "").strip().lower() in ("true", "1")
        name = prefix + (model.get("name") or "")
        links = [dict(X_WL=compose(X_WM, parse_pose(link.findtext("pose"))), inertial=link_inertial(link),
                      shapes=link_shapes(link)) for link in model.findall("link")]
        models.append(dict(name=name, static=static, links=links))
        for sub in model.findall("model"):
            walk(sub, X_WM, static, name + "::")

    for world in ([root] if root.tag == "world" else root.findall("world")):
        for model in world.findall("model"):
            walk(model, (np.zeros(3), np.array([1.0, 0, 0, 0])), False, "")
    return models


def add_shape(body, kind, size, X, contype, conaffinity):
    if kind == "box":
        t, s = mujoco.mjtGeom.mjGEOM_BOX, [v / 2 for v in size]
    elif kind == "cylinder":
        t, s = mujoco.mjtGeom.mjGEOM_CYLINDER, [size[0], size[1] / 2, 0.0]
    else:
        t, s = mujoco.mjtGeom.mjGEOM_SPHERE, [size[0], 0.0, 0.0]
    return body.add_geom(type=t, size=s, pos=list(X[0]), quat=list(X[1]), contype=contype,
                         conaffinity=conaffinity)


def add_world(spec, world_file, car_bits):
    """Ground plane, then the world's models: static models' shapes on the world body, each link of
    a moving model a free body (joints between a model's links are not modelled: the benchmark's
    worlds have none). World geoms touch each other and every car (car_bits). Returns (shapes
    added, [(model name, its first link's body name)] of the moving models)."""
    spec.worldbody.add_geom(name="ground_plane", type=mujoco.mjtGeom.mjGEOM_PLANE, size=[0, 0, 1],
                            contype=1, conaffinity=1 | car_bits)
    if not world_file:
        return 0, []
    n, free = 0, []
    for model in world_models(world_file):
        first = None
        for k, link in enumerate(model["links"]):
            if not link["shapes"]:
                continue
            n += len(link["shapes"])
            if model["static"]:
                for kind, size, X_LG in link["shapes"]:
                    add_shape(spec.worldbody, kind, size, compose(link["X_WL"], X_LG), 1, 1 | car_bits)
                continue
            mass, full, (ipos, iquat) = link["inertial"]
            name = "%s::link%d" % (model["name"], k)
            body = spec.worldbody.add_body(name=name, pos=list(link["X_WL"][0]), quat=list(link["X_WL"][1]))
            body.add_freejoint()
            body.explicitinertial = True
            body.mass, body.ipos, body.iquat = mass, list(ipos), list(iquat)
            body.fullinertia = full
            for kind, size, X_LG in link["shapes"]:
                add_shape(body, kind, size, X_LG, 1, 1 | car_bits)
            first = first or name
        if first is not None:
            free.append((model["name"], first))
    return n, free


def gazebo_mu(urdf):
    """{link: mu1} from the URDF's <gazebo reference="link"><mu1> (the seed's wheels 2, chassis 0):
    MuJoCo's URDF import reads no <gazebo> element."""
    out = {}
    for g in ET.parse(urdf).getroot().findall("gazebo"):
        mu = g.find("mu1")
        if g.get("reference") and mu is not None:
            out[g.get("reference")] = float(mu.get("value", mu.text or 1.0))
    return out


def car_spec(urdf, mu, own_bit, car_bits):
    """One car from the URDF, its root given a free joint and a site at the lidar's origin. Its
    geoms touch the world and the other cars, never each other (as PyBullet's and our URDF
    import: no self-collision); each has its link's Gazebo mu, used against anything (priority
    1: ODE, whose rule Gazebo uses, takes the smaller mu, and the ground's is 100)."""
    car = mujoco.MjSpec.from_file(urdf)
    root = car.worldbody.first_body()
    root.add_freejoint()
    for body in car.bodies:
        for geom in body.geoms:
            geom.contype, geom.conaffinity = own_bit, 1 | (car_bits & ~own_bit)
            geom.priority = 1
            geom.friction = [mu.get(body.name, 1.0), geom.friction[1], geom.friction[2]]
            if geom.friction[0] == 0.0:
                geom.condim = 1  # frictionless (the seed's chassis): a pyramid of zero width is singular
    car.body(LIDAR["link"]).add_site(name="lidar_origin", pos=[0.0, 0.0, LIDAR["z_offset"]])
    return car, root.name


def build(urdf, world, poses):
    spec = mujoco.MjSpec()
    spec.compiler.fusestatic = True  # the URDF's fixed children fuse into their parent, as its own import
    spec.option.timestep = STEP
    spec.option.gravity = [0.0, 0.0, -9.8]
    spec.option.integrator = mujoco.mjtIntegrator.mjINT_IMPLICITFAST
    # Resting bodies sleep, as Gazebo's auto-disable (on by default), PyBullet's free bodies here
    # and our simulator do: 50 resting boxes cost 292 us a step awake, 51 us with sleeping. A
    # driving car never sleeps (its steps and figures are the same either way).
    spec.option.enableflags |= mujoco.mjtEnableBit.mjENBL_SLEEP
    car_bits = sum(2 << k for k in range(len(poses)))
    n_world, free = add_world(spec, world, car_bits)
    mu = gazebo_mu(urdf)
    cars = []
    for k, (x, y, yaw) in enumerate(poses):
        car, root = car_spec(urdf, mu, 2 << k, car_bits)
        prefix = "car%d/" % k
        frame = spec.worldbody.add_frame(pos=[x, y, 1.0], quat=list(quat_from_rpy([0.0, 0.0, yaw])))
        frame.attach_body(car.body(root), prefix, "")
        for j in WHEELS:
            a = spec.add_actuator(name=prefix + j, target=prefix + j, trntype=mujoco.mjtTrn.mjTRN_JOINT)
            a.set_to_velocity(kv=WHEEL_KV)
            a.forcelimited, a.forcerange = True, [-WHEEL_FORCE, WHEEL_FORCE]
        for j in HINGES:
            a = spec.add_actuator(name=prefix + j, target=prefix + j, trntype=mujoco.mjtTrn.mjTRN_JOINT)
            a.set_to_position(kp=HINGE_KP, kv=HINGE_KD)
            a.forcelimited, a.forcerange = True, [-10.0, 10.0]
        cars.append(dict(prefix=prefix, root=prefix + root))
    m = spec.compile()
    d = mujoco.MjData(m)
    for c in cars:
        c["body"] = m.body(c["root"]).id
        c["qpos"] = m.jnt_qposadr[m.body_jntadr[c["body"]]]
        c["site"] = m.site(c["prefix"] + "lidar_origin").id
        c["ctrl"] = [m.actuator(c["prefix"] + j).id for j in WHEELS + HINGES]
    put_on_ground(m, d, cars)
    return m, d, cars, n_world, [(name, m.body(b).id) for name, b in free]


def put_on_ground(m, d, cars):
    """Each car lowered until its lowest collision vertex is 0.1 mm above the ground (the
    simulator's z:=auto, pybullet_bench's AABB drop)."""
    mujoco.mj_forward(m, d)
    for c in cars:
        lowest = math.inf
        for g in range(m.ngeom):
            if m.body_rootid[m.geom_bodyid[g]] != c["body"]:
                continue
            if m.geom_type[g] == mujoco.mjtGeom.mjGEOM_MESH:
                mesh = m.geom_dataid[g]
                a, n = m.mesh_vertadr[mesh], m.mesh_vertnum[mesh]
                z = m.mesh_vert[a:a + n] @ d.geom_xmat[g].reshape(3, 3)[2] + d.geom_xpos[g][2]
                lowest = min(lowest, float(z.min()))
            else:
                lowest = min(lowest, d.geom_xpos[g][2] - m.geom_rbound[g])
        d.qpos[c["qpos"] + 2] -= lowest - 1e-4
    mujoco.mj_forward(m, d)


class Lidar:
    """1081 rays from the hokuyo's origin in one mj_multiRay; the car's own root body (which the
    lidar's link is fused into) is left out, as our lidar passes through its own head."""

    def __init__(self, m, d, car):
        self.m, self.d, self.car = m, d, car
        a = np.linspace(LIDAR["min_angle"], LIDAR["max_angle"], LIDAR["samples"])
        self.dirs = np.stack([np.cos(a), np.sin(a), np.zeros_like(a)], axis=1)
        self.vec = np.zeros(3 * LIDAR["samples"])
        self.geomid = np.zeros(LIDAR["samples"], dtype=np.int32)
        self.dist = np.zeros(LIDAR["samples"])

    def scan(self):
        d, site = self.d, self.car["site"]
        R = d.site_xmat[site].reshape(3, 3)
        self.vec[:] = (self.dirs @ R.T).ravel()
        mujoco.mj_multiRay(self.m, d, d.site_xpos[site], self.vec, None, 1, self.car["body"], self.geomid,
                           self.dist, None, LIDAR["samples"], LIDAR["max_range"])
        r = self.dist.astype(np.float32)
        r[(self.dist < LIDAR["min_range"]) | (self.dist > LIDAR["max_range"])] = np.inf
        return r


def run(urdf, world, kinds, duration, wheel_omega, steer, max_wall, poses):
    m, d, cars, n_world, free = build(urdf, world, poses)
    for c in cars:
        d.ctrl[c["ctrl"]] = [wheel_omega, wheel_omega, steer, steer]
    start = {name: d.xpos[b].copy() for name, b in free}
    sensors = []
    if "lidar" in kinds:
        for c in cars:
            sensors.append(["lidar", LIDAR["period"], Lidar(m, d, c).scan])
    counts = {s[0]: 0 for s in sensors}
    sensor_cpu = {s[0]: 0.0 for s in sensors}
    next_due = [0.0] * len(sensors)
    tracks = [[] for _ in cars]
    every = int(round(TRACK_PERIOD / STEP))
    steps = int(round(duration / STEP))
    cpu0, wall0 = time.process_time(), time.perf_counter()
    i = 0
    while i < steps:
        i += 1
        mujoco.mj_step(m, d)
        t = i * STEP
        for k, (name, period, fn) in enumerate(sensors):
            if t + 1e-9 >= next_due[k]:
                next_due[k] += period
                c = time.process_time()
                fn()
                sensor_cpu[name] += time.process_time() - c
                counts[name] += 1
        if i % every == 0:
            for c, track in zip(cars, tracks):
                q = d.qpos[c["qpos"]:c["qpos"] + 7]
                track.append((t, q[0], q[1], lap.up_z(q[4], q[5])))
        if max_wall and i % 100 == 0 and time.perf_counter() - wall0 > max_wall:
            break
    wall = time.perf_counter() - wall0
    cpu = time.process_time() - cpu0
    moved = [name for name, b in free if np.linalg.norm(d.xpos[b] - start[name]) > MOVED]
    laps = [lap.lap(tr) for tr in tracks]
    # MuJoCo resets the state when its accelerations blow up (and only warns): a run that did
    # measures something else, which the harness refuses.
    unstable = int(d.warning[mujoco.mjtWarning.mjWARN_BADQACC].number)
    base = d.qpos[cars[0]["qpos"]:cars[0]["qpos"] + 2]
    return dict(sensors=list(kinds), sim_seconds=i * STEP, requested_sim_seconds=steps * STEP, wall_seconds=wall,
                rtf=i * STEP / wall, cpu_seconds=cpu, cpu_cores=cpu / wall,
                counts=counts,
                sensor_cpu_ms_each={k: 1000 * v / max(1, counts[k]) for k, v in sensor_cpu.items()},
                world_shapes=n_world, final_base_xy=[float(v) for v in base], mujoco_version=mujoco.__version__,
                cars=len(cars), laps=laps, lap=lap.summary(laps), unstable=unstable,
                free_models=len(free), free_models_moved=len(moved), moved_threshold_m=MOVED,
                model_sizes=dict(nbody=int(m.nbody), ngeom=int(m.ngeom), nv=int(m.nv)))


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
            ap.error("unknown sensor '%s' (known on the MuJoCo side: %s)" % (k, ", ".join(SENSORS)))
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
