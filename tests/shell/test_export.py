"""`thermocomp export`: the generated code is the deployed model.

Every linear family x denoise x selector is fitted on a small simulated dataset, made deployable
as `replay` does with `monitor.adaptive=false` (the plain stream, envelope clamp on), exported;
the C is compiled with the system compiler and the test campaigns (one sensor pushed out of the
training envelope half-way, so the clamp acts) are streamed through the binary as CSV; the
Structured Text is parsed with blark (one short block, whose constructs every other block has;
`make test` holds it to the construct blark parsed, `make test-all` parses it again) and run by
a small transpiler of the subset it uses.  Both must equal the stream `replay` runs to 1e-6 µm.
`make test` streams a covering set of the pairwise cases (:data:`COVERING`), `make test-all` all.
"""

from __future__ import annotations

import hashlib
import io
import json
import re
import shutil
import subprocess
from itertools import combinations
from math import exp, pow
from pathlib import Path

import numpy as np
import pandas as pd
import pytest
from hydra import compose, initialize_config_dir

from cbuild import CONTROL, LEVEL, compiled
from conftest import FAST, deployed_as_replay, refused
from covering import covering_of
from thermocomp.apps.deploy.export import Simulator, exported_files, state_space
from thermocomp.apps.deploy.streaming import replay
from thermocomp.base.paths import conf_dir
from thermocomp.shell.builders import build_compensator, deploy_stream
from thermocomp.shell.cli import main
from thermocomp.shell.model_store import save_model
from thermocomp.shell.source import read_streamed

TOLERANCE_UM = 1e-6
FAMILIES = {"mlr": [], "pcr": [], "arx": ["model.estimator.ar=false"],
            "arx_ar": ["model.estimator.ar=true", "model.estimator.delays=[2]"],   # x(t-2) only
            "lagbank": []}
SELECTORS = ("all", "pearson", "greedy_residual", "cluster_grey")
DENOISERS = ("none", "emd")
# An all-pairs (pairwise) covering design instead of the 40-case product, as test_replay's: each
# family streams once with each selector, the denoiser turning with family and selector, so every
# pair of values of any two axes is met (20 cases; checked below).  The family's law, the FIR
# taps and the inputs a selector keeps per target are separate arrays of the export.
CASES = [(family, DENOISERS[(f + s) % len(DENOISERS)], select)
         for f, family in enumerate(FAMILIES) for s, select in enumerate(SELECTORS)]
# `make test` streams their covering set (tests/covering.py): each family, each selector and
# both denoisers (checked below); the other cases are ``full``.
PARAMS = covering_of("an all-pairs case past make test's covering set", {case: case for case in CASES})
COVERING = [p.values for p in PARAMS if not p.marks]
CAMPAIGNS = (("K01", "train"), ("K02", "train"), ("K03", "train"), ("K04", "train"),
             ("K05", "test"), ("K06", "test"))
PUSH_C = 30.0          # added to one sensor from mid-campaign: far outside the training envelope
# the sensors here move independently, a pattern spanning every input that the default gate
# never clamps: the clamp's arithmetic is proved on every excursion (the gate:
# test_envelope_pattern.py)
EVERY_EXCURSION = "promote.envelope.pattern=false"
needs_cc = pytest.mark.skipif(shutil.which("gcc") is None, reason="no C compiler")


def built_stream(folder: Path, files: dict | None = None) -> Path:
    """``files`` (name -> text) written into ``folder`` and its C compiled warnings as errors at
    the tests' level (tests/cbuild.py): the ``stream`` program."""
    for name, text in (files or {}).items():
        (folder / name).parent.mkdir(parents=True, exist_ok=True)
        (folder / name).write_text(text)
    compiled(folder)
    return folder / "stream"


def adaptive_mlr(folder: Path) -> tuple:
    """``(adaptive MLR as replay deploys it, the dataset, its test campaign ids)``, on this
    module's record written into ``folder`` (the exported monitor's tests: cmon76, cdrop77, cmon80)."""
    return deployed_as_replay(_compose(f"data.path={_make_dataset(folder)}", "track=false",
                                       "monitor.adaptive=true", "model=mlr"))


