#!/usr/bin/env python3
"""Parametric generator for the tianracer meshes (binary STL, metres).

We do not have the original CAD meshes, so this script builds simple but recognisable
stand-ins sized to the joint layout of urdf/tianracer_description.xacro:

  base_link.STL            chassis (lower plate, A-arms, diffs, motor, battery, upper deck,
                           standoffs, computer box, bumpers, side skirts, rear wing)
  {left,right}_steering_hinge.STL   knuckle, kingpin, stub axle, steering arm
  {left,right}_{front,rear}_wheel.STL   rim + tyre, radius 0.032 m, width 0.025 m, axis y
  lidar.STL                2D lidar (body + puck) on a mounting post
  camera.STL               camera box with lens on a bracket
  real_sense.STL           depth camera bar on a post

Every mesh is expressed in its own link frame (the frame of the link's joint origin).
Constraints respected (checked by test/test_description.cpp):
  * wheels: vertices at most 0.032 m from the y axis, symmetric in y (centred), watertight;
  * nothing that is not a wheel goes below z = -0.003 in base_link (ground is at -0.0095);
  * the chassis stays out of the wheels' volumes, front wheels swept over +-0.6 rad of steering;
  * the lidar's scanning head (a 42 mm puck, z from -0.005 to +0.025 in the lidar frame) encloses
    its scan plane (z = +0.0124), so another car's lidar sees it; its own rays start at range min
    (0.1 m), past the head, as Gazebo's do. The rest of the car stays below z = 0.125 in
    base_link, so the car's own lidar sees past it;
  * camera and depth-camera meshes stay behind their optical frames (x <= 0) so they do not
    appear in their own images.

Every primitive is a closed, outward-facing triangle mesh (counter-clockwise seen from outside).
The output is deterministic: same bytes on every run.

Usage: generate_meshes.py [OUTPUT_DIR]   (default: ../meshes next to this script)
"""

import math
import os
import struct
import sys

import numpy as np

# ---------------------------------------------------------------------------------------------
# Layout from the xacro (base_link frame). Kept here literally; the test compares with the URDF.
LEFT_HINGE = (0.1237, 0.070647, 0.0235)
RIGHT_HINGE = (0.12626, -0.065953, 0.0235)
FRONT_WHEEL_OFFSET_Y = 0.015649          # wheel origin from its hinge, outward
LEFT_REAR = (-0.12626, 0.081602, 0.0225)
RIGHT_REAR = (-0.1237, -0.086296, 0.0225)
LIDAR = (0.093603, -8.284e-05, 0.12377)
CAMERA = (0.14851, 0.0022137, 0.0975)
REAL_SENSE = (0.19864, 0.0038046, 0.052021)

WHEEL_RADIUS = 0.032
WHEEL_HALF_WIDTH = 0.0125
WHEEL_SEGMENTS = 64

DECK_BOTTOM = 0.068                      # upper deck, above the wheel tops (0.0555)
DECK_TOP = 0.072

HEADER = b"tianracer_description generate_meshes.py (parametric, metres)"


class Mesh:
    """Closed primitives as blocks of float64 vertices + int faces (CCW seen from outside)."""

    def __init__(self):
        self.vertices = []
        self.faces = []

    def add(self, vertices, faces):
        base = sum(len(v) for v in self.vertices)
        self.vertices.append(np.asarray(vertices, dtype=np.float64))
        self.faces.append(np.asarray(faces, dtype=np.int64) + base)
        return self

    def arrays(self):
        return np.concatenate(self.vertices), np.concatenate(self.faces)


# ---------------------------------------------------------------------------------------------
# Closed primitives.

def box(mesh, lo, hi):
    """Axis-aligned box from corner lo to corner hi."""
    (x0, y0, z0), (x1, y1, z1) = lo, hi
    assert x0 < x1 and y0 < y1 and z0 < z1, (lo, hi)
    v = [(x0, y0, z0), (x1, y0, z0), (x1, y1, z0), (x0, y1, z0),
         (x0, y0, z1), (x1, y0, z1), (x1, y1, z1), (x0, y1, z1)]
    f = [(0, 2, 1), (0, 3, 2),      # bottom (-z)
         (4, 5, 6), (4, 6, 7),      # top (+z)
         (0, 1, 5), (0, 5, 4),      # -y
         (2, 3, 7), (2, 7, 6),      # +y
         (1, 2, 6), (1, 6, 5),      # +x
         (3, 0, 4), (3, 4, 7)]      # -x
    return mesh.add(v, f)


