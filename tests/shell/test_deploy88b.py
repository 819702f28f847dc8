"""Deployed as scored, the warm-up (deploy88b): ``promote`` reports what the sensor monitor did
while a test campaign's stream was warmed on the campaigns it continues, as ``replay`` does
(``lead_in_events``, the ``warm-up:`` line; extension of ``promote.json``).

deploy88 gave ``replay`` that report; promote's "as deployed" figures stream the same way
through its own path (``stream_scores``) and said nothing: a figure moved by a spike on the
lead-in with no event behind it.  Here test_deploy88's chain: C continues the test part B,
which holds a one-sample -4 °C spike on T3.  And ``init`` says a cut run of two loggers'
files once (data88b's record).
"""

from __future__ import annotations

import json

from test_deploy import mlflow_store
from test_deploy88 import spiked_chain
from test_deployed_as_scored import COLUMNS, FAST, record  # noqa: F401  (the fixture)
from thermocomp.shell.cli import main


def test_promote_says_what_the_monitor_did_on_a_lead_in_as_replay_does(record, tmp_path, capsys):  # noqa: F811
    chain = spiked_chain(record, tmp_path / "chain")
    uri = mlflow_store(tmp_path)
    fast = [o for o in FAST if not o.startswith(("track=", "eval.validation="))]
    common = [f"data.path={chain}", "data.reference=none", COLUMNS, *fast]
    assert main(["run", f"out={tmp_path / 'run'}", f"tracking_uri={uri}", "model=lagbank", *common]) == 0
    import mlflow

    mlflow.set_tracking_uri(uri)
    run_id = mlflow.search_runs(experiment_names=["thermocomp"])["run_id"].iloc[0]
    capsys.readouterr()
    assert main(["replay", f"out={tmp_path / 'replay'}", f"replay.model={tmp_path / 'run' / 'model.pkl'}",
                 *common]) == 0
    replayed_said = capsys.readouterr().out
    assert main(["promote", f"out={tmp_path / 'promote'}", f"tracking_uri={uri}",
                 f"promote.run_id={run_id}", *common]) == 0
    said = capsys.readouterr().out
    replayed = json.loads((tmp_path / "replay" / "replay.json").read_text())
    promoted = json.loads((tmp_path / "promote" / "promote.json").read_text())["candidate"]
    warm = replayed["lead_in_events"]
    assert {e["campaign"] for e in warm} == {"C"}            # C's stream, warmed through B
    assert promoted["lead_in_events"] == warm                # the same stream, the same events
    first = next(e for e in promoted["lead_in_events"] if e.get("sensor") == "T_3")
    assert first["to"] == "excluded" and first["time"] < 0   # before C's first row
    line = next(x for x in said.splitlines() if x.startswith("warm-up: "))
    assert line == next(x for x in replayed_said.splitlines() if x.startswith("warm-up: "))


def test_init_says_a_cut_run_of_two_loggers_files_once(tmp_path, capsys):
    """(data88b) ``thermocomp init`` on a folder of one run in two loggers' files cuts it into a
    train and a test part; its "two loggers ... one run" line was printed once per part, each
    with that part's rows: one run, one line, its parts named and its rows all counted."""
    from test_data88b import _pair, _record

    rows = _record()
    _pair(tmp_path / "pair", rows)
    assert main(["init", str(tmp_path / "pair"), f"out={tmp_path / 'init'}"]) == 0
    said = [x for x in capsys.readouterr().out.splitlines() if ": two loggers, " in x]
    assert len(said) == 1
    assert said[0].startswith("run01_train, run01_test: two loggers, run01_temp.csv")
    assert said[0].endswith(f"; {len(rows)} rows")
