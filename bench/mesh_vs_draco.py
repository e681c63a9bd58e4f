#!/usr/bin/env python3
"""Size of pupwave's .pwm (sqrt(3) multiresolution, quantised + range coded) against Draco at
equal maximum vertex error, on meshes with sqrt(3) connectivity (what .pwm codes).

For each mesh and each Draco position quantisation (-qp), Draco's file is decoded and its max
vertex error measured (Draco reorders vertices, so each decoded vertex is matched to its
nearest original and vice versa: the larger of the two maxima, which equals the true
per-vertex error while errors are far below the vertex spacing). pupwave then codes the same
mesh with --max-error set to exactly that error, and its decoded mesh is measured the same way
(vertex order is kept, so directly). Usage (from the repository root, after a build):

  /usr/bin/python3 bench/mesh_vs_draco.py [--out T.md]   (default /tmp/mesh_vs_draco.md; tables for bench/results/meshes.md)

Needs Debian's draco (draco_encoder, draco_decoder) and libcgal-demo (the base meshes).
"""
import argparse, os, subprocess, sys, tarfile, tempfile, time
import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
PUPWAVE = os.path.join(ROOT, "build", "tools", "pupwave")
CGAL = "/usr/share/doc/libcgal-dev/data.tar.gz"


def run(args):
    r = subprocess.run(args, capture_output=True, text=True)
    if r.returncode != 0:
        sys.exit("failed: %s\n%s%s" % (" ".join(args), r.stdout, r.stderr))
    return r.stdout


def read_obj(path):
    v, f = [], []
    for line in open(path):
        t = line.split()
        if not t:
            continue
        if t[0] == "v":
            v.append([float(x) for x in t[1:4]])
        elif t[0] == "f":
            f.append([int(x.split("/")[0]) - 1 for x in t[1:4]])
    return np.array(v), np.array(f)


def write_obj(path, v, f):
    with open(path, "w") as out:
        for p in v:
            out.write("v %.17g %.17g %.17g\n" % tuple(p))
        for t in f:
            out.write("f %d %d %d\n" % tuple(t + 1))


def nearest_max(a, b):
    """max over a of the distance to the nearest point of b."""
    worst = 0.0
    for i in range(0, len(a), 512):
        d = ((a[i:i + 512, None, :] - b[None, :, :]) ** 2).sum(axis=2)
        worst = max(worst, float(np.sqrt(d.min(axis=1)).max()))
    return worst


def draco_point(fine_obj, v, qp, tmp):
    drc, dec = os.path.join(tmp, "x.drc"), os.path.join(tmp, "x_dec.obj")
    run(["draco_encoder", "-i", fine_obj, "-o", drc, "-qp", str(qp), "-cl", "10"])
    run(["draco_decoder", "-i", drc, "-o", dec])
    w, _ = read_obj(dec)
    return os.path.getsize(drc), max(nearest_max(w, v), nearest_max(v, w))


def pupwave_point(fine_obj, v, levels, bound, tmp):
    pwm, back = os.path.join(tmp, "x.pwm"), os.path.join(tmp, "x_back.obj")
    run([PUPWAVE, "mesh", "decompose", fine_obj, pwm, "--levels", str(levels), "--max-error", repr(bound)])
    run([PUPWAVE, "mesh", "reconstruct", pwm, back])
    w, _ = read_obj(back)
    return os.path.getsize(pwm), float(np.sqrt(((w - v) ** 2).sum(axis=1)).max())


def make_cases(tmp):
    with tarfile.open(CGAL) as t:
        for name in ("dragknob.off", "nefertiti.off", "pig.off"):
            t.extract("data/meshes/" + name, tmp)
    cases = []
    for name in ("dragknob", "nefertiti", "pig"):
        fine = os.path.join(tmp, name + "_s3.obj")
        run([PUPWAVE, "mesh", "subdivide", os.path.join(tmp, "data/meshes", name + ".off"), fine, "--levels", "3"])
        cases.append((name + " subdivided 3x (smooth)", fine))
        v, f = read_obj(fine)
        rng = np.random.default_rng(22)
        diag = np.linalg.norm(v.max(axis=0) - v.min(axis=0))
        noisy = os.path.join(tmp, name + "_s3_noise.obj")
        write_obj(noisy, v + rng.uniform(-1, 1, v.shape) * 1e-3 * diag, f)
        cases.append((name + " subdivided 3x + noise 0.1% of diagonal", noisy))
    # Section 9's torus: a 24 x 16 grid subdivided 3x, every vertex projected onto the torus.
    R, r, nu, nv = 1.0, 0.4, 24, 16
    u, w = np.meshgrid(2 * np.pi * np.arange(nu) / nu, 2 * np.pi * np.arange(nv) / nv, indexing="ij")
    pts = np.stack([(R + r * np.cos(w)) * np.cos(u), (R + r * np.cos(w)) * np.sin(u), r * np.sin(w)], -1).reshape(-1, 3)
    idx = lambda i, j: (i % nu) * nv + (j % nv)
    faces = []
    for i in range(nu):
        for j in range(nv):
            faces += [[idx(i, j), idx(i + 1, j), idx(i + 1, j + 1)], [idx(i, j), idx(i + 1, j + 1), idx(i, j + 1)]]
    base = os.path.join(tmp, "torus.obj")
    write_obj(base, pts, np.array(faces))
    sub = os.path.join(tmp, "torus_s3.obj")
    run([PUPWAVE, "mesh", "subdivide", base, sub, "--levels", "3"])
    v, f = read_obj(sub)
    uu, rr = np.arctan2(v[:, 1], v[:, 0]), np.hypot(v[:, 0], v[:, 1])
    ww = np.arctan2(v[:, 2], rr - R)
    on = np.stack([(R + r * np.cos(ww)) * np.cos(uu), (R + r * np.cos(ww)) * np.sin(uu), r * np.sin(ww)], -1)
    torus = os.path.join(tmp, "torus_s3_sampled.obj")
    write_obj(torus, on, f)
    cases.append(("torus 24x16 subdivided 3x, sampled on the torus (Sec. 9)", torus))
    return cases


