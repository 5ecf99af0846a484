#!/usr/bin/python3
"""The report's statistics against published values.

Wilcoxon rank-sum: Hollander & Wolfe (1973), p. 69, permeability constants of the human
chorioamnion (the example of R's wilcox.test): x at term, y at 12-26 weeks. R prints W = 35 and
the exact one-sided p = 0.1272 (alternative "greater"); the two-sided exact p is twice that.
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
print(f"Hollander & Wolfe: U = {u:g}, two-sided p = {p:.4f} (R: 2 x 0.1272); PASS")
