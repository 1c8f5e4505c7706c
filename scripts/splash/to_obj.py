#!/usr/bin/env python3
"""Turns a SPLASH-3 RADIOSITY patch dump (gv_dump.c, GV_SPLASH_DUMP) into globalvis files.

    to_obj.py DUMP SCENE.obj [RUN_DIR]

SCENE.obj (+ SCENE.mtl): one triangle per SPLASH patch, in dump order, one material per distinct
(reflectance, emittance) pair, so that `globalvis radiosity` and `globalvis photons` run on the
scene SPLASH solved. RUN_DIR (optional): a radiosity.txt with SPLASH's radiosity per patch, in
the format `globalvis photons --compare` reads. That comparison needs a reference shot with
`--no-contact-split --keep-hidden`, so that the patches are the OBJ's faces one for one.
"""
import os
import sys


def main():
    if len(sys.argv) not in (3, 4):
        sys.exit(__doc__)
    dump, obj = sys.argv[1], sys.argv[2]
    run = sys.argv[3] if len(sys.argv) == 4 else None
    patches = []
    with open(dump) as f:
        for number, line in enumerate(f, 1):
            fields = line.split()
            if not fields:
                continue
            if len(fields) != 18:
                sys.exit(f"{dump}:{number}: expected 18 numbers, found {len(fields)}")
            try:
                values = [float(x) for x in fields]
            except ValueError as e:
                sys.exit(f"{dump}:{number}: {e}")
            patches.append(values)
    if not patches:
        sys.exit(f"{dump}: no patches")
    materials = {}
    for p in patches:
        materials.setdefault(tuple(p[9:15]), f"m{len(materials)}")
    mtl = os.path.splitext(obj)[0] + ".mtl"
    with open(mtl, "w") as f:
        f.write("# SPLASH-3 RADIOSITY room: Kd = patch color, Ke = emittance\n")
        for key, name in materials.items():  # key: reflectance r g b, emittance r g b
            f.write(f"newmtl {name}\nKd {key[0]:.9g} {key[1]:.9g} {key[2]:.9g}\n"
                    f"Ke {key[3]:.9g} {key[4]:.9g} {key[5]:.9g}\n\n")
    with open(obj, "w") as f:
        f.write(f"# SPLASH-3 RADIOSITY patches ({len(patches)} triangles), from {os.path.basename(dump)}\n")
        f.write(f"mtllib {os.path.basename(mtl)}\n")
        for p in patches:
            for k in range(3):
                f.write(f"v {p[3 * k]:.9g} {p[3 * k + 1]:.9g} {p[3 * k + 2]:.9g}\n")
        current = None
        for i, p in enumerate(patches):
            name = materials[tuple(p[9:15])]
            if name != current:
                f.write(f"usemtl {name}\n")
                current = name
            f.write(f"f {3 * i + 1} {3 * i + 2} {3 * i + 3}\n")
    if run:
        os.makedirs(run, exist_ok=True)
        with open(os.path.join(run, "radiosity.txt"), "w") as f:
            f.write("# globalvis radiosity: one line per patch of patches.obj, in face order\n")
            f.write(f"# SPLASH-3 RADIOSITY, from {os.path.basename(dump)}\n")
            for i, p in enumerate(patches):
                f.write(f"{i} {p[15]:.9g} {p[16]:.9g} {p[17]:.9g}\n")


if __name__ == "__main__":
    main()
