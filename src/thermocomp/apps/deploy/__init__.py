"""Deployment: the fitted compensator as a causal, stateful process a CNC can call.

:mod:`.streaming` is pure core (no MLflow); :mod:`.pyfunc` wraps it as an
``mlflow.pyfunc`` model (import it explicitly, it loads MLflow).  The fault-tolerant compensator
is deployed code too: :mod:`.pod` (POD reconstruction from any sensor subset),
:mod:`.surveillance` (self-prediction error, detectors, adaptive sensor set), :mod:`.guard`
(bounded, rate-limited correction) and :mod:`.adaptive`, which combines them around a stream.
Depends on the core only, never on :mod:`thermocomp.apps.monitor` (which uses deploy), on Hydra
or on the stages.
"""

from .adaptive import AdaptiveCompensator
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

__all__ = ["POLICIES", "AdaptiveCompensator", "Envelope", "OutOfEnvelopeError",
           "StreamingCompensator", "has_stream_protocol", "replay", "stream_scores", "streaming_deviation"]
