"""MAP-Elites (Mouret and Clune 2015), small and in the shape of pyribs (archive, emitters,
scheduler; ask/tell), so that a user who has pyribs can swap it in (python/README.md).

The algorithm: an archive is a grid over the behaviour descriptor (the "measures"), one elite per
cell, the best solution whose measures fell in it. Each generation the emitters ask for new
solutions: before the archive holds anything, x0 plus Gaussian noise; after, elites drawn
uniformly from the archive plus Gaussian noise (sigma per value), clipped to the bounds. Told
their objectives and measures, the archive keeps each one that lands in an empty cell or beats
its cell's elite. Every random draw comes from the numpy Generator seeded by the emitter's
`seed`, so a run is a pure function of its seeds, and pickling the scheduler checkpoints it.
"""
import numpy as np

# add() statuses, as pyribs numbers them.
NOT_ADDED, IMPROVE_EXISTING, NEW = 0, 1, 2


class GridArchive:
    """A grid of `dims` cells per measure over `ranges` [(low, high), ...]; measures outside a
    range fall into its first or last cell. `elite` entries keep each elite's solution,
    objective, measures and the metadata it was told with."""

    def __init__(self, solution_dim, dims, ranges):
        if len(dims) != len(ranges) or not dims:
            raise ValueError("dims and ranges: one entry per measure")
        for d, (low, high) in zip(dims, ranges):
            if int(d) < 1 or not high > low:
                raise ValueError("dims must be >= 1 and each range (low, high) with high > low")
        self.solution_dim = int(solution_dim)
        self.dims = tuple(int(d) for d in dims)
        self.lower = np.array([r[0] for r in ranges], dtype=float)
        self.upper = np.array([r[1] for r in ranges], dtype=float)
        self._cells = {}  # index tuple -> {"solution", "objective", "measures", "metadata"}

    def index_of(self, measures):
        """The cell (a tuple) of one measures vector."""
        m = np.asarray(measures, dtype=float)
        if m.shape != self.lower.shape or not np.all(np.isfinite(m)):
            raise ValueError("measures: %d finite values" % len(self.dims))
        share = (m - self.lower) / (self.upper - self.lower)
        return tuple(int(min(max(np.floor(s * d), 0), d - 1)) for s, d in zip(share, self.dims))

    def add(self, solutions, objectives, measures, metadata=None):
        """Adds a batch; returns {"status": [NOT_ADDED | IMPROVE_EXISTING | NEW, ...],
        "value": [improvement over the cell's elite, or the objective for a new cell, ...]}.
        A solution whose measures are None is not added."""
        if metadata is None:
            metadata = [None] * len(solutions)
        if not len(solutions) == len(objectives) == len(measures) == len(metadata):
            raise ValueError("solutions, objectives, measures and metadata: one entry each")
        status, value = [], []
        for x, f, m, meta in zip(solutions, objectives, measures, metadata):
            if m is None:  # no behaviour to place it by (an AHHS episode that failed)
                status.append(NOT_ADDED)
                value.append(0.0)
                continue
            if not np.isfinite(f):
                raise ValueError("objective: a finite number")
            cell = self.index_of(m)
            old = self._cells.get(cell)
            if old is None or f > old["objective"]:
                status.append(NEW if old is None else IMPROVE_EXISTING)
                value.append(float(f) if old is None else float(f - old["objective"]))
                self._cells[cell] = {"solution": np.array(x, dtype=float),
                                     "objective": float(f),
                                     "measures": np.array(m, dtype=float), "metadata": meta}
            else:
                status.append(NOT_ADDED)
                value.append(float(f - old["objective"]))
        return {"status": np.array(status), "value": np.array(value)}

    def __len__(self):
        return len(self._cells)

    def __iter__(self):
        """(cell, elite) in cell order."""
        return iter(sorted(self._cells.items()))

    def empty(self):
        return not self._cells

    def sample_elites(self, n, rng):
        """`n` elites drawn uniformly with replacement (by `rng`), in the archive's cell order."""
        cells = sorted(self._cells)
        picks = rng.integers(0, len(cells), size=n)
        return [self._cells[cells[i]] for i in picks]

    @property
    def stats(self):
        """num_elites, coverage (share of cells), qd_score (sum of objectives), obj_max."""
        objectives = [e["objective"] for e in self._cells.values()]
        return {"num_elites": len(objectives),
                "coverage": len(objectives) / float(np.prod(self.dims)),
                "qd_score": float(sum(objectives)),
                "obj_max": max(objectives) if objectives else None}


class GaussianEmitter:
    """Asks `batch_size` solutions: elites (or x0 while the archive is empty) plus N(0, sigma),
    clipped to `bounds` [(low, high), ...] (None: unbounded)."""

    def __init__(self, archive, sigma, x0, bounds=None, batch_size=36, seed=None):
        self.archive = archive
        self.x0 = np.array(x0, dtype=float)
        if self.x0.shape != (archive.solution_dim,):
            raise ValueError("x0: %d values" % archive.solution_dim)
        self.sigma = np.broadcast_to(np.array(sigma, dtype=float), self.x0.shape).copy()
        self.lower = np.array([b[0] for b in bounds]) if bounds is not None else None
        self.upper = np.array([b[1] for b in bounds]) if bounds is not None else None
        self.batch_size = int(batch_size)
        self.rng = np.random.default_rng(seed)

    def ask(self):
        if self.archive.empty():
            parents = np.repeat(self.x0[None, :], self.batch_size, axis=0)
        else:
            parents = np.array([e["solution"]
                                for e in self.archive.sample_elites(self.batch_size, self.rng)])
        x = parents + self.rng.normal(0.0, 1.0, parents.shape) * self.sigma
        if self.lower is not None:
            x = np.clip(x, self.lower, self.upper)
        return x

    def tell(self, solutions, objectives, measures, add_info):
        pass  # a Gaussian emitter learns nothing


class Scheduler:
    """Asks every emitter in turn and tells each its part of the batch (pyribs' Scheduler)."""

    def __init__(self, archive, emitters):
        self.archive = archive
        self.emitters = list(emitters)
        self._asked = None  # (the batch, each emitter's share of it)

    def ask(self):
        parts = [e.ask() for e in self.emitters]
        batch = np.concatenate(parts)
        self._asked = (batch, [len(p) for p in parts])
        return batch

    def tell(self, objective, measures, metadata=None):
        """Adds the batch of the last ask() with its objectives, measures and (optional)
        metadata to the archive; returns the archive's add() answer."""
        if self._asked is None:
            raise RuntimeError("tell() without ask()")
        solutions, shares = self._asked
        info = self.archive.add(solutions, objective, measures, metadata)
        start = 0
        for e, n in zip(self.emitters, shares):
            end = start + n
            e.tell(solutions[start:end], objective[start:end], measures[start:end],
                   {k: v[start:end] for k, v in info.items()})
            start = end
        self._asked = None
        return info