def _frame(axis):
    """Orthonormal (u, w, a) with a along the axis and u x w = a."""
    a = np.asarray(axis, dtype=np.float64)
    a = a / np.linalg.norm(a)
    helper = np.array([0.0, 0.0, 1.0]) if abs(a[2]) < 0.9 else np.array([1.0, 0.0, 0.0])
    u = np.cross(helper, a)
    u /= np.linalg.norm(u)
    w = np.cross(a, u)
    return u, w, a


def revolve(mesh, centre, axis, profile, segments):
    """Surface of revolution of a closed (r, h) profile about axis through centre.

    profile runs from a point on the axis (r = 0, largest h) to another point on the axis
    (r = 0, smallest h), i.e. clockwise in the (r, h) half plane, which makes the normals point
    outward. Poles become single vertices so the result is watertight.
    """
    assert profile[0][0] == 0.0 and profile[-1][0] == 0.0
    u, w, a = _frame(axis)
    c = np.asarray(centre, dtype=np.float64)
    ang = 2.0 * math.pi * np.arange(segments) / segments
    cos, sin = np.cos(ang), np.sin(ang)
    verts = [c + a * profile[0][1]]
    rings = []
    for r, h in profile[1:-1]:
        start = len(verts)
        ring = c + a * h + r * (np.outer(cos, u) + np.outer(sin, w))
        verts.extend(ring)
        rings.append(start)
    verts.append(c + a * profile[-1][1])
    top, bottom = 0, len(verts) - 1
    faces = []
    n = segments
    for i in range(n):
        j = (i + 1) % n
        faces.append((top, rings[0] + j, rings[0] + i))
    for ra, rb in zip(rings[:-1], rings[1:]):
        for i in range(n):
            j = (i + 1) % n
            faces.append((ra + i, ra + j, rb + j))
            faces.append((ra + i, rb + j, rb + i))
    for i in range(n):
        j = (i + 1) % n
        faces.append((bottom, rings[-1] + i, rings[-1] + j))
    # The loops above wind clockwise seen from outside (u x w = a, angles grow about a): flip.
    return mesh.add(verts, [(f[0], f[2], f[1]) for f in faces])


def cylinder(mesh, centre, axis, radius, length, segments=20):
    """Solid cylinder centred at centre, along axis."""
    h = 0.5 * length
    return revolve(mesh, centre, axis, [(0.0, h), (radius, h), (radius, -h), (0.0, -h)], segments)


def cylinder_between(mesh, p0, p1, radius, segments=16):
    p0, p1 = np.asarray(p0, float), np.asarray(p1, float)
    return cylinder(mesh, (p0 + p1) / 2, p1 - p0, radius, np.linalg.norm(p1 - p0), segments)


# ---------------------------------------------------------------------------------------------
# Parts.

def wheel():
    """Rim + tyre, symmetric in y so it is centred on the link origin and fits either side."""
    R, W = WHEEL_RADIUS, WHEEL_HALF_WIDTH
    half = [(0.0, 0.006),          # hub / dished rim face
            (0.020, 0.006),
            (0.0225, 0.0115),      # rim lip
            (0.026, W),            # tyre sidewall
            (R, 0.0095)]           # tyre shoulder -> tread
    profile = half + [(r, -h) for r, h in reversed(half)]
    return revolve(Mesh(), (0.0, 0.0, 0.0), (0.0, 1.0, 0.0), profile, WHEEL_SEGMENTS)


def steering_hinge(side):
    """Knuckle in the hinge frame; side = +1 (left, wheel at +y) or -1 (right)."""
    m = Mesh()
    s = float(side)
    cylinder(m, (0.0, 0.0, 0.0), (0, 0, 1), 0.0045, 0.028, 16)             # kingpin
    y0, y1 = sorted((-0.002 * s, 0.005 * s))
    box(m, (-0.006, y0, -0.011), (0.006, y1, 0.011))                       # knuckle body
    cylinder_between(m, (0.0, 0.0, 0.0), (0.0, s * 0.0115, 0.0), 0.003, 12)  # stub axle
    y0, y1 = sorted((-0.004 * s, 0.001 * s))
    box(m, (-0.020, y0, -0.003), (0.0, y1, 0.001))                         # steering arm
    return m


