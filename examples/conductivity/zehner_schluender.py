#!/usr/bin/env python3
"""Compare k_eff of `tmdem study conductivity` CSVs with the Zehner-Schluender-Bauer correlation.

For each row: the measured porosity psi, the correlation's k_eff / k_f for spheres
(Zehner & Schluender 1970 with Bauer's shape factor, as in the VDI Heat Atlas, section D6.3,
without radiation, contact flattening or the Smoluchowski gas effect):
    B = 1.25 ((1 - psi) / psi)^(10/9),  kappa = k_s / k_f,  N = 1 - B / kappa
    k_eff / k_f = 1 - sqrt(1 - psi)
                + 2 sqrt(1 - psi) / N * ( (1 - 1/kappa) B / N^2 ln(kappa / B)
                                          - (B + 1) / 2 - (B - 1) / N )
and tmdem's k_eff / k_f from the same row. Prints a table; writes no file.

    /usr/bin/python3 examples/conductivity/zehner_schluender.py --ks 1.0 --kf 0.0262 k.csv ...
"""
import argparse
import csv
import math


def zsb(psi, kappa):
    b = 1.25 * ((1.0 - psi) / psi) ** (10.0 / 9.0)
    n = 1.0 - b / kappa
    s = math.sqrt(1.0 - psi)
    core = (1.0 - 1.0 / kappa) * b / n ** 2 * math.log(kappa / b) - (b + 1.0) / 2.0 - (b - 1.0) / n
    return 1.0 - s + 2.0 * s / n * core


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("csv", nargs="+")
    parser.add_argument("--ks", type=float, required=True, help="solid conductivity, W/(m K)")
    parser.add_argument("--kf", type=float, default=0.0262, help="fluid conductivity, W/(m K)")
    args = parser.parse_args()
    kappa = args.ks / args.kf
    print(f"k_s / k_f = {kappa:.4g}")
    print("file, porosity, tmdem k_eff/k_f, ZSB k_eff/k_f, tmdem / ZSB")
    for path in args.csv:
        with open(path, newline="") as f:
            for row in csv.DictReader(f):
                psi = float(row["porosity"])
                measured = float(row["k_eff_W_per_mK"]) / args.kf
                predicted = zsb(psi, kappa)
                print(f"{path}, {psi:.4f}, {measured:.4g}, {predicted:.4g}, {measured / predicted:.3f}")


if __name__ == "__main__":
    main()
