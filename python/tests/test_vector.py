"""ahhs.vector against ahhs-genome: the same layout, and the same genome from the same vector."""
import json
import math
import os
import random
import subprocess
import tempfile
import unittest

import ahhs

BIN = os.environ["AHHS_BIN"]


def genome_cli(*args, stdin=None):
    out = subprocess.run([os.path.join(BIN, "ahhs-genome")] + list(args), input=stdin,
                         capture_output=True, text=True, check=True)
    return json.loads(out.stdout)


def same_numbers(a, b):
    """Equal documents, numbers compared as floats (1 and 1.0 alike), meta ignored."""
    if isinstance(a, dict):
        keys = set(a) - {"meta"}
        return keys == set(b) - {"meta"} and all(same_numbers(a[k], b[k]) for k in keys)
    if isinstance(a, list):
        return len(a) == len(b) and all(same_numbers(x, y) for x, y in zip(a, b))
    if isinstance(a, (int, float)) and not isinstance(a, bool):
        return float(a) == float(b)
    return a == b


SHAPES = [("ahhs2", 5, 30, 4, 1), ("ahhs1", 5, 80, 4, 1), ("ahhs2", 15, 15, 10, 2),
          ("ahhs1", 15, 60, 10, 2), ("ahhs1", 1, 3, 1, 1)]


class VectorTest(unittest.TestCase):
    def test_to_vector_and_layout_equal_ahhs_genome(self):
        for seed, (variant, h, r, s, a) in enumerate(SHAPES, start=1):
            g = genome_cli("random", "--variant", variant, "--hormones", str(h), "--rules", str(r),
                           "--sensors", str(s), "--actuators", str(a), "--seed", str(seed))
            with tempfile.NamedTemporaryFile("w", suffix=".json") as f:
                json.dump(g, f)
                f.flush()
                cli = genome_cli("to-vector", f.name)
            shape = ahhs.Shape.of(g)
            self.assertEqual(cli["shape"], shape.to_json())
            self.assertEqual(ahhs.to_vector(g), cli["x"])  # bit for bit
            names, lower, upper = ahhs.layout(shape)
            self.assertEqual((names, lower, upper), (cli["names"], cli["lower"], cli["upper"]))
            back = ahhs.from_vector(shape, ahhs.to_vector(g))
            self.assertTrue(same_numbers(back, g))

    def test_any_vector_gives_the_genome_ahhs_genome_gives(self):
        rng = random.Random(7)
        for variant, h, r, s, a in SHAPES:
            shape = ahhs.Shape(variant, h, r, s, a)
            names, lower, upper = ahhs.layout(shape)
            for _ in range(5):
                x = [rng.uniform(lo - 0.5, hi + 0.5) for lo, hi in zip(lower, upper)]
                doc = {"format": "ahhs-genome-vector", "version": 1, "shape": shape.to_json(), "x": x}
                cli = genome_cli("from-vector", "-", stdin=json.dumps(doc))
                self.assertTrue(same_numbers(ahhs.from_vector(shape, x), cli), (variant, x[:5]))

    def test_bad_vectors_are_refused_by_name(self):
        shape = ahhs.Shape("ahhs2", 1, 1, 2, 1)
        with self.assertRaisesRegex(ValueError, "a vector of 5 values for a genome of 16"):
            ahhs.from_vector(shape, [0.0] * 5)
        x = [0.0] * 16
        x[4] = math.nan
        with self.assertRaisesRegex(ValueError, r"vector\[4\] \(rules\[0\].weights.sensor\)"):
            ahhs.from_vector(shape, x)


if __name__ == "__main__":
    unittest.main()
