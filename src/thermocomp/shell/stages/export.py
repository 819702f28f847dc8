"""`thermocomp export`: the deployed compensator as coefficients and code (``docs/cli.md``).

``export.model``: a pyfunc folder or ``models:/<name>@<alias>`` is exported as deployed; a
``model.pkl`` is first made deployable as ``replay`` does it (its envelope, and with
``monitor.adaptive`` its guard, from the train split of ``data.path``; ``adapt.*``).  Of an
adaptive compensator the plain stream, its correction guard and time rule are exported (its
sensor monitor stays with the served model: the message and the provenance say so);
``adapt.method`` (bias, rls) is exported with them.  Beside the code, the conformance pack
``check/`` (``export.check``, ``export.campaigns``: :mod:`~thermocomp.apps.deploy.export.pack`):
rows of ``data.path`` as the code takes them and the corrections the served model gives for
them, which ``stream --check`` compares.  The files are written into ``out`` together, or not
at all (:func:`~thermocomp.base.files.staged_outputs`).
"""

from __future__ import annotations

import json
import math
from datetime import datetime, timezone
from pathlib import Path

from omegaconf import DictConfig

from ...apps.deploy.export import NotExportable, check_exportable, exported_files, not_in_code
from ...apps.deploy.export.pack import CHECK as PACK
from ...apps.deploy.export.pack import conformance_pack
from ...apps.deploy.export.statespace import StateSpace
from ...apps.deploy.export.text import per_target
from ...apps.deploy.naming import raw_names
from ...apps.deploy.report import plain
from ...base.errors import ConfigError
from ...base.files import staged_outputs
from ...base.log import logger, say
from ...base.paths import resolve
from ...core.continuation import lead_ins
from ...core.io.bits import STATE
from ...core.io.bits import parsed as parsed_bits
from ...core.io.contract import TIME
from ...core.io.dayfirst import ORDER
from ...core.io.derived import sources as derived_sources
from ...core.io.roles import RUN
from ...core.io.source import check_streamed_columns
from ...core.io.timestamps import CLOCK, OF_DAY_KIND
from ...core.io.twins import copy_refused
from ...core.scoring.evaluation import require_split
from ..builders import day_seconds, deployable_model, is_registered, pause_seconds, with_model_bits
from ..config.checks import check_config
from ..model_store import load_model, model_family
from ..registry import registered_version
from ..source import read_streamed, slashed_time
from ..store import is_registered_model

# every code file some format writes: one of them an export does not write, left in ``out`` by an
# earlier export of another format, is another compensator's code (audit87)
CODE = ("compensator.c", "compensator.h", "stream.c", "compensator.st")


def _registry_provenance(source: str) -> dict:
    """The MLflow run a registered ``models:/name@alias`` (or ``/version``) came from and the
    dataset it was promoted on (the version's ``dataset_hash`` tag, which ``promote`` writes):
    the code of a champion names its data as the code of its run's ``model.pkl`` does."""
    from mlflow import MlflowClient

    try:
        found = registered_version(MlflowClient(), source)
    except Exception:
        return {"run_id": None, "dataset_hash": None}
    return {"run_id": found.run_id, "dataset_hash": (found.tags or {}).get("dataset_hash")}


def _refused(source: str, family: str, fmt: str, exc: NotExportable) -> ConfigError:
    return ConfigError(f"export.model={source} ({family}) cannot be exported as {fmt}: {exc}")


def _deployed(cfg: DictConfig, source: str, fmt: str) -> tuple[object, dict, object]:
    """``(deployed compensator, provenance, dataset read or None)`` of ``export.model``."""
    def exportable(comp):     # before its envelope and guard are derived from the train split
        try:
            check_exportable(comp, fmt)
        except NotExportable as exc:
            raise _refused(source, model_family(comp), fmt, exc) from None

    registered = is_registered(source)
    loaded = None if registered else load_model(resolve(source))
    if loaded is not None:    # before data.path is read: its absence is no reason to give first
        exportable(loaded)
    ds, train_ids = (None, []) if registered else read_streamed(cfg)[:2]
    deployed = deployable_model(cfg, ds, train_ids, source, "export.model", loaded)[0]
    if registered:
        if is_registered_model(source):
            return deployed, _registry_provenance(source), None
        return deployed, {"run_id": None, "dataset_hash": None}, None
    return deployed, {"run_id": None, "dataset_hash": ds.meta["digest"]}, ds


