"""A logger set to another sample rate inside one record, 1 min then 10 s (session 56)."""

from __future__ import annotations

from thermocomp.base.log import logger
from thermocomp.core.io import read_dataset

CHANGED = [60.0 * i for i in range(40)] + [2340.0 + 10 * i for i in range(1, 121)]
PAUSED = [60.0 * i for i in range(80)] + [4800.0 + 3 * 3600 + 60 * i for i in range(80)]


def record(path, times):
    path.write_text("time,T_spindle,E_X\n" + "".join(
        f"{t:g},{20 + 0.001 * t:.3f},{0.002 * t:.2f}\n" for t in times), encoding="utf-8")
    return path


def said(caplog, path, cfg=None) -> str:
    """What reading ``path`` logs (the thermocomp logger does not propagate to caplog)."""
    caplog.clear()
    logger.addHandler(caplog.handler)
    try:
        read_dataset(path, cfg)
    finally:
        logger.removeHandler(caplog.handler)
    return caplog.text


def test_a_sample_period_changing_inside_a_record_is_said_with_its_row(tmp_path, caplog):
    # read without a word: a model whose lags count samples took a sample for 60 s before the
    # row and for 10 s after it
    path = record(tmp_path / "lab.csv", CHANGED)
    text = said(caplog, path)
    assert (f"{path}, column 'time', line 42 (data row 41): the sample period changes from 60 s "
            "to 10 s here") in text
    assert "data.resample_s=60 puts the record on one grid" in text
    # one rate with a pause of hours (a logger restarted), or the record put on one grid: not said
    assert "sample period changes" not in said(caplog, path, {"resample_s": 60})
    assert "sample period changes" not in said(caplog, record(tmp_path / "pause.csv", PAUSED))


def test_a_sample_period_changing_inside_a_stream_on_stdin_is_said_as_the_files(tmp_path, caplog):
    # audit107: monitor.input=- streamed 100 s rows, then 1000 s ones, without a word where the
    # file reader said the change of the same rows (replay of the file)
    from thermocomp.core.io.options import ReadOptions
    from thermocomp.core.io.stdin import stream_campaigns

    text = record(tmp_path / "lab.csv", CHANGED).read_text(encoding="utf-8")
    steady = "\n".join(text.splitlines()[:41]) + "\n"           # one rate throughout
    said = []
    for rows in (text, steady):
        caplog.clear()
        logger.addHandler(caplog.handler)
        try:
            streamed, _ = stream_campaigns(rows, ["T_spindle"], ReadOptions.from_cfg({}))
        finally:
            logger.removeHandler(caplog.handler)
        said.append(caplog.text)
    assert ("<stdin>, column 'time', data row 41: the sample period changes from 60 s to 10 s "
            "here") in said[0]
    assert "sample period changes" not in said[1] and len(streamed["stdin"]) == 40
