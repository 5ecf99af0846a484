#!/usr/bin/python3
"""Random pendulum controllers, before evolution: the table of docs/results.md ("The pendulum
comes out the other way round").

  studies/paper-2010-random-genomes.py BIN_DIR [--count N]

For k = 1..N it makes the random genome of seed k (`ahhs-genome random`, the pendulum's 15
hormones, 10 sensors and 2 actuators) of each setting below, replays it once on the pendulum
with evaluation seed k (`ahhs-replay --csv`) and prints, per setting, a Markdown row: how many
score below 0.02, the median and best fitness, the share whose actuators still vary by more
than 0.05 in the episode's second half, and the median over genomes of mean |A0| + |A1| over
that half. Two settings change an AHHS2 genome after it is drawn (not options of the tools):
trigger window centres mapped from [-1, 1] onto [0, 1], where concentrations and sensors live,
and each rule's type weights made one-hot on its largest weight (the paper's future work:
"initialized with specialized sensor, hormone, and actuator rules").
"""
import argparse
import json
import os
import subprocess
import sys
import tempfile

import numpy as np

TYPES = ["idle", "sensor", "linear", "nonlinear", "actuator"]


def random_genome(bin_dir, variant, rules, seed):
    out = subprocess.run([os.path.join(bin_dir, "ahhs-genome"), "random", "--variant", variant,
                          "--hormones", "15", "--rules", str(rules), "--sensors", "10",
                          "--actuators", "2", "--seed", str(seed)],
                         check=True, capture_output=True, text=True).stdout
    return json.loads(out)


def centred(genome):
    for r in genome["rules"]:
        r["zeta"] = (r["zeta"] + 1) / 2
    return genome


def specialised(genome):
    for r in genome["rules"]:
        top = max(TYPES, key=lambda t: r["weights"][t])
        r["weights"] = {t: 1.0 if t == top else 0.0 for t in TYPES}
    return genome


SETTINGS = [
    ("AHHS1-60", lambda b, s: random_genome(b, "ahhs1", 60, s)),
    ("AHHS1-15", lambda b, s: random_genome(b, "ahhs1", 15, s)),
    ("AHHS2-15", lambda b, s: random_genome(b, "ahhs2", 15, s)),
    ("AHHS2-60", lambda b, s: random_genome(b, "ahhs2", 60, s)),
    ("AHHS2-15, window centres in [0, 1]", lambda b, s: centred(random_genome(b, "ahhs2", 15, s))),
    ("AHHS2-15, one-hot type weights", lambda b, s: specialised(random_genome(b, "ahhs2", 15, s))),
    ("AHHS2-15, both", lambda b, s: specialised(centred(random_genome(b, "ahhs2", 15, s)))),
]


def evaluate(bin_dir, genome, seed, scratch):
    """(fitness, an actuator varies by > 0.05 in the second half, mean |A0| + |A1| there)."""
    path, trace = os.path.join(scratch, "genome.json"), os.path.join(scratch, "trace.csv")
    with open(path, "w") as f:
        json.dump(genome, f)
    out = subprocess.run([os.path.join(bin_dir, "ahhs-replay"), "--genome", path, "--scenario",
                          "pendulum", "--seed", str(seed), "--csv", trace, "--overwrite"],
                         check=True, capture_output=True, text=True).stdout
    fitness = float(out.rsplit("fitness: ", 1)[1].split()[0])
    t = np.genfromtxt(trace, delimiter=",", names=True)
    half = t[t["tick"] >= (t["tick"].max() + 1) / 2]
    varies = any(np.ptp(half[a][half["module"] == m]) > 0.05
                 for m in np.unique(half["module"]) for a in ("a0", "a1"))
    return fitness, varies, float(np.mean(np.abs(half["a0"]) + np.abs(half["a1"])))


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("bin", help="directory of ahhs-genome and ahhs-replay")
    p.add_argument("--count", type=int, default=200, help="genomes per setting (default 200)")
    args = p.parse_args()
    print("| random genomes | below 0.02 | median fitness | best | actuators still vary "
          "(second half) | mean abs(A0) + abs(A1), median |")
    print("|---|---|---|---|---|---|")
    with tempfile.TemporaryDirectory() as scratch:
        for name, make in SETTINGS:
            res = [evaluate(args.bin, make(args.bin, k), k, scratch)
                   for k in range(1, args.count + 1)]
            f = np.array([r[0] for r in res])
            print(f"| {name} | {np.sum(f < 0.02)} of {args.count} | {np.median(f):.4f} | "
                  f"{f.max():.3f} | {np.mean([r[1] for r in res]):.0%} | "
                  f"{np.median([r[2] for r in res]):.3f} |", flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