def checked_pack(out: Path) -> str:
    """``out``'s C compiled warnings as errors (:func:`built_stream`) and its check pack
    (``check/check.sh``) run: the pack's messages, after asserting it passed."""
    built_stream(out)
    script = subprocess.run(["sh", "check/check.sh"], cwd=out, capture_output=True, text=True)
    assert script.returncode == 0, script.stderr
    return script.stderr


def own_expected(out: Path) -> list[Path]:
    """``out``'s pack's ``expected.csv`` of the record's own campaigns, in ``check.json``'s order:
    not the copies the pack plants a jump and a freeze on for the code's sensor monitor (cmon76),
    whose folders a glob may list first."""
    check = json.loads((out / "check" / "check.json").read_text())
    return [out / c["folder"] / "expected.csv" for c in check["campaigns"] if "planted" not in c]


def _compose(*overrides):
    with initialize_config_dir(config_dir=str(conf_dir()), version_base="1.3"):
        return compose(config_name="config", overrides=list(overrides))


def _make_dataset(root: Path, rows: int = 40) -> Path:
    """Six campaigns (four train, two test) of a three-sensor machine, two error axes, one sample
    every 2 min; E_Z also follows a slow integral of T_a's rise (what lags and AR pick up)."""
    root.mkdir(parents=True)
    rng = np.random.default_rng(1)
    t = np.arange(rows) * 120.0
    for i, (cid, _) in enumerate(CAMPAIGNS):
        amb = 16 + 2.5 * i
        a = amb + (4 + i % 3) * (1 - np.exp(-t / 1500)) + rng.normal(0, 0.05, rows)
        b = amb + (2 + i % 2) * (1 - np.exp(-t / 3000)) + rng.normal(0, 0.05, rows)
        c = amb + 0.5 * np.sin(t / 2000 + i) + rng.normal(0, 0.05, rows)
        ex = 3 * (a - a[0]) - 1.2 * (b - b[0]) + rng.normal(0, 0.2, rows)
        ez = 2 * (b - b[0]) + 1.5 * (c - c[0]) + 0.5 * np.cumsum(np.r_[0, np.diff(a)]) \
            + rng.normal(0, 0.2, rows)
        door = (np.arange(rows) % 10 < 2).astype(float)      # what arx_rf reads
        pd.DataFrame({"time": t, "T_a": a, "T_b": b, "T_amb": c, "S_door": door,
                      "E_X": ex, "E_Z": ez}).to_csv(
            root / f"{cid}.csv", index=False)
    pd.DataFrame([(c, f"{c}.csv", s, "") for c, s in CAMPAIGNS],
                 columns=["campaign", "file", "split", "notes"]).to_csv(root / "campaigns.csv", index=False)
    return root


@pytest.fixture(scope="module")
def dataset(tmp_path_factory) -> Path:
    return _make_dataset(tmp_path_factory.mktemp("export") / "data")


_FITTED: dict = {}


