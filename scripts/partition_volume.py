#!/usr/bin/env python3
"""Communication volume of a distributed bed, measured from a real contact graph.

Reads the last frame of a tmdem result file (positions and the contact pairs), optionally
tiles the bed k x k times in the floor plane (x, z) to reach 10^5 particles (contacts across
the tile seams are not added: the figures are then a slight under-count at the seams), splits
the particles into P parts by recursive coordinate bisection (RCB, each cut across the longest
extent at the median, as LAMMPS' `balance rcb` and Zoltan's RCB), and prints per P:

  interface contacts   pair contacts whose two particles lie in different parts
  shared bodies        particles with a contact in a part other than their own (ghosts)
  ghost copies         sum over shared bodies of the other parts they appear in
  bytes per sweep      ghost copies x 2 (gather + scatter) x 6 doubles (v, omega) x 8 B: what a
                       subdomain block Gauss-Seidel exchanges after each local sweep
                       (Preclik and Rude 2015); LMGC90's DDM exchanges the same interface
                       velocities per iteration
  bytes per thermal rhs ghost copies x 8 B: one ghost temperature per copy for each
                       right-hand-side evaluation of a split thermal network

Usage: scripts/partition_volume.py RESULT.h5 [--tile K] [--parts 2,4,8,16,64]
"""
import argparse
import sys

import h5py
import numpy as np


def rcb(points, index, parts, out, first):
    """Recursive coordinate bisection of `index` into `parts` parts numbered from `first`."""
    if parts == 1:
        out[index] = first
        return
    extent = points[index].max(axis=0) - points[index].min(axis=0)
    axis = int(np.argmax(extent))
    order = index[np.argsort(points[index, axis], kind="stable")]
    left_parts = parts // 2
    cut = len(order) * left_parts // parts
    rcb(points, order[:cut], left_parts, out, first)
    rcb(points, order[cut:], parts - left_parts, out, first + left_parts)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("result")
    ap.add_argument("--tile", type=int, default=1)
    ap.add_argument("--parts", default="2,4,8,16,64")
    a = ap.parse_args()
    with h5py.File(a.result, "r") as f:
        position = f["frames/position"][-1]
        offset = f["frames/contact_offset"][:]
        pair = f["contacts/pair"][offset[-2]:offset[-1]]
    pair = pair[pair[:, 1] >= 0]  # particle pairs (walls are fixed: nothing to exchange)
    n = len(position)
    span = position.max(axis=0) - position.min(axis=0)
    points, pairs = [], []
    for tx in range(a.tile):
        for tz in range(a.tile):
            k = len(points)
            points.append(position + np.array([tx * span[0] * 1.02, 0.0, tz * span[2] * 1.02]))
            pairs.append(pair + k * n)
    points = np.concatenate(points)
    pairs = np.concatenate(pairs)
    print(f"{len(points)} particles, {len(pairs)} pair contacts "
          f"(from {a.result}: {n} particles, {len(pair)} pair contacts, tiled {a.tile} x {a.tile})")
    print("| parts | interface contacts | share | shared bodies | ghost copies | "
          "MB per GS sweep | kB per thermal rhs, largest part |")
    print("|---|---|---|---|---|---|---|")
    for P in [int(p) for p in a.parts.split(",")]:
        part = np.empty(len(points), dtype=np.int64)
        rcb(points, np.arange(len(points)), P, part, 0)
        pi, pj = part[pairs[:, 0]], part[pairs[:, 1]]
        cut = pi != pj
        # (body, foreign part) pairs: a body is a ghost in each other part it has a contact in.
        ghost = np.unique(np.concatenate([
            pairs[cut, 0] * P + pj[cut],
            pairs[cut, 1] * P + pi[cut]]))
        bodies = np.unique(ghost // P)
        ghosts_per_part = np.bincount(ghost % P, minlength=P)
        mb = len(ghost) * 2 * 6 * 8 / 1e6
        print(f"| {P} | {cut.sum():,} | {cut.mean():.2%} | {len(bodies):,} | {len(ghost):,} | "
              f"{mb:.2f} | {ghosts_per_part.max() * 8 / 1e3:.1f} |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
