#!/usr/bin/env python3
"""CMA-ES (Hansen and Ostermeier 2001) on an AHHS scenario, through DEAP's ask/tell cma.Strategy
(Debian's python3-deap) and the evaluation service. Copy it and change what you like.

    python3 examples/optimizers/cmaes.py runs/cma-pendulum \\
        --bin build/bin -- --scenario pendulum --variant ahhs2 --hormones 15 --rules 15

The run directory is a run like ahhs-evolve's (ahhs-report, ahhs-replay, ahhs-view --run read
it) with the optimizer checkpointed beside it: run the same command again after a kill (or
Ctrl-C) and the search resumes and ends as if it had never stopped. The options after `--` are
ahhs-evaluate's scenario and evaluation options (scenario, shape, trials, envelope, seed).

CMA-ES searches the genome vector's unit cube: y in [0, 1]^n maps to lower + (upper - lower) * y
(values outside are clipped), so that one step size fits values of every range. It starts at
the cube's centre with step size --sigma.
"""
import argparse
import os
import sys

import numpy as np
from deap import base, cma

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "python"))
import ahhs  # noqa: E402
from ahhs.search import interrupted, run_search, stop_on_signals  # noqa: E402


class FitnessMax(base.Fitness):
    weights = (1.0,)


class Individual(list):
    """What DEAP's strategy makes and ranks: a list of floats with a fitness."""

    def __init__(self, values):
        super().__init__(values)
        self.fitness = FitnessMax()


class CmaEs:
    """The optimizer run_search drives (ahhs/search.py): ask, tell, picklable."""

    def __init__(self, shape, population, sigma, seed):
        _, lower, upper = ahhs.layout(shape)
        self.lower, self.span = np.array(lower), np.array(upper) - np.array(lower)
        np.random.seed(seed)  # DEAP's strategy draws from numpy's global generator
        self.strategy = cma.Strategy(centroid=[0.5] * len(lower), sigma=sigma,
                                     lambda_=population)
        self._asked = None

    def ask(self):
        self._asked = self.strategy.generate(Individual)
        return [self.lower + self.span * np.clip(np.array(y), 0.0, 1.0) for y in self._asked]

    def tell(self, vectors, results):
        for individual, result in zip(self._asked, results):
            individual.fitness.values = (result["fitness"],)
        self.strategy.update(self._asked)
        self._asked = None


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("run_dir")
    p.add_argument("--population", type=int, default=20, help="lambda, genomes per generation")
    p.add_argument("--generations", type=int, default=200)
    p.add_argument("--sigma", type=float, default=0.2, help="initial step size in the unit cube")
    p.add_argument("--seed", type=int, default=1, help="the optimizer's seed")
    p.add_argument("--bin", help="directory of ahhs-evaluate (default: $AHHS_BIN or PATH)")
    p.add_argument("--farm", default="", help="ahhs-evaluate's farm options, e.g. '--workers 2'")
    p.epilog = "After --: ahhs-evaluate's scenario and evaluation options (scenario, shape, trials, envelope, seed)."
    argv, evaluation = sys.argv[1:], []
    if "--" in argv:
        argv, evaluation = argv[:argv.index("--")], argv[argv.index("--") + 1:]
    a = p.parse_args(argv)
    binary = os.path.join(a.bin, "ahhs-evaluate") if a.bin else None
    stop_on_signals()
    try:
        run_search(a.run_dir, lambda ev: CmaEs(ev.shape, a.population, a.sigma, a.seed),
                   evaluation=evaluation,
                   population=a.population, generations=a.generations, name="cma-es (deap)",
                   farm=a.farm.split(), binary=binary, log=lambda line: print(line, flush=True))
    except KeyboardInterrupt:
        interrupted(a.run_dir)
    print("best genome: ahhs-replay %s" % a.run_dir)


if __name__ == "__main__":
    main()
