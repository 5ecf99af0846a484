"""ahhs.qd, MAP-Elites in pyribs' shape: the archive's cells and statuses against hand-worked
cases, emitters as pure functions of their seeds, and a pickled scheduler that goes on exactly
as the one it was pickled from."""
import pickle
import unittest

import numpy as np

from ahhs.qd import IMPROVE_EXISTING, NEW, NOT_ADDED, GaussianEmitter, GridArchive, Scheduler


class ArchiveTest(unittest.TestCase):
    def test_cells_clip_to_the_ranges(self):
        a = GridArchive(2, [4, 2], [(0, 1), (-1, 1)])
        self.assertEqual(a.index_of([0.0, -1.0]), (0, 0))
        self.assertEqual(a.index_of([0.26, 0.0]), (1, 1))
        self.assertEqual(a.index_of([0.999, 0.5]), (3, 1))
        self.assertEqual(a.index_of([1.0, 1.0]), (3, 1))  # the upper edge is the last cell
        self.assertEqual(a.index_of([-5.0, 7.0]), (0, 1))
        with self.assertRaises(ValueError):
            a.index_of([float("nan"), 0])

    def test_one_elite_per_cell_the_best(self):
        a = GridArchive(1, [2, 2], [(0, 1), (0, 1)])
        info = a.add([[1], [2], [3], [4], [5]], [0.5, 0.4, 0.7, 0.1, 0.2],
                     [[0.1, 0.1], [0.2, 0.2], [0.3, 0.1], [0.9, 0.9], None])
        self.assertEqual(list(info["status"]), [NEW, NOT_ADDED, IMPROVE_EXISTING, NEW, NOT_ADDED])
        self.assertAlmostEqual(info["value"][1], -0.1)
        self.assertAlmostEqual(info["value"][2], 0.2)
        self.assertEqual(len(a), 2)
        cells = dict(a)
        self.assertEqual(list(cells[(0, 0)]["solution"]), [3.0])
        self.assertEqual(a.stats["num_elites"], 2)
        self.assertAlmostEqual(a.stats["qd_score"], 0.8)
        self.assertEqual(a.stats["coverage"], 0.5)


def make(seed):
    archive = GridArchive(3, [5, 5], [(0, 1), (0, 1)])
    emitter = GaussianEmitter(archive, sigma=0.2, x0=[0.5] * 3, bounds=[(0, 1)] * 3,
                              batch_size=6, seed=seed)
    return Scheduler(archive, [emitter])


def step(scheduler):
    x = scheduler.ask()
    scheduler.tell(-np.sum((x - 0.3) ** 2, axis=1), x[:, :2])
    return x


class SchedulerTest(unittest.TestCase):
    def test_a_pure_function_of_the_seed_within_bounds(self):
        a, b = make(3), make(3)
        for _ in range(5):
            xa, xb = step(a), step(b)
            self.assertTrue(np.array_equal(xa, xb))
            self.assertTrue(np.all((xa >= 0) & (xa <= 1)))
        self.assertFalse(np.array_equal(step(make(3)), step(make(4))))
        self.assertGreater(len(a.archive), 1)

    def test_a_pickled_scheduler_goes_on_as_the_original(self):
        s = make(7)
        for _ in range(3):
            step(s)
        copy = pickle.loads(pickle.dumps(s))
        for _ in range(3):
            self.assertTrue(np.array_equal(step(s), step(copy)))
        self.assertEqual(s.archive.stats, copy.archive.stats)

    def test_tell_needs_an_ask(self):
        with self.assertRaises(RuntimeError):
            make(1).tell(np.zeros(6), np.zeros((6, 2)))


if __name__ == "__main__":
    unittest.main()
