#!/usr/bin/python3
"""The numbers `ahhs-report RUN` gives beside a gait replay's filmstrip (report_lib.gait_motion),
on a made-up trace whose answers are known by hand: two hinges swinging 20 degrees around 10 at
1 Hz, the second 0.2 s behind (zero-lag correlation cos(2 pi 0.2) = 0.309, best lag +0.2 s), a
hinge that holds still, a swing fast enough that a once-a-second sample would alias it, a small
swing on top of a large change of posture, a regular kick, noise, and a centroid moving 1 cm per
second; the held-out episode a report replays is the one at n // 2 of
the sorted fitnesses; an episode too short to judge is one clear error."""
import math
import os
import random
import sys
import tempfile

SOURCE = os.environ["AHHS_SOURCE_DIR"]
sys.path.insert(0, os.path.join(SOURCE, "tools", "report"))
import report_lib as rl  # noqa: E402

TICK = 0.05


def check(cond, what):
    if not cond:
        print("FAIL:", what)
        sys.exit(1)


def near(a, b, tol):
    return a is not None and abs(a - b) <= tol


def write(tmp, angles, duration):
    """angles: per module, degrees as a function of time."""
    trace = os.path.join(tmp, "trace.csv")
    body = os.path.join(tmp, "body.csv")
    ticks = int(round(duration / TICK))
    with open(trace, "w") as t, open(body, "w") as b:
        t.write("tick,time,module,hinge_angle\n")
        b.write("tick,time,centroid_x,centroid_y\n")
        for k in range(ticks):
            time = (k + 1) * TICK
            for m, f in enumerate(angles):
                t.write(f"{k},{time!r},{m},{math.radians(f(time))!r}\n")
            b.write(f"{k},{time!r},{0.01 * time!r},{-0.002 * time!r}\n")
    return trace, body


def wave(lag, freq=1.0):
    return lambda t: 10 + 20 * math.sin(2 * math.pi * freq * (t - lag))


with tempfile.TemporaryDirectory() as tmp:
    # 56 s after the first 5 (1120 ticks): a whole number of periods of 1 Hz and of 3.75 Hz.
    trace, body = write(tmp, [wave(0.0), wave(0.2), lambda t: -1.0, wave(0.0, 3.75)], 60.95)
    m = rl.gait_motion(trace, body)
    h = m["hinges"]
    check(m["settle"] == 5.0, f"settle {m['settle']}")
    check(near(h[0]["mean"], 10, 1e-6) and near(h[0]["sd"], 20 / math.sqrt(2), 1e-6),
          f"mean and standard deviation of a sine: {h[0]}")
    check(near(h[0]["min"], -10, 1e-3) and near(h[0]["max"], 30, 1e-3), f"min and max: {h[0]}")
    check(near(h[0]["frequency"], 1.0, 1e-9) and near(h[1]["frequency"], 1.0, 1e-9),
          f"1 Hz: {h[0]['frequency']}, {h[1]['frequency']}")
    # The swing is taken on 51 s (half the 5-s window off each end): bins of 1 / 51 Hz.
    check(near(h[3]["frequency"], 3.75, 0.5 / 51), f"3.75 Hz, not an alias: {h[3]['frequency']}")
    check(all(near(x["swing_sd"], 20 / math.sqrt(2), 0.3) and x["share"] > 0.95
              for x in (h[0], h[1], h[3])), f"a sine is all swing, all at its rhythm: {h}")
    check(h[2]["frequency"] is None and h[2]["share"] is None and near(h[2]["mean"], -1, 1e-9)
          and h[2]["sd"] < 1e-9 and h[2]["swing_sd"] < 1e-9, f"a still hinge: {h[2]}")
    n = m["neighbours"]
    check(near(n[0]["correlation"], math.cos(2 * math.pi * 0.2), 1e-3),
          f"zero-lag correlation {n[0]['correlation']}")
    check(near(n[0]["lag"], 0.2, 1e-9) and near(n[0]["lag_correlation"], 1.0, 1e-6),
          f"the second follows by 0.2 s: {n[0]}")
    check(n[1]["correlation"] is None and n[1]["lag"] is None and n[2]["correlation"] is None,
          f"no correlation with a still hinge: {n[1]}, {n[2]}")
    check(all(near(t, q, 0.051) for (t, _), q in zip(m["distance"], [15.24, 30.48, 45.71, 60.95])),
          f"quarters {m['distance']}")
    speed = math.hypot(0.01, 0.002)
    check(all(near(d, speed * (t - TICK), 1e-9) for t, d in m["distance"]),
          f"distances {m['distance']}")
    check(near(m["end"][0], 0.01 * 60.9, 1e-9) and near(m["end"][1], -0.002 * 60.9, 1e-9),
          f"end {m['end']}")
    # The second neighbour leading: a negative lag.
    trace, body = write(tmp, [wave(0.2), wave(0.0)], 60.95)
    check(near(rl.gait_motion(trace, body)["neighbours"][0]["lag"], -0.2, 1e-9), "a lead")
    # A swing of 5 degrees at 1.5 Hz on top of a change of posture from -60 to +60 degrees at
    # 30 s: the posture is in the standard deviation, the swing and its rhythm are the sine's.
    # A kick of a quarter of each second (+20 degrees, else -15): 1 Hz, its harmonics holding
    # much of the rest. Noise: no rhythm.
    rng = random.Random(1)
    trace, body = write(tmp, [lambda t: (-60 if t < 30 else 60) + 5 * math.sin(3 * math.pi * t),
                              lambda t: 20 if t % 1 < 0.25 else -15,
                              lambda t: rng.gauss(0, 10)], 60.95)
    h = rl.gait_motion(trace, body)["hinges"]
    check(near(h[0]["sd"], 60, 2) and near(h[0]["swing_sd"], 5 / math.sqrt(2), 0.5)
          and near(h[0]["frequency"], 1.5, 0.5 / 51) and h[0]["share"] > 0.8,
          f"a swing on a change of posture: {h[0]}")
    check(near(h[1]["frequency"], 1.0, 1e-9) and 0.4 < h[1]["share"] < 0.7, f"a kick: {h[1]}")
    check(h[2]["share"] < 0.1, f"noise: {h[2]}")
    # A short episode settles for a quarter of it; one without ticks after that is an error.
    trace, body = write(tmp, [wave(0.0), wave(0.1)], 3.0)
    check(rl.gait_motion(trace, body)["settle"] == 0.75, "a 3-s episode settles 0.75 s")
    trace, body = write(tmp, [wave(0.0)], 0.1)
    try:
        rl.gait_motion(trace, body)
        check(False, "two ticks accepted")
    except rl.ReportError as e:
        check("under 4 ticks" in str(e), str(e))

post = {"per_episode": [{"seed": 1, "fitness": 0.3}, {"seed": 2, "fitness": 0.1},
                        {"seed": 3, "fitness": None}, {"seed": 4, "fitness": 0.4},
                        {"seed": 5, "fitness": 0.2}],
        "envelope_half_widths": {"envelope.mass": 0.05, "envelope.friction": 0.05}}
check(rl.median_episode(post)["seed"] == 1, "of 0.1, 0.2, 0.3, 0.4 the one at 4 // 2")
check(rl.envelope_argv(post) == ["--envelope", "none", "--envelope.friction", "0.05",
                                 "--envelope.mass", "0.05"], f"{rl.envelope_argv(post)}")
try:
    rl.median_episode({"per_episode": [{"seed": 1, "fitness": None}]})
    check(False, "no valid episode accepted")
except rl.ReportError:
    pass
print("PASS: gait_motion, median_episode and envelope_argv")
