#!/usr/bin/env python3
"""Area-weighted L2 of B-Ke of a SPLASH run against a photon reference, per SPLASH triangle.

    l2.py DUMP RUN_RADIOSITY_TXT REFERENCE_RADIOSITY_TXT [--skip i,j,...] [--worst N]

DUMP: gv_dump.c's file (geometry, Ke); the radiosity files: one line per triangle, in dump order
(to_obj.py's and `globalvis photons --no-contact-split --keep-hidden`'s). Prints the L2 over all
triangles, then over all but --skip (e.g. a rug lying in the floor's plane, which SPLASH leaves
black: issue #19's SPLASH figures match the L2 without it), and the N triangles that make most of
the squared error. The same metric as `globalvis photons --compare` (sqrt of the area-weighted
sum of squared errors over the area-weighted sum of squared reference values, all channels).
"""
import math
import sys


def read_rgb(path):
    values = {}
    with open(path) as f:
        for line in f:
            if line.startswith("#") or not line.strip():
                continue
            fields = line.split()
            values[int(fields[0])] = [float(x) for x in fields[1:4]]
    return values


def main():
    args = sys.argv[1:]
    skip, worst = set(), 0
    if "--skip" in args:
        k = args.index("--skip")
        skip = {int(x) for x in args[k + 1].split(",") if x}
        del args[k:k + 2]
    if "--worst" in args:
        k = args.index("--worst")
        worst = int(args[k + 1])
        del args[k:k + 2]
    if len(args) != 3:
        sys.exit(__doc__)
    dump = [[float(t) for t in line.split()] for line in open(args[0]) if line.strip()]
    run, ref = read_rgb(args[1]), read_rgb(args[2])
    if len(run) != len(dump) or len(ref) != len(dump):
        sys.exit(f"{len(dump)} triangles in the dump, {len(run)} in the run, {len(ref)} in the reference")
    err = [0.0, 0.0]  # squared error: all, kept
    norm = [0.0, 0.0]
    parts = []
    for i, x in enumerate(dump):
        p = [x[0:3], x[3:6], x[6:9]]
        u = [p[1][k] - p[0][k] for k in range(3)]
        v = [p[2][k] - p[0][k] for k in range(3)]
        n = [u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]]
        area = 0.5 * math.sqrt(sum(t * t for t in n))
        e = sum(area * ((run[i][c] - x[12 + c]) - (ref[i][c] - x[12 + c])) ** 2 for c in range(3))
        r = sum(area * (ref[i][c] - x[12 + c]) ** 2 for c in range(3))
        err[0] += e
        norm[0] += r
        if i not in skip:
            err[1] += e
            norm[1] += r
        parts.append((e, i))
    print(f"L2 of B-Ke, all {len(dump)} triangles: {100 * math.sqrt(err[0] / norm[0]):.2f} %")
    if skip:
        print(f"L2 of B-Ke without triangles {sorted(skip)}: {100 * math.sqrt(err[1] / norm[1]):.2f} %")
    for e, i in sorted(parts, reverse=True)[:worst]:
        print(f"triangle {i}: {100 * e / err[0]:.1f} % of the squared error, run {run[i]}, reference {ref[i]}")


if __name__ == "__main__":
    main()
