"""Deployment: the fitted compensator as a causal, stateful process a CNC can call.

:mod:`.streaming` is pure core (no MLflow); :mod:`.pyfunc` wraps it as an
``mlflow.pyfunc`` model (import it explicitly, it loads MLflow).
Depends on the core only, never on Hydra or the stages.
"""

from .streaming import (
                        POLICIES,
                        Envelope,
                        OutOfEnvelopeError,
                        StreamingCompensator,
                        has_stream_protocol,
                        replay,
                        stream_scores,
                        streaming_deviation,
)

__all__ = ["POLICIES", "Envelope", "OutOfEnvelopeError", "StreamingCompensator",
           "has_stream_protocol", "replay", "stream_scores", "streaming_deviation"]
