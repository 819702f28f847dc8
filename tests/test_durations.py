"""The order `make test` starts its units in (tests/durations.py, tests/conftest.py)."""

from __future__ import annotations

import json
from types import SimpleNamespace

import conftest
import durations


def _item(nodeid: str) -> SimpleNamespace:
    return SimpleNamespace(nodeid=nodeid, get_closest_marker=lambda name: None)


def test_units_start_longest_first_unmeasured_before_all_a_modules_order_kept():
    seconds = durations.load()
    page = max((u for u in seconds if "::" in u), key=seconds.get)    # a README page, alone
    modules = [u for u in seconds if "::" not in u and seconds[u] < seconds[page]]
    short, long = min(modules, key=seconds.get), max(modules, key=seconds.get)
    assert seconds[short] < seconds[long] < seconds[page]
    items = [_item(f"{short}::test_a"), _item(f"{short}::test_b"), _item(f"{long}::test_a"),
             _item(page), _item("tests/test_new_module.py::test_a"), _item(f"{short}::test_c")]
    conftest.pytest_collection_modifyitems(items)
    assert [i.nodeid for i in items] == [
        "tests/test_new_module.py::test_a", page, f"{long}::test_a",
        f"{short}::test_a", f"{short}::test_b", f"{short}::test_c"]


def test_stored_durations_add_up_a_units_phases_and_keep_the_units_not_run(tmp_path):
    path = tmp_path / "durations.json"
    path.write_text(json.dumps({"tests/test_a.py": 9.0, "tests/test_b.py": 1.0}))
    recorder = durations.Recorder(conftest._unit, path)
    for nodeid, seconds in [("tests/test_b.py::test_x", 0.25), ("tests/test_b.py::test_x", 2.0),
                            ("tests/test_b.py::test_y", 1.0), ("tests/test_c.py::test_z", 0.5)]:
        recorder.pytest_runtest_logreport(SimpleNamespace(nodeid=nodeid, duration=seconds))
    worker = SimpleNamespace(config=SimpleNamespace(workerinput={}))
    recorder.pytest_sessionfinish(worker)
    assert json.loads(path.read_text())["tests/test_b.py"] == 1.0      # a worker writes nothing
    recorder.pytest_sessionfinish(SimpleNamespace(config=SimpleNamespace()))
    assert json.loads(path.read_text()) == {"tests/test_a.py": 9.0, "tests/test_b.py": 3.2,
                                            "tests/test_c.py": 0.5}


def test_every_unit_measured_is_a_test_module_or_a_test_of_one():
    missing = [u for u in durations.load() if not (conftest.ROOT / u.split("::")[0]).is_file()]
    assert not missing, f"tests/durations.json names modules that are gone: {missing}"
