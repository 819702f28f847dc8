"""What every model family shares: the side-input and streaming protocol (:mod:`thermocomp.context`)."""

from __future__ import annotations

from collections.abc import Mapping

import numpy as np

from ..context import SideInputs


class LinearStreamMixin(SideInputs):
    """Streaming of a static linear law ``y = x·coef_ + intercept_``: one dot product a sample."""

    def stream_step(self, x_row, state, context: Mapping | None = None):
        return float(np.asarray(x_row, dtype=float) @ self.coef_ + self.intercept_), state
