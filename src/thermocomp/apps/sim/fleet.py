r"""Scenario ``fleet``: many machines of one type, each logged for weeks, as Parquet partitions.

A plant runs ``n_machines`` machining centres of one model.  Each is the same
lumped network (a spindle motor, bearings, headstock, the two column walls and
an unmeasured column core, bed, table; :class:`~thermocomp.apps.sim.network.ThermalNetwork`)
with its own capacities and convection (each drawn within ``spread`` of the
nominal, as castings, covers and positions in the hall differ), its own hall
air (:class:`~thermocomp.apps.sim.long_record.WorkshopClimate`, weather drawn per
machine) and its own shifts and jobs (:func:`~thermocomp.apps.sim.long_record.workload`).
``n_sensors`` temperatures are logged every ``sample_period_s``: 4 in the air
(``T_amb``, ``T_amb_2`` ...), the others ``T_sNN`` on the structure, each a mix of
two measured nodes (a probe between two masses) with noise and a 0.01 °C
quantum.  ``E_X``, ``E_Y``, ``E_Z`` (µm) are linear in the node rises (the
column core included, which no sensor sees) with gains drawn per machine,
plus 0.2 µm noise.  ``S_spindle_rpm`` is logged too.

Heat: spindle motor :math:`25 + 15 n + 2 n^2` W (:math:`n` in 1000 rpm),
bearings :math:`8 n` W, the X drive 40 W while a job runs.  The network is
advanced exactly (matrix exponential, inputs held over a sample period).

Layout (DATA_FORMAT.md, extended by metadata only): one campaign per machine
and day (``M003-D07``) in ``machine=M003/day=07.parquet`` (Hive-style
partitions), the manifest column ``machine`` says whose it is; the last
``test_days`` days of each machine are ``test``, the others ``train``.  Each
day is referenced to its first sample (``data.reference: first_sample``) as a
machinist zeroes the error at the day's first part.

Generation is parallel (joblib, ``n_jobs`` processes, one machine at a time in
each: memory is bounded by one machine whatever the fleet size) and written
partition by partition; the manifest comes last, so an interrupted generation
leaves no dataset that looks complete.
"""

from __future__ import annotations

import zlib
from pathlib import Path

import numpy as np
import pandas as pd

from thermocomp.apps.sim.ambient import DAY_S
from thermocomp.apps.sim.long_record import WorkshopClimate, jobs_signal, workload
from thermocomp.apps.sim.network import Link, Node, ThermalNetwork
from thermocomp.apps.sim.scenario import MAX_SAMPLES, plain
from thermocomp.apps.sim.sensors import quantise
from thermocomp.base.files import atomic_dir
from thermocomp.base.params import POSITIVE, check_params, check_values, integer, number, numbers

MANIFEST = "campaigns.csv"
N_AMBIENT = 4
# node: (capacity J/K, convection W/K); the column core has no sensor
NODES = {"motor": (2.0e4, 6.0), "bearings": (4.0e3, 1.5), "head": (6.0e4, 10.0),
         "column_front": (1.2e5, 8.0), "column_back": (1.2e5, 20.0), "column_core": (1.4e6, 0.0),
         "bed": (4.0e5, 30.0), "table": (1.4e5, 6.0)}
LINKS = (("motor", "bearings", 3.0), ("bearings", "head", 6.0), ("motor", "head", 4.0),
         ("head", "column_front", 5.0), ("column_front", "column_core", 25.0),
         ("column_back", "column_core", 25.0), ("column_core", "bed", 20.0), ("bed", "table", 10.0))
MEASURED = ("motor", "bearings", "head", "column_front", "column_back", "bed", "table")
# µm/K of node rises, nominal; each machine draws its own within `spread`
GAINS = {"E_X": {"head": 0.8, "column_front": -0.6, "column_back": 0.6, "table": 0.5, "bed": -0.3},
         "E_Y": {"head": 1.2, "bearings": 0.4, "column_core": 1.5, "bed": -0.4},
         "E_Z": {"motor": 0.5, "bearings": 1.5, "head": 3.0, "column_front": -1.5,
                 "column_back": -1.5, "column_core": -8.0, "bed": 2.0, "table": 1.0}}


def machine_id(i: int) -> str:
    return f"M{i + 1:03d}"


