"""Deployment speed of the compensator (prints numbers; no assertions).

1. Streaming update latency of a 10-input ARX compensator, in process
   (``StreamingCompensator.step``: reference frame, envelope clamp, ARX state),
   against a bare NumPy dot product of the same size (the floor any Python-side
   update pays) -- target <= 50 µs per sample.
2. Batch prediction of 10 k rows through the ``mlflow.pyfunc`` model (loaded
   from a local folder), ARX (streamed sample by sample) and MLR (static).

Run: ``.venv/bin/python benchmarks/bench_deploy.py`` (``make benchmark`` runs every bench).
"""

from __future__ import annotations

import os
import tempfile
import time

os.environ.setdefault("MLFLOW_ENABLE_ARTIFACTS_PROGRESS_BAR", "false")

import numpy as np
import pandas as pd

from thermocomp.apps.deploy import StreamingCompensator
from thermocomp.apps.deploy.pyfunc import save_compensator
from thermocomp.core.compensator import Compensator
from thermocomp.core.models import MLR
from thermocomp.core.models.arx import ARX

N_SENSORS = 10


def campaign(rng, n: int, dt: float = 60.0) -> pd.DataFrame:
    """10 heated sensors with their own time constants; E_Z is a first-order lag of all of them."""
    t = np.arange(n) * dt
    cols = {"time": t}
    drive = np.zeros(n)
    for j in range(N_SENSORS):
        tau = 1500.0 * (1 + j)
        T = 20 + (2 + j) * (1 - np.exp(-t / tau)) + 0.3 * np.sin(t / (900 + 200 * j) + j)
        cols[f"T_{j}"] = T + rng.normal(0, 0.01, n)
        drive += (1.0 if j % 2 else -0.7) * (1 + 0.2 * j) * (T - T[0])
    ez = np.zeros(n)
    for i in range(1, n):
        ez[i] = 0.7 * ez[i - 1] + 0.3 * drive[i]
    cols["E_Z"] = ez + rng.normal(0, 0.05, n)
    return pd.DataFrame(cols)


def per_call_us(fn, rows, repeats: int = 5) -> float:
    """Best of ``repeats`` mean per-call time (µs) of ``fn(row)`` over ``rows``."""
    best = np.inf
    for _ in range(repeats):
        t0 = time.perf_counter()
        for r in rows:
            fn(r)
        best = min(best, (time.perf_counter() - t0) / len(rows))
    return best * 1e6


def main() -> None:
    print(f"load before: {os.getloadavg()}  (2-core machine shared with other work)")
    rng = np.random.default_rng(0)
    train = {f"K{i}": campaign(rng, 2500) for i in range(4)}
    test = campaign(rng, 10_000)

    arx = Compensator(ARX(max_inputs=N_SENSORS, ar=True)).fit(train)
    est = arx.estimators_["E_Z"]
    print(f"ARX: {len(arx.selected_['E_Z'])} inputs offered, {len(est.terms_)} input terms chosen, "
          f"AR coefficient {est.ar_coef_:.3f}")
    s = StreamingCompensator.from_training(arx, train, policy="clamp")
    rows = test[s.columns_].to_numpy()[:5000]
    clamped = int((s.predict(test.iloc[:5000])["n_clamped"] > 0).sum())
    print(f"{clamped} of {len(rows)} benchmark samples have an input clamped to the training envelope")

    def stream(row):
        return s.step(row)

    s.reset()
    wrapper_us = per_call_us(stream, rows)
    state = est.stream_init()

    def model_only(row):
        nonlocal state
        _, state = est.stream_step(row, state)

    model_us = per_call_us(model_only, rows)
    hot = rows + np.r_[[0.0] * (N_SENSORS - 1), 50.0]       # the last sensor far out: every sample clamped
    s.reset()
    clamp_us = per_call_us(stream, hot)
    b = np.linspace(-1, 1, N_SENSORS)
    dot_us = per_call_us(lambda row: row @ b, rows)
    print(f"streaming update, in process (StreamingCompensator.step, 10-input ARX): "
          f"{wrapper_us:.1f} µs/sample  (target <= 50 µs)")
    print(f"  of which ARX.stream_step alone: {model_us:.1f} µs/sample; "
          f"with every sample clamped: {clamp_us:.1f} µs/sample")
    print(f"  bare NumPy dot product of the same size: {dot_us:.2f} µs  -> ratio {wrapper_us / dot_us:.0f}x")

    frame = test[s.columns_ + ["time"]]
    with tempfile.TemporaryDirectory() as tmp:
        import mlflow

        for name, comp in (("ARX", arx), ("MLR", Compensator(MLR()).fit(train))):
            path = save_compensator(StreamingCompensator.from_training(comp, train), f"{tmp}/{name}",
                                    input_example=frame.head(3))
            model = mlflow.pyfunc.load_model(str(path))
            times = []
            for _ in range(3):
                t0 = time.perf_counter()
                out = model.predict(frame, params={"reset": True})
                times.append(time.perf_counter() - t0)
            best = min(times)
            print(f"pyfunc batch prediction, {len(frame)} rows, {name}: {best * 1e3:.0f} ms "
                  f"({len(frame) / best / 1e3:.0f} k rows/s; {best / len(frame) * 1e6:.1f} µs/row); "
                  f"output columns {list(out.columns)}")
    print(f"load after: {os.getloadavg()}")


if __name__ == "__main__":
    main()
