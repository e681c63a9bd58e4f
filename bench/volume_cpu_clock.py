#!/usr/bin/env python3
"""CPU time (perf stat task-clock, ms, whole process) of pupwave and zfp on wmag91 at 1e-2/1e-3/1e-4 of its
range: median of 25 interleaved runs per command. For volumes too small for /usr/bin/time's 0.01 s
resolution (bench/volume_speed.sh). Usage: bench/volume_cpu_clock.py PUPWAVE testimages/wmag91.float RANGE
(RANGE = max - min of the field: 265.24582678452134 for wmag91). Writes files in /tmp."""
import subprocess, statistics, sys
B, W, R = sys.argv[1], sys.argv[2], float(sys.argv[3])
def clock(cmd):
    p = subprocess.run(["perf","stat","-x,","-e","task-clock"]+cmd, capture_output=True, text=True)
    for l in p.stderr.splitlines():
        if "task-clock" in l: return float(l.split(",")[0])
for rel in (1e-2, 1e-3, 1e-4):
    tol = repr(R*rel)
    cmds = {"pw_enc": [B,"compress","--threads","1","--dims","91,91,91","--dtype","f32","--max-error",tol,W,"/tmp/w.pw"],
            "pw_dec": [B,"decompress","--threads","1","/tmp/w.pw","/tmp/w.out"],
            "zfp_enc": ["zfp","-f","-3","91","91","91","-a",tol,"-i",W,"-z","/tmp/z.zfp"],
            "zfp_dec": ["zfp","-f","-3","91","91","91","-a",tol,"-z","/tmp/z.zfp","-o","/tmp/z.out"]}
    t = {k: [] for k in cmds}
    for i in range(25):
        for k, c in cmds.items(): t[k].append(clock(c))
    m = {k: statistics.median(v) for k, v in t.items()}
    print(f"| {rel} | {m['pw_enc']:.1f} | {m['zfp_enc']:.1f} | {m['pw_enc']/m['zfp_enc']:.2f} | {m['pw_dec']:.1f} | {m['zfp_dec']:.1f} | {m['pw_dec']/m['zfp_dec']:.2f} |")
