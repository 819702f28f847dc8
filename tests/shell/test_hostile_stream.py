"""Hostile streams: a total sensor dropout, a step on every sensor, and the served model's requests.

The adaptive compensator must take its sensors back once they read again (an ``excluded`` →
``ok`` event for each), report transitions only, and give a held correction for a row without
any temperature; the served model must refuse a request too big or too deep before it parses it.
"""

from __future__ import annotations

import io as text_io
import json
import re
import sys

import numpy as np
import pandas as pd
import pytest
from hydra.utils import instantiate
from omegaconf import OmegaConf

from conftest import ROOT, UNTRACKED
from thermocomp.apps.deploy import StreamingCompensator
from thermocomp.apps.deploy.pyfunc import CompensatorModel
from thermocomp.apps.monitor import STATES, AdaptiveCompensator
from thermocomp.apps.monitor.report import stream_campaign as _stream
from thermocomp.base.errors import ConfigError
from thermocomp.core import io
from thermocomp.core.compensator import Compensator
from thermocomp.shell.cli import _compose, main

FAST = [*UNTRACKED, "plots=none"]


@pytest.fixture(scope="session")
def deployed(default_dataset):
    """``(adaptive compensator, test campaigns)``: the default scenario's MLR behind the monitor."""
    ds, _ = io.read_dataset(default_dataset, {})
    train = {c: ds.campaigns[c] for c in ds.ids("train")}
    est = instantiate(OmegaConf.load(ROOT / "conf/model/mlr.yaml").estimator)
    comp = Compensator(est).fit(train)
    adaptive = AdaptiveCompensator.from_training(StreamingCompensator.from_training(comp, train), train)
    return adaptive, {c: ds.campaigns[c] for c in ds.ids("test")}


def _temperatures(df: pd.DataFrame) -> list[str]:
    return [c for c in df.columns if c.startswith("T_")]


def _dropout(df: pd.DataFrame, first: int, rows: int = 3) -> pd.DataFrame:
    """``df`` with every temperature missing in ``rows`` consecutive rows from ``first``."""
    df = df.copy()
    df.loc[df.index[first:first + rows], _temperatures(df)] = np.nan
    return df


def _rmse(adaptive, df: pd.DataFrame, y: np.ndarray) -> np.ndarray:
    measured = adaptive.compensator.measured({"c": df})["c"][adaptive.targets_].to_numpy(float)
    return np.sqrt(np.nanmean((measured - y) ** 2, axis=0))


def _per_row(adaptive, df: pd.DataFrame) -> tuple[list[list[dict]], np.ndarray]:
    """Each row's events and the sensor states after it, streamed from a reset."""
    adaptive.reset()
    X, t = df[adaptive.columns_].to_numpy(float), df["time"].to_numpy(float)
    events, states = [], []
    for i in range(len(X)):
        adaptive._step(X[i], t[i])
        events.append(adaptive.last_events_)
        states.append(adaptive.monitor.states)
    adaptive.reset()
    return events, np.array(states)


# -- a total dropout: every sensor comes back (item 3) --------------------------------------------

@pytest.mark.parametrize("campaign, first, rows, near", [(0, None, 3, ("fixed", "healthy")),
                                                         (1, 3, 6, ("fixed",))])
