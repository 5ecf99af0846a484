"""The optimizer examples (examples/optimizers) on the pendulum against a real ahhs-evaluate (run
inside a network namespace): CMA-ES and MAP-Elites runs killed with SIGKILL at a random
generation and resumed end exactly as uninterrupted ones (every genome, seed and fitness of the
run directory, and the archive); an archive cell replays to its fitness with ahhs-replay; the
report draws the archive; ahhs-evolve refuses to resume such a run."""
import json
import os
import random
import shutil
import signal
import sqlite3
import subprocess
import sys
import tempfile
import time
import unittest

BIN = os.environ["AHHS_BIN"]
SOURCE = os.environ["AHHS_SOURCE_DIR"]
URL = "udpm://239.255.42.63:7754?ttl=0&recv_buf_size=4194304"
TASK = ["--", "--scenario", "pendulum", "--variant", "ahhs2", "--hormones", "3", "--rules", "6",
        "--trials", "2", "--envelope", "paper"]
FARM = ["--farm", "--workers 2 --lcm-url " + URL, "--bin", BIN]


def example(name):
    return [sys.executable, os.path.join(SOURCE, "examples", "optimizers", name)]


def dump(run_dir):
    """Every individual and trial of a run, without timings or workers."""
    db = sqlite3.connect(os.path.join(run_dir, "run.sqlite"))
    rows = db.execute("SELECT generation, idx, genome_hash, eval_seed, fitness FROM individuals "
                      "ORDER BY generation, idx").fetchall()
    rows += db.execute("SELECT generation, idx, trial, seed, fitness FROM trials "
                       "ORDER BY generation, idx, trial").fetchall()
    db.close()
    return rows


def checkpoint_generation(run_dir):
    path = os.path.join(run_dir, "optimizer.pickle")
    try:
        import pickle
        with open(path, "rb") as f:
            return pickle.load(f)["generation"]
    except (OSError, EOFError, KeyError, ImportError, AttributeError, ValueError):
        return 0


def wait_for_service_to_end(run_dir, seconds=30):
    """A killed search's ahhs-evaluate ends at the end of its input; until then it holds the run."""
    end = time.time() + seconds
    while time.time() < end:
        if subprocess.run(["pgrep", "-f", "ahhs-evaluate.*" + run_dir],
                          capture_output=True).returncode != 0:
            return
        time.sleep(0.05)
    raise AssertionError("the killed search's ahhs-evaluate did not end")


class FinishByTest(unittest.TestCase):
    def test_a_time_of_day_or_a_duration_from_now_else_a_value_error(self):
        from ahhs.search import parse_finish_by
        noon = time.mktime((2026, 12, 6, 12, 0, 0, 0, 0, -1))
        self.assertEqual(parse_finish_by("90m", noon), noon + 5400)
        self.assertEqual(parse_finish_by("2.5h", noon), noon + 9000)
        self.assertEqual(parse_finish_by("600s", noon), noon + 600)
        self.assertEqual(parse_finish_by("17:30", noon), noon + 5 * 3600 + 1800)
        tomorrow = time.localtime(parse_finish_by("11:15", noon))
        self.assertEqual((tomorrow.tm_mday, tomorrow.tm_hour, tomorrow.tm_min), (7, 11, 15))
        self.assertGreater(parse_finish_by("12:00", noon), noon)
        for bad in ("", "90", "90x", "-5m", "0h", "25:00", "12:60", "7:30", "12:30:00", "soon",
                    "1e9h", "5m later"):
            with self.assertRaises(ValueError, msg=bad):
                parse_finish_by(bad, noon)


