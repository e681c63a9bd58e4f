# Before/after check of a volume coder speed change: two pupwave binaries and zfp,
# whole-process CPU time (user + system), median of 3 interleaved runs, 1 thread, at 1e-2, 1e-3
# and 1e-4 of the range on wmag91 and a 256^3 turbulence field; both binaries must give the same
# stream, and decode the old binary's stream to the same bytes.
# Usage: cd DIR_WITH(wmag91.float, turb256.raw) && python3 volume_speed_ab.py OLD_PUPWAVE NEW_PUPWAVE
# (turb256.raw from `pupwave generate-volume --kind turbulence --size 256 turb256.raw`; the value
# ranges below are those bench/volume_maxerr.c reports for the two files).
import statistics, subprocess, sys
base, new = sys.argv[1], sys.argv[2]
def cpu(cmd):
    p = subprocess.run(["/usr/bin/time", "-f", "%U %S"] + cmd, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True, check=True)
    u, s = p.stderr.strip().splitlines()[-1].split()
    return float(u) + float(s)
print("| volume | E / range | base enc | new enc | zfp enc | base dec | new dec | zfp dec | new enc / zfp | new dec / zfp | streams identical |")
print("|---|---|---|---|---|---|---|---|---|---|---|")
for f, n, r in (("wmag91.float", 91, 265.24582656), ("turb256.raw", 256, 8.58081411)):
    for rel in (1e-2, 1e-3, 1e-4):
        tol = repr(rel * r); d = f"{n},{n},{n}"
        enc = {"base": [base, "compress", f, "ab_b.pw", "--dims", d, "--dtype", "f32", "--max-error", tol, "--threads", "1"],
               "new": [new, "compress", f, "ab_n.pw", "--dims", d, "--dtype", "f32", "--max-error", tol, "--threads", "1"],
               "zfp": ["zfp", "-f", "-3", str(n), str(n), str(n), "-a", tol, "-i", f, "-z", "ab.zfp"]}
        dec = {"base": [base, "decompress", "ab_b.pw", "ab_b.out", "--threads", "1"],
               "new": [new, "decompress", "ab_b.pw", "ab_n.out", "--threads", "1"],
               "zfp": ["zfp", "-f", "-3", str(n), str(n), str(n), "-a", tol, "-z", "ab.zfp", "-o", "ab_z.out"]}
        te = {k: [] for k in enc}; td = {k: [] for k in dec}
        for _ in range(3):
            for k in enc: te[k].append(cpu(enc[k]))
            for k in dec: td[k].append(cpu(dec[k]))
        m = lambda t: {k: statistics.median(v) for k, v in t.items()}
        e, dd = m(te), m(td)
        same = open("ab_b.pw", "rb").read() == open("ab_n.pw", "rb").read() and open("ab_b.out", "rb").read() == open("ab_n.out", "rb").read()
        print(f"| {f} | {rel:g} | {e['base']:.2f} | {e['new']:.2f} | {e['zfp']:.2f} | {dd['base']:.2f} | {dd['new']:.2f} | {dd['zfp']:.2f} | "
              f"{e['new'] / e['zfp']:.1f} | {dd['new'] / dd['zfp']:.1f} | {'yes' if same else 'NO'} |", flush=True)