def test_every_sensor_comes_back_after_a_total_dropout_and_the_error_stays_near_fixed(
        deployed, campaign, first, rows, near):
    """Three rows a third in; six early in the warm-up, whose change across the gap is no jump
    (it was taken for one: four sensors re-referenced by it, three never back, 7.5x fixed; the
    gap itself costs the fixed compensator 1.4x the healthy error there)."""
    adaptive, test = deployed
    fixed = adaptive.streaming
    healthy = list(test.values())[campaign]
    df = _dropout(healthy, len(healthy) // 3 if first is None else first, rows)
    y_ad, events, _ = _stream(adaptive, df)
    y_fix, _, _ = _stream(fixed, df)          # holds its last correction on the missing rows
    y_ok, _, _ = _stream(adaptive, healthy)
    back = {e["sensor"] for e in events if e["from"] == "excluded" and e["to"] == "ok"}
    assert back == set(adaptive.monitor.names), events
    last = {e["sensor"]: e["to"] for e in events if e["sensor"] in adaptive.monitor.names}
    assert set(last.values()) == {"ok"}, last
    assert np.isfinite(y_ad).all()
    got = _rmse(adaptive, df, y_ad)
    against = {"fixed": _rmse(adaptive, df, y_fix), "healthy": _rmse(adaptive, healthy, y_ok)}
    for name in near:
        assert (got <= 1.2 * against[name]).all(), (name, got, against)


def test_monitor_on_stdin_takes_the_sensors_back_after_a_total_dropout(default_dataset, tmp_path,
                                                                       monkeypatch):
    manifest = pd.read_csv(default_dataset / "campaigns.csv")
    df = pd.read_csv(default_dataset / manifest.query("split == 'test'")["file"].iloc[0])
    monkeypatch.setattr(sys, "stdin", text_io.StringIO(_dropout(df, len(df) // 3).to_csv(index=False)))
    assert main(["monitor", "monitor.input=-", f"data.path={default_dataset}", f"out={tmp_path}",
                 *FAST]) == 0
    report = json.loads((tmp_path / "monitor.json").read_text())
    back = {e["sensor"] for e in report["events"] if (e["from"], e["to"]) == ("excluded", "ok")}
    assert back == set(report["sensors"])
    for target, r in report["targets"].items():
        assert r["all_finite"] and r["rmse_adaptive"] <= 1.2 * r["rmse_fixed"], (target, r)


def test_rows_without_any_temperature_get_the_held_correction_from_the_pyfunc(deployed):
    adaptive, test = deployed
    model = CompensatorModel(adaptive)
    model.load_context(None)
    frame = next(iter(test.values()))[adaptive.columns_ + ["time"]].reset_index(drop=True)
    corrections = [c for c in model.predict(None, frame.head(1), {"reset": True}).columns
                   if c.startswith("C_")]
    before = model.predict(None, frame.iloc[1:20], {})
    blank = frame.iloc[20:23].copy()
    blank[_temperatures(blank)] = np.nan
    answers = [model.predict(None, blank.iloc[[i]], {}) for i in range(len(blank))]  # one a request
    for out in answers:
        np.testing.assert_array_equal(out[corrections].to_numpy(), before[corrections].tail(1))
    dropped = {e["sensor"] for e in json.loads(answers[0]["events"][0]) if "dropout" in e["reason"]}
    assert dropped == set(adaptive.monitor.names)
    after = model.predict(None, frame.iloc[23:], {})
    assert np.isfinite(after[corrections].to_numpy()).all()
    assert after["excluded_inputs"].iloc[-1] == ""           # every sensor back by the end


# -- the event log: transitions only, every return logged (item 4) -------------------------------

def test_a_step_on_every_sensor_logs_each_change_of_state_once_and_every_return(deployed,
                                                                              monkeypatch):
    # the log of many exclusions and returns at once: the sensors judged one by one, as before
    # stop 56 (since, the same step on most sensors is one event of the logger, re-referenced
    # without an exclusion: tests/apps/test_monitor_common_step56.py)
    from thermocomp.apps.deploy.surveillance import faults, monitor

    for module in (faults, monitor):          # each reads the constant by its own name
        monkeypatch.setattr(module, "COMMON_MIN", 10 ** 9)
    adaptive, test = deployed
    returns = 0
    for cid, healthy in list(test.items())[:3]:
        df = healthy.copy()
        df.loc[df.index[len(df) // 2:], _temperatures(df)] += 5.0
        events, states = _per_row(adaptive, df)
        flat = [json.dumps(e, sort_keys=True) for row in events for e in row]
        assert len(flat) == len(set(flat)), cid              # no event twice
        before = np.zeros(len(adaptive.monitor.names), dtype=int)
        for row, now in zip(events, states):
            for j, name in enumerate(adaptive.monitor.names):
                chain = [(e["from"], e["to"]) for e in row if e["sensor"] == name and e["to"] in STATES]
                if before[j] == now[j]:
                    assert chain == [], (cid, name, chain)
                else:   # the row's events lead from the state before it to the state after it
                    assert chain and chain[0][0] == STATES[before[j]] and chain[-1][1] == STATES[now[j]]
                    assert all(a[1] == b[0] for a, b in zip(chain, chain[1:])), chain
            returns += sum(e["to"] == "ok" and e["from"] == "excluded" for e in row)
            before = now
    assert returns > 0


def test_a_failing_adaptive_step_is_raised_not_logged_again_with_the_last_rows_events(deployed,
                                                                                      monkeypatch):
    """`monitor` held the correction of an adaptive step that raised, and logged the previous
    row's events once more for every such row (1,130 duplicates of 1,210 events)."""
    adaptive, test = deployed
    df = _dropout(next(iter(test.values())), 9, rows=1)     # row 9 has events, row 10 fails
    update = adaptive.monitor.update

    def failing(x, t):
        if t >= df["time"].iloc[10]:
            raise ValueError("a defect in the monitor")
        return update(x, t)

    monkeypatch.setattr(adaptive.monitor, "update", failing)
    with pytest.raises(ValueError, match="a defect in the monitor"):
        _stream(adaptive, df)
    assert adaptive.last_events_ == []
    monkeypatch.undo()
    adaptive.reset()


# -- the served model: request limits (item 10) and a warning for a public host (item 14) --------

def _asgi(app, body: bytes, chunk: int = 1 << 16, content_type: str = "application/json",
          declare: bool = True, query: str = "") -> tuple[int, dict, int]:
    """``(status, JSON answer, bytes the app let the client send)`` of one POST through ``app``."""
    import asyncio

    chunks = [body[i:i + chunk] for i in range(0, len(body), chunk)] or [b""]
    read, sent = [0], []

    async def receive():
        if read[0] >= len(chunks):
            return {"type": "http.disconnect"}
        read[0] += 1
        return {"type": "http.request", "body": chunks[read[0] - 1],
                "more_body": read[0] < len(chunks)}

    async def send(message):
        sent.append(message)

    headers = [(b"content-type", content_type.encode())]
    if declare:
        headers.append((b"content-length", str(len(body)).encode()))
    scope = {"type": "http", "asgi": {"version": "3.0"}, "http_version": "1.1", "method": "POST",
             "scheme": "http", "path": "/invocations", "raw_path": b"/invocations",
             "query_string": query.encode(), "headers": headers, "server": ("127.0.0.1", 80),
             "client": ("127.0.0.1", 1)}
    asyncio.run(app(scope, receive, send))
    answer = b"".join(m.get("body", b"") for m in sent if m["type"] == "http.response.body")
    return sent[0]["status"], json.loads(answer), sum(len(c) for c in chunks[:read[0]])


def _split(frame: pd.DataFrame, **params) -> bytes:
    split = frame.astype(object).where(frame.notna(), None).to_dict(orient="split")
    split.pop("index")
    return json.dumps({"dataframe_split": split, "params": params}).encode()


@pytest.fixture(scope="module")
def scoring(deployed, tmp_path_factory):
    """``(pyfunc folder, MLflow's scoring app for it, a block of healthy rows)``."""
    import mlflow
    from mlflow.pyfunc import scoring_server

    from thermocomp.apps.deploy.pyfunc import save_compensator

    adaptive, test = deployed
    adaptive.slashed_ = None     # as builders.deployable sets it: a record without dates with slashes
    rows = next(iter(test.values()))[adaptive.columns_ + ["time"]].reset_index(drop=True)
    folder = save_compensator(adaptive, tmp_path_factory.mktemp("served") / "model",
                              input_example=rows.head(3))
    app = scoring_server.init(mlflow.pyfunc.load_model(str(folder)))
    return folder, app, rows


def test_the_served_model_refuses_too_big_too_many_and_too_deep_before_it_parses(scoring, monkeypatch):
    from thermocomp.apps.deploy.server import MAX_DEPTH, RequestLimits

    _, app, rows = scoring
    parsed = []
    monkeypatch.setattr("mlflow.pyfunc.scoring_server.invocations",
                        lambda *a: parsed.append(a) or pytest.fail("the app parsed it"))
    block = _split(rows.head(20), reset=True)
    limited = RequestLimits(app, max_body_bytes=len(block) + 100, max_rows=30)
    too_big = _split(pd.concat([rows] * 5), reset=True)
    status, answer, read = _asgi(limited, too_big)              # Content-Length: nothing read
    assert (status, read) == (413, 0) and "serve.max_body_mb" in answer["message"]
    status, answer, read = _asgi(limited, too_big, chunk=1024, declare=False)   # chunked
    assert status == 413 and read <= len(block) + 100 + 1024 < len(too_big)
    many = _split(pd.DataFrame(np.zeros((31, 1)), columns=["T_x"]))
    assert len(many) < len(block)
    status, answer, _ = _asgi(limited, many)
    assert status == 413 and "31 rows over serve.max_rows (30)" in answer["message"]
    for fmt in ("dataframe_records", "instances"):
        body = json.dumps({fmt: [{"T_x": 0.0}] * 31}).encode()
        assert _asgi(limited, body)[0] == 413, fmt
    csv = ("T_x\n" + "0\n" * 31).encode()
    assert _asgi(limited, csv, content_type="text/csv")[0] == 413
    deep = b'{"dataframe_split": ' + b"[" * (MAX_DEPTH + 1) + b"]" * (MAX_DEPTH + 1) + b"}"
    status, answer, _ = _asgi(limited, deep)
    assert status == 400 and f"nested more than {MAX_DEPTH} deep" in answer["message"]
    assert "[" not in answer["message"] and parsed == []


def test_the_served_model_answers_a_block_within_the_limits_as_without_them(scoring):
    from thermocomp.apps.deploy.server import RequestLimits

    _, app, rows = scoring
    block = _split(rows.head(20), reset=True)
    plain = _asgi(app, block)
    limited = _asgi(RequestLimits(app, max_body_bytes=len(block), max_rows=20), block, chunk=500,
                    declare=False)
    assert plain[0] == limited[0] == 200 and limited[1] == plain[1]
    assert len(limited[1]["predictions"]) == 20


@pytest.fixture(scope="module", params=["mlr", "arx", "mlr+bias"])
def served_short(short_dataset, tmp_path_factory, request):
    """``(a function giving a fresh limited scoring app, a test campaign's rows)`` of the short
    scenario's MLR or ARX (a lag model), behind the monitor as ``promote`` registers it; or MLR
    deployed with ``adapt.method=bias`` (its rows carry ``E_X`` references every 10th row)."""
    from thermocomp.apps.deploy.adapt import Adaptation, ReferenceAdapter
    from thermocomp.apps.deploy.pyfunc import save_compensator

    family, _, adapt = request.param.partition("+")
    ds, _ = io.read_dataset(short_dataset, {})
    train = {c: ds.campaigns[c] for c in ds.ids("train")}
    est = instantiate(OmegaConf.load(ROOT / f"conf/model/{family}.yaml").estimator)
    streaming = StreamingCompensator.from_training(Compensator(est).fit(train), train)
    adaptive = AdaptiveCompensator.from_training(streaming, train)
    if adapt:
        adaptive.adapt_ = Adaptation(ReferenceAdapter(len(adaptive.targets_), adapt))
    rows = ds.campaigns[ds.ids("test")[0]][adaptive.columns_ + ["time"]].reset_index(drop=True)
    if adapt:
        rows["E_X"] = ds.campaigns[ds.ids("test")[0]]["E_X"].to_numpy()
        rows.loc[rows.index % 10 != 5, "E_X"] = np.nan
    folder = save_compensator(adaptive, tmp_path_factory.mktemp("csv") / "model")
    return (lambda: _served_app(folder)), rows      # a server just started: no session held


def _served_app(folder, max_rows: int = 1000):
    """``thermocomp serve``'s app (:func:`~thermocomp.apps.deploy.server.scoring_app`) on the
    pyfunc ``folder``, as its server process starts it (its limits in the environment)."""
    from unittest import mock

    from mlflow.pyfunc.scoring_server import _SERVER_MODEL_PATH

    from thermocomp.apps.deploy import server

    with mock.patch.dict("os.environ", {_SERVER_MODEL_PATH: folder.as_uri(),
                                        server.ROWS_ENV: str(max_rows),
                                        server.BODY_ENV: str(1 << 20)}):
        return server.scoring_app()


def _csv(frame: pd.DataFrame) -> bytes:
    return frame.to_csv(index=False).encode()


@pytest.mark.parametrize("clock", ["seconds", "timestamps"])
def test_rows_posted_as_csv_get_the_corrections_the_same_rows_get_as_json(served_short, clock):
    """csv70: every ``text/csv`` request was refused (400, MLflow's "some of the inputs types are
    not DataType": its CSV parse wants a pandas type for the time column, which takes seconds
    or timestamps).  Two blocks of a campaign, a missing cell in the second, as CSV (no params:
    the default session, started at its first block) and as JSON (``reset`` first): the same."""
    fresh_app, rows = served_short
    rows = rows.head(30).astype({"time": object})
    if clock == "timestamps":
        start = pd.Timestamp("2026-12-01 08:00:00")
        rows["time"] = [(start + pd.Timedelta(seconds=float(t))).strftime("%Y-%m-%d %H:%M:%S")
                        for t in rows["time"]]
    rows.loc[20, rows.columns[1]] = np.nan
    as_json, as_csv = fresh_app(), fresh_app()
    for block, params in ((rows.iloc[:15], {"reset": True}), (rows.iloc[15:], {})):
        by_json = _asgi(as_json, _split(block, **params))
        by_csv = _asgi(as_csv, _csv(block), content_type="text/csv")
        assert by_json[0] == by_csv[0] == 200, by_csv[1]
        assert by_csv[1] == by_json[1]
    assert np.isfinite([r["C_X"] for r in by_csv[1]["predictions"]]).all()


def test_csv_sessions_by_the_query_string_interleave_as_each_alone_and_equal_json_params(
        served_short):
    """deploy71: a CSV request carried no params (every CSV client in the session ``default``, no
    way to restart a campaign).  ``?session=..&reset=true`` gives them: two sessions' blocks
    interleaved get what each gets alone, a reset restarts, and the answers are the JSON body's
    ``params``' (and a JSON body's with the query string), exactly."""
    fresh_app, rows = served_short
    first, second = rows.head(30).copy(), rows.iloc[30:60].reset_index(drop=True)
    first.loc[20, first.columns[1]] = np.nan            # a missing cell
    blocks = {"A": (first.iloc[:15], first.iloc[15:]), "B": (second.iloc[:15], second.iloc[15:])}

    def post(app, block, session, reset, how):
        query = f"session={session}" + ("&reset=true" if reset else "")
        if how == "csv":
            return _asgi(app, _csv(block), content_type="text/csv", query=query)
        if how == "json+query":
            return _asgi(app, _split(block), query=query)
        return _asgi(app, _split(block, session=session, **({"reset": True} if reset else {})))

    def answers(app, order, how="csv"):
        got = {}
        for session, k in order:
            status, answer, _ = post(app, blocks[session][k], session, k == 0, how)
            assert status == 200, answer
            got[session, k] = answer
        return got

    alone = {**answers(fresh_app(), [("A", 0), ("A", 1)]), **answers(fresh_app(), [("B", 0), ("B", 1)])}
    order = [("A", 0), ("B", 0), ("A", 1), ("B", 1)]
    assert answers(fresh_app(), order) == alone
    assert answers(fresh_app(), order, "json") == alone
    assert answers(fresh_app(), order, "json+query") == alone
    by_csv, by_json = fresh_app(), fresh_app()
    answers(by_csv, order)
    answers(by_json, order, "json")
    again = answers(by_csv, [("A", 0)])            # reset: the campaign started again
    assert again == answers(by_json, [("A", 0)], "json")
    if "E_X" not in rows:                          # (a model that learns keeps what it learned)
        assert again == {("A", 0): alone["A", 0]}
    assert alone["A", 0] != alone["B", 0]


@pytest.mark.parametrize("query, says", [
    ("sesion=M1", "query parameter 'sesion': the model takes reset, session, continues, ambient_c"),
    ("reset=yes", "query parameter reset='yes': not true or false (true, false, 1, 0)"),
    ("session=M1&ambient_c=warm", "query parameter ambient_c='warm': not a finite number (double)"),
    ("session=M1&session=M2", "query parameter 'session' given twice"),
    ("session", "query string 'session': not name=value pairs joined by '&' (percent-encoded "
                "UTF-8)"),
    ("session=M2&reset=1", "parameter 'session': 'M2' in the query string, 'M1' in the body's "
                           "params"),
    ("session=M1&continues=R9", "continues='R9': the model holds no end state of that campaign"),
])
def test_a_bad_query_parameter_is_refused_in_one_line(scoring, query, says):
    folder, _, rows = scoring
    app = _served_app(folder)
    status, answer, _ = _asgi(app, _split(rows.head(3), session="M1"), query=query)
    assert status == 400 and answer["message"].startswith(says), answer
    assert "\n" not in answer["message"]
    if "body" not in says:                  # (a CSV body has no params of its own)
        status, answer, _ = _asgi(app, _csv(rows.head(3)), content_type="text/csv", query=query)
        assert status == 400 and answer["message"].startswith(says), answer


def test_a_csv_with_a_bad_cell_is_refused_naming_its_column_and_row(served_short):
    fresh_app, rows = served_short
    block = rows.head(5).astype(object)
    column = block.columns[1]
    block.loc[2, column] = "20,6"            # a decimal comma
    status, answer, _ = _asgi(fresh_app(), _csv(block), content_type="text/csv; charset=utf-8")
    assert status == 400
    assert answer["message"] == (f"column '{column}', data row 3 of the block: value '20,6' is not "
                                 "a number (float64; a decimal point, a missing value as an empty "
                                 "cell)")
    lines = _csv(rows.head(5)).decode().splitlines()
    lines[4] += ",7"                         # data row 4: a cell more than the header
    status, answer, _ = _asgi(fresh_app(), "\n".join(lines).encode(), content_type="text/csv")
    assert status == 400 and answer["message"] == (
        f"CSV body, data row 4: {len(rows.columns) + 1} cells under a header of "
        f"{len(rows.columns)} columns")


def test_serve_runs_the_limited_app_and_warns_when_the_network_can_reach_it(scoring, tmp_path,
                                                                            caplog):
    from thermocomp.apps.deploy import server
    from thermocomp.shell.stages.serve import serve_command

    folder = scoring[0]
    common = [f"serve.model={folder}", f"tracking_uri=sqlite:///{tmp_path / 'mlflow.db'}"]
    argv, env = serve_command(_compose(common + ["serve.max_rows=7", "serve.max_body_mb=0.5"]))
    assert argv[argv.index("--factory") + 1] == "thermocomp.apps.deploy.server:scoring_app"
    assert argv[argv.index("--workers") + 1] == "1"
    assert (env[server.ROWS_ENV], env[server.BODY_ENV]) == ("7", str(2**19))
    assert not [r for r in caplog.records if r.levelname == "WARNING"]
    for host in ("0.0.0.0", "192.168.1.5", "::", "machine.example"):
        caplog.clear()
        serve_command(_compose(common + [f"serve.host={host}"]))
        [warning] = [r.getMessage() for r in caplog.records if r.levelname == "WARNING"]
        assert f"serve.host={host}" in warning and "reachable from the network" in warning
    for host in ("127.0.0.1", "localhost", "::1", "127.0.0.2"):
        caplog.clear()
        serve_command(_compose(common + [f"serve.host={host}"]))
        assert not [r for r in caplog.records if r.levelname == "WARNING"], host
    for override in ("serve.max_rows=0", "serve.max_body_mb=0", "serve.max_body_mb=nan"):
        with pytest.raises(ConfigError, match=re.escape(override.split("=")[0])):
            serve_command(_compose(common + [override]))


@pytest.mark.slow
@pytest.mark.full
def test_thermocomp_serve_answers_413_and_400_over_http_and_serves_on(scoring, tmp_path):
    """``full``: test_serve's test_thermocomp_serve_answers_as_in_process_without_an_activated_venv
    posts the same refused requests (depth, rows, body) to its server started with the same
    limits, and a block within them after (a server start is ~10 s of CPU); this one serves a
    model folder instead of the registered champion."""
    import subprocess

    import requests

    from conftest import BIN, free_port, stop_process_group, wait_until_up

    folder, _, rows = scoring
    port = free_port()
    log = open(tmp_path / "serve.log", "w")
    server = subprocess.Popen([str(BIN / "thermocomp"), "serve", f"serve.model={folder}",
                               f"serve.port={port}", "serve.max_rows=20", "serve.max_body_mb=0.01",
                               f"tracking_uri=sqlite:///{tmp_path / 'mlflow.db'}"], cwd=tmp_path,
                              stdout=log, stderr=subprocess.STDOUT, start_new_session=True)
    url = f"http://127.0.0.1:{port}/invocations"

    def post(body: bytes):
        return requests.post(url, data=body, headers={"Content-Type": "application/json"}, timeout=60)

    try:
        wait_until_up(port, server, tmp_path / "serve.log")
        assert post(b"[" * 5000 + b"]" * 5000).status_code == 400
        many = post(_split(rows.head(21).round(2), reset=True))
        assert many.status_code == 413 and "serve.max_rows" in many.json()["message"]
        big = post(b" " * 20_000)
        assert big.status_code == 413 and "serve.max_body_mb" in big.json()["message"]
        ok = post(_split(rows.head(20), reset=True))
        assert ok.status_code == 200 and len(ok.json()["predictions"]) == 20
    finally:
        stop_process_group(server)
        log.close()


def test_a_stream_on_a_loggers_clock_without_its_first_time_keeps_its_events_in_its_clock(
        deployed):
    """A stream in seconds on a logger's clock (150100 s, ...) whose first time is missing: the
    guard took the first time as 0.0, so the row lay 150100 s before the next (its event at
    -150100 s from the stream's start in monitor.json); by the time rule (core/timerule.py) the
    substitute is the stream's start, the next row one period after it."""
    from thermocomp.core.io.options import ReadOptions
    from thermocomp.core.io.stdin import read_stream
    adaptive, test = deployed
    healthy = list(test.values())[0].iloc[:200]
    logged = healthy.assign(time=healthy["time"] + 150100.0).astype({"time": object})
    logged.loc[logged.index[0], "time"] = None
    frame, missing = read_stream(logged.to_csv(index=False), adaptive.columns_,
                                 ReadOptions.from_cfg({}))
    assert missing.get("time") == 1
    _, events, _ = _stream(adaptive, frame)
    known = frame["time"].dropna()
    period = known.iloc[1] - known.iloc[0]
    substituted = [e for e in events if e["sensor"] == "time" and e["to"] == "substituted"]
    assert len(substituted) == 1 and substituted[0]["time"] == 0.0
    # the next row one period on (it was at 0 too: a step of 0 s, one filter step lost)
    back = [e for e in events if e["sensor"] == "time" and e["to"] == "ok"]
    assert [e["time"] for e in back] == [period], events
    span = known.iloc[-1] - known.iloc[0] + period
    assert all(0.0 <= e["time"] <= span for e in events), events


def test_monitor_says_how_many_samples_were_clamped_as_replay_does(default_dataset, tmp_path,
                                                                  capsys):
    # a record's last tenth hotter than its training: monitor's RMSE fixed was 8x what `run`
    # scored (6.59 against 0.79 µm, a lab's cut of large_mill_week seed 7717) without a word
    import shutil
    data = shutil.copytree(default_dataset, tmp_path / "warmer")
    manifest = pd.read_csv(data / "campaigns.csv")
    test = data / manifest.query("split == 'test'")["file"].iloc[0]
    df = pd.read_csv(test)
    ramp = np.linspace(0.0, 15.0, len(df))          # every sensor warmer, well past training
    df[_temperatures(df)] = df[_temperatures(df)].add(ramp, axis=0)
    df.to_csv(test, index=False)
    args = [f"data.path={data}", *FAST]
    assert main(["replay", *args, "monitor.adaptive=false", f"out={tmp_path / 'r'}"]) == 0
    assert main(["monitor", *args, f"out={tmp_path / 'm'}"]) == 0
    said = capsys.readouterr().out
    replayed = json.loads((tmp_path / "r" / "replay.json").read_text())["targets"]
    monitored = json.loads((tmp_path / "m" / "monitor.json").read_text())["targets"]
    clamped = {r["clamped_samples"] for r in replayed.values()}
    assert len(clamped) == 1 and clamped.pop() > 0
    for t, r in monitored.items():
        assert (r["clamped_samples"], r["n_samples"]) == \
            (replayed[t]["clamped_samples"], replayed[t]["n_samples"])
    assert re.search(rf"clamped: {r['clamped_samples']} of {r['n_samples']} samples had an input "
                     r"outside the training envelope", said)
