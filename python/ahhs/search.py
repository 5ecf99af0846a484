"""A search whose generations are a run: every generation evaluated by ahhs-evaluate --out and
recorded in RUN_DIR like an ahhs-evolve run (ahhs-report, ahhs-replay RUN --generation G
--individual I and ahhs-view --run read it), and the optimizer checkpointed beside it after every
generation (RUN_DIR/optimizer.pickle, written atomically), so that a search killed at any moment
resumes from its checkpoint and ends as the uninterrupted one, bit for bit.

An optimizer is any object with
    ask() -> a batch of genome vectors (docs/genome.md, "Genome vectors"), `population` of them;
    tell(vectors, results): the service's results of that batch, in order;
    after_generation(run_dir, generation, vectors, results) (optional): files of its own, such as
        a MAP-Elites archive; called before the checkpoint, so a resume rewrites them.
It must be picklable, and draw its random numbers from generators it holds (or from numpy's and
Python's global ones, which the checkpoint saves too).

Ctrl-C (KeyboardInterrupt) stops the service too, even when the signal reached this process
alone, and is raised again once it has stopped. A search's main calls `stop_on_signals` first
and `interrupted` on KeyboardInterrupt.
"""
import os
import pickle
import random
import signal
import sys
import warnings

import numpy as np

from .evaluate import Evaluator

CHECKPOINT = "optimizer.pickle"


def _save(run_dir, state):
    path = os.path.join(run_dir, CHECKPOINT)
    tmp = path + ".tmp"
    with open(tmp, "wb") as f:
        pickle.dump(state, f)
        f.flush()
        os.fsync(f.fileno())
    os.replace(tmp, path)


def _load(run_dir):
    path = os.path.join(run_dir, CHECKPOINT)
    if not os.path.exists(path):
        return None
    with open(path, "rb") as f:
        return pickle.load(f)


def stop_on_signals():
    """For a search's main: SIGINT and SIGTERM raise KeyboardInterrupt, so `kill -INT PID` and
    `kill PID` stop a search and its service in order (a resumable run), also when it was started
    in the background by a script, whose shell has it ignore SIGINT."""
    def interrupt(signum, frame):
        raise KeyboardInterrupt

    signal.signal(signal.SIGINT, signal.default_int_handler)
    signal.signal(signal.SIGTERM, interrupt)


def interrupted(run_dir):
    """What a search's main does on Ctrl-C: one line on how to go on, and exit 130 (as
    ahhs-evolve)."""
    print("interrupted: the same command resumes %s from its last checkpoint" % run_dir,
          file=sys.stderr)
    sys.exit(130)


def parse_finish_by(text, now):
    """A time to finish by, as `ahhs-study run --finish-by` takes it: "HH:MM" (the next such local
    time, today or tomorrow) or a duration from `now` ("90m", "2.5h", "600s"); seconds since the
    epoch. ValueError otherwise."""
    import re
    import time
    bad = ValueError("--finish-by %s: give a time of day HH:MM or a duration such as 90m, 2.5h "
                     "or 600s" % text)
    clock = re.fullmatch(r"(\d\d):(\d\d)", text)
    if clock:
        hours, minutes = int(clock.group(1)), int(clock.group(2))
        if hours > 23 or minutes > 59:
            raise bad
        t = time.localtime(now)
        at = time.mktime((t.tm_year, t.tm_mon, t.tm_mday, hours, minutes, 0, 0, 0, -1))
        if at <= now:  # tomorrow
            at = time.mktime((t.tm_year, t.tm_mon, t.tm_mday + 1, hours, minutes, 0, 0, 0, -1))
        return at
    duration = re.fullmatch(r"(\d+(?:\.\d*)?)([smh])", text)
    if not duration or not 0 < float(duration.group(1)) <= 1e7:
        raise bad
    return now + float(duration.group(1)) * {"s": 1, "m": 60, "h": 3600}[duration.group(2)]


def write_json_atomically(path, doc):
    """For after_generation's files: never half-written."""
    import json
    tmp = path + ".tmp"
    with open(tmp, "w") as f:
        json.dump(doc, f, indent=1)
        f.flush()
        os.fsync(f.fileno())
    os.replace(tmp, path)


def run_search(run_dir, make_optimizer, evaluation=(), population=None, generations=None,
               name=None, farm=(), binary=None, log=None, task=None):
    """Runs (or resumes, when RUN_DIR holds a run) a search to its last generation and returns
    the optimizer. `make_optimizer(evaluator)` makes a fresh one (a new run, or a run killed
    before its first checkpoint); `evaluation` are ahhs-evaluate's scenario and evaluation options
    (scenario, shape, trials, envelope, seed) and `farm` its farm options (workers, --lcm-url,
    arena kind), the only ones a resume takes. `log(text)` gets one line per generation.
    `task` is the old name of `evaluation`, deprecated."""
    if task is not None:
        warnings.warn("run_search(task=...) is deprecated and will go; use evaluation=",
                      DeprecationWarning, stacklevel=2)
        evaluation = task
    resume = os.path.exists(os.path.join(run_dir, "run.sqlite"))
    if resume:
        options = ["--resume", run_dir] + list(farm)
    else:
        if population is None or generations is None or not name:
            raise ValueError("a new run needs population, generations and name")
        options = list(evaluation) + ["--out", run_dir, "--population", population, "--generations",
                                generations, "--optimizer", name] + list(farm)
    with Evaluator(options, binary) as ev:
        run = ev.hello["run"]
        state = _load(run_dir) if resume else None
        if state is None:
            optimizer, generation = make_optimizer(ev), 0
        else:
            optimizer, generation = pickle.loads(state["optimizer"]), state["generation"]
            np.random.set_state(state["numpy_random"])
            random.setstate(state["random"])
        if log and resume:
            log("resuming %s at generation %d (the run holds %d)" %
                (run_dir, generation, run["next_generation"]))
        while generation < run["generations"]:
            vectors = [list(map(float, x)) for x in optimizer.ask()]
            results = ev.evaluate(vectors, generation=generation)
            optimizer.tell(vectors, results)
            if hasattr(optimizer, "after_generation"):
                optimizer.after_generation(run_dir, generation, vectors, results)
            generation += 1
            # The optimizer pickled apart: the checkpoint's generation reads without its classes.
            _save(run_dir, {"generation": generation, "optimizer": pickle.dumps(optimizer),
                            "numpy_random": np.random.get_state(), "random": random.getstate()})
            if log:
                best = max(r["fitness"] for r in results)
                log("generation %d of %d: best %.6g" % (generation - 1, run["generations"], best))
        # The end of the service's input: a complete run is validated and post-evaluated now.
        said = ev.close()
        if log:
            for line in said.splitlines():
                if line.startswith(("validation:", "post-evaluation")):
                    log(line)
    return optimizer
