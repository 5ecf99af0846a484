#!/usr/bin/python3
"""The physics-step rule of ahhs-report steps (tools/report/step_report.py) on hand-made
distributions: a step agrees with half of it when its median is within 10 % and its
over-the-wall share within 0.15; the quartiles are reported when they move by more than 10 % of
the median at half the step, and never change the verdict."""
import os
import sys

sys.path.insert(0, os.path.join(os.environ["AHHS_SOURCE_DIR"], "tools", "report"))
import step_report as sr  # noqa: E402


def dist(median, lower, upper, share=0.0):
    return {"median": median, "lower_quartile": lower, "upper_quartile": upper,
            "success_share": share}


half = dist(0.50, 0.45, 0.55, 0.10)
assert sr.agrees(dist(0.549, 0.45, 0.55, 0.25), half)       # 9.8 % and 0.15: agrees
assert not sr.agrees(dist(0.551, 0.45, 0.55, 0.10), half)   # 10.2 %
assert not sr.agrees(dist(0.50, 0.45, 0.55, 0.26), half)    # 0.16 more over the wall
assert not sr.agrees(dist(None, None, None), half)          # no valid episode: never agrees
# The robust study's AHHS2-50 seed-1 best (docs/findings.md): at 12.5 ms against 6.25 ms the
# median agrees (+5.3 %) but the lower quartile was 0.039 at 6.25 ms, a second hump there.
fine = dist(0.5159, 0.0395, 0.5576)
coarse = dist(0.5430, 0.5243, 0.5680)
assert sr.agrees(coarse, fine)
assert sr.quartiles_moved(coarse, fine) == [("lower quartile", 0.5243, 0.0395)]
# Moves within 10 % of the median (0.05 here) are not reported; both quartiles can move.
assert sr.quartiles_moved(dist(0.5, 0.401, 0.599), half) == []
assert sr.quartiles_moved(dist(0.5, 0.39, 0.61), half) == [("lower quartile", 0.39, 0.45),
                                                           ("upper quartile", 0.61, 0.55)]
assert sr.quartiles_moved(dist(0.5, None, None), half) == []
print("PASS")
