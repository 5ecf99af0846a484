#!/usr/bin/python3
"""What the pendulum runs' best controllers do, per configuration of a study or its export: the
behaviour table of docs/results.md ("Watched, the best AHHS1-60 pendulum controller uses the
wall" and "The pendulum's open choices").

  studies/pendulum-behaviour.py BIN_DIR STUDY_OR_EXPORT_DIR

Replays every complete run's best genome (a run directory with `ahhs-replay RUN`, an exported
run with `ahhs-replay --genome best.json`, which carries its task choices) with `--body-csv` and
prints a Markdown row per pendulum configuration: runs, the median best fitness, the share of
ticks with the cart within 1 cm of a wall (or in it, with soft walls) as median and range over
the runs and how many runs spend more than half of their ticks there, the median share of ticks
with the bob above the pivot, and the median number of passes over the top (the pole angle
changing sign within 86 degrees of upright between two ticks).
"""
import csv
import glob
import os
import subprocess
import sys
import tempfile

import numpy as np

WALL = 1.0 - 0.1  # the cart's centre where it touches a wall (docs/scenarios.md: 1 m, 10 cm)
NEAR = 0.01


def behaviour(bin_dir, run, scratch):
    """(fitness, share near a wall, share above the pivot, passes over the top) of a run's best."""
    body = os.path.join(scratch, "body.csv")
    target = [run] if os.path.exists(os.path.join(run, "run.sqlite")) else \
        ["--genome", os.path.join(run, "best.json"), "--scenario", "pendulum"]
    out = subprocess.run([os.path.join(bin_dir, "ahhs-replay")] + target +
                         ["--body-csv", body, "--overwrite"], capture_output=True, text=True)
    lines = [l for l in out.stdout.splitlines() if l.startswith("fitness: ")]
    if out.returncode != 0 or not lines:
        raise SystemExit("%s: ahhs-replay failed: %s" % (run, out.stderr.strip()))
    with open(body) as f:
        rows = list(csv.DictReader(f))
    x = np.array([float(r["cart_x"]) for r in rows])
    angle = np.array([float(r["pole_angle"]) for r in rows])
    near = float(np.mean(np.abs(x) >= WALL - NEAR))
    above = float(np.mean(np.cos(angle) > 0))
    a, b = angle[:-1], angle[1:]
    passes = int(np.sum((a * b < 0) & (np.abs(a) < 1.5) & (np.abs(b) < 1.5)))
    return float(lines[0].split()[1]), near, above, passes


def main():
    if len(sys.argv) != 3:
        raise SystemExit(__doc__)
    bin_dir, study = sys.argv[1], sys.argv[2]
    print("| configuration | runs | best fitness: median | near a wall: median (range) | "
          "runs near a wall > 50 % | bob above the pivot: median | passes over the top: median |")
    print("|---|---|---|---|---|---|---|")
    with tempfile.TemporaryDirectory() as scratch:
        for config in sorted(glob.glob(os.path.join(study, "pendulum-*"))):
            runs = sorted((d for d in glob.glob(os.path.join(config, "seed-*"))
                           if os.path.isfile(os.path.join(d, "summary.json"))),
                          key=lambda d: int(d.rsplit("-", 1)[1]))
            if not runs:
                continue
            b = np.array([behaviour(bin_dir, r, scratch) for r in runs])
            print("| %s | %d | %.3f | %.0f %% (%.0f-%.0f %%) | %d | %.0f %% | %g |" % (
                os.path.basename(config), len(runs), np.median(b[:, 0]), 100 * np.median(b[:, 1]),
                100 * np.min(b[:, 1]), 100 * np.max(b[:, 1]), int(np.sum(b[:, 1] > 0.5)),
                100 * np.median(b[:, 2]), np.median(b[:, 3])))


if __name__ == "__main__":
    main()
