#!/usr/bin/env python3
"""Lift helper's A/B: encode/decode CPU (user+sys, --threads 1, median of REPS) and bytes of
`pupwave compress --max-error` with the default transform and with pups:cinpact-interp-vm4, for
two pupwave binaries (before, after) run interleaved, on wmag91 and a 256^3 turbulence field at
bounds 1e-2, 1e-3, 1e-4 of the value range; every decoded voxel is checked against the bound by
bench/volume_maxerr.c. Usage: bench/lift_ab.py BEFORE AFTER [REPS] (prints a Markdown table)."""
import os, statistics, subprocess, sys, tempfile

here = os.path.dirname(os.path.abspath(__file__))
before, after = sys.argv[1], sys.argv[2]
reps = int(sys.argv[3]) if len(sys.argv) > 3 else 3
work = tempfile.mkdtemp()
maxerr = f"{work}/maxerr"
subprocess.run(["cc", "-O2", "-o", maxerr, f"{here}/volume_maxerr.c", "-lm"], check=True)
turb = f"{work}/turb256.raw"
subprocess.run([after, "generate-volume", "--kind", "turbulence", "--size", "256", turb], check=True,
               stdout=subprocess.DEVNULL)
inputs = [(f"{here}/../testimages/wmag91.float", 91, "wmag91"), (turb, 256, "turbulence 256^3")]
transforms = [("default", []), ("vm4", ["--transform", "pups:cinpact-interp-vm4"])]

def cpu(cmd):
    p = subprocess.run(["/usr/bin/time", "-f", "%U %S"] + cmd, check=True, stdout=subprocess.DEVNULL,
                       stderr=subprocess.PIPE, text=True)
    u, s = p.stderr.strip().splitlines()[-1].split()
    return float(u) + float(s)

print("| input | bound | transform | bytes before | bytes after | encode CPU s before | after |"
      " decode CPU s before | after | max error / E after | voxels over E |")
print("|---|---|---|---|---|---|---|---|---|---|---|")
for path, n, name in inputs:
    lo, hi = map(float, subprocess.run([maxerr, path], check=True, capture_output=True, text=True).stdout.split())
    for rel in (1e-2, 1e-3, 1e-4):
        tol = rel * (hi - lo)
        enc = {(b, t): [] for b in ("before", "after") for t, _ in transforms}
        dec = {k: [] for k in enc}
        size, worst = {}, {}
        for _ in range(reps):
            for b, exe in (("before", before), ("after", after)):
                for t, extra in transforms:
                    s, o = f"{work}/{b}{t}.pw", f"{work}/{b}{t}.out"
                    enc[b, t].append(cpu([exe, "compress", path, s, "--dims", f"{n},{n},{n}", "--dtype", "f32",
                                          "--max-error", repr(tol), "--threads", "1"] + extra))
                    dec[b, t].append(cpu([exe, "decompress", s, o, "--threads", "1"]))
                    size[b, t] = os.path.getsize(s)
                    w, over = subprocess.run([maxerr, path, o, repr(tol)], check=True, capture_output=True,
                                             text=True).stdout.split()
                    worst[b, t] = (float(w) / tol, int(over))
        med = lambda d, k: statistics.median(d[k])
        for t, _ in transforms:
            print(f"| {name} | {rel:g} | {t} | {size['before', t]} | {size['after', t]} | "
                  f"{med(enc, ('before', t)):.2f} | {med(enc, ('after', t)):.2f} | {med(dec, ('before', t)):.2f} | "
                  f"{med(dec, ('after', t)):.2f} | {worst['after', t][0]:.4f} | "
                  f"{worst['before', t][1]} / {worst['after', t][1]} |", flush=True)
