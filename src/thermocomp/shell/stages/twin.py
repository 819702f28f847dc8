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

from omegaconf import DictConfig

from ...apps.machine.record import served_campaigns, served_record
from ...base.errors import ConfigError
from ...base.files import write_json
from ...base.log import say
from ...base.paths import resolve
from ..config.checks import check_config
from ..source import read_streamed, reference


def twin(cfg: DictConfig) -> dict:
    """Serve the test campaigns until they are done; ``twin.json``'s content."""
    check_config(cfg)
    from ...apps.machine.nodes import NodeMap
    from ...apps.machine.twin import Outage, Twin, twin_report

    ds, _, test_ids, _ = read_streamed(cfg)
    test_ids = served_campaigns(cfg.twin.get("campaigns"), test_ids)
    rec = served_record(ds, test_ids, reference(cfg), cfg.adapt.every_s, f"data.path={cfg.data.path}")
    if rec.chains:
        say("served after the campaigns they continue (unscored): "
            + ", ".join(f"{c} after {' + '.join(ids[:-1])}" for c, ids in rec.chains.items()))
    t = cfg.twin
    nodes = NodeMap.from_config(cfg.connect.nodes)
    if nodes.missing():        # a vendor's mapping (opcua67): the twin serves its own protocol
        raise ConfigError(f"connect.nodes.{nodes.missing()[0]}=null: the twin serves every status "
                          "node (sample, campaign, campaign_sample, done, offset_sample)")
    machine = Twin(nodes, rec.campaigns, rec.columns, rec.errors,
                   rec.targets,
                   host=str(t.host), port=int(t.port), speed=float(t.speed),
                   drops=[Outage(*p) for p in t.drops], restarts=[Outage(*p) for p in t.restarts],
                   wait_s=float(t.wait_s), lead_ins=rec.lead_ins, references=rec.references,
                   lockstep=bool(t.lockstep))
    n = sum(len(df) for df in rec.campaigns.values())
    say(f"twin at {machine.endpoint}: {len(rec.campaigns)} test campaigns, {n} samples at "
        f"{float(t.speed):g} per second; offsets of {', '.join(rec.targets)}")
    report, path = {}, Path(resolve(cfg.out)) / "twin.json"

    def finished(served) -> None:     # before `done`: the record is there when the client ends
        report.update(twin_report(served, rec.errors, rec.targets), endpoint=machine.endpoint,
                      speed=float(t.speed), lockstep=bool(t.lockstep), test_campaigns=test_ids,
                      columns=rec.columns,
                      reference=reference(cfg), references=rec.n_references)
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
