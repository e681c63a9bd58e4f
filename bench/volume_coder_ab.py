# Before/after check of a volume coder change that changes the stream (the coefficient coder of
# max-error bricks, stream version 4): two pupwave binaries and zfp at 1e-2, 1e-3, 1e-4 of the
# range on wmag91 and a 256^3 turbulence field; whole-process CPU time (user + system), median of
# 3 interleaved runs, 1 thread; compressed sizes; each decoded file checked against the bound on
# every voxel by bench/volume_maxerr.c (built as ./maxerr).
# Usage: cd DIR_WITH(wmag91.float, turb256.raw, maxerr) && python3 volume_coder_ab.py OLD NEW
import os, statistics, subprocess, sys

base, new = sys.argv[1], sys.argv[2]


def cpu(cmd):
    p = subprocess.run(["/usr/bin/time", "-f", "%U %S"] + cmd, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE,
                       text=True, check=True)
    u, s = p.stderr.strip().splitlines()[-1].split()
    return float(u) + float(s)


def value_range(path):
    lo, hi = map(float, subprocess.run(["./maxerr", path], check=True, capture_output=True, text=True).stdout.split())
    return hi - lo


print("| volume | E / range | base ratio | new ratio | new / base size | base enc | new enc | zfp enc | base dec | "
      "new dec | zfp dec | new enc / zfp | new dec / zfp | new max err / E | new voxels > E |")
print("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|")
for f, n in (("wmag91.float", 91), ("turb256.raw", 256)):
    r = value_range(f)
    for rel in (1e-2, 1e-3, 1e-4):
        tol = repr(rel * r)
        d = f"{n},{n},{n}"
        enc = {k: [b, "compress", f, f"ab_{k}.pw", "--dims", d, "--dtype", "f32", "--max-error", tol, "--threads", "1"]
               for k, b in (("base", base), ("new", new))}
        enc["zfp"] = ["zfp", "-f", "-3", str(n), str(n), str(n), "-a", tol, "-i", f, "-z", "ab.zfp"]
        dec = {k: [b, "decompress", f"ab_{k}.pw", f"ab_{k}.out", "--threads", "1"] for k, b in (("base", base), ("new", new))}
        dec["zfp"] = ["zfp", "-f", "-3", str(n), str(n), str(n), "-a", tol, "-z", "ab.zfp", "-o", "ab_z.out"]
        te = {k: [] for k in enc}
        td = {k: [] for k in dec}
        for _ in range(3):
            for k in enc:
                te[k].append(cpu(enc[k]))
            for k in dec:
                td[k].append(cpu(dec[k]))
        # CPU time has 0.01 s resolution: zfp on wmag91 can read 0 (ratios then use 0.01 s).
        e = {k: max(statistics.median(v), 0.01) for k, v in te.items()}
        dd = {k: max(statistics.median(v), 0.01) for k, v in td.items()}
        raw = os.path.getsize(f)
        sb, sn = os.path.getsize("ab_base.pw"), os.path.getsize("ab_new.pw")
        worst, over = subprocess.run(["./maxerr", f, "ab_new.out", tol], check=True, capture_output=True,
                                     text=True).stdout.split()
        print(f"| {f} | {rel:g} | {raw / sb:.2f} | {raw / sn:.2f} | {sn / sb:.4f} | {e['base']:.2f} | {e['new']:.2f} | "
              f"{e['zfp']:.2f} | {dd['base']:.2f} | {dd['new']:.2f} | {dd['zfp']:.2f} | {e['new'] / e['zfp']:.1f} | "
              f"{dd['new'] / dd['zfp']:.1f} | {float(worst) / float(tol):.4f} | {over} |")
        sys.stdout.flush()
