"""ahhs.Evaluator against a real ahhs-evaluate (run inside a network namespace): answers, the
same answer for the same seed, what ahhs-launch gives, and errors raised with the service's
message."""
import json
import os
import subprocess
import tempfile
import unittest

import ahhs

BIN = os.environ["AHHS_BIN"]
URL = "udpm://239.255.42.62:7753?ttl=0&recv_buf_size=4194304"
TASK = ["--scenario", "pendulum", "--duration", "5"]


class EvaluatorTest(unittest.TestCase):
    def test_a_batch_of_documents_and_vectors(self):
        options = TASK + ["--variant", "ahhs2", "--hormones", "3", "--rules", "4", "--trials", "2",
                          "--workers", "2", "--lcm-url", URL]
        with ahhs.Evaluator(options) as ev:
            self.assertEqual(ev.hello["scenario"], "pendulum")
            self.assertRegex(ev.physics, r"^2[0-9]{3}-[0-9]{2}-[0-9]{2}")  # the build's, named
            self.assertEqual(ev.descriptor_names, ["above_pivot", "at_wall"])
            shape = ev.shape
            self.assertEqual((shape.sensors, shape.actuators), (10, 2))
            vector = [0.3] * ev.vector_size
            genome = ahhs.from_vector(shape, [0.6] * ev.vector_size)
            results = ev.evaluate([genome, vector], seed=5)
            self.assertEqual(len(results), 2)
            self.assertEqual(ev.last_seed, 5)
            for r in results:
                self.assertEqual(len(r["trials"]), 2)
                self.assertEqual(r["fitness"], (r["trials"][0]["fitness"] + r["trials"][1]["fitness"]) / 2)
                d = [t["descriptor"] for t in r["trials"]]
                self.assertTrue(all(0 <= x <= 1 for x in d[0] + d[1]), d)
                self.assertEqual(r["descriptor"], [(d[0][j] + d[1][j]) / 2 for j in range(2)])
            self.assertEqual(ev.evaluate([genome, vector], seed=5), results)
            with self.assertRaisesRegex(ahhs.EvaluationError, "a vector of 3 values"):
                ev.evaluate([[0.1, 0.2, 0.3]])
            # The service goes on after an error.
            self.assertEqual(ev.evaluate([genome], seed=5)[0], results[0])
        # Trial 0 of the genome document is what ahhs-launch gives.
        with tempfile.NamedTemporaryFile("w", suffix=".json") as f:
            json.dump(genome, f)
            f.flush()
            t = results[0]["trials"][0]
            out = subprocess.run([os.path.join(BIN, "ahhs-launch")] + TASK +
                                 ["--genome", f.name, "--seed", str(t["seed"]), "--arena-kind", "fused"],
                                 capture_output=True, text=True, check=True).stdout
        launched = [l for l in out.splitlines() if l.startswith("fitness: ")][-1]
        self.assertEqual(float(launched.split()[1]), t["fitness"])
        # and its descriptor: "descriptor: above_pivot A, at_wall W"
        described = [l for l in out.splitlines() if l.startswith("descriptor: ")][-1]
        values = [float(part.split()[1]) for part in described[len("descriptor: "):].split(", ")]
        self.assertEqual(values, t["descriptor"])

    def test_a_service_that_cannot_start_says_why(self):
        with self.assertRaisesRegex(ahhs.EvaluationError, "unknown scenario"):
            with ahhs.Evaluator(["--scenario", "walker"]):
                pass


if __name__ == "__main__":
    unittest.main()
