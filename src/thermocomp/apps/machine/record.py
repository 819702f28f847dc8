"""What the virtual machine serves: its test campaigns, their inputs, the machine's error in the
frame the models predict, the reference measurements it takes, the campaigns each continues."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ...base.errors import ConfigError
from ...core.context import TIME
from ...core.continuation import chains, lead_in
from ...core.frame import stack
from ..deploy.adapt import ReferenceSchedule, scheduled


def served_campaigns(chosen, test_ids: list[str]) -> list[str]:
    """``twin.campaigns`` (None: every test campaign), in the test split's order."""
    if chosen is None:
        return test_ids
    unknown = [c for c in chosen if c not in test_ids]
    if unknown:
        raise ConfigError(f"twin.campaigns={list(chosen)}: {', '.join(unknown)} not a test campaign "
                          f"of the data (test: {', '.join(test_ids)})")
    return [c for c in test_ids if c in set(chosen)]


@dataclass
class Record:
    campaigns: dict            # id -> its frame, as recorded
    columns: list[str]         # the inputs published (time, T_, S_)
    targets: list[str]         # the E_ errors compensated
    errors: dict               # id -> (n, targets) the machine's error in the models' frame
    references: dict           # id -> (n, targets) a reference measurement or NaN
    chains: dict               # id -> the campaigns it continues, oldest first, then itself
    lead_ins: dict             # id -> those it continues joined, served before it (unscored)

    @property
    def n_references(self) -> int:
        return int(sum(np.isfinite(r).any(axis=1).sum() for r in self.references.values()))


def served_record(ds, test_ids: list[str], reference: str, every_s: float, where: str) -> Record:
    """The record the twin serves of ``ds``'s ``test_ids``; with ``reference="none"`` a campaign
    is served after those it continues (its state carried over, as ``replay`` warms it)."""
    campaigns = {c: ds.campaigns[c] for c in test_ids}
    first = campaigns[test_ids[0]]
    common = [c for c in first.columns if all(c in df.columns for df in campaigns.values())]
    targets = [c for c in common if c.startswith("E_")]
    if not targets:
        raise ConfigError(f"{where}: the test campaigns have no E_ error column in common: the "
                          "twin has no error to compensate")
    continued = chains(ds, test_ids) if reference == "none" else {}
    m = stack(campaigns, [], targets, reference)
    errors = {c: m.Y[m.rows_of(c)].to_numpy(float) for c in campaigns}
    references = {c: scheduled(errors[c], df[TIME].to_numpy(float),   # the reader made `time`
                               ReferenceSchedule(float(every_s)))
                  for c, df in campaigns.items()}
    return Record(campaigns, [c for c in common if not c.startswith("E_")], targets, errors,
                  references, continued, {c: lead_in(ds, ids) for c, ids in continued.items()})