def write_report(rows, path, draco_version):
    with open(path, "w") as out:
        out.write("# Mesh coding: pupwave .pwm against Draco at equal max vertex error\n\n")
        out.write("Generated by `/usr/bin/python3 bench/mesh_vs_draco.py` (%s) on a shared 2-core AMD EPYC, Debian 12;\n"
                  % time.strftime("%Y-%m-%d"))
        out.write("Draco %s (`draco_encoder -qp QP -cl 10`). For each Draco point its decoded max vertex error\n"
                  "(Euclidean, vertices matched by nearest neighbour) is measured, then pupwave codes the same mesh with\n"
                  "`pupwave mesh decompose --levels 3 --max-error <that error>`; its own decoded max error is in the next\n"
                  "column (it must not exceed Draco's). Both files hold positions and connectivity only. Meshes: real\n"
                  "CGAL models (libcgal-demo) subdivided 3 times by `pupwave mesh subdivide` (smooth sqrt(3) surfaces,\n"
                  "pupwave's best case), the same with uniform noise of 0.1%% of the bounding-box diagonal per\n"
                  "coordinate (incompressible detail), and Section 9's torus sampled from its equation.\n\n" % draco_version)
        out.write("## Summary: geometric mean of pupwave bytes / Draco bytes over the qp settings\n\n")
        out.write("| mesh | pupwave / Draco |\n|---|---:|\n")
        labels = []
        for r in rows:
            if r[0] not in labels:
                labels.append(r[0])
        for label in labels:
            ratios = [r[7] / r[5] for r in rows if r[0] == label]
            out.write("| %s | %.2f |\n" % (label, float(np.exp(np.mean(np.log(ratios))))))
        out.write("\nWhat the numbers say: where the geometry is what sqrt(3) refinement predicts (smooth\n"
                  "subdivision surfaces, and the torus sampled from its equation, whose details are genuine but\n"
                  "small) pupwave's files are several times smaller than Draco's at the same max vertex error:\n"
                  "only the coarsest mesh (3.7 % of the vertices after 3 levels) and small details are coded, and\n"
                  "the connectivity of the finer levels is implied. With incompressible noise pupwave loses. Each\n"
                  "reversal amplifies independent noise by about 2 (the A row norm, docs/sqrt3.md, Fig. 22), and\n"
                  "the max-error search has to cover the worst vertex after all levels' quantisation errors add\n"
                  "up; Draco's parallelogram prediction quantises each vertex once. Halving the step per coarser\n"
                  "level (the encoder's rule) gained up to 14 % over one step for all on the noisy meshes. Not\n"
                  "tried: outlier corrections at the finest level (as the volume codec does), richer contexts.\n"
                  "pupwave also needs a mesh with sqrt(3) connectivity (it codes the hierarchy); Draco codes any.\n")
        out.write("\n## All points\n\n")
        out.write("| mesh | vertices | faces | Draco qp | Draco max error | Draco bytes | pupwave max error | pupwave bytes | pupwave / Draco |\n")
        out.write("|---|---:|---:|---:|---:|---:|---:|---:|---:|\n")
        for label, nv, nf, qp, de, ds, pe, ps in rows:
            out.write("| %s | %d | %d | %d | %.3g | %d | %.3g | %d | %.2f |\n" % (label, nv, nf, qp, de, ds, pe, ps, ps / ds))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--out", default="/tmp/mesh_vs_draco.md")
    ap.add_argument("--qp", default="8,10,12,14,16")
    args = ap.parse_args()
    draco_version = run(["dpkg-query", "-W", "-f=${Version}", "draco"])
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        for label, fine in make_cases(tmp):
            v, f = read_obj(fine)
            for qp in [int(q) for q in args.qp.split(",")]:
                d_size, d_err = draco_point(fine, v, qp, tmp)
                p_size, p_err = pupwave_point(fine, v, 3, d_err, tmp)
                rows.append((label, len(v), len(f), qp, d_err, d_size, p_err, p_size))
                print("%-58s qp %2d  draco %8d B err %.3g | pupwave %8d B err %.3g" % (label, qp, d_size, d_err, p_size, p_err))
                sys.stdout.flush()
    write_report(rows, args.out, draco_version)
    print("wrote", args.out)


if __name__ == "__main__":
    main()