class Fleet:
    """Digital twin of a fleet: ``n_machines`` x ``days`` days, one Parquet partition per day.

    Parameters
    ----------
    n_machines : int
        Machines of the fleet.
    days : int
        Days logged per machine (one campaign each).
    sample_period_s : float
        Logging period (s).
    n_sensors : int
        Temperature sensors per machine (4 in the air, the rest on the structure), >= 5.
    test_days : int
        The last days of each machine in the ``test`` split.
    spread : float
        Relative spread of capacities, convection and error gains between machines.
    start_day : int
        Day of the year of the first sample (00:00).
    speeds_rpm : sequence of float
        Spindle speeds of the jobs.
    n_jobs : int
        Processes generating machines at once (joblib).
    seed : int
        Everything random derives from it and the machine's number.
    """

    def __init__(self, n_machines=100, days=30, sample_period_s=30.0, n_sensors=40, test_days=6,
                 spread=0.2, start_day=74, speeds_rpm=(1500, 3000, 4500, 6000, 8000), n_jobs=2, seed=0):
        # checked before the conversions below (int(nan) was a traceback, exit 1)
        check_values(dict(n_machines=n_machines, days=days, sample_period_s=sample_period_s,
                          n_sensors=n_sensors, test_days=test_days, spread=spread,
                          start_day=start_day, speeds_rpm=speeds_rpm, n_jobs=n_jobs),
                     self.param_rules, "sim.generator")
        self.n_machines, self.days, self.sample_period_s = int(n_machines), int(days), float(sample_period_s)
        self.n_sensors, self.test_days, self.spread = int(n_sensors), int(test_days), float(spread)
        self.start_day, self.speeds_rpm = int(start_day), tuple(float(s) for s in speeds_rpm)
        self.n_jobs, self.seed = int(n_jobs), int(seed)

    param_rules = {"n_machines": integer(1, at_most=10_000), "days": integer(2, at_most=3660),
                   "sample_period_s": POSITIVE, "n_sensors": integer(N_AMBIENT + 1, at_most=1000),
                   "test_days": integer(1, at_most=3660),
                   "spread": number(0.0, 1.0, open_hi=True), "start_day": integer(0, 364),
                   "speeds_rpm": numbers(0.0), "n_jobs": integer(-1, at_most=1024)}

    def param_relations(self) -> list[tuple[str, str]]:
        out = []
        if self.test_days >= self.days:
            out.append(("test_days", f"must be below sim.generator.days={self.days}"))
        if self.n_jobs == 0:
            out.append(("n_jobs", "must not be 0 (-1: every core)"))
        if DAY_S < 2 * self.sample_period_s:
            out.append(("sample_period_s", "must fit twice in a day"))
        per_machine = self.days * DAY_S / self.sample_period_s   # one machine is held at once
        if per_machine > MAX_SAMPLES:
            out.append(("sample_period_s", f"makes {per_machine:,.0f} samples per machine over "
                                           f"{self.days} days, more than {MAX_SAMPLES:,}"))
        elif self.n_machines * per_machine > 10 * MAX_SAMPLES:
            out.append(("n_machines", f"makes {self.n_machines * per_machine:,.0f} samples in all, "
                                      f"more than {10 * MAX_SAMPLES:,}"))
        return out

    def get_params(self) -> dict:
        return plain({k: v for k, v in vars(self).items()})

    # --- one machine ---------------------------------------------------------------------------

    def _rng(self, machine: int) -> np.random.Generator:
        return np.random.default_rng([self.seed, machine, zlib.crc32(b"fleet")])

    def _draw(self, rng, nominal: float) -> float:
        return float(nominal * rng.uniform(1 - self.spread, 1 + self.spread))

    def machine(self, i: int) -> tuple[dict[str, pd.DataFrame], dict]:
        """Day frames (``D01`` ...) of machine ``i`` (0-based) and its truth."""
        rng = self._rng(i)
        net = ThermalNetwork([Node(n, self._draw(rng, c), self._draw(rng, h)) for n, (c, h) in NODES.items()],
                             [Link(a, b, self._draw(rng, g)) for a, b, g in LINKS])
        step = self.sample_period_s
        n = int(round(self.days * DAY_S / step))
        start_s = self.start_day * DAY_S
        t = np.arange(n) * step
        air = WorkshopClimate(setpoint_c=float(rng.uniform(19.0, 23.0))).sample(start_s + t, rng)
        programme, jobs, _ = workload(rng, start_s, n * step, step, self.speeds_rpm)
        rpm = programme.rpm_at(t)
        k = rpm / 1000.0
        heat = np.zeros((n, net.n_nodes))
        heat[:, net.index["motor"]] = np.where(rpm > 0, 25 + 15 * k + 2 * k**2, 0.0)
        heat[:, net.index["bearings"]] = 8.0 * k
        heat[:, net.index["table"]] = 40.0 * jobs_signal(jobs)(t)
        nodes = _simulate(net, step, air, heat)
        rises = nodes - nodes[0]
        gains = {e: {node: self._draw(rng, g) for node, g in gs.items()} for e, gs in GAINS.items()}
        frame = {"time": t}
        for j in range(N_AMBIENT):
            name = "T_amb" if j == 0 else f"T_amb_{j + 1}"
            frame[name] = air + rng.normal(0.0, 0.05) + rng.normal(0.0, 0.03, n)
        measured = [net.index[m] for m in MEASURED]
        for j in range(self.n_sensors - N_AMBIENT):
            a, b = rng.choice(measured, size=2, replace=False)
            w = rng.uniform(0.5, 1.0)
            frame[f"T_s{j + 1:02d}"] = w * nodes[:, a] + (1 - w) * nodes[:, b] + rng.normal(0.0, 0.03, n)
        for name in list(frame)[1:]:
            frame[name] = quantise(frame[name], 0.01)
        for e, gs in gains.items():
            frame[e] = sum(g * rises[:, net.index[node]] for node, g in gs.items()) + rng.normal(0.0, 0.2, n)
        frame["S_spindle_rpm"] = rpm
        record = pd.DataFrame(frame)
        per_day = int(round(DAY_S / step))
        days = {}
        for d in range(self.days):
            day = record.iloc[d * per_day:(d + 1) * per_day].reset_index(drop=True)
            day["time"] = day["time"] - day["time"].iloc[0]
            days[f"D{d + 1:02d}"] = day
        truth = {"machine": machine_id(i), "network": net.to_dict(), "gains_um_per_K": gains,
                 "unmeasured_nodes": ["column_core"]}
        return days, truth

    def _rows(self, i: int) -> list[dict]:
        start = pd.Timestamp("2023-01-01") + pd.Timedelta(days=self.start_day)
        return [{"campaign": f"{machine_id(i)}-D{d + 1:02d}",
                 "file": f"machine={machine_id(i)}/day={d + 1:02d}.parquet",
                 "split": "test" if d >= self.days - self.test_days else "train",
                 "start": (start + pd.Timedelta(days=d)).isoformat(), "machine": machine_id(i)}
                for d in range(self.days)]

    def _write_machine(self, root: Path, i: int) -> dict:
        days, truth = self.machine(i)
        with atomic_dir(root / f"machine={machine_id(i)}") as tmp:
            for d, frame in enumerate(days.values()):
                frame.to_parquet(tmp / f"day={d + 1:02d}.parquet", index=False)
        return truth

    # --- the whole fleet -----------------------------------------------------------------------

    def write(self, path) -> dict:
        """Write the fleet dataset to ``path`` (partitions in parallel, manifest last); returns the truth."""
        from joblib import delayed

        from thermocomp.base.files import atomic_write_text
        from thermocomp.base.lifetime import parallel

        check_params(self)
        root = Path(path)
        root.mkdir(parents=True, exist_ok=True)
        (root / MANIFEST).unlink(missing_ok=True)       # until every partition is there
        truths = parallel(self.n_jobs)(delayed(self._write_machine)(root, i)
                                              for i in range(self.n_machines))
        rows = [r for i in range(self.n_machines) for r in self._rows(i)]
        atomic_write_text(root / MANIFEST, pd.DataFrame(rows).to_csv(index=False))
        per_day = int(round(DAY_S / self.sample_period_s))
        return self._truth(truths, campaigns=len(rows), rows=len(rows) * per_day)

    def generate(self):
        """The fleet in memory (small fleets: tests); :meth:`write` streams a big one to disk."""
        from thermocomp.core.io.contract import Dataset

        check_params(self)
        campaigns, rows, truths = {}, [], []
        for i in range(self.n_machines):
            days, truth = self.machine(i)
            truths.append(truth)
            for row, frame in zip(self._rows(i), days.values()):
                campaigns[row["campaign"]] = frame
                rows.append(row)
        manifest = pd.DataFrame(rows).set_index("campaign").drop(columns="file")
        return Dataset(manifest, campaigns, "fleet"), self._truth(truths)

    def _truth(self, machines: list[dict], **counts) -> dict:
        """The fleet's truth: its parameters, ``counts`` (written: campaigns, rows), each machine's."""
        return {"scenario": "fleet", "params": self.get_params(), **counts,
                "machines": {t["machine"]: t for t in machines}}


def _simulate(net: ThermalNetwork, step_s: float, air: np.ndarray, heat: np.ndarray) -> np.ndarray:
    """Node temperatures (n, nodes) from the steady state of the first sample, inputs held per step."""
    prop = net.propagator(step_s)
    drive = np.outer(air, prop.gamma_ambient) + heat @ prop.gamma_heat.T   # input term of each step
    out = np.empty((len(air), net.n_nodes))
    out[0] = net.steady_state(air[0], heat[0])
    phi = prop.phi
    for k in range(1, len(air)):
        out[k] = phi @ out[k - 1] + drive[k - 1]
    return out