class SearchTest(unittest.TestCase):
    def run_killed_and_whole(self, script, options, generations, evaluation=()):
        tmp = tempfile.mkdtemp(prefix="ahhs-search-")
        self.addCleanup(shutil.rmtree, tmp, ignore_errors=True)
        whole, killed = os.path.join(tmp, "whole"), os.path.join(tmp, "killed")
        argv = (example(script) + options + ["--generations", str(generations)] + FARM + TASK +
                list(evaluation))
        subprocess.run(argv[:2] + [whole] + argv[2:], check=True, capture_output=True)
        at = random.Random().randint(2, generations - 3)
        p = subprocess.Popen(argv[:2] + [killed] + argv[2:], stdout=subprocess.DEVNULL,
                             stderr=subprocess.DEVNULL)
        while checkpoint_generation(killed) < at and p.poll() is None:
            time.sleep(0.002)
        p.send_signal(signal.SIGKILL)
        p.wait()
        stored = checkpoint_generation(killed)
        self.assertLess(stored, generations, "the search ended before the kill")
        wait_for_service_to_end(killed)
        out = subprocess.run(argv[:2] + [killed] + argv[2:], check=True, capture_output=True,
                             text=True).stdout
        self.assertIn("resuming %s at generation %d" % (killed, stored), out)
        self.resumed_output = out
        self.assertEqual(dump(whole), dump(killed), "killed after %d generations" % stored)
        self.assertEqual(len(dump(whole)), generations * 8 * 3)
        return whole, killed, stored

    def test_cma_es_resumes_exactly_and_validates_its_best(self):
        whole, killed, stored = self.run_killed_and_whole(
            "cmaes.py", ["--population", "8"], 12,
            ["--validation", "3", "--validation-candidates", "3", "--post-eval", "4"])
        print("cma-es: killed after %d generations, resumed: identical" % stored)
        # Its best is chosen by validation and post-evaluated when it ends, as ahhs-evolve does it:
        # the same in the killed run (validated by the resumed service) as in the whole one.
        validation = "SELECT candidate, generation, idx, episode, seed, fitness FROM validation " \
                     "ORDER BY candidate, episode"
        tables = [sqlite3.connect(os.path.join(d, "run.sqlite")).execute(validation).fetchall()
                  for d in (whole, killed)]
        self.assertEqual(len(tables[0]), 3 * len({row[0] for row in tables[0]}))
        self.assertEqual(tables[0], tables[1])
        post = []
        for d in (whole, killed):
            with open(os.path.join(d, "post-eval.json")) as f:
                post.append(json.load(f))
            with open(os.path.join(d, "best.json")) as f:
                self.assertEqual(json.load(f)["meta"]["validation"]["episodes"], 3)
        self.assertEqual(post[0], post[1])
        self.assertEqual(post[0]["episodes"], 4)
        self.assertIn("post-evaluation on 4 held-out episodes", self.resumed_output)
        # The GA does not resume it.
        out = subprocess.run([os.path.join(BIN, "ahhs-evolve"), "--resume", whole],
                             capture_output=True, text=True)
        self.assertNotEqual(out.returncode, 0)
        self.assertIn("is a run of cma-es (deap) recorded by ahhs-evaluate", out.stderr)

    def test_map_elites_resumes_exactly_and_its_cells_replay(self):
        whole, killed, stored = self.run_killed_and_whole(
            "map_elites.py", ["--batch", "8", "--cells", "5", "--sigma", "0.3"], 12)
        with open(os.path.join(whole, "archive.json")) as f:
            archive = json.load(f)
        with open(os.path.join(killed, "archive.json")) as f:
            self.assertEqual(json.load(f), archive)
        print("map-elites: killed after %d generations, resumed: identical; %d cells" %
              (stored, len(archive["cells"])))
        self.assertEqual(archive["descriptor"], ["above_pivot", "at_wall"])
        self.assertGreater(len(archive["cells"]), 1)
        cell = max(archive["cells"], key=lambda c: c["fitness"])
        out = subprocess.run([os.path.join(BIN, "ahhs-replay"), whole, "--generation",
                              str(cell["generation"]), "--individual", str(cell["individual"])],
                             capture_output=True, text=True, check=True).stdout
        self.assertIn("reproduced exactly", out)
        # The cell's fitness is its trials' mean: the replay's first trial is one of them.
        db = sqlite3.connect(os.path.join(whole, "run.sqlite"))
        (fitness,) = db.execute("SELECT fitness FROM individuals WHERE generation = ? AND idx = ?",
                                (cell["generation"], cell["individual"])).fetchone()
        self.assertEqual(fitness, cell["fitness"])
        report = os.path.join(os.path.dirname(whole), "report")
        subprocess.run([os.path.join(BIN, "ahhs-report"), whole, "-o", report, "--no-replay"],
                       check=True, capture_output=True)
        self.assertTrue(os.path.getsize(os.path.join(report, "archive-whole.png")) > 0)
        with open(os.path.join(report, "summary.md")) as f:
            self.assertIn("## The archive of", f.read())

    def test_sigint_to_a_background_search_alone_stops_its_service_and_the_run_resumes(self):
        # A search started in the background by a script (its shell has it ignore SIGINT), then
        # SIGINT to its process only: it stops its service, says how to go on and exits 130; the
        # run resumes. (It used to ignore the signal, and its service went on.)
        tmp = tempfile.mkdtemp(prefix="ahhs-search-")
        self.addCleanup(shutil.rmtree, tmp, ignore_errors=True)
        run_dir = os.path.join(tmp, "run")
        argv = (example("cmaes.py") + [run_dir, "--population", "8", "--generations", "12"] +
                FARM + TASK + ["--validation", "3", "--post-eval", "4"])
        p = subprocess.Popen(argv, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True,
                             preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_IGN))
        while checkpoint_generation(run_dir) < 2 and p.poll() is None:
            time.sleep(0.002)
        p.send_signal(signal.SIGINT)
        try:
            _, said = p.communicate(timeout=30)
        except subprocess.TimeoutExpired:
            p.kill()
            p.communicate()
            raise AssertionError("the search went on after SIGINT")
        self.assertEqual(p.returncode, 130, said)
        self.assertIn("interrupted: the same command resumes " + run_dir, said)
        wait_for_service_to_end(run_dir, seconds=5)
        stored = checkpoint_generation(run_dir)
        self.assertLess(stored, 12, "the search ended before the signal")
        out = subprocess.run(argv, check=True, capture_output=True, text=True).stdout
        self.assertIn("resuming %s at generation %d" % (run_dir, stored), out)
        self.assertEqual(len(dump(run_dir)), 12 * 8 * 3)


if __name__ == "__main__":
    unittest.main()
