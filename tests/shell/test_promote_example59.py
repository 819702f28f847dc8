"""``promote`` says no restart mid-campaign that did not happen (deploy59).

restart58 made the served model warn when a block comes for a session it does not hold and
without ``reset`` (a server restarted while the machine ran).  MLflow predicts the registered
model's input example to check it against the signature, without params: every ``promote`` of
a new version printed ``warning: session 'default' is not held by this server (new, the server
restarted, ...)`` though nothing was served.  The example is now a campaign's first block as a
caller sends it, ``reset: true``, which is also what the model's serving example shows.
"""

from __future__ import annotations

import json
from pathlib import Path

from test_lab_promote57 import lab_run
from thermocomp.shell.cli import main


def test_promote_warns_of_no_unheld_session_and_its_example_starts_a_campaign(tmp_path, capsys):
    common, uri, run_id = lab_run(tmp_path)
    capsys.readouterr()
    assert main(["promote", *common, f"promote.run_id={run_id}", f"out={tmp_path / 'promote'}"]) == 0
    said = capsys.readouterr()
    assert "is not held by this server" not in said.err + said.out
    assert json.loads((tmp_path / "promote" / "promote.json").read_text())["registered"]
    examples = list(Path(tmp_path / "mlruns").rglob("serving_input_example.json"))
    assert len(examples) == 1
    assert json.loads(examples[0].read_text())["params"] == {"reset": True}