def _pack(cfg: DictConfig, deployed, ds, compensator_json: str, fmt: str
          ) -> tuple[dict, dict] | None:
    """The conformance pack's ``({path: text}, check.json)`` (:mod:`~...apps.deploy.export.pack`)
    of ``export.campaigns`` (the test split of ``data.path`` by default), or None: ``export.check``
    null writes it where the export read ``data.path`` anyway (a ``model.pkl``), true reads it
    for a registered model too, false writes none."""
    wanted = cfg.export.get("check")
    if wanted is False or (wanted is None and ds is None):
        return None
    if ds is None:
        ds = read_streamed(cfg)[0]
    chosen = cfg.export.get("campaigns")
    if chosen is None:
        ids = require_split(ds, "test")
    else:
        ids = [str(c) for c in chosen]
        unknown = [c for c in ids if c not in ds.campaigns]
        if unknown:
            raise ConfigError(f"export.campaigns names {', '.join(map(repr, unknown))}, no campaign "
                              f"of data.path (it has {', '.join(map(repr, list(ds.campaigns)[:8]))}"
                              f"{', ...' if len(ds.campaigns) > 8 else ''})")
    check_streamed_columns(ds, ids, plain(deployed).columns_, "the deployed model",
                           getattr(deployed, "bits_", None))
    files = {c: ds.rows_named(c) for c in ids}
    ss = StateSpace.from_dict(json.loads(compensator_json))
    return conformance_pack(deployed, ss, {c: ds.campaigns[c] for c in ids},
                            lead_ins(plain(deployed).compensator, ds, ids), files,
                            script=fmt == "c")


def _said(pack: dict) -> str:
    """One line of what the pack holds and how to run it."""
    listed = pack["campaigns"]
    rows = sum(e["rows"] for e in listed)
    cut = [f"{e['campaign']} at row {e['cut']['row']} ({e['cut']['why']})" for e in listed
           if e["cut"]]
    return (f"check: {rows:,} rows of {sum(1 for e in listed if e['rows'])} campaign(s) and the "
            f"corrections the code must give (|C - expected| <= {pack['tolerance_um']:g} um + "
            f"{pack['tolerance_relative']:g} x |expected|)" + (f"; cut: {'; '.join(cut)}" if cut
                                                               else ""))


# the size of an exported forest's code beyond which a PLC may not take it (many controllers'
# program memory is a few MB, and their ST compilers slow down on long initialiser lists)
PLC_LIMIT_BYTES = 1 << 20


def _forest_said(exported: dict, files: dict) -> str:
    """One line of an arx_rf model's forests in the code: trees, nodes, depth, the files' size,
    and a warning where the code exceeds :data:`PLC_LIMIT_BYTES`."""
    nodes, trees = len(exported["node_left"]), len(exported["tree_root"])
    sizes = {name: len(text.encode("utf-8")) for name, text in files.items()
             if name.endswith((".c", ".st")) and name != "stream.c"}
    said = (f"forest: {len(exported['forest_target'])} forest(s) of {trees} trees, {nodes:,} "
            f"nodes (depth <= {exported['tree_depth']}) walked as arrays: "
            + ", ".join(f"{name} {size / 1024:,.0f} KB" for name, size in sizes.items()))
    big = [name for name, size in sizes.items() if size > PLC_LIMIT_BYTES]
    if big:
        said += (f"; {' and '.join(big)} beyond 1 MB: more than many PLCs take (fewer or shallower "
                 "trees: model.estimator.forest.n_estimators, max_depth, min_samples_leaf)")
    return said


