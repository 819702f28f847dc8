"""A run promoted with ``adapt.method=bias`` is registered learning references (diagexport59).

``promote`` registers no new version of a run already registered "deployed the same way", and
the way was the hash of ``monitor.adaptive``, the ``monitor`` settings and the envelope: not
``adapt``, though the registered object learns from reference measurements only with it.  So
a run promoted once without adaptation and again with ``adapt.method=bias`` said "already
registered, no new version", and the champion exported and served without the bias learning
the second command asked for (seen on a diagnosed door model,
benchmarks/bench_diagnosed_to_code59.py).  The adaptation is now part of the key when it is on.
"""

from __future__ import annotations

import json

from test_lab_promote57 import lab_run
from thermocomp.shell.cli import main


def test_promote_with_adapt_after_without_registers_the_adapting_version(tmp_path):
    common, uri, run_id = lab_run(tmp_path)
    reports = {}
    for name, extra in (("frozen", []), ("bias", ["adapt.method=bias"]),
                        ("again", ["adapt.method=bias"])):
        out = tmp_path / name
        assert main(["promote", *common, f"promote.run_id={run_id}", f"out={out}", *extra]) == 0
        reports[name] = json.loads((out / "promote.json").read_text())
    assert reports["bias"]["registered"]                     # a new version, not the frozen one
    assert reports["bias"]["version"] != reports["frozen"]["version"]
    import mlflow

    from thermocomp.apps.deploy.pyfunc import load_deployed
    mlflow.set_tracking_uri(uri)
    learns = {name: load_deployed(f"models:/thermocomp-compensator/{r['version']}").adapt_
              for name, r in reports.items()}
    assert learns["frozen"] is None
    assert learns["bias"] is not None and learns["bias"].adapter.method == "bias"
    assert not reports["again"]["registered"]                # the same deployment: idempotent
    assert reports["again"]["version"] == reports["bias"]["version"]
