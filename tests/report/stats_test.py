#!/usr/bin/python3
"""The report's statistics against published values.

Wilcoxon rank-sum: Hollander & Wolfe (1973), p. 69, permeability constants of the human
chorioamnion (the example of R's wilcox.test): x at term, y at 12-26 weeks. R prints W = 35 and
the exact one-sided p = 0.1272 (alternative "greater"); the two-sided exact p is twice that.

Log-rank: Freireich et al. (1963), weeks of remission of 42 leukaemia patients, 6-MP against
placebo (the example of Kalbfleisch & Prentice and of R's survdiff on the `gehan` data): 6-MP
observed 9 events where 19.25 were expected; chi-square 16.79 on 1 degree of freedom,
p = 4.17e-5.
"""
import os
import sys

sys.path.insert(0, os.path.join(os.environ["AHHS_SOURCE_DIR"], "tools", "report"))
import report_lib  # noqa: E402

x = [0.80, 0.83, 1.89, 1.04, 1.45, 1.38, 1.91, 1.64, 0.73, 1.46]
y = [1.15, 0.88, 0.90, 0.74, 1.21]
u, p = report_lib.rank_sum_test(x, y)
assert u == 35, u
assert abs(p - 2 * 0.1272) < 1e-4, p
# Symmetric: swapping the samples gives U' = n_x n_y - U and the same p.
u2, p2 = report_lib.rank_sum_test(y, x)
assert u2 == 50 - 35 and abs(p2 - p) < 1e-12, (u2, p2)
# Clearly separated samples: exact p = 2 / C(8, 4) = 0.02857.
u3, p3 = report_lib.rank_sum_test([1, 2, 3, 4], [5, 6, 7, 8])
assert u3 == 0 and abs(p3 - 2 / 70) < 1e-12, (u3, p3)
# With ties the normal approximation, by hand: U = 0 against a mean of 6; the variance with the
# tie correction 12 / 12 * (8 - (6 + 6) / 42) = 7.714; z = (6 - 0.5) / 2.777 = 1.980;
# two-sided p = 0.0477.
u4, p4 = report_lib.rank_sum_test([1, 2, 2], [3, 3, 4, 5])
assert u4 == 0 and abs(p4 - 0.0477) < 1e-4, (u4, p4)
# Ten against ten without ties: exact, 2 / C(20, 10) for separated samples (the normal
# approximation would give 1.8e-4).
_, p5 = report_lib.rank_sum_test(list(range(10)), list(range(10, 20)))
assert abs(p5 - 2 / 184756) < 1e-15, p5

mp = [6, 6, 6, 7, 10, 13, 16, 22, 23, 6, 9, 10, 11, 17, 19, 20, 25, 32, 32, 34, 35]
mp_event = [True] * 9 + [False] * 12
placebo = [1, 1, 2, 2, 3, 4, 4, 5, 5, 8, 8, 8, 8, 11, 11, 12, 12, 15, 17, 22, 23]
o, e, p6 = report_lib.logrank_test(mp, mp_event, placebo, [True] * 21)
assert o == 9 and abs(e - 19.25) < 0.01 and abs(p6 - 4.17e-5) < 0.01e-5, (o, e, p6)
# No event at all: no test.
assert report_lib.logrank_test([5, 5], [False, False], [5], [False])[2] is None
print(f"Hollander & Wolfe: U = {u:g}, two-sided p = {p:.4f} (R: 2 x 0.1272); "
      f"Freireich 6-MP: O = {o:g}, E = {e:.2f}, log-rank p = {p6:.3g}; PASS")