def _lstm_said(exported: dict, files: dict) -> str:
    """One line of an lstm model's networks in the code: their shape, weights, the files' size,
    and a warning where the code exceeds :data:`PLC_LIMIT_BYTES`."""
    weights = sum(_count(exported[k]) for k in (
        "lstm_w_ih", "lstm_w_hh", "lstm_b_ih", "lstm_b_hh", "lstm_head", "lstm_head_bias"))
    sizes = _code_sizes(files)
    said = (f"lstm: {len(exported['lstm_target'])} network(s) of {exported['lstm_layers']} "
            f"layer(s), hidden size {exported['lstm_hidden']}, {weights:,} weights stepped per "
            "sample (double): " + ", ".join(f"{name} {size / 1024:,.0f} KB"
                                            for name, size in sizes.items()))
    big = [name for name, size in sizes.items() if size > PLC_LIMIT_BYTES]
    if big:
        said += (f"; {' and '.join(big)} beyond 1 MB: more than many PLCs take (a smaller "
                 "network: model.estimator.hidden_size, num_layers)")
    return said


def _count(values) -> int:
    """The numbers in a nested list (one for a number)."""
    return sum(map(_count, values)) if isinstance(values, list) else 1


def _code_sizes(files: dict) -> dict:
    return {name: len(text.encode("utf-8")) for name, text in files.items()
            if name.endswith((".c", ".st")) and name != "stream.c"}


# keysight70: a date with slashes in either order (TC_SLASHED: 1 day first, 2 month first)
SLASHED = {f"{ORDER[day_first]}{year} %H:%M{seconds}": 2 - day_first for day_first in (True, False)
           for year in ("%Y", "%y") for seconds in (":%S", "")}
# data.time values whose times stream.c reads as the reader does (its own parser: driver.py):
# day-first with a four- or two-digit year, ISO 8601's order, the seconds optional in each
# (iso67: and a logger's elapsed h:mm:ss, TC_ELAPSED; lead91: data.time=of_day, TC_DAY_SECONDS)
STREAM_C_TIMES = frozenset({"auto", "seconds", "iso8601", "elapsed", OF_DAY_KIND,
                            *(f"{date} %H:%M{seconds}" for date in ("%d.%m.%Y", "%d.%m.%y")
                              for seconds in (":%S", "")),
                            *(f"%Y-%m-%d{sep}%H:%M{seconds}" for sep in (" ", "T")
                              for seconds in (":%S", "")),
                            *SLASHED})


def _stream_encoding(cfg, fmt: str) -> str:
    """``data.encoding`` as ``stream.c`` decodes it (``utf-8``, ``cp1252``, ``latin-1``); another
    character set is refused for the C (exit 2), as ``stream.c`` could not read its headers."""
    import codecs

    given = str(cfg.data.get("encoding") or "utf-8")
    if given == "auto":     # (data87) stream.c reads a UTF-8 line as it is, any other as cp1252
        return "cp1252"
    try:
        name = codecs.lookup(given).name
    except LookupError:
        name = given
    known = {"utf-8": "utf-8", "utf-8-sig": "utf-8", "cp1252": "cp1252", "iso8859-1": "latin-1"}
    if fmt == "c" and name not in known:
        raise ConfigError(f"export.format=c: data.encoding={given!r}: stream.c decodes utf-8, "
                          "cp1252 and latin-1 only; convert the files to UTF-8 first")
    return known.get(name, name)


def _convertible(cfg: DictConfig, converted: dict, time_header, clock: list) -> None:
    """Refuse a column whose unit ``stream.c`` cannot convert as the reader did: a header read
    two ways (a letter unit, 'Probe K', taken apart by its first value), or a time written as
    ``data.time`` says (a strptime format: stream.c reads seconds, elapsed h:mm:ss and ISO 8601
    or day-first dates and times only; a date and its time of day in two columns, ``clock``
    their time-of-day headers, are joined as the reader joins them)."""
    for raw, (contract, scale, offset) in converted.items():
        if scale is None or not all(map(math.isfinite, (scale, offset))) or scale == 0:
            raise ConfigError(f"export.format=c: the column {raw!r} ({contract}) was read in "
                              "two units or one stream.c cannot convert: name its unit "
                              f"(data.units, {{{raw!r}: ...}}) or convert the file")
    shown = time_header if isinstance(time_header, str) else time_header[0]
    written = str(cfg.data.get("time") or "auto")
    if written not in STREAM_C_TIMES:
        raise ConfigError(f"export.format=c: the time column {shown!r} is read as data.time="
                          f"{written}, which stream.c cannot convert (it reads seconds, elapsed "
                          "h:mm:ss, ISO 8601, day-first dates with dots or dates with slashes and "
                          "times): convert the time, or export as json")


