"""A campaign's start is read twice: from its file's first row before the read (the order
``data.test_fraction`` holds out in, :func:`thermocomp.core.io.starts.campaign_starts`, so that a
group of a folder holds out as the whole) and from the read's own time column (the manifest's
``start`` a read or an ingest fills, ``time_origin``).  Where both read a time they must agree,
else an ingested folder holds out other campaigns than the raw one."""

from pathlib import Path

import pandas as pd
import pytest

from thermocomp.core.io.manifest import read_manifest
from thermocomp.core.io.options import ReadOptions
from thermocomp.core.io.read import read_dataset
from thermocomp.core.io.starts import campaign_starts

START = pd.Timestamp("2026-03-02T10:00:00")
FORMS = {   # a campaign file per way of writing its times (rows 60 s apart, each file a day later)
    "iso": lambda t: t.isoformat(),
    "offset": lambda t: t.isoformat() + "+01:00",
    "zulu": lambda t: t.isoformat() + "Z",
    "decimal_comma": lambda t: t.strftime("%Y-%m-%d %H:%M:%S,250"),
    "day_first": lambda t: t.strftime("%d.%m.%Y %H:%M:%S"),
    "summer": lambda t: (t + pd.Timedelta(days=120)).isoformat(),
}


def _write(folder: Path) -> None:
    for day, (name, written) in enumerate(FORMS.items()):
        times = [START + pd.Timedelta(days=day, seconds=60 * i) for i in range(30)]
        rows = "".join(f"{written(t)};{20 + 0.1 * i:.1f};{0.2 * i:.1f}\n" for i, t in enumerate(times))
        (folder / f"{name}.csv").write_text("time;T_a;E_X\n" + rows)
        if name == "day_first":      # a converted file too: the first row read through plain.as_read
            (folder / "utf16.csv").write_text("time\tT_a\tE_X\n" + rows.replace(";", "\t").replace(
                f"{START.day + day:02d}.03.", f"{START.day + 9:02d}.03."), encoding="utf-16")


@pytest.mark.parametrize("zone", [None, "Europe/Berlin"])
def test_the_first_rows_start_is_the_reads_start(tmp_path, zone):
    _write(tmp_path)
    cfg = {"timezone": zone} if zone else {}
    opts = ReadOptions.from_cfg(cfg)
    before = campaign_starts(tmp_path, read_manifest(tmp_path, opts), opts)
    ds, _ = read_dataset(tmp_path, cfg)
    after = campaign_starts(tmp_path, ds.manifest, opts)     # the start the read filled
    assert before.notna().all() and ds.manifest["start"].notna().all()
    pd.testing.assert_series_equal(after.sort_index(), before.sort_index())
