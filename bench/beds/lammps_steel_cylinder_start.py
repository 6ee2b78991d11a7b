#!/usr/bin/python3
"""Writes init.data, the start of lammps_steel_cylinder.in: 2,500 steel spheres (diameters 2 and
3 mm, half and half, shuffled) on a loose square lattice of 3.4 mm inside a 13.2 mm circle, jittered
by up to 0.1 mm, up to 0.19 m high. Run it beside the input, then `lmp -in lammps_steel_cylinder.in`."""
import numpy as np

rng = np.random.default_rng(5)
step = 0.0034
points = [(x, y, z)
          for z in np.arange(0.003, 0.3, step)
          for x in np.arange(-0.0135, 0.0136, step)
          for y in np.arange(-0.0135, 0.0136, step)
          if x * x + y * y < 0.0132 ** 2]
points = np.array(points)[:2500]
types = rng.permutation(np.r_[np.ones(1250, int), 2 * np.ones(1250, int)])
points = points + rng.uniform(-0.0001, 0.0001, points.shape)
with open("init.data", "w") as f:
    f.write("LAMMPS data\n\n2500 atoms\n2 atom types\n-0.016 0.016 xlo xhi\n-0.016 0.016 ylo yhi\n"
            "0 0.3 zlo zhi\n\nAtoms # sphere\n\n")
    for i, (p, t) in enumerate(zip(points, types)):
        f.write(f"{i + 1} {t} {0.002 if t == 1 else 0.003} 7800 {p[0]:.7f} {p[1]:.7f} {p[2]:.7f}\n")