def _slashed(cfg: DictConfig, ds) -> int:
    """``TC_SLASHED``: the order of ``data.time``'s dates with slashes, or, where it is ``auto``,
    of the record's (the order its files' time columns say, as ``init`` writes it and the
    reader reads it, :mod:`~thermocomp.core.io.slashed`: a Keysight DAQ's ``Time`` or a field
    past 12; a run of such a record without ``init`` exported a stream that refused the raw
    export's every time); 0 where none is."""
    return SLASHED.get(slashed_time(cfg, ds) or "", 0)


def export(cfg: DictConfig) -> dict:
    """Write the export of ``export.model`` in ``export.format`` to ``out``; ``{file: path}``."""
    # a registered model is read from the store: none created (export logs no run)
    check_config(cfg, inputs=("export.model",),
                 existing_store=is_registered_model(cfg.export.get("model") or ""))
    source = cfg.export.get("model")
    if source is None or not str(source).strip():
        raise ConfigError("export.model is needed: a model.pkl, a pyfunc folder or "
                          "models:/<name>@<alias>")
    from ...base.log import version  # the installed distribution's, as --version prints it

    source, fmt = str(source), str(cfg.export.format)
    deployed, provenance, ds = _deployed(cfg, source, fmt)
    if ds is None:      # (data86) a registered model's status words: as it declares them
        cfg = with_model_bits(cfg, deployed, f"export.model={source}")
    stream = plain(deployed)
    left = not_in_code(deployed, fmt)
    # (small72) stream.c computes a derived target's reference from its error columns as the
    # reader does (TC_DERIVED_REFERENCE): they are read under their lab's headers too
    derive = dict(getattr(deployed, "derived_", {}) or {})
    sources = [c for name, text in derive.items() for c in derived_sources(name, text)]
    if left:
        say(f"not in the code (the served model only): {'; '.join(left)}")
    family = model_family(stream.compensator)
    units = {c: "degC" if c.startswith("T_") else "" for c in stream.columns_}
    # the lab's headers of the inputs, the time and the errors (`Pt01 [°C]` for T_Pt01): what
    # the machine's signals are called where the model was made; the code reads either name
    named = getattr(deployed, "lab_names_", {}) or {}
    lab = {c: raws[0] if len(raws) == 1 else raws
           for c in dict.fromkeys((*stream.columns_, TIME, *stream.targets_, *sources))
           if (raws := raw_names(named, c))}
    # the long file's run column travels with the model's names: from the registry as from a run
    run_column = next(iter(raw_names(named, RUN)), None)
    read = {*stream.columns_, TIME, *stream.targets_, *sources}
    converted = {raw: unit for raw, unit in (getattr(deployed, "lab_units_", {}) or {}).items()
                 if unit[0] in read}
    if fmt == "c":
        # (the reader joins the date and its time of day and keeps no lab's name of the second)
        # (data.roles.time=auto found the pair: the model keeps its header under CLOCK)
        joined = (cfg.data.get("roles") or {}).get("time") or ()
        clock = raw_names(named, CLOCK) or (
            [] if isinstance(joined, str) or len(joined) != 2 else list(joined)[1:])
        _convertible(cfg, converted, lab.get(TIME, TIME), [str(c) for c in clock])
        # (stranger65: stream.c joins the date and its time of day, as the reader does; the
        # export was refused)
        provenance.update(clock_column=str(clock[0]) if clock else None)
        # (cin103) the contract names of the inputs whose copy, its values apart, the reader
        # refuses (stream.c refused none of them: exit 0, the first column read).  A lab's
        # header is read by the lab's roles, which the model does not carry (an export from the
        # registry has none): its copy is read as the first, as a roles-read file's copy is.
        provenance.update(twins_refused=[c for c in stream.columns_ if copy_refused(c)])
    # (bits85) the inputs a PLC's status word packs, as the model declares them (a model
    # pickled before it carried none: the config's): stream.c names the word where they lack
    declared = getattr(deployed, "bits_", None) or parsed_bits(cfg.data.get("bits"))
    provenance.update(bits={f"{STATE}{n}": [w, b] for w, named in declared.items()
                            for b, n in named.items() if f"{STATE}{n}" in stream.columns_})
    thousands = cfg.data.get("thousands")       # (the lab's 1.234,5: stream.c ungroups it)
    provenance.update(thousands=None if thousands is None else str(thousands)[:1],
                      elapsed=str(cfg.data.get("time") or "auto") == "elapsed",
                      slashed=_slashed(cfg, ds), pause_s=pause_seconds(cfg, ds, deployed),
                      day_seconds=day_seconds(cfg, ds, raw_names(named, TIME), deployed))
    # (streamraw65: the lab's raw file as the reader reads it -- its character set and its marks
    # of a value not measured travel with the model, as data.thousands does)
    provenance.update(encoding=_stream_encoding(cfg, fmt),
                      missing_values=[str(m) for m in cfg.data.get("missing_values") or ()])
    provenance.update(model=family, source=source, version=version(), units=units, lab_names=lab,
                      lab_units=converted, run_column=run_column, derive=derive,
                      exported=datetime.now(timezone.utc).strftime("%Y-%m-%dT%H:%M:%SZ"),
                      not_in_code=left)
    try:
        files = exported_files(deployed, fmt, provenance)
    except NotExportable as exc:
        raise _refused(source, family, fmt, exc) from None
    packed = _pack(cfg, deployed, ds, files["compensator.json"], fmt)
    out = Path(resolve(cfg.out))
    earlier = [name for name in CODE if name not in files and (out / name).is_file()]
    with staged_outputs(out, last=("compensator.json",)) as tmp:
        for name, text in {**files, **(packed[0] if packed else {})}.items():
            (tmp / name).parent.mkdir(parents=True, exist_ok=True)
            (tmp / name).write_text(text, encoding="utf-8")
    written = {name: out / name for name in files}
    exported = json.loads(files["compensator.json"])
    laws = exported["provenance"].get("laws")
    kept = f"; per target: {per_target(laws)}" if laws else ""   # what auto / ATI kept
    say(f"export ({fmt}, {family}{kept}): {', '.join(str(p) for p in written.values())}")
    if earlier:
        logger.warning(f"{', '.join(earlier)} in {out}: an earlier export's code, not this "
                       f"compensator's ({fmt}): remove them, or export into a folder of its own")
    if exported.get("forest_target"):
        say(_forest_said(exported, files))
    if exported.get("lstm_target"):
        say(_lstm_said(exported, files))
    if fmt == "c":
        say(f"build: cd {out} && cc compensator.c stream.c -lm -o stream && ./stream < rows.csv"
            " (--state FILE: a restarted stream goes on from FILE)")
        bits = provenance["bits"]
        if bits:            # (lead91: stream.c decodes the word as the reader does)
            say(f"{', '.join(f'{c} (bit {b} of {w!r})' for c, (w, b) in bits.items())}: "
                "data.bits; the code reads each as a column of its own, as `thermocomp rows` "
                "writes them, or from the word in their place, decoded as the reader decodes it "
                "(the word and a bit of it both: refused by name, exit 2)")
    if packed:
        written[PACK] = out / PACK
        say(f"{_said(packed[1])}: {out / PACK}" + (f" (after the build, in {out}: sh check/check.sh)"
                                                  if fmt == "c" else ""))
    elif (out / PACK / "check.json").is_file():
        say(f"{out / PACK} is an earlier export's pack, not this code's (export.check=false)")
    elif cfg.export.get("check") is None:      # (stranger78: a champion's code came without one, unsaid)
        say("no conformance pack (check/): a registered model is exported without reading data; "
            "export.check=true writes the pack of data.path's test split")
    return written