def _deployed(dataset, family, denoise, select):
    """``(plain stream as replay deploys it, test campaigns with a sensor pushed out)``, fitted
    once per combination."""
    key = (str(dataset), family, denoise, select)
    if key in _FITTED:
        return _FITTED[key]
    model = family.split("_")[0]
    cfg = _compose(f"model={model}", f"denoise={denoise}", f"select={select}",
                   f"data.path={dataset}", "track=false", "monitor.adaptive=false",
                   EVERY_EXCURSION, *FAMILIES[family])
    ds, train_ids, test_ids, _ = read_streamed(cfg)
    train = {c: ds.campaigns[c] for c in train_ids}
    stream = deploy_stream(cfg, build_compensator(cfg, ds=ds).fit(train), train)
    tests = []
    for k, c in enumerate(test_ids):
        df = ds.campaigns[c].reset_index(drop=True).copy()
        df.loc[len(df) // 2:, stream.columns_[0]] += PUSH_C
        if k == 1:   # irregular sampling: the lags step by the time actually elapsed
            df["time"] += np.r_[0.0, np.random.default_rng(k).uniform(-30, 30, len(df) - 1)]
        tests.append(df)
    _FITTED[key] = stream, tests
    return stream, tests


def _replayed(stream, tests) -> np.ndarray:
    """The corrections ``replay`` streams (minus the predicted error), campaigns stacked; the
    envelope clamp acts on the pushed sensor."""
    streamed = [replay(stream, df) for df in tests]
    assert all(s["n_clamped"].iloc[len(s) // 2:].gt(0).all() for s in streamed)
    return np.vstack([-s[stream.targets_].to_numpy(float) for s in streamed])


# -- a transpiler of the Structured Text subset the export uses ------------------------------------

_DECL = re.compile(r"^\s*(\w+)\s*:\s*(ARRAY\[([^\]]*)\]\s+OF\s+)?(\w+)(\s*:=\s*(.*))?;\s*$")
_TYPES = {"LREAL": float, "INT": int, "DINT": int, "BOOL": bool}
# the conversions an arx_rf model's forest makes: to REAL as IEC 61131-3 rounds it (to nearest)
_CONVERSIONS = {"LREAL_TO_REAL": lambda v: float(np.float32(v)), "REAL_TO_LREAL": float,
                "DINT_TO_LREAL": float}


def _value(text: str, kind):
    text = text.strip()
    if text in ("TRUE", "FALSE"):
        return text == "TRUE"
    return kind(float(text)) if kind is not bool else bool(float(text))


def _declarations(block: str) -> dict:
    names = {}
    for line in block.splitlines():
        m = _DECL.match(line)
        if not m:
            continue
        name, dims, kind, init = m.group(1), m.group(3), _TYPES[m.group(4)], m.group(6)
        if dims:
            shape = tuple(int(d.split("..")[1]) + 1 for d in dims.split(","))
            arr = np.zeros(shape, dtype=object if kind is bool else kind)
            if init:
                arr.flat[:] = [_value(v, kind) for v in init.strip()[1:-1].split(",")]
            names[name] = arr
        else:
            names[name] = _value(init, kind) if init else kind(0)
    return names


def _python(body: str) -> str:
    out, depth = [], 0
    for raw in body.splitlines():
        line = re.sub(r"\(\*.*?\*\)", "", raw).strip()
        if not line:
            continue
        if line in ("END_FOR;", "END_IF;"):
            depth -= 1
            continue
        if line == "ELSE":
            out.append("    " * (depth - 1) + "else:")
            continue
        m = re.match(r"FOR (\w+) := (.+) TO (.+?)( BY -1)? DO$", line)
        if m:
            var, lo, hi, down = m.groups()
            rng = f"range({_expr(lo)}, ({_expr(hi)}) - 1, -1)" if down else \
                f"range({_expr(lo)}, ({_expr(hi)}) + 1)"
            out.append("    " * depth + f"for {var} in {rng}:")
            depth += 1
            continue
        m = re.match(r"(IF|ELSIF) (.+) THEN$", line)
        if m:
            if m.group(1) == "ELSIF":
                out.append("    " * (depth - 1) + f"elif {_expr(m.group(2))}:")
            else:
                out.append("    " * depth + f"if {_expr(m.group(2))}:")
                depth += 1
            continue
        m = re.match(r"(.+?) := (.+);$", line)
        assert m, f"not in the subset: {line!r}"
        out.append("    " * depth + f"{m.group(1)} = {_expr(m.group(2))}")
    assert depth == 0
    return "\n".join(out)


def _expr(text: str) -> str:
    text = text.replace("<>", "!=")
    text = re.sub(r"(?<![<>!=:])=(?!=)", "==", text)
    text = re.sub(r"\bAND\b", "and", text)
    text = re.sub(r"\bOR\b", "or", text)
    text = re.sub(r"\bNOT\b", "not", text)
    return text.replace("EXP(", "exp(").replace("TRUE", "True").replace("FALSE", "False")


class StructuredText:
    """Runs the function block: every call a scan of its body over the kept variables."""

    def __init__(self, source: str):
        head, body = source.split("END_VAR\n\n", 1) if "END_VAR\n\n" in source else (None, None)
        assert head is not None
        self.vars = _declarations(head)
        self.code = compile(_python(body.replace("END_FUNCTION_BLOCK", "")), "compensator.st", "exec")

    def __call__(self, u, time_s, reset) -> np.ndarray:
        v = self.vars
        v["u"][:] = u
        v["has_time"], v["time_s"], v["reset"] = bool(np.isfinite(time_s)), time_s, reset
        exec(self.code, {"exp": exp, "EXPT": pow, **_CONVERSIONS}, v)   # EXPT: a Hammerstein power
        return np.array(v["c"], float)


# -- proofs -------------------------------------------------------------------------------------

def _stdin(stream, tests, reset_column: bool = False) -> str:
    """The campaigns as the driver reads them: a blank row between campaigns, or a ``reset``
    column holding 1 on each campaign's first row."""
    cols = ["time", *stream.columns_]
    if reset_column:
        frames = [df[cols].assign(reset=(np.arange(len(df)) == 0).astype(int)) for df in tests]
        return pd.concat(frames).to_csv(index=False, float_format="%.17g")
    parts = [df[cols].to_csv(index=False, float_format="%.17g") for df in tests]
    return parts[0] + "".join("\n" + p.split("\n", 1)[1] for p in parts[1:])


def _compiled(stream, folder: Path, driver: str = CONTROL) -> Path:
    """``stream``'s C written into ``folder`` and built into ``folder/stream``: the model's code
    (``compensator.c``) always at :data:`cbuild.CONTROL` (the warnings gcc finds only when
    optimizing), the driver (``stream.c``, one text for every model) at ``driver``.  The driver
    at ``-O2`` is ~0.5 of gcc's ~0.7 s of CPU a build (ci102b): this module's proofs build it
    at CONTROL once per family (``select=all``), the other proofs at :data:`cbuild.LEVEL`."""
    files = exported_files(stream, "c")
    for name, text in files.items():
        (folder / name).write_text(text)
    if driver == CONTROL:
        compiled(folder, level=CONTROL)
    else:       # the model's object alone ("-c": no link), then linked with the driver's
        compiled(folder, ("-c", "compensator.c"), "compensator.o", level=CONTROL)
        _driver_object(folder, files["stream.c"] + files["compensator.h"], driver)
        compiled(folder, ("compensator.o", "stream.o"), level=driver)
    return folder / "stream"


_DRIVER_OBJECTS: dict = {}


def _driver_object(folder: Path, text: str, level: str) -> None:
    """``folder/stream.o``: the driver compiled once per text of ``stream.c`` and the header it
    includes (the sizes of the model's arrays) and level, its bytes written again for the same
    texts (ci104c: many proofs build models of one shape; gcc's -c of it ~0.12 s of CPU, a link
    ~0.02 s).  The same texts and flags compile to the same object and warnings."""
    key = (hashlib.sha256(text.encode()).hexdigest(), level)
    if key not in _DRIVER_OBJECTS:
        compiled(folder, ("-c", "stream.c"), "stream.o", level=level)
        _DRIVER_OBJECTS[key] = (folder / "stream.o").read_bytes()
    else:
        (folder / "stream.o").write_bytes(_DRIVER_OBJECTS[key])


def _streamed(binary: Path, text: str) -> pd.DataFrame:
    run = subprocess.run([str(binary)], input=text, text=True, capture_output=True, check=True)
    return pd.read_csv(io.StringIO(run.stdout))


def test_the_cases_cover_every_pair_of_values():
    axes = (list(FAMILIES), DENOISERS, SELECTORS)
    pairs = {(i, a, j, b) for i, j in combinations(range(3), 2) for a in axes[i] for b in axes[j]}
    met = {(i, case[i], j, case[j]) for case in CASES for i, j in combinations(range(3), 2)}
    assert met == pairs and len(set(CASES)) == len(CASES) == len(FAMILIES) * len(SELECTORS)
    # `make test`'s covering set: every value of every axis, each family once
    assert all({case[i] for case in COVERING} == set(axes[i]) for i in range(3))
    assert len(COVERING) == len(FAMILIES) and set(COVERING) <= set(CASES)


@needs_cc
@pytest.mark.parametrize("family, denoise, select", PARAMS)
def test_the_compiled_c_and_the_structured_text_stream_as_replay(dataset, tmp_path, family,
                                                                  denoise, select):
    stream, tests = _deployed(dataset, family, denoise, select)
    expected = _replayed(stream, tests)
    ss = state_space(stream)
    assert (family == "arx_ar") == any(a != 0 for a in ss.ar) == (ss.depth == 2)
    assert (family == "lagbank") == bool(ss.taus) and (denoise == "emd") == (len(ss.fir) > 1)
    binary = _compiled(stream, tmp_path, CONTROL if select == "all" else LEVEL)
    for reset_column in (False, True):
        got = _streamed(binary, _stdin(stream, tests, reset_column))
        assert list(got.columns) == ["C_" + t[2:] for t in stream.targets_]
        assert np.max(np.abs(got.to_numpy(float) - expected)) <= TOLERANCE_UM
    sim = Simulator(ss)            # the numpy reading of the same arrays
    rows = []
    for df in tests:
        sim.reset()
        rows += [sim.step(r, t) for r, t in zip(df[stream.columns_].to_numpy(float), df["time"])]
    assert np.max(np.abs(np.array(rows) - expected)) <= TOLERANCE_UM
    fb = StructuredText(exported_files(stream, "st")["compensator.st"])
    rows = [fb(r, t, k == 0) for df in tests
            for k, (r, t) in enumerate(zip(df[stream.columns_].to_numpy(float), df["time"]))]
    assert np.max(np.abs(np.array(rows) - expected)) <= TOLERANCE_UM


PARSED_BLOCK = ("arx_ar", "none", "all")    # family, denoise, select of the block blark parses


def _construct(st: str) -> str:
    """The block with every literal one placeholder of its kind (R a real, N an integer, B a
    boolean) and every initializer list of one kind one item, banner (a comment) left out: what
    is left is what the grammar sees of it."""
    code = st[st.index("*)\nFUNCTION_BLOCK") + 3:]
    code = re.sub(r"-?\d+\.\d+(e[+-]\d+)?", "R", code)
    code = re.sub(r"(?<!\w)-?\d+", "N", code)           # not the digits of a name (x0)
    code = re.sub(r"\[([NR])(, \1)*\]", r"[\1]", code)
    return re.sub(r"\b(TRUE|FALSE)\b", "B", code)


def parses_as_the_parsed_block(text: str, parsed: str) -> None:
    """``text`` parses as IEC 61131-3 as ``parsed`` does (conftest's ``parsed_block``, the block
    :func:`test_the_structured_text_parses_as_iec_61131_3` holds to what blark parsed: an Earley
    parser, 15-40 s of CPU a block whatever its constants): the comments before its block are comments
    (none opened or closed within), and the block is ``parsed``'s up to literal values of the
    same kind and list lengths."""
    head = text[:text.index("\nFUNCTION_BLOCK") + 1]
    assert re.fullmatch(r"(\(\*((?!\(\*|\*\)).)*\*\)\n)+", head, re.S), head
    assert _construct(text) == _construct(parsed)


# The construct (:func:`_construct`) of the block blark parsed, and blark's and lark's versions
# then (:func:`_parsed_digest`): `make test` holds the block to it instead of parsing it again
# (blark's Earley parse: 15-18 s of CPU, a tenth of what the export tests cost); `make test-all`
# parses it every time (:func:`test_blark_parses_the_block`). A new construct is parsed, and its
# digest asked for here.
PARSED_DIGEST = "86936efd770f51343d8316c0c0c34798da14b9a32f40f8a759b5ba272c333dbb"


def _parsed_digest(block: str) -> str:
    """sha256 of ``block``'s construct with the versions of the parser: a block equal to the one
    blark parsed up to literal values and list lengths, for the same grammar."""
    from importlib.metadata import version

    parser = f"blark {version('blark')}, lark {version('lark')}\n"
    return hashlib.sha256((parser + _construct(block)).encode()).hexdigest()


def _parses(block: str) -> None:
    """blark parses ``block`` as IEC 61131-3 (an Earley parser: seconds per block, more for long
    constant lists) into the function block."""
    from blark import parse_source_code

    parsed = parse_source_code(block, fn="compensator.st")
    assert parsed.exception is None, parsed.exception
    assert "FB_ThermoComp" in str(parsed.transform())


def test_the_structured_text_parses_as_iec_61131_3(dataset, parsed_block):
    """The block is one text around the model's constants, so a short one (no FIR taps, no lags)
    is parsed and every family's block, with and without the FIR denoiser, must equal it up to
    literal values and list lengths: the same declarations and statements, all parsed here.
    Other modules' blocks are held to it so (:func:`parses_as_the_parsed_block`). The short one
    is the construct blark parsed (:data:`PARSED_DIGEST`), or it is parsed now."""
    text = exported_files(_deployed(dataset, *PARSED_BLOCK)[0], "st")["compensator.st"]
    assert text == parsed_block          # the same data, the same block
    parses_as_the_parsed_block(text, text)     # its banner plain comments, as any block's
    digest = _parsed_digest(text)
    if digest != PARSED_DIGEST:
        _parses(text)
        pytest.fail(f"a new construct of the block, and blark parses it: PARSED_DIGEST = {digest!r}")
    for family in FAMILIES:
        for denoise in DENOISERS:
            stream, _ = _deployed(dataset, family, denoise, "all")
            parses_as_the_parsed_block(exported_files(stream, "st")["compensator.st"], text)


@pytest.mark.full
def test_blark_parses_the_block(parsed_block):
    """`make test-all`: the block parsed again, whatever :data:`PARSED_DIGEST` says (`make test`
    parses it only when its construct is new)."""
    _parses(parsed_block)
    assert _parsed_digest(parsed_block) == PARSED_DIGEST


def test_a_block_held_to_the_parsed_one_is_no_rubber_stamp(parsed_block):
    """:func:`parses_as_the_parsed_block` takes the parsed block itself, and fails a statement
    without its semicolon, a real literal where an integer stands (an array bound), a comment
    closed within the banner, a name changed; and :data:`PARSED_DIGEST` tells each from the
    block blark parsed (the banner's by the same check of its comments)."""
    parses_as_the_parsed_block(parsed_block, parsed_block)
    assert _parsed_digest(parsed_block) == PARSED_DIGEST
    bad = [parsed_block.replace("lfac := factor[LSTM_LAW[nk]];", "lfac := factor[LSTM_LAW[nk]]"),
           parsed_block.replace("ARRAY[0..2] OF", "ARRAY[0..2.0] OF", 1),
           parsed_block.replace("(*\n", "(*\n*) x\n", 1),
           parsed_block.replace("FUNCTION_BLOCK FB_ThermoComp", "FUNCTION_BLOCK FB_ThermoComp2")]
    assert all(b != parsed_block for b in bad)
    for text in bad:
        with pytest.raises(AssertionError):
            parses_as_the_parsed_block(text, parsed_block)
    assert [_parsed_digest(text) == PARSED_DIGEST for text in bad] == [False, False, True, False]
    with pytest.raises(AssertionError):
        parses_as_the_parsed_block(bad[2], bad[2])


def _fitted(dataset, tmp_path, model: str, *extra: str) -> Path:
    """``model.pkl`` of ``model`` fitted on the train split, not scored (what a refusal reads);
    fitted once per dataset, model and overrides (ati63's and ambient62's tests export the same
    fit twice: ci104c), saved into each caller's ``tmp_path``."""
    key = (str(dataset), model, extra)
    if key not in _FITTED_PKL:
        cfg = _compose(f"model={model}", f"data.path={dataset}", "track=false", *extra)
        ds, train_ids, _, _ = read_streamed(cfg)
        _FITTED_PKL[key] = build_compensator(cfg, ds=ds).fit({c: ds.campaigns[c] for c in train_ids})
    return save_model(_FITTED_PKL[key], tmp_path / model / "model.pkl")


_FITTED_PKL: dict = {}


def _exported_code(dataset, tmp_path, fmt: str, model: str, *extra: str) -> Path:
    """``thermocomp export`` (with its check pack) of ``model`` fitted on the train split
    (:func:`_fitted`), written into ``tmp_path/code``."""
    pkl = _fitted(dataset, tmp_path, model, *extra)
    out = tmp_path / "code"
    assert main(["export", f"data.path={dataset}", f"export.model={pkl}", f"export.format={fmt}",
                 f"out={out}", "track=false"]) == 0
    return out


def _trained(dataset, tmp_path, model: str, *extra: str) -> Path:
    """``model.pkl`` of a FAST ``thermocomp run`` into ``tmp_path/model``: run once per dataset,
    model and overrides, its folder copied for a later caller (check61's two tests export the
    same run: ci104c)."""
    out, key = tmp_path / model, (str(dataset), model, extra)
    if key in _TRAINED:
        shutil.copytree(_TRAINED[key], out)
    else:
        assert main(["run", f"data.path={dataset}", f"model={model}", f"out={out}", *FAST, *extra]) == 0
        _TRAINED[key] = out
    return out / "model.pkl"


_TRAINED: dict = {}


@needs_cc
def test_export_writes_code_that_builds_with_cc_and_carries_its_provenance(dataset, tmp_path,
                                                                           capsys):
    model = _trained(dataset, tmp_path, "lagbank")
    out = tmp_path / "code"
    assert main(["export", f"data.path={dataset}", f"export.model={model}", "export.format=c",
                 f"out={out}", "track=false", EVERY_EXCURSION]) == 0
    assert {"compensator.json", "compensator.h", "compensator.c", "stream.c"} <= {
        p.name for p in out.iterdir()}
    coefficients = json.loads((out / "compensator.json").read_text())
    assert coefficients["inputs"] == ["T_a", "T_b", "T_amb"] and coefficients["clamp"]
    assert coefficients["provenance"]["model"] == "lagbank"
    assert len(coefficients["provenance"]["dataset_hash"]) == 64
    header = (out / "compensator.h").read_text()
    assert all(c in header for c in ("T_a", "lagbank", coefficients["provenance"]["dataset_hash"]))
    compiled(out)
    rows = pd.read_csv(dataset / "K05.csv").drop(columns=["E_X", "E_Z", "S_door"])
    got = _streamed(out / "stream", rows.to_csv(index=False))
    assert list(got.columns) == ["C_X", "C_Z"] and len(got) == len(rows)
    # bad rows: exit 2, one line naming the row or the column (cdrop77: a monitored sensor's
    # missing reading mid-campaign is the code's monitor's, tests/shell/test_export_cdrop77.py;
    # at a campaign's first row it cannot rebuild it)
    rows.loc[0, "T_b"] = np.nan
    for text, says in ((rows.to_csv(index=False), "line 2: input T_b has no finite value, which "
                        "the code's sensor monitor does not rebuild here (not in the code: a "
                        "missing reading at a campaign's first sample): the row is refused (the "
                        "served model rebuilds it)"),
                       (rows.drop(columns=["T_a"]).to_csv(index=False), "lacks input column T_a")):
        run = subprocess.run([str(out / "stream")], input=text, text=True, capture_output=True)
        assert run.returncode == 2 and run.stderr.strip().endswith(says), run.stderr
        assert len(run.stderr.strip().splitlines()) == 1
    # the same model exported as ST and JSON carries the same arrays
    for fmt, name in (("st", "compensator.st"), ("json", "compensator.json")):
        assert main(["export", f"data.path={dataset}", f"export.model={model}",
                     f"export.format={fmt}", f"out={tmp_path / fmt}", "track=false"]) == 0
        assert (tmp_path / fmt / name).is_file()
        again = json.loads((tmp_path / fmt / "compensator.json").read_text())
        assert again["g"] == coefficients["g"] and again["fir"] == coefficients["fir"]


@needs_cc
def test_optimization_levels_stream_the_same_bytes(dataset, tmp_path):
    """The tests build at ``-O0`` (tests/cbuild.py), a control at ``-O2``: the same bytes out of
    both on every campaign of a monitored export's pack (adaptive MLR, the pack's planted jump and
    freeze), so the level is no part of what the tests hold."""
    out = _exported_code(dataset, tmp_path, "c", "mlr", "monitor.adaptive=true")
    checked_pack(out)                                     # at the tests' level, its check passing
    # (the pack's build is the -O0 one when that is the tests' level: the same gcc command)
    built = [out / "stream" if LEVEL == "-O0" else compiled(out, program="stream-O0", level="-O0"),
             compiled(out, program=f"stream{CONTROL}", level=CONTROL)]
    folders = sorted((out / "check").glob("*/rows.csv"))
    assert len(folders) >= 3                              # the record's own and the planted copies
    for rows in folders:
        runs = [subprocess.run([str(b)], stdin=rows.open("rb"), capture_output=True)
                for b in built]
        assert runs[0].returncode == 0 and runs[0].stdout.count(b"\n") > 10
        assert runs[0].stdout == runs[1].stdout and runs[0].stderr == runs[1].stderr, rows


@pytest.mark.parametrize("model,extra,says", [
    # (arx_rf and lstm within an ATI model, refused here before, export since exportati63;
    # a family the export does not know: test_export_refusal59.py)
    ("mlr", ["export.format=onnx"], ["onnx", "mlr, pcr, arx, lagbank"]),
    ("mlr", ["denoise=emd", "denoise.denoiser.causal=window"], ["causal=fir"]),
    ("mlr", ["promote.envelope.policy=refuse"], ["refuse", "policy=clamp"]),
], ids=["onnx", "window-denoiser", "refuse-policy"])
def test_what_is_not_one_linear_system_is_refused_in_one_line(dataset, tmp_path, capsys, model,
                                                              extra, says):
    deploy = [e for e in extra if e.startswith(("export.", "promote."))]
    pkl = _fitted(dataset, tmp_path, model, *(e for e in extra if e not in deploy))
    out = tmp_path / "code"
    refused(["export", f"data.path={dataset}", f"export.model={pkl}", f"out={out}",
             "track=false", *deploy], capsys, f"export.model={pkl}", *says)
    assert not out.exists()


def test_export_without_a_model_is_refused(dataset, tmp_path, capsys):
    refused(["export", f"data.path={dataset}", f"out={tmp_path / 'x'}", "track=false"], capsys,
            "export.model is needed")
    refused(["export", f"data.path={dataset}", "export.model=m.pkl", "export.format=pdf",
             f"out={tmp_path / 'x'}", "track=false"], capsys, "export.format")
    assert not (tmp_path / "x").exists()


def test_a_saved_pyfunc_model_exports_as_deployed(dataset, tmp_path):
    """A pyfunc folder (what promote registers) exports the stream it holds, with its envelope:
    no data needed."""
    from thermocomp.apps.deploy.pyfunc import save_compensator

    stream, tests = _deployed(dataset, "lagbank", "none", "all")
    folder = save_compensator(stream, tmp_path / "pyfunc")
    assert main(["export", f"export.model={folder}", "export.format=json",
                 f"out={tmp_path / 'json'}", "track=false"]) == 0
    exported = json.loads((tmp_path / "json" / "compensator.json").read_text())
    assert exported["lo"] == stream.envelope.lo.tolist() and exported["taus"]
    assert exported["provenance"]["source"] == str(folder)
    assert exported == {**state_space(stream).to_dict(), "provenance": exported["provenance"]}
