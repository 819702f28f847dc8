"""(connect71) A step of an OPC UA server's clock told by the client's own: set, or a pause.

Between two samples it takes the client sees the server's clock (``CurrentTime``) go on
``server_s`` and its own ``client_s``.  A pause (the machine off, the server down, the link
lost) advances both; a clock set (an operator, DST, an NTP correction) while the machine ran
only the server's.  The rule (``tests/shell/test_opcua67.py`` holds it and what must not change):

- told only where the server's clock runs at the client's rate: over the last
  :data:`RATE_SAMPLES` steps of under :data:`~...core.io.rates.GAP_PERIODS` periods, the
  server's seconds within :data:`RATE_TOLERANCE` of the client's.  A simulated machine's clock
  runs faster (the tests' vendor server ~1000 times, the twin at ``twin.speed``) and a new
  process has timed no step yet: there a step is kept as before, and said;
- a step of the server's clock :data:`SET_PERIODS` periods or more beyond the client's, or back
  at all, is the clock set by the difference: the caller moves the stream's time with it, so
  the model's time goes on as the client's clock did.

Pure: the client passes its clock's readings (:func:`~.client.own_clock`)."""

from __future__ import annotations

from collections import deque

from ...core.io.rates import GAP_PERIODS

SET_PERIODS = 1.0       # the server's clock this many periods beyond the client's: set
RATE_TOLERANCE = 0.1    # the server's clock at the client's rate: within 10 %
RATE_SAMPLES = 8        # over the last this many regular steps


class OwnClock:
    """What the client's clock (its readings at the samples taken) says of the server's."""

    def __init__(self, period_s: float | None):
        self.period_s = float(period_s or 0.0)
        self.at: float | None = None            # the client's clock at the last sample taken
        self.steps: deque = deque(maxlen=RATE_SAMPLES)   # (server s, client s) of regular steps

    def rate(self) -> float | None:
        """The server's seconds per client second over the regular steps timed (None: none)."""
        if not self.steps:
            return None
        client = sum(c for _, c in self.steps)
        return sum(s for s, _ in self.steps) / client if client > 0 else float("inf")

    def why_not(self) -> str:
        """Why a step of the server's clock cannot be told a set or a pause ('' where it can)."""
        rate = self.rate()
        if rate is None:
            return ("the client has no step of the server's clock timed yet (a new process): a "
                    "clock set forward is not told from a pause")
        if abs(rate - 1) > RATE_TOLERANCE:
            return (f"the server's clock ran {rate:.4g} times the client's over its last "
                    f"{len(self.steps)} samples (a simulated machine?): a clock set forward is "
                    "not told from a pause")
        return ""

    def set_by(self, server_s: float, now: float) -> float | None:
        """The seconds the server's clock was set by (> 0 forward) since the last sample taken,
        ``server_s`` ago on it, the client's clock reading ``now``; None: not set, or not told."""
        if self.at is None or self.period_s <= 0 or self.why_not():
            return None
        client_s = now - self.at
        if server_s < 0 or abs(server_s - client_s) >= SET_PERIODS * self.period_s:
            return server_s - client_s
        return None

    def taken(self, server_s: float | None, now: float) -> None:
        """A sample taken, ``server_s`` after the last on the server's clock (None: a campaign's
        first, or a set one: not a step to time the rate by)."""
        if (server_s is not None and self.at is not None
                and server_s < GAP_PERIODS * self.period_s):
            self.steps.append((server_s, now - self.at))
        self.at = now
