"""``model=auto`` on the measured fl_thermal record, its LSTM blended in, to code (lstmexport62).

``data=fl_thermal`` (the vendored spindle record, the last 10 % its test part, README) is fitted
with the default ``model=auto`` as ``thermocomp run`` fits it (its blends hold the LSTM on
several channels) and exported as C and as ST with the pack; the C is built (gcc -O2) and run
through ``check/check.sh``.  Printed: what auto kept, the networks' size line, each file's
size, each export's CPU (user + sys of the child) and the check's largest |difference|.
Everything in a scratch root.

    PYTHONPATH=$PWD/src .venv/bin/python benchmarks/bench_export_lstm62.py
"""

from __future__ import annotations

import os
from pathlib import Path

from bench_export_forest62 import thermocomp
from compiled_stream import checked

ROOT = Path(os.environ.get("BENCH_ROOT", "/tmp/lstmexport62-bench"))


def main() -> None:
    model = ROOT / "model"
    cpu, _ = thermocomp("run", "data=fl_thermal", "model=auto", f"out={model}", "track=false")
    print(f"run: {cpu:.1f} s CPU")
    for fmt in ("c", "st"):
        out = ROOT / f"code-{fmt}"
        cpu, said = thermocomp("export", "data=fl_thermal", f"export.model={model / 'model.pkl'}",
                               f"export.format={fmt}", f"out={out}", "track=false")
        for key in ("export (", "lstm:"):
            line = next(ln for ln in said.splitlines() if key in ln)
            print(f"{fmt}: {line.split('] ', 1)[-1]}")
        sizes = {p.name: p.stat().st_size for p in sorted(out.iterdir()) if p.is_file()
                 and p.suffix in (".c", ".h", ".st", ".json")}
        print(f"   export {cpu:.2f} s CPU; " + ", ".join(f"{k} {v / 1024:,.0f} KB"
                                                    for k, v in sizes.items()))
        if fmt != "c":
            continue
        print("   " + checked(out))


if __name__ == "__main__":
    main()
