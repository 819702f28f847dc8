"""streamunits60: the compiled ``stream.c`` fed jig_grinder's test sessions as the lab wrote them
(its headers, °F, mm, MIN, the cells' own text; only the fixed-width columns made CSV, which
stream.c does not read), against ``replay`` of the same model on the dataset as read.

Run after ``bench_new_machines60.py write|init|run ROOT --data jig_grinder --families mlr
lagbank``: ``python bench_stream_units60.py ROOT``.
"""
import io
import json
import subprocess
import sys
from pathlib import Path

import numpy as np
import pandas as pd

from thermocomp.apps.deploy.streaming import replay
from thermocomp.shell.builders import deploy_stream
from thermocomp.shell.cli import main as tc
from thermocomp.shell.config.overrides import compose
from thermocomp.shell.model_store import load_model
from thermocomp.shell.source import read_streamed


def main(root: Path) -> None:
    """Export mlr and lagbank as C, compile, stream the lab's test sessions; print the figures."""
    R = root
    data = [f"hydra.searchpath=[file://{R}/init-jig_grinder/conf]", "data=jig_grinder"]
    for family in ("mlr", "lagbank"):
        code = R / "out" / f"jig-{family}-code"
        model = R / "out" / f"jig_grinder-{family}" / "model.pkl"
        assert tc(["export", *data, "monitor.adaptive=false", "export.format=c", "track=false",
                   f"export.model={model}", f"out={code}"]) == 0
        subprocess.run(["gcc", "-std=c99", "-Wall", "-Wextra", "-Werror", "-O2", "compensator.c",
                        "stream.c", "-lm", "-o", "stream"], cwd=code, check=True)
        units = json.loads((code / "compensator.json").read_text())["provenance"]["lab_units"]
        cfg = compose([*data, f"model={family}", "monitor.adaptive=false", "track=false"])
        ds, train_ids, test_ids, report = read_streamed(cfg)
        stream = deploy_stream(cfg, load_model(model), {c: ds.campaigns[c] for c in train_ids})
        want = np.vstack([-replay(stream, ds.campaigns[c])[stream.targets_].to_numpy(float)
                          for c in test_ids])
        blocks = []
        for cid in test_ids:
            text = (R / "jig_grinder" / f"{cid}.TXT").read_text().splitlines()
            rows = [ln.split() for ln in text[7:] if ln.strip()]
            blocks.append("\n".join(",".join(r) for r in rows))
        # the reader's headers in file order (a header's two lines joined: 'HEAD [DEG F]')
        raw = list(ds.meta["column_map"])
        print(family, "headers:", raw)
        print(family, "lab_units:", units)
        csv = ",".join(raw) + "\n" + "\n\n".join(blocks) + "\n"
        (code / "lab_test.csv").write_text(csv)
        run = subprocess.run(["./stream"], cwd=code, input=csv.encode(), capture_output=True)
        print(family, "exit", run.returncode, run.stderr.decode()[-300:])
        got = pd.read_csv(io.BytesIO(run.stdout)).to_numpy(float)
        print(family, "rows", got.shape, want.shape, "max|C - replay| =", np.abs(got - want).max())


if __name__ == "__main__":
    main(Path(sys.argv[1]).resolve())
