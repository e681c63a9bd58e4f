#!/usr/bin/env python3
"""Independent check of the coding gains in docs/pups.md (no pupwave code, no numpy).

Katto-Yasuda generalized coding gain of the dyadic tree of a two-channel filter bank for a
unit-variance AR(1) source: G = -10 sum_b eta_b log10(sigma_b^2 |g_b|^2), with eta_b the share
of samples of band b, sigma_b^2 the variance of its equivalent analysis filter's output and
g_b its equivalent synthesis filter. Filters: CDF 9/7 and 5/3 of ISO/IEC 15444-1 Annex F
(high-pass filters are the modulated low-pass filters of the other side).

    python3 bench/cdf_coding_gain.py      # prints levels 1..6 for both banks at rho = 0.95
"""

H0_97 = [0.026748757411, -0.016864118443, -0.078223266529, 0.266864118443, 0.602949018236,
         0.266864118443, -0.078223266529, -0.016864118443, 0.026748757411]
G0_97 = [-0.091271763114, -0.057543526229, 0.591271763114, 1.115087052457, 0.591271763114,
         -0.057543526229, -0.091271763114]
H0_53 = [-0.125, 0.25, 0.75, 0.25, -0.125]
G0_53 = [0.5, 1.0, 0.5]


def modulate(f):
    return [c * (-1) ** i for i, c in enumerate(f)]


def convolve(a, b):
    out = [0.0] * (len(a) + len(b) - 1)
    for i, x in enumerate(a):
        for j, y in enumerate(b):
            out[i + j] += x * y
    return out


def upsample(f, m):
    out = [0.0] * ((len(f) - 1) * m + 1)
    out[::m] = f
    return out


def ar1_variance(f, rho):
    n = len(f)
    return sum((1 if k == 0 else 2) * sum(f[i] * f[i + k] for i in range(n - k)) * rho ** k for k in range(n))


def coding_gain_db(h0, g0, levels, rho=0.95):
    import math
    h1, g1 = modulate(g0), modulate(h0)
    a, s, total = [1.0], [1.0], 0.0
    for j in range(1, levels + 1):
        up = 2 ** (j - 1)
        hd, gd = convolve(a, upsample(h1, up)), convolve(s, upsample(g1, up))
        total += 2.0 ** -j * math.log10(ar1_variance(hd, rho) * sum(x * x for x in gd))
        a, s = convolve(a, upsample(h0, up)), convolve(s, upsample(g0, up))
    total += 2.0 ** -levels * math.log10(ar1_variance(a, rho) * sum(x * x for x in s))
    return -10 * total


if __name__ == "__main__":
    for name, h0, g0 in (("cdf97", H0_97, G0_97), ("cdf53", H0_53, G0_53)):
        print(name, " ".join("L%d %.3f" % (l, coding_gain_db(h0, g0, l)) for l in range(1, 7)))
