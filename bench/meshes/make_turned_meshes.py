#!/usr/bin/env python3
"""Writes the turned benchmark meshes (ASCII STL, millimetres) beside this script.

Each part is a closed profile in (r, z), drawn counter-clockwise with r to the right, revolved
about z with a fixed number of flat facets, as a CAD exporter tessellates a turned part. The files
are kept in the repository; run this only to change them.
  stepped_shaft.stl  a slender shaft 90 mm long: 10 mm body, a 22 mm collar 6 mm wide, a 14 mm step
  pipe_reducer.stl   a hollow reducer coupling 50 mm long: 32 mm outside to 22 mm, 24 and 16 mm bores
"""
import math
import pathlib

SEGMENTS = 48

PARTS = {
    "stepped_shaft": [(0, -45), (5, -45), (5, 10), (11, 10), (11, 16), (7, 16), (7, 35), (5, 35),
                      (5, 45), (0, 45)],
    "pipe_reducer": [(12, -25), (16, -25), (16, 0), (11, 8), (11, 25), (8, 25), (8, 4), (12, -2)],
}


def on_circle(r, z, step, segments=SEGMENTS):
    angle = 2 * math.pi * step / segments
    return (r * math.cos(angle), r * math.sin(angle), z)


def normal_of(a, b, c):
    u = [b[i] - a[i] for i in range(3)]
    v = [c[i] - a[i] for i in range(3)]
    n = (u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0])
    length = math.sqrt(sum(x * x for x in n))
    return tuple(x / length for x in n)


def revolve(profile, segments=SEGMENTS):
    """Triangles of the profile's edges revolved; an edge on the axis (r = 0) closes nothing."""
    triangles = []
    for i, (r0, z0) in enumerate(profile):
        r1, z1 = profile[(i + 1) % len(profile)]
        if r0 == 0 and r1 == 0:
            continue
        for step in range(segments):
            a0, a1 = on_circle(r0, z0, step, segments), on_circle(r0, z0, step + 1, segments)
            b0, b1 = on_circle(r1, z1, step, segments), on_circle(r1, z1, step + 1, segments)
            # The quad a0 a1 b1 b0 of a counter-clockwise profile, split so that both triangles
            # face outward, (dz, -dr) in (r, z); a corner on the axis leaves one triangle.
            if r1 != 0:
                triangles.append((a0, b1, b0))
            if r0 != 0:
                triangles.append((a0, a1, b1))
    return triangles


def write_stl(path, name, triangles):
    with open(path, "w") as out:
        out.write(f"solid {name}\n")
        for a, b, c in triangles:
            n = normal_of(a, b, c)
            out.write(f"  facet normal {n[0]:.6f} {n[1]:.6f} {n[2]:.6f}\n    outer loop\n")
            for v in (a, b, c):
                out.write(f"      vertex {v[0]:.6f} {v[1]:.6f} {v[2]:.6f}\n")
            out.write("    endloop\n  endfacet\n")
        out.write(f"endsolid {name}\n")


if __name__ == "__main__":
    here = pathlib.Path(__file__).resolve().parent
    for name, profile in PARTS.items():
        write_stl(here / f"{name}.stl", name, revolve(profile))
