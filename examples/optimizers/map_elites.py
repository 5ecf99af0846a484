#!/usr/bin/env python3
"""MAP-Elites (Mouret and Clune 2015) on an AHHS scenario: a grid over the behaviour descriptor
(docs/scenarios.md, "Behaviour descriptors"), one elite per cell, through ahhs.qd (pyribs'
shape) and the evaluation service. Copy it and change what you like.

    python3 examples/optimizers/map_elites.py runs/me-pendulum \\
        --bin build/bin -- --scenario pendulum --variant ahhs2 --hormones 15 --rules 15

The run directory is a run like ahhs-evolve's (every genome evaluated is in it) with the
optimizer checkpointed beside it (run the command again to resume after a kill) and the archive
in archive.json after every generation: each cell's fitness, descriptor, and the generation and
individual that ahhs-replay RUN --generation G --individual I replays (add --log F.lcm and watch
it with ahhs-view F.lcm). ahhs-report RUN draws the archive as a heatmap.

With pyribs: replace ahhs.qd's GridArchive, GaussianEmitter and Scheduler by ribs.archives,
ribs.emitters and ribs.schedulers' classes of the same names (pass the metadata as
`tell(objective, measures, metadata=...)`, an extra field in pyribs 0.5 and later).
"""
import argparse
import os
import sys

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "python"))
import ahhs  # noqa: E402
from ahhs.qd import GaussianEmitter, GridArchive, Scheduler  # noqa: E402
from ahhs.search import (interrupted, run_search, stop_on_signals,  # noqa: E402
                         write_json_atomically)

# The descriptors' ranges (docs/scenarios.md): the pendulum's are shares, the gait's metres
# (the wall's inner face is 1 m from the start).
RANGES = {"pendulum": [(0.0, 1.0), (0.0, 1.0)], "gait": [(-1.5, 1.5), (-1.5, 1.5)]}


class MapElites:
    """The optimizer run_search drives (ahhs/search.py), in the genome vector's unit cube."""

    def __init__(self, shape, scenario, descriptor, cells, batch, sigma, seed):
        _, lower, upper = ahhs.layout(shape)
        self.lower, self.span = np.array(lower), np.array(upper) - np.array(lower)
        n = len(lower)
        self.descriptor, self.ranges = descriptor, RANGES[scenario]
        self.archive = GridArchive(n, [cells, cells], self.ranges)
        emitter = GaussianEmitter(self.archive, sigma=sigma, x0=[0.5] * n,
                                  bounds=[(0.0, 1.0)] * n, batch_size=batch, seed=seed)
        self.scheduler = Scheduler(self.archive, [emitter])
        self.generation = 0

    def ask(self):
        return [self.lower + self.span * y for y in self.scheduler.ask()]

    def tell(self, vectors, results):
        self.scheduler.tell(np.array([r["fitness"] for r in results]),
                            [r["descriptor"] for r in results],
                            metadata=[{"generation": self.generation, "individual": i}
                                      for i in range(len(results))])
        self.generation += 1

    def after_generation(self, run_dir, generation, vectors, results):
        write_json_atomically(os.path.join(run_dir, "archive.json"), {
            "format": "ahhs-archive", "version": 1, "generation": generation,
            "descriptor": self.descriptor, "ranges": self.ranges,
            "dims": list(self.archive.dims), "stats": self.archive.stats,
            "cells": [{"cell": list(cell), "fitness": e["objective"],
                       "descriptor": list(map(float, e["measures"])), **e["metadata"]}
                      for cell, e in self.archive]})


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("run_dir")
    p.add_argument("--batch", type=int, default=20, help="genomes per generation")
    p.add_argument("--generations", type=int, default=200)
    p.add_argument("--cells", type=int, default=10, help="cells per descriptor value")
    p.add_argument("--sigma", type=float, default=0.1, help="mutation step in the unit cube")
    p.add_argument("--seed", type=int, default=1, help="the optimizer's seed")
    p.add_argument("--bin", help="directory of ahhs-evaluate (default: $AHHS_BIN or PATH)")
    p.add_argument("--farm", default="", help="ahhs-evaluate's farm options, e.g. '--workers 2'")
    p.epilog = "After --: ahhs-evaluate's scenario and evaluation options (scenario, shape, trials, envelope, seed)."
    argv, evaluation = sys.argv[1:], []
    if "--" in argv:
        argv, evaluation = argv[:argv.index("--")], argv[argv.index("--") + 1:]
    a = p.parse_args(argv)
    binary = os.path.join(a.bin, "ahhs-evaluate") if a.bin else None

    def make(ev):
        return MapElites(ev.shape, ev.hello["scenario"], ev.descriptor_names, a.cells, a.batch,
                         a.sigma, a.seed)

    stop_on_signals()
    try:
        me = run_search(a.run_dir, make, evaluation=evaluation, population=a.batch,
                        generations=a.generations, name="map-elites", farm=a.farm.split(),
                        binary=binary, log=lambda line: print(line, flush=True))
    except KeyboardInterrupt:
        interrupted(a.run_dir)
    stats = me.archive.stats
    print("archive: %d of %d cells, best %.6g" % (stats["num_elites"], a.cells * a.cells,
                                                   stats["obj_max"]))


if __name__ == "__main__":
    main()
