#!/usr/bin/env python3
"""Write ring.stl: the ring of michi's xarm6_ring problem as an ASCII STL torus.

The torus is centred at the origin with its axis along z (the problem file turns and places it).
Defaults: hole (inner) radius 0.13 m, tube radius 0.025 m, so the centre line of the tube has radius
0.155 m and the outer radius is 0.18 m; 36 segments around the axis, 12 around the tube (864 triangles).
Vertices lie on the true torus; the flat facets stray from it by at most 0.9 mm across the tube and 0.5 mm
around the axis.

Usage: python3 make_ring.py [--inner 0.13] [--tube 0.025] [--major-segments 36] [--minor-segments 12]
                            [--out ring.stl]
Only the Python standard library is used. Written for michi; no external data.
"""
import argparse
import math
import os


def torus_triangles(major_radius, minor_radius, nu, nv):
    """Triangles (three (x, y, z) tuples each, counter-clockwise seen from outside) of a torus."""

    def point(i, j):
        u = 2.0 * math.pi * (i % nu) / nu
        v = 2.0 * math.pi * (j % nv) / nv
        ring = major_radius + minor_radius * math.cos(v)
        return (ring * math.cos(u), ring * math.sin(u), minor_radius * math.sin(v))

    triangles = []
    for i in range(nu):
        for j in range(nv):
            a, b = point(i, j), point(i + 1, j)
            c, d = point(i + 1, j + 1), point(i, j + 1)
            triangles.append((a, b, c))
            triangles.append((a, c, d))
    return triangles


def normal(a, b, c):
    u = [b[k] - a[k] for k in range(3)]
    w = [c[k] - a[k] for k in range(3)]
    n = (u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0])
    length = math.sqrt(sum(x * x for x in n)) or 1.0
    return tuple(x / length for x in n)


def write_ascii_stl(path, name, triangles):
    def fmt(x):
        text = "%.6f" % x
        return "0.000000" if text == "-0.000000" else text

    with open(path, "w") as out:
        out.write("solid %s\n" % name)
        for tri in triangles:
            out.write("  facet normal %s\n    outer loop\n" % " ".join(fmt(x) for x in normal(*tri)))
            for p in tri:
                out.write("      vertex %s\n" % " ".join(fmt(x) for x in p))
            out.write("    endloop\n  endfacet\n")
        out.write("endsolid %s\n" % name)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--inner", type=float, default=0.13, help="radius of the hole, metres")
    parser.add_argument("--tube", type=float, default=0.025, help="radius of the tube, metres")
    parser.add_argument("--major-segments", type=int, default=36)
    parser.add_argument("--minor-segments", type=int, default=12)
    parser.add_argument("--out", default=os.path.join(os.path.dirname(os.path.abspath(__file__)), "ring.stl"))
    args = parser.parse_args()
    if args.inner <= 0 or args.tube <= 0 or args.major_segments < 3 or args.minor_segments < 3:
        parser.error("radii must be positive and segment counts at least 3")
    triangles = torus_triangles(args.inner + args.tube, args.tube, args.major_segments, args.minor_segments)
    write_ascii_stl(args.out, "ring", triangles)
    print("%s: %d triangles, hole radius %.4f m, tube radius %.4f m" % (args.out, len(triangles), args.inner,
                                                                        args.tube))


if __name__ == "__main__":
    main()
