"""`thermocomp twin`: the test campaigns of ``data.path`` served as a virtual machine tool over
OPC UA (:class:`~thermocomp.apps.machine.twin.Twin`, node ids ``connect.nodes``); writes
``<out>/twin.json`` when they are done (CLI.md).

The machine's error is each campaign's measured error in the frame the models predict
(``data.reference``), so the compensated RMS compares with ``replay``'s.  It takes a reference
measurement of that error every ``adapt.every_s`` of a campaign's time, as ``replay`` simulates
them, and publishes it (``connect`` learns from it with ``adapt``).  ``twin.campaigns`` serves
some of the test campaigns only.
"""

from __future__ import annotations

import asyncio
from pathlib import Path

import numpy as np
from omegaconf import DictConfig

from ...apps.deploy.adapt import ReferenceSchedule, scheduled
from ...base.errors import ConfigError
from ...base.files import write_json
from ...base.log import say
from ...base.paths import resolve
from ...core.context import TIME
from ...core.continuation import chain, lead_in, predecessors
from ...core.frame import stack
from ..config.checks import check_config
from ..source import read_streamed, reference


def served_campaigns(chosen, test_ids: list[str]) -> list[str]:
    """``twin.campaigns`` (null: every test campaign), in the test split's order."""
    if chosen is None:
        return test_ids
    unknown = [c for c in chosen if c not in test_ids]
    if unknown:
        raise ConfigError(f"twin.campaigns={list(chosen)}: {', '.join(unknown)} not a test campaign "
                          f"of the data (test: {', '.join(test_ids)})")
    return [c for c in test_ids if c in set(chosen)]


def twin(cfg: DictConfig) -> dict:
    """Serve the test campaigns until they are done; ``twin.json``'s content."""
    check_config(cfg)
    from ...apps.machine.nodes import NodeMap
    from ...apps.machine.twin import Outage, Twin, twin_report

    ds, _, test_ids, _ = read_streamed(cfg)
    test_ids = served_campaigns(cfg.twin.get("campaigns"), test_ids)
    campaigns = {c: ds.campaigns[c] for c in test_ids}
    first = campaigns[test_ids[0]]
    common = [c for c in first.columns if all(c in df.columns for df in campaigns.values())]
    targets = [c for c in common if c.startswith("E_")]
    columns = [c for c in common if not c.startswith("E_")]
    if not targets:
        raise ConfigError(f"data.path={cfg.data.path}: the test campaigns have no E_ error "
                          "column in common: the twin has no error to compensate")
    lead_ins = {}
    if reference(cfg) == "none":      # state carried over: served after the campaigns it continues
        links = predecessors(ds)
        lead_ins = {c: lead_in(ds, chain(ds, c, links)) for c in test_ids if c in links}
        if lead_ins:
            say("served after the campaigns they continue (unscored): "
                + ", ".join(f"{c} after {' + '.join(chain(ds, c, links)[:-1])}" for c in lead_ins))
    m = stack(campaigns, [], targets, reference(cfg))
    errors = {c: m.Y[m.rows_of(c)].to_numpy(float) for c in campaigns}
    references = {c: scheduled(errors[c], df[TIME].to_numpy(float),   # the reader made `time`
                               ReferenceSchedule(float(cfg.adapt.every_s)))
                  for c, df in campaigns.items()}
    t = cfg.twin
    machine = Twin(NodeMap.from_config(cfg.connect.nodes), campaigns, columns, errors, targets,
                   host=str(t.host), port=int(t.port), speed=float(t.speed),
                   drops=[Outage(*p) for p in t.drops], restarts=[Outage(*p) for p in t.restarts],
                   wait_s=float(t.wait_s), lead_ins=lead_ins, references=references)
    n = sum(len(df) for df in campaigns.values())
    say(f"twin at {machine.endpoint}: {len(campaigns)} test campaigns, {n} samples at "
        f"{float(t.speed):g} per second; offsets of {', '.join(targets)}")
    report, path = {}, Path(resolve(cfg.out)) / "twin.json"

    def finished(served) -> None:     # before `done`: the record is there when the client ends
        report.update(twin_report(served, errors, targets), endpoint=machine.endpoint,
                      speed=float(t.speed), test_campaigns=test_ids, columns=columns,
                      reference=reference(cfg), references=int(sum(
                          np.isfinite(r).any(axis=1).sum() for r in references.values())))
        write_json(path, report)

    try:
        asyncio.run(machine.serve(finished))
    except OSError as exc:
        raise ConfigError(f"twin.port={t.port}: cannot serve at {machine.endpoint} ({exc})") from None
    for name, r in report["targets"].items():
        say(f"{name}: RMS {r['rms_uncompensated']:.3f} -> {r['rms_compensated']:.3f} µm "
            f"compensated, peak {r['peak_compensated']:.3f}, {r['stale_samples']} stale samples")
    say(f"twin: {path}")
    return report
