"""The torch side of :class:`~thermocomp.core.models.lstm.LSTM`: its network and tensor helpers.

Apart from lstm.py so that building and checking an LSTM config imports no torch (~4 s): a
mistyped ``model.estimator`` value is refused at once, and torch is imported by the first fit or
prediction (``LSTM.requires``: a missing torch is still refused before any data is read).
"""

from __future__ import annotations

import numpy as np
import torch
from torch import nn


class _Net(nn.Module):
    """``w·x + c`` plus a linear read-out of the LSTM state carried from the campaign start."""

    def __init__(self, n_inputs: int, hidden_size: int, num_layers: int, dropout: float):
        super().__init__()
        self.skip = nn.Linear(n_inputs, 1)
        self.lstm = nn.LSTM(n_inputs, hidden_size, num_layers=num_layers, batch_first=True,
                            dropout=dropout if num_layers > 1 else 0.0)
        self.head = nn.Linear(hidden_size, 1)
        # the residual starts at zero: the untrained model is the least-squares fit
        nn.init.zeros_(self.head.weight)
        nn.init.zeros_(self.head.bias)
        # forget gates open at start (bias 1): a thermal state is remembered by default
        for name, p in self.lstm.named_parameters():
            if name.startswith("bias_ih"):
                with torch.no_grad():
                    p[hidden_size:2 * hidden_size].fill_(1.0)

    def forward(self, x, state=None):
        """``(y, residual, (h, c))`` for ``x`` of shape (batch, time, inputs)."""
        out, state = self.lstm(x, state)
        residual = self.head(out).squeeze(-1)
        return self.skip(x).squeeze(-1) + residual, residual, state


class _torch_threads:
    """Run a block with ``torch.set_num_threads(n)`` and restore the previous value."""

    def __init__(self, n: int):
        self.n = n

    def __enter__(self):
        self.previous = torch.get_num_threads()
        torch.set_num_threads(self.n)

    def __exit__(self, *exc):
        torch.set_num_threads(self.previous)


def _padded(values: np.ndarray, bounds, length: int, dtype) -> torch.Tensor:
    """Rows of each campaign as one padded batch ``(n_campaigns, length, ...)`` (zeros after the end)."""
    out = np.zeros((len(bounds), length) + values.shape[1:])
    for b, (start, stop) in enumerate(bounds):
        out[b, :stop - start] = values[start:stop]
    return torch.tensor(out, dtype=dtype)
