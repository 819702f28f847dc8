"""A TDM/TDX pair NI's own software wrote (LabVIEW 15.0's TDM storage, vendored from tdm_loader
1.2.7's tests, MIT: ``tests/data/realexport73/README.md``), not one written from memory: it
checks the LabVIEW timestamps (``eTimeUsi``) against the times tdm_loader's own test expects
of it, and DIAdem's date scale against the header's own ``minimum`` of that channel (NI's
library wrote both: before, DIAdem dates were read a day early, the epoch a year 0 of 366 days)."""

from __future__ import annotations

import re
import shutil
import zipfile
from pathlib import Path

import numpy as np

from thermocomp.core.io.tdm import DIADEM_EPOCH_S, tdm_records

DATA = Path(__file__).parents[1] / "data" / "realexport73"
PAIR = DATA / "test_file_time.tdm"
# tdm_loader's test_time_channel.py: the first and last of the 27 stamps
FIRST, LAST = np.datetime64("2022-11-04T14:37:48.565332889"), np.datetime64("2022-11-04T14:38:05.765357017")


def test_labviews_timestamps_are_the_times_tdm_loader_reads():
    (record,) = tdm_records(PAIR)
    time = record.channels[0].time
    assert record.utc and time.size == 27 and len(record.channels) == 5
    assert abs(time[0] - FIRST) < np.timedelta64(1, "us") and abs(time[-1] - LAST) < np.timedelta64(1, "us")
    assert [c.header for c in record.channels][:2] == ["Untitled", "Untitled 1"]
    np.testing.assert_allclose(record.channels[1].values[:3], [27.01, 26.97, 26.96])


def test_diadems_date_scale_is_the_headers_own():
    """The time channel's ``minimum`` (DIAdem's seconds since 0000-01-01, written by NI's library
    beside the stamps) less DIAdem's epoch is the first stamp."""
    header = PAIR.read_text(encoding="utf-8")
    minimum = float(re.search(r"<name>Time</name>.*?<minimum>([0-9.]+)</minimum>", header).group(1))
    first = (FIRST - np.datetime64("1970-01-01")) / np.timedelta64(1, "s")
    assert abs(minimum - DIADEM_EPOCH_S - first) < 1e-3


def test_a_zipped_header_reads_as_the_plain_one(tmp_path):
    """Some writers zip the header (tdm_loader's DIAdem test file is one: ``header.xml`` in a zip
    named ``.tdm``); before: "not a TDM header that is read (its XML: not well-formed ...)"."""
    with zipfile.ZipFile(tmp_path / "zipped.tdm", "w", zipfile.ZIP_DEFLATED) as zipped:
        zipped.writestr("header.xml", PAIR.read_bytes())
    shutil.copy(PAIR.with_suffix(".tdx"), tmp_path / "test_file_time.tdx")
    (plain,), (packed,) = tdm_records(PAIR), tdm_records(tmp_path / "zipped.tdm")
    assert [c.header for c in packed.channels] == [c.header for c in plain.channels]
    for a, b in zip(packed.channels, plain.channels):
        np.testing.assert_array_equal(a.values, b.values)
        np.testing.assert_array_equal(a.time, b.time)
