#!/usr/bin/env python3
"""Writes a closed cylinder as an ASCII STL: axis along x, centred at the origin,
diameter D and length L (metres), `--facets` facets on the perimeter (32: the
guillard2015 cylinder), `--rows` rows along the length (12: 32*12*2 + 2*32 =
832 triangles). Normals point outwards. Usage:
    make_cylinder_stl.py D L out.stl [--facets 32] [--rows 12]
"""
import argparse
import math


def triangles(D, L, facets, rows):
    r = D / 2.0
    ring = [(r * math.cos(2 * math.pi * k / facets), r * math.sin(2 * math.pi * k / facets)) for k in range(facets)]
    xs = [-L / 2.0 + L * i / rows for i in range(rows + 1)]
    tris = []
    for i in range(rows):
        for k in range(facets):
            (y0, z0), (y1, z1) = ring[k], ring[(k + 1) % facets]
            a, b = (xs[i], y0, z0), (xs[i], y1, z1)
            c, d = (xs[i + 1], y1, z1), (xs[i + 1], y0, z0)
            tris += [(a, b, c), (a, c, d)]
    for x, sign in ((-L / 2.0, -1), (L / 2.0, 1)):
        centre = (x, 0.0, 0.0)
        for k in range(facets):
            (y0, z0), (y1, z1) = ring[k], ring[(k + 1) % facets]
            p, q = (x, y0, z0), (x, y1, z1)
            tris.append((centre, q, p) if sign < 0 else (centre, p, q))
    return tris


def normal(t):
    (ax, ay, az), (bx, by, bz), (cx, cy, cz) = t
    ux, uy, uz, vx, vy, vz = bx - ax, by - ay, bz - az, cx - ax, cy - ay, cz - az
    n = (uy * vz - uz * vy, uz * vx - ux * vz, ux * vy - uy * vx)
    m = math.sqrt(sum(c * c for c in n)) or 1.0
    return tuple(c / m for c in n)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("D", type=float)
    ap.add_argument("L", type=float)
    ap.add_argument("out")
    ap.add_argument("--facets", type=int, default=32)
    ap.add_argument("--rows", type=int, default=12)
    a = ap.parse_args()
    n = write(a.out, a.D, a.L, a.facets, a.rows)
    print("%s: %d triangles (D %g m, L %g m)" % (a.out, n, a.D, a.L))


def write(path, D, L, facets=32, rows=12):
    """Writes the cylinder's ASCII STL to path; returns the number of triangles."""
    tris = triangles(D, L, facets, rows)
    with open(path, "w") as f:
        f.write("solid cylinder\n")
        for t in tris:
            f.write("  facet normal %.9g %.9g %.9g\n    outer loop\n" % normal(t))
            for v in t:
                f.write("      vertex %.9g %.9g %.9g\n" % v)
            f.write("    endloop\n  endfacet\n")
        f.write("endsolid cylinder\n")
    return len(tris)


if __name__ == "__main__":
    main()
