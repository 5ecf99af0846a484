"""A client of ahhs-evaluate, the ask/tell evaluation service (docs/protocol.md, "Evaluation
service"): genomes (documents or vectors) in, every trial's seed, fitness and behaviour
descriptor and their aggregate out, evaluated by the same farm as ahhs-evolve.

    with Evaluator(["--scenario", "pendulum", "--trials", "3"]) as ev:
        results = ev.evaluate([genome_doc, [0.5] * ev.vector_size])
        results[0]["fitness"], results[0]["descriptor"], results[0]["trials"]
"""
import json
import os
import shutil
import signal
import subprocess

from .vector import Shape

PROTOCOL_VERSION = 2


class EvaluationError(RuntimeError):
    """A request the service answered with an error line (its message), or a service that ended."""


def find_service(binary=None):
    """The ahhs-evaluate to run: `binary`, $AHHS_BIN/ahhs-evaluate, or the one on PATH."""
    if binary:
        return binary
    if os.environ.get("AHHS_BIN"):
        return os.path.join(os.environ["AHHS_BIN"], "ahhs-evaluate")
    found = shutil.which("ahhs-evaluate")
    if not found:
        raise FileNotFoundError("ahhs-evaluate not found: pass binary=, set AHHS_BIN or PATH")
    return found


class Evaluator:
    """One ahhs-evaluate process for the lifetime of the object (a context manager). `options`
    are its command-line options (scenario, envelope, trials, workers, LCM URL)."""

    def __init__(self, options=(), binary=None):
        self._argv = [find_service(binary)] + [str(o) for o in options]
        self._proc = None
        self.hello = None

    def __enter__(self):
        self._proc = subprocess.Popen(self._argv, stdin=subprocess.PIPE, stdout=subprocess.PIPE,
                                      stderr=subprocess.PIPE, text=True, bufsize=1)
        line = self._proc.stdout.readline()
        if not line:
            self._proc.wait()
            why = self._proc.stderr.read().strip()
            for stream in (self._proc.stdin, self._proc.stdout, self._proc.stderr):
                stream.close()
            self._proc = None
            raise EvaluationError("ahhs-evaluate ended before its hello line: " + why)
        self.hello = json.loads(line)
        if self.hello.get("v") != PROTOCOL_VERSION:
            self.close()
            raise EvaluationError("ahhs-evaluate speaks protocol version %r, this client %d" %
                                  (self.hello.get("v"), PROTOCOL_VERSION))
        return self

    def __exit__(self, exc_type, *exc):
        if exc_type is KeyboardInterrupt:
            self.interrupt()
        else:
            self.close()
        return False

    @property
    def shape(self):
        """The shape of vector genomes."""
        return Shape.from_json(self.hello["shape"])

    @property
    def vector_size(self):
        return self.hello["vector_size"]

    @property
    def physics(self):
        """The physics version the service evaluates in (its --physics, or its build's own;
        None from a service older than the hello's "physics" key)."""
        return self.hello.get("physics")

    @property
    def descriptor_names(self):
        """What a result's "descriptor" holds, value by value (docs/scenarios.md, "Behaviour
        descriptors"): ["above_pivot", "at_wall"] for the pendulum, ["end_x", "end_y"] for the
        gait."""
        return list(self.hello["descriptor"])

    def evaluate(self, genomes, seed=None, request_id=None, generation=None):
        """Evaluates a batch: each genome a document (dict) or a vector (sequence of numbers).
        Returns one result per genome: {"fitness", "descriptor", "genome_hash",
        "trials": [{"seed", "fitness", "descriptor"}]} (a descriptor is None for an episode that
        failed; the result's is the mean of its trials').
        A service that records a run (--out, --resume) takes `generation` instead of a seed.
        Raises EvaluationError with the service's message for a bad request."""
        batch = [g if isinstance(g, dict) else {"vector": [float(v) for v in g]} for g in genomes]
        request = {"v": PROTOCOL_VERSION, "genomes": batch}
        if seed is not None:
            request["seed"] = int(seed)
        if request_id is not None:
            request["id"] = request_id
        if generation is not None:
            request["generation"] = int(generation)
        self._proc.stdin.write(json.dumps(request) + "\n")
        self._proc.stdin.flush()
        line = self._proc.stdout.readline()
        if not line:
            raise EvaluationError("ahhs-evaluate ended: " + self._proc.stderr.read().strip())
        answer = json.loads(line)
        if "error" in answer:
            raise EvaluationError(answer["error"])
        self.last_seed = answer["seed"]
        return answer["results"]

    def interrupt(self):
        """Stops the service as Ctrl-C does (SIGINT; a recorded run keeps its complete
        generations and resumes) and waits for it, at most 60 s. For a Ctrl-C that reached this
        process alone, as a signal sent to one process in the background does; one sent to the
        terminal's whole process group has reached the service too, and a second does no harm."""
        if self._proc is None:
            return
        # A further Ctrl-C while the service stops would leave it running behind us.
        previous = signal.signal(signal.SIGINT, signal.SIG_IGN)
        try:
            self._proc.send_signal(signal.SIGINT)
            try:
                self._proc.communicate(timeout=60)
            except subprocess.TimeoutExpired:
                self._proc.kill()
                self._proc.communicate()
        finally:
            signal.signal(signal.SIGINT, previous)
        self._proc = None

    def close(self):
        """Ends the service (end of its input) and waits for it: at most 30 s, or, for a recorded
        run that validates and post-evaluates its best when its last generation is in (its
        hello's "run" says so), until it has done that. Returns what the service wrote to its
        standard error (e.g. the post-evaluation's line), "" once closed."""
        if self._proc is None:
            return ""
        run = (self.hello or {}).get("run") or {}
        finishing = run.get("validation", 0) > 0 or run.get("post_eval", 0) > 0
        # communicate closes its input and reads its output meanwhile (a full pipe cannot stop it).
        try:
            _, said = self._proc.communicate(timeout=None if finishing else 30)
        except subprocess.TimeoutExpired:
            self._proc.kill()
            _, said = self._proc.communicate()
        self._proc = None
        return said or ""
