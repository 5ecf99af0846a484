"""What a study's claims are judged with (ahhs-report study): a claim row per statement, and
the rules that keep a verdict honest: no verdict on a configuration without runs, on fewer than
MIN_RUNS runs, or on runs whose robust fitness is missing. A study's own claims live beside its
plan in studies/ (studies/<plan name>-claims.py, e.g. studies/paper-2010-claims.py); a study
without its own is judged against the paper's."""
import numpy as np

from report_lib import rank_sum_test

MIN_RUNS = 5  # fewer complete runs of a configuration give a claim no verdict yet


def fmt(v, digits=3):
    return "-" if v is None else f"{v:.{digits}g}"


def pct(v):
    return "-" if v is None else f"{100 * v:.0f} %"


class Claims:
    """The claims on one per-run statistic: "best" (each run's best fitness) or "robust"."""

    def __init__(self, configs, maxima, stat="best"):
        self.by = {c.name: c for c in configs}
        self.maxima = maxima
        self.stat = stat
        self.rows = []

    def get(self, name):
        c = self.by.get(name)
        return c if c is not None and len(c.runs) > 0 else None

    def values(self, name):
        return getattr(self.get(name), self.stat)

    def test(self, a, b):
        ca, cb = self.get(a), self.get(b)
        if not ca or not cb or len(ca.runs) < 2 or len(cb.runs) < 2:
            return None
        return rank_sum_test(list(self.values(a)), list(self.values(b)))[1]

    def add(self, claim, paper, ours, verdict):
        self.rows.append((claim, paper, ours, verdict))

    def missing(self, claim, paper, *names, per_run=True):
        """True (and a row saying so) when a configuration has no run, or, for a claim about
        runs (per_run), fewer than MIN_RUNS."""
        absent = [n for n in names if not self.get(n)]
        if absent:
            self.add(claim, paper, "not run yet (" + ", ".join(absent) + ")", "open")
            return True
        if per_run and any(self.values(n) is None for n in names):
            self.add(claim, paper, "no robust fitness (a best genome's replays failed)", "open")
            return True
        few = [f"{n}: {len(self.get(n).runs)}" for n in names
               if per_run and len(self.get(n).runs) < MIN_RUNS]
        if few:
            self.add(claim, paper, "too few complete runs so far (" + ", ".join(few) + ")", "open")
            return True
        return False

    def speed_test(self, a, b):
        return rank_sum_test(list(self.get(a).speed), list(self.get(b).speed))[1]

    def median(self, name):
        return float(np.median(self.values(name)))

    def within(self, name, level):
        return float(np.mean(self.values(name) >= level))

    def iqr(self, name):
        return float(np.subtract(*np.percentile(self.values(name), [75, 25])))

    def not_fitness(self, claim, paper):
        """For a claim that is not about runs' fitness: True (and an empty row) unless this is
        the "best" pass, which judges it."""
        if self.stat == "best":
            return False
        self.add(claim, paper, None, None)
        return True

def merge_claims(best, robust):
    """Rows (claim, paper, ours, verdict, ours robust, verdict robust)."""
    assert [r[0] for r in best] == [r[0] for r in robust], (best, robust)
    return [b + (r[2], r[3]) for b, r in zip(best, robust)]