def chassis():
    """Chassis in base_link. Ground is at z = -0.0095; the plate bottom is at z = 0."""
    m = Mesh()
    # Lower plate: narrow at the front (clear of the steered wheels), wider in the middle.
    box(m, (-0.175, -0.036, 0.0), (0.215, 0.036, 0.004))
    box(m, (-0.085, -0.062, 0.0), (0.075, 0.062, 0.004))
    box(m, (-0.170, -0.056, 0.0), (-0.090, 0.056, 0.004))
    # Side skirts between the axles.
    for s in (1, -1):
        y0, y1 = sorted((0.058 * s, 0.064 * s))
        box(m, (-0.080, y0, 0.004), (0.070, y1, 0.024))
    # Front bumper (ahead of the wheels' reach x <= 0.169) and its mount.
    box(m, (0.205, -0.060, 0.004), (0.225, 0.060, 0.022))
    box(m, (0.175, -0.012, 0.004), (0.205, 0.012, 0.012))
    # Rear bumper.
    box(m, (-0.190, -0.050, 0.004), (-0.175, 0.050, 0.020))
    # Front and rear differentials.
    box(m, (0.105, -0.028, 0.004), (0.145, 0.028, 0.036))
    box(m, (-0.145, -0.034, 0.004), (-0.105, 0.034, 0.040))
    # Steering servo and tie rod bar.
    box(m, (0.070, -0.020, 0.004), (0.100, 0.020, 0.030))
    # Front A-arms, lower and upper, ending just inside each kingpin (clear of the steered wheel).
    for hx, hy, hz in (LEFT_HINGE, RIGHT_HINGE):
        s = 1.0 if hy > 0 else -1.0
        y0, y1 = sorted((0.026 * s, hy - 0.0055 * s))
        box(m, (hx - 0.005, y0, hz - 0.014), (hx + 0.005, y1, hz - 0.010))
        box(m, (hx - 0.004, y0, hz + 0.010), (hx + 0.004, y1, hz + 0.013))
    # Rear hub carriers and drive shafts, stopping just short of the tyre's inner plane.
    for wx, wy, wz in (LEFT_REAR, RIGHT_REAR):
        s = 1.0 if wy > 0 else -1.0
        inner = wy - s * (WHEEL_HALF_WIDTH + 0.0015)                        # tyre inner plane
        y0, y1 = sorted((0.050 * s, inner))
        box(m, (wx - 0.006, y0, wz - 0.012), (wx + 0.006, y1, wz + 0.010))
        cylinder_between(m, (wx, 0.030 * s, wz), (wx, wy - s * (WHEEL_HALF_WIDTH + 0.0005), wz),
                         0.003, 12)
    # Motor (axis x) and battery.
    cylinder(m, (-0.065, -0.030, 0.020), (1, 0, 0), 0.016, 0.050, 24)
    box(m, (-0.080, 0.002, 0.004), (0.065, 0.054, 0.030))
    # Standoffs and the upper deck that carries the sensors.
    for x in (-0.085, 0.055, 0.150):
        for y in (-0.030, 0.030):
            cylinder(m, (x, y, 0.5 * (0.004 + DECK_BOTTOM)), (0, 0, 1), 0.003,
                     DECK_BOTTOM - 0.004, 10)
    box(m, (-0.100, -0.050, DECK_BOTTOM), (0.170, 0.050, DECK_TOP))
    # Onboard computer with a heat sink.
    box(m, (-0.090, -0.040, DECK_TOP), (0.040, 0.040, 0.088))
    for i in range(6):
        x0 = -0.080 + 0.02 * i
        box(m, (x0, -0.030, 0.088), (x0 + 0.004, 0.030, 0.096))
    # Rear wing on two posts (below the lidar's scan plane).
    for y in (-0.030, 0.030):
        box(m, (-0.170, y - 0.003, 0.004), (-0.164, y + 0.003, 0.090))
    box(m, (-0.195, -0.075, 0.090), (-0.155, 0.075, 0.094))
    for s in (1, -1):
        y0, y1 = sorted((0.072 * s, 0.075 * s))
        box(m, (-0.195, y0, 0.070), (-0.160, y1, 0.094))                    # end plates
    return m


