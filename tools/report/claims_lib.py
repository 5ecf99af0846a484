"""What a study's claims are judged with (ahhs-report study): a claim row per statement, and
the rules that keep a verdict honest: no verdict on a configuration without runs, on fewer than
MIN_RUNS runs, or on runs whose robust fitness is missing; a comparison is "reproduced" only with
the paper's direction and the paper's significance (ALPHA, two-sided rank-sum, exact without
ties); every verdict names its n. A study's own claims live beside its plan in studies/
(studies/<plan name>-claims.py, e.g. studies/paper-2010-claims.py); a study without its own is
judged against the paper's. VERDICTS says what each word means (results.md prints it)."""
import numpy as np

from report_lib import logrank_test, rank_sum_test

MIN_RUNS = 5  # fewer complete runs of a configuration give a claim no verdict yet
ALPHA = 0.05  # the paper's significance level (Wilcoxon p < 0.05)
CLOSE = 0.15  # a share is "close" to the paper's within this many (x 100) percentage points

VERDICTS = [
    "**reproduced**: the paper's direction and the paper's significance (p < 0.05, two-sided "
    "Wilcoxon rank-sum, exact when the runs have no tied values); for \"no significant "
    "difference\", p >= 0.05; for a statement of fact, the fact holds",
    "**differs, reversed**: significant in the opposite direction",
    "**not significant**: the paper's direction (or the reverse, said so) without significance "
    "where the paper has it",
    "**differs**: significant where the paper finds no difference, or the fact does not hold",
    "**close**: a share within 15 percentage points of the paper's",
    "**open**: a configuration has fewer than 5 complete runs (or none)",
    "n: complete runs of each configuration named, in the claim's order",
]


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

    def n(self, *names):
        """"n = 10, 8": the complete runs of each configuration, in order."""
        return "n = " + ", ".join(str(len(self.get(x).runs)) for x in names)

    def add(self, claim, paper, ours, verdict, names=()):
        """A row; with `names`, the verdict ends with their n."""
        if verdict is not None and names:
            verdict = f"{verdict} ({self.n(*names)})"
        self.rows.append((claim, paper, ours, verdict))

    def higher(self, a, b, label_b, values=None):
        """The verdict on "a is higher than b" (the paper: significantly), with p: reproduced,
        differs, reversed, or not significant (in which direction)."""
        x, y = (self.values(a), self.values(b)) if values is None else (values[a], values[b])
        p = rank_sum_test(list(x), list(y))[1]
        up = np.median(x) > np.median(y)
        if p < ALPHA:
            return ("reproduced" if up else f"differs, reversed: {label_b} is higher"), p
        return ("not significant" + ("" if up else f", reversed: {label_b}'s median is higher")), p

    def no_difference(self, a, b, label_a, label_b):
        """The verdict on "a and b do not differ significantly", with p."""
        p = self.test(a, b)
        if p >= ALPHA:
            return "reproduced", p
        hi = label_a if self.median(a) > self.median(b) else label_b
        return f"differs: {hi} is significantly higher", p

    def reached(self, name):
        """Per run: whether it reached the speed level (a run that did not is censored)."""
        c = self.get(name)
        return list(getattr(c, "reached", None) or [True] * len(c.speed))

    def speed_summary(self, name, label):
        """"7 of 10 AHHS2-15 runs reach it (median generation of those 40)"."""
        c, hit = self.get(name), self.reached(name)
        gens = [g for g, h in zip(c.speed, hit) if h]
        when = f", median generation of those {np.median(gens):g}" if gens else ""
        return f"{sum(hit)} of {len(hit)} {label} runs reach it{when}"

    def speed_logrank(self, a, b):
        """The log-rank test of the generations reaching the level: (observed, expected, p) of a."""
        return logrank_test(self.get(a).speed, self.reached(a), self.get(b).speed,
                            self.reached(b))

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

    def median(self, name):
        return float(np.median(self.values(name)))

    def within(self, name, level):
        return float(np.mean(self.values(name) >= level))

    def iqr(self, name):
        return float(np.subtract(*np.percentile(self.values(name), [75, 25])))

    def success_note(self, names, label, what="over the wall"):
        """In the robust pass, when every configuration named has its runs' held-out successes
        (study_report.Config.success): "; held-out episodes over the wall: AHHS2-30 40 % (7 of
        10 runs), ..."; else "". Where held-out fitness has two humps, a median between them
        moves with sampling and this share does not."""
        cs = [self.get(n) for n in names]
        if self.stat == "best" or any(c is None or getattr(c, "success", None) is None
                                      for c in cs):
            return ""
        return f"; held-out episodes {what}: " + ", ".join(
            f"{label(n)} {pct(float(np.mean(c.success)))} ({sum(x > 0 for x in c.success)} of "
            f"{len(c.success)} runs)" for n, c in zip(names, cs))

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
