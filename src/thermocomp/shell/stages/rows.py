"""`thermocomp rows <file-or-folder>` (extension, lab78): a lab's file or folder, read with the
data config (``data=<name>`` that ``init`` wrote, ``data.*``) as ``replay`` and a served model
read it, written on stdout as the rows the exported ``stream.c`` and a served block read
(:mod:`thermocomp.apps.deploy.export.rows`): every format the reader takes reaches the code, under
the names the model was fitted with.  Nothing is written before the whole data are read: a bad
file is exit 2 naming file, column and row, stdout empty.
"""

from __future__ import annotations

import sys

from omegaconf import DictConfig

from ...apps.deploy.export.rows import rows_text
from ...base.errors import ConfigError
from ...base.log import say
from ...base.paths import resolve
from ...core import io
from ..config.checks import data_options
from ..source import open_source, resolve_reference


def chosen(cfg: DictConfig, ds) -> list[str]:
    """``rows.campaigns`` (every campaign of ``ds`` where null), each one of ``ds``'s."""
    wanted = cfg.rows.get("campaigns")
    if wanted is None:
        return ds.ids()
    ids = [str(c) for c in wanted]
    unknown = [c for c in ids if c not in ds.campaigns]
    if unknown:
        have = list(ds.campaigns)
        raise ConfigError(f"rows.campaigns names {', '.join(map(repr, unknown))}, no campaign of "
                          f"data.path (it has {', '.join(map(repr, have[:8]))}"
                          f"{', ...' if len(have) > 8 else ''})")
    return ids


def rows(cfg: DictConfig) -> dict:
    """Write ``data.path``'s campaigns (``rows.campaigns``) on stdout as ``stream.c`` reads rows;
    ``{"blocks": [{campaigns, rows}, ...]}``."""
    io.ReadOptions.from_cfg(data_options(cfg))       # data.*: before any file is read
    # (as replay and the pack read it); a file's inputs alone without rows.errors (stranger83:
    # a run's DAQ file, its errors in the probe's log, was refused "no E_ column")
    lone = resolve(cfg.data.path).is_file() and not cfg.rows.errors
    ds = open_source(cfg, stream=True, needs_errors=not lone)
    reference = resolve_reference(cfg, ds)
    text, listed = rows_text(ds, chosen(cfg, ds), reference, bool(cfg.rows.errors))
    sys.stdout.write(text)
    sys.stdout.flush()
    chained = [" + ".join(b["campaigns"]) for b in listed if len(b["campaigns"]) > 1]
    say(f"rows: {sum(b['rows'] for b in listed):,} rows of {len(listed)} campaign(s) on stdout, "
        "a blank line between campaigns (where stream.c starts one)"
        + (f"; one stream, state carried over: {'; '.join(chained)}" if chained else ""))
    return {"blocks": listed}