def lidar():
    """2D lidar in its frame; the scanning head encloses the scan plane z = +0.0124."""
    m = Mesh()
    box(m, (-0.025, -0.025, -0.035), (0.025, 0.025, -0.005))                 # body
    cylinder(m, (0.0, 0.0, 0.010), (0, 0, 1), 0.021, 0.030, 32)             # scanning head
    post_bottom = DECK_TOP - LIDAR[2] - 0.001                               # into the deck
    cylinder(m, (0.0, 0.0, 0.5 * (post_bottom - 0.035)), (0, 0, 1), 0.007,
             -0.035 - post_bottom, 16)                                       # mounting post
    box(m, (-0.02, -0.02, -0.038), (0.02, 0.02, -0.035))                    # mounting plate
    return m


def camera():
    """Camera box behind its optical frame, on a bracket down to the deck."""
    m = Mesh()
    box(m, (-0.030, -0.018, -0.015), (-0.005, 0.018, 0.015))
    cylinder(m, (-0.0025, 0.0, 0.0), (1, 0, 0), 0.008, 0.005, 20)          # lens, x <= 0
    bottom = DECK_TOP - CAMERA[2] - 0.001
    box(m, (-0.022, -0.006, bottom), (-0.012, 0.006, -0.015))               # bracket
    return m


def real_sense():
    """Depth camera bar (about 90 x 25 x 25 mm) on a post down to the lower plate."""
    m = Mesh()
    box(m, (-0.025, -0.045, -0.0125), (-0.002, 0.045, 0.0125))
    for y in (-0.03, -0.01, 0.015, 0.03):                                   # lens bumps
        cylinder(m, (-0.001, y, 0.0), (1, 0, 0), 0.004, 0.002, 12)
    bottom = 0.004 - REAL_SENSE[2] - 0.001
    box(m, (-0.020, -0.006, bottom), (-0.010, 0.006, -0.0125))              # post
    return m


# ---------------------------------------------------------------------------------------------
# Output.

def stl_bytes(mesh):
    vertices, faces = mesh.arrays()
    v = vertices.astype(np.float32)
    tri = v[faces]                                        # (n, 3, 3)
    normal = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0]).astype(np.float64)
    length = np.linalg.norm(normal, axis=1)
    assert np.all(length > 0.0), "degenerate triangle"
    normal = (normal / length[:, None]).astype(np.float32)
    record = np.zeros(len(faces), dtype=[("n", "<f4", 3), ("v", "<f4", (3, 3)), ("a", "<u2")])
    record["n"] = normal
    record["v"] = tri
    return HEADER.ljust(80, b" ") + struct.pack("<I", len(faces)) + record.tobytes()


def meshes():
    left_hinge_mesh = steering_hinge(+1)
    right_hinge_mesh = steering_hinge(-1)
    return {
        "base_link.STL": chassis(),
        "left_steering_hinge.STL": left_hinge_mesh,
        "right_steering_hinge.STL": right_hinge_mesh,
        "left_front_wheel.STL": wheel(),
        "right_front_wheel.STL": wheel(),
        "left_rear_wheel.STL": wheel(),
        "right_rear_wheel.STL": wheel(),
        "lidar.STL": lidar(),
        "camera.STL": camera(),
        "real_sense.STL": real_sense(),
    }


def main(argv):
    here = os.path.dirname(os.path.abspath(__file__))
    out = argv[1] if len(argv) > 1 else os.path.join(here, os.pardir, "meshes")
    os.makedirs(out, exist_ok=True)
    for name, mesh in sorted(meshes().items()):
        data = stl_bytes(mesh)
        with open(os.path.join(out, name), "wb") as f:
            f.write(data)
        count = struct.unpack_from("<I", data, 80)[0]
        print("%-26s %5d triangles" % (name, count))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
