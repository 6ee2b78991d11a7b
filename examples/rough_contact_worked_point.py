#!/usr/bin/env python3
"""The rough-contact law (thermal.conductance = "bahrami") and its macro-gap at a worked point.

Beaulieu's steel spheres (d 6.4 mm, k 42 W/(m K), E 200 GPa, nu 0.29, roughness 19 nm, asperity
slope 0.056, microhardness 3 GPa) in air (k_g 0.027 W/(m K), mean free path 68 nm at 101325 Pa,
accommodation 0.7, gamma 1.4, Pr 0.69), at a few normal forces: the resistances R_L, R_s, R_g
(K/W), the contact conductance H and the macro-gap (W/K), written out from the equations of
docs/heat-modes.md "Rough contacts" with the standard library only (the table there is this
script's output).

  python3 examples/rough_contact_worked_point.py
"""
import math


def erfc_inverse(y):
    """x with erfc(x) = y, 0 < y < 2, by bisection."""
    lo, hi = -30.0, 30.0
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if math.erfc(mid) > y:
            lo = mid
        else:
            hi = mid
    return 0.5 * (lo + hi)


R, k, E, nu = 3.2e-3, 42.0, 200e9, 0.29                  # m, W/(m K), Pa, -
sigma = math.hypot(19e-9, 19e-9)                         # m, the pair's combined roughness
slope = math.hypot(0.056, 0.056)                         # the pair's combined asperity slope
H_mic = 3e9                                              # Pa
k_g = 0.027                                              # W/(m K)
M = 2 * (2 - 0.7) / 0.7 * (2 * 1.4 / 2.4) * 68e-9 / 0.69  # m, Bahrami's gas parameter
R_star, E_star = R / 2, 1 / (2 * (1 - nu**2) / E)

print(f"gas parameter M = {M:.4g} m")
print("| F (N) | a (um) | P0 (MPa) | R_L (K/W) | R_s (K/W) | R_g (K/W) | H (W/K) | 2 k a (W/K) | macro-gap (W/K) |")
for F in (0.01, 0.1, 1.0):
    a = (3 * F * R_star / (4 * E_star)) ** (1 / 3)
    P0 = 3 * F / (2 * math.pi * a * a)
    R_L = 1 / (2 * k * a)
    R_s = (1 + 0.95 / 2) / (1.25 * math.pi * k * a * a) * sigma / slope * (H_mic / P0) ** 0.95
    a1 = erfc_inverse(2 * P0 / H_mic)
    a2 = erfc_inverse(0.03 * P0 / H_mic) - a1
    width = 2 * math.sqrt(2) * sigma
    R_g = width * a2 / (math.pi * k_g * a * a * math.log1p(a2 / (a1 + M / width)))
    H = 1 / (R_L + 1 / (1 / R_s + 1 / R_g))
    A = 2 * math.sqrt(R * R - a * a)
    macrogap = 0.5 * math.pi * k_g * ((A + M) * math.log((A + M) / M) - A)
    print(f"| {F:g} | {a * 1e6:.3g} | {P0 / 1e6:.3g} | {R_L:.4g} | {R_s:.4g} | {R_g:.2g} | "
          f"{H:.3g} | {2 * k * a:.3g} | {macrogap:.3g} |")
