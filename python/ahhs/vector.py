"""Genome vectors: a genome as a flat list of floats with bounds (docs/genome.md, "Genome vectors").

The same layout, encoding and decoding as ahhs-genome to-vector / from-vector
(modules/core/genome_vector.h), value for value: a vector decoded here and by ahhs-genome gives
the same genome to the last bit.
"""
import math

KINDS_AHHS2 = ("idle", "sensor", "linear", "nonlinear", "actuator")
TYPES_AHHS1 = ("idle", "sensor", "hormone", "actuator")
DIRECTIONS = ("below", "above")
ALPHA_MAX, ZETA, ETA, KAPPA_MAX, LAMBDA_MAX = 0.1, (-1.0, 1.0), (0.01, 0.5), 0.2, 2.0
WEIGHT_SUM_TOLERANCE = 1e-9


class Shape:
    """What a genome is made for: variant ("ahhs1" or "ahhs2"), hormones, rules, sensors, actuators."""

    def __init__(self, variant, hormones, rules, sensors, actuators):
        if variant not in ("ahhs1", "ahhs2"):
            raise ValueError("variant must be ahhs1 or ahhs2")
        self.variant, self.hormones, self.rules = variant, int(hormones), int(rules)
        self.sensors, self.actuators = int(sensors), int(actuators)

    @classmethod
    def of(cls, genome):
        """The shape of a genome document."""
        return cls(genome["variant"], len(genome["hormones"]), len(genome["rules"]),
                   genome["sensors"], genome["actuators"])

    @classmethod
    def from_json(cls, doc):
        return cls(doc["variant"], doc["hormones"], doc["rules"], doc["sensors"], doc["actuators"])

    def to_json(self):
        return {"variant": self.variant, "hormones": self.hormones, "rules": self.rules,
                "sensors": self.sensors, "actuators": self.actuators}

    def __eq__(self, other):
        return isinstance(other, Shape) and self.to_json() == other.to_json()

    def __repr__(self):
        return "Shape(%s)" % ", ".join("%s=%r" % kv for kv in self.to_json().items())


def layout(shape):
    """(names, lower, upper) of every value of a genome of `shape`, in vector order."""
    names, lower, upper = [], [], []

    def add(name, lo, hi):
        names.append(name)
        lower.append(float(lo))
        upper.append(float(hi))

    for h in range(shape.hormones):
        f = "hormones[%d]." % h
        add(f + "alpha", 0, ALPHA_MAX)
        add(f + "mu", 0, 1)
        add(f + "diffusion", 0, 1)
    for r in range(shape.rules):
        f = "rules[%d]." % r
        if shape.variant == "ahhs2":
            for kind in KINDS_AHHS2:
                add(f + "weights." + kind, 0, 1)
            add(f + "zeta", *ZETA)
            add(f + "eta", *ETA)
            add(f + "kappa", -KAPPA_MAX, KAPPA_MAX)
            add(f + "lambda", -LAMBDA_MAX, LAMBDA_MAX)
            add(f + "sensor", 0, shape.sensors)
            add(f + "input", 0, shape.hormones)
            add(f + "output", 0, shape.hormones)
            add(f + "actuator", 0, shape.actuators)
        else:
            add(f + "type", 0, len(TYPES_AHHS1))
            add(f + "input", 0, 1)
            add(f + "output", 0, 1)
            add(f + "tau", 0, 1)
            add(f + "direction", 0, len(DIRECTIONS))
            add(f + "lambda", -LAMBDA_MAX, LAMBDA_MAX)
            add(f + "kappa", -KAPPA_MAX, KAPPA_MAX)
    return names, lower, upper


def _in_range(shape, rule_type):
    return shape.sensors if rule_type == "sensor" else shape.hormones


def _out_range(shape, rule_type):
    return shape.actuators if rule_type == "actuator" else shape.hormones


def to_vector(genome):
    """A genome document's vector: reals copied, discrete fields at their intervals' middles."""
    shape = Shape.of(genome)
    x = []
    for h in genome["hormones"]:
        x += [float(h["alpha"]), float(h["mu"]), float(h["diffusion"])]
    for r in genome["rules"]:
        if shape.variant == "ahhs2":
            x += [float(r["weights"][k]) for k in KINDS_AHHS2]
            x += [float(r[k]) for k in ("zeta", "eta", "kappa", "lambda", "sensor", "input",
                                        "output", "actuator")]
        else:
            t = r["type"]
            x += [TYPES_AHHS1.index(t) + 0.5, (r["input"] + 0.5) / _in_range(shape, t),
                  (r["output"] + 0.5) / _out_range(shape, t), float(r["tau"]),
                  DIRECTIONS.index(r["direction"]) + 0.5, float(r["lambda"]), float(r["kappa"])]
    return x


def from_vector(shape, x):
    """The genome document (without meta) a vector gives: values clipped into their bounds, a
    floating index to just below its upper bound, AHHS2 weights that do not sum to 1 divided by
    their sum (all zero: an idle rule). Raises ValueError for a wrong length or a value that is
    not finite, naming the field."""
    names, lower, upper = layout(shape)
    x = [float(v) for v in x]
    if len(x) != len(names):
        raise ValueError("a vector of %d values for a genome of %d" % (len(x), len(names)))
    k = 0

    def take():
        nonlocal k
        v = x[k]
        if not math.isfinite(v):
            raise ValueError("vector[%d] (%s) is not finite" % (k, names[k]))
        v = min(max(v, lower[k]), upper[k])
        k += 1
        return v

    def take_index():
        n = upper[k]
        return min(take(), math.nextafter(n, 0.0))

    def floor_index(v, n):
        return min(n - 1, math.floor(v))

    genome = {"format": "ahhs-genome", "version": 1, "variant": shape.variant,
              "sensors": shape.sensors, "actuators": shape.actuators, "hormones": [], "rules": []}
    for _ in range(shape.hormones):
        genome["hormones"].append({"alpha": take(), "mu": take(), "diffusion": take()})
    for _ in range(shape.rules):
        if shape.variant == "ahhs2":
            weights = []
            total = 0.0
            for _kind in KINDS_AHHS2:
                w = take()
                weights.append(w)
                total += w
            if total == 0:
                weights = [1.0, 0.0, 0.0, 0.0, 0.0]
            elif abs(total - 1.0) > WEIGHT_SUM_TOLERANCE:
                weights = [w / total for w in weights]
            rule = {"weights": dict(zip(KINDS_AHHS2, weights))}
            for key in ("zeta", "eta", "kappa", "lambda"):
                rule[key] = take()
            for key in ("sensor", "input", "output", "actuator"):
                rule[key] = take_index()
        else:
            t = TYPES_AHHS1[floor_index(take(), len(TYPES_AHHS1))]
            n_in, n_out = _in_range(shape, t), _out_range(shape, t)
            rule = {"type": t, "input": floor_index(take() * n_in, n_in),
                    "output": floor_index(take() * n_out, n_out), "tau": take()}
            rule["direction"] = DIRECTIONS[floor_index(take(), len(DIRECTIONS))]
            rule["lambda"] = take()
            rule["kappa"] = take()
        genome["rules"].append(rule)
    return genome
