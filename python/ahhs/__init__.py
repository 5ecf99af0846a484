"""AHHS from Python: genome vectors, the evaluation service's client, MAP-Elites (ahhs.qd) and
resumable searches over the service (ahhs.search); python/README.md."""
from .evaluate import EvaluationError, Evaluator, find_service
from .vector import Shape, from_vector, layout, to_vector

__all__ = ["EvaluationError", "Evaluator", "Shape", "find_service", "from_vector", "layout",
           "to_vector"]
__version__ = "0.1.0"
