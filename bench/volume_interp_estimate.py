#!/usr/bin/python3
"""Estimate of an SZ3-style prediction coder's size under a point-wise bound E.

Each brick (64^3 as the volume coder's) alone: the corner anchor quantized directly, then
multilevel interpolation from the coarsest stride down, along x, then y, then z at each level
(cubic where 4 neighbours exist, else quadratic/linear/copy), predicting from the already
reconstructed values; residual quantized with bin 2E (|error| <= E by construction before the
float32 rounding, checked). Cost: adaptive order-0 entropy per (level, axis, context) where the
context is a bucket of the local spread |f(i-h) - f(i+h)| / E (known to the decoder).
Reports the static empirical entropy (a lower bound for an adaptive coder) in bytes.
Optional beta > 1: level-wise bounds E / beta^log2(stride) (capped at 4x), as QoZ tunes SZ3.

    /usr/bin/python3 bench/volume_interp_estimate.py testimages/wmag91.float 91 91 91 1e-3 [brick [beta]]
"""
import sys
import numpy as np


def entropy_bits(codes, ctx):
    """Sum over contexts of n H(codes | ctx) (empirical, static), in bits."""
    bits = 0.0
    if codes.size == 0:
        return 0.0
    key = ctx.astype(np.int64) * (1 << 32) + (codes.astype(np.int64) + (1 << 31))
    _, counts = np.unique(key, return_counts=True)
    _, ctx_counts = np.unique(ctx, return_counts=True)
    bits = -(counts * np.log2(counts)).sum() + (ctx_counts * np.log2(ctx_counts)).sum()
    return bits


def code_brick(x, E0, stats, nctx, beta=1.0):
    """x: float64 brick (z, y, x order array). Returns reconstruction; appends (codes, ctx, tag)."""
    r = np.zeros_like(x)
    dims = x.shape
    maxd = max(dims)
    H = 1
    while H * 2 < maxd:
        H *= 2
    # anchors: points on stride 2H grid (just the origin for a 64 brick... and far corners)
    sl = tuple(slice(0, None, 2 * H) for _ in range(3))
    a = x[sl]
    E = E0 / beta ** 6
    q = np.rint(a / (2 * E))
    r[sl] = q * 2 * E
    stats.append((q.ravel().astype(np.int64), np.zeros(q.size, np.int64), 'anchor'))
    h = H
    level = 0
    while h >= 1:
        E = E0 / min(beta ** int(np.log2(h)), 4.0) if beta != 1.0 else E0
        for axis in (2, 1, 0):  # numpy axes: 2 is x
            # positions: along `axis` odd multiples of h; along axes already done at this level
            # multiples of h; along axes not yet done multiples of 2h.
            idx = []
            for ax in range(3):
                if ax == axis:
                    idx.append(np.arange(h, dims[ax], 2 * h))
                elif (ax > axis):  # x (2) done before y (1) before z (0): ax > axis means done
                    idx.append(np.arange(0, dims[ax], h))
                else:
                    idx.append(np.arange(0, dims[ax], 2 * h))
            if any(len(i) == 0 for i in idx):
                continue
            t = idx[axis]
            n = dims[axis]
            # neighbours along axis
            def take(off):
                pos = t + off
                valid = (pos >= 0) & (pos < n)
                pos_c = np.clip(pos, 0, n - 1)
                ix = list(idx)
                ix[axis] = pos_c
                v = r[np.ix_(*ix)]
                shape = [1, 1, 1]
                shape[axis] = len(t)
                return v, valid.reshape(shape)
            m1, v1 = take(-h)
            p1, w1 = take(h)
            m3, v3 = take(-3 * h)
            p3, w3 = take(3 * h)
            cubic = (-m3 + 9 * m1 + 9 * p1 - p3) / 16
            lin = (m1 + p1) / 2
            quad_left = (-m3 + 6 * m1 + 3 * p1) / 8  # no p3
            quad_right = (3 * m1 + 6 * p1 - p3) / 8  # no m3
            extrap = m1  # one neighbour only (the last target of an even-length axis): copy it
            pred = np.where(v1 & w1 & v3 & w3, cubic,
                    np.where(v1 & w1 & v3, quad_left,
                    np.where(v1 & w1 & w3, quad_right,
                    np.where(v1 & w1, lin, extrap))))
            orig = x[np.ix_(*idx)]
            q = np.rint((orig - pred) / (2 * E))
            rec = (pred + q * 2 * E).astype(np.float32).astype(np.float64)
            bad = np.abs(rec - orig) > E
            # float32 rounding can break it: such points would be sent exact (counted)
            rec = np.where(bad, orig, rec)
            r[np.ix_(*idx)] = rec
            spread = np.abs(np.where(w1, p1, m1) - m1) / E0
            c = np.minimum(np.floor(np.log2(spread + 1) * 2), nctx - 1).astype(np.int64)
            c = np.broadcast_to(c, q.shape)
            lev = min(level, 3)
            stats.append((q.ravel().astype(np.int64), c.ravel() + nctx * (3 * lev + axis),
                          ('bad', int(bad.sum()))))
        h //= 2
        level += 1
    return r


def main():
    path, nx, ny, nz, rel = sys.argv[1], int(sys.argv[2]), int(sys.argv[3]), int(sys.argv[4]), float(sys.argv[5])
    brick = int(sys.argv[6]) if len(sys.argv) > 6 else 64
    v = np.fromfile(path, dtype=np.float32).reshape(nz, ny, nx).astype(np.float64)
    rng = float(v.max() - v.min())
    E = rel * rng
    nctx = 12
    stats = []
    maxerr = 0.0
    for z in range(0, nz, brick):
        for y in range(0, ny, brick):
            for x in range(0, nx, brick):
                b = v[z:z + brick, y:y + brick, x:x + brick]
                r = code_brick(b, E, stats, nctx, float(sys.argv[7]) if len(sys.argv) > 7 else 1.0)
                maxerr = max(maxerr, float(np.abs(r - b).max()))
    codes = np.concatenate([s[0] for s in stats])
    ctx = np.concatenate([s[1] for s in stats])
    bad = sum(s[2][1] for s in stats if isinstance(s[2], tuple))
    h0 = entropy_bits(codes, np.zeros_like(ctx)) / 8
    hc = entropy_bits(codes, ctx) / 8
    # per-level split entropy (no spread context)
    lvl = ctx // nctx
    hl = entropy_bits(codes, lvl) / 8
    nz_frac = float((codes != 0).mean())
    print(f"{path} rel={rel} E={E:.6g} voxels={v.size} maxerr/E={maxerr / E:.4f} float-bad={bad} "
          f"nonzero={nz_frac:.3f} H0={h0:.0f}B Hlevel={hl:.0f}B Hctx={hc:.0f}B "
          f"ratio_ctx={v.size * 4 / hc:.2f}")


if __name__ == '__main__':
    main()
