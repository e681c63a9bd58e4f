#!/usr/bin/env python3
"""BD-PSNR of every codec of a `pupwave bench rd` results.csv against a chosen anchor codec
(the harness reports them against OpenJPEG only). Same method as tools/bench/bd_metrics.h:
cubic least-squares fit of PSNR in log10(achieved bpp), mean gap over the common range,
averaged over images. Pure Python (no numpy).

    python3 bench/bd_vs.py bench/results/pups/results.csv cdf97
"""
import csv
import math
import sys
from collections import defaultdict


def polyfit(xs, ys, degree):
    # Normal equations of the least-squares polynomial (small, well-scaled problems only).
    n = degree + 1
    a = [[sum(x ** (i + j) for x in xs) for j in range(n)] for i in range(n)]
    b = [sum(y * x ** i for x, y in zip(xs, ys)) for i in range(n)]
    for col in range(n):  # Gaussian elimination with partial pivoting
        piv = max(range(col, n), key=lambda r: abs(a[r][col]))
        a[col], a[piv], b[col], b[piv] = a[piv], a[col], b[piv], b[col]
        for r in range(col + 1, n):
            f = a[r][col] / a[col][col]
            a[r] = [u - f * v for u, v in zip(a[r], a[col])]
            b[r] -= f * b[col]
    c = [0.0] * n
    for r in reversed(range(n)):
        c[r] = (b[r] - sum(a[r][k] * c[k] for k in range(r + 1, n))) / a[r][r]
    return c  # c[k] multiplies x^k


def integral(c, lo, hi):
    return sum(ck / (k + 1) * (hi ** (k + 1) - lo ** (k + 1)) for k, ck in enumerate(c))


def bd_psnr(anchor, test):
    la, lt = [math.log10(p[0]) for p in anchor], [math.log10(p[0]) for p in test]
    ca = polyfit(la, [p[1] for p in anchor], min(3, len(anchor) - 1))
    ct = polyfit(lt, [p[1] for p in test], min(3, len(test) - 1))
    lo, hi = max(min(la), min(lt)), min(max(la), max(lt))
    return (integral(ct, lo, hi) - integral(ca, lo, hi)) / (hi - lo)


def main(path, anchor):
    curves = defaultdict(lambda: defaultdict(list))
    for r in csv.DictReader(open(path)):
        if r["status"] == "ok":
            curves[r["codec"]][r["image"]].append((float(r["bpp"]), float(r["psnr_db"])))
    images = sorted(curves[anchor])
    print("| codec | BD-PSNR vs %s (dB) | %s |" % (anchor, " | ".join(images)))
    print("|---|---:|" + "---:|" * len(images))
    for codec, per in curves.items():
        vals = [bd_psnr(sorted(curves[anchor][im]), sorted(per[im])) for im in images]
        print("| %s | %+.3f | %s |" % (codec, sum(vals) / len(vals), " | ".join("%+.3f" % v for v in vals)))


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2] if len(sys.argv) > 2 else "cdf97")
