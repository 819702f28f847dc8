"""The scoring server of ``thermocomp serve``: MLflow's, behind request limits.

MLflow's scoring app reads the whole body, parses it and predicts in one worker
thread that its timeout cannot stop: a 92 MB request of 1,000,000 rows held the
single worker for a minute past its 504 (and every other session with it), and a
deeply nested JSON body ended in a RecursionError (HTTP 500).  :class:`RequestLimits`
refuses such a request before the app sees it, with one line of JSON
(``{"error_code", "message"}``, as MLflow's errors): 413 for a body over
``max_body_bytes`` (from its ``Content-Length`` before a byte is read, else as
soon as the bytes read exceed it), 400 for JSON nested deeper than
:data:`MAX_DEPTH` (counted on the raw bytes, before any parsing) and 413 for more
than ``max_rows`` rows.  uvicorn runs :func:`scoring_app` (a factory) with the
limits in the environment (:data:`ROWS_ENV`, :data:`BODY_ENV`).

The plumbing around it (:func:`trusted_copy`, :func:`server_command`, :func:`run_server`):
the model folder the server loads, written by this installed package around the model's
signed pickle (its own code never runs); the server's command line and environment (the
project's store in ``MLFLOW_TRACKING_URI``, this Python's executables first on ``PATH``);
the server as a child that ends with its parent and whose folder is removed however it ends.

Request: ``POST http://<host>:<port>/invocations`` with
``{"dataframe_split": {"columns": [...], "data": [[...]]}, "params": {"session": "machine-7",
"reset": true}}`` (``reset`` on the first block of each campaign).  A ``text/csv`` body (a
logger's rows, header first) is answered as the ``dataframe_split`` of the same cells
(:func:`csv_as_split`): MLflow's own CSV parse needs a pandas type for every column its
signature names, and the time column (seconds or a logger's timestamps) has none.
The ``params`` may come in the query string instead (:func:`query_params`, extension deploy71:
``POST /invocations?session=machine-7&reset=true``), the one way a CSV body carries them; a JSON
body may take them so too (merged into its ``params``; a parameter given both ways must agree).
"""

from __future__ import annotations

import csv
import io
import json
import math
import os
import re
import shutil
import sys
from pathlib import Path
from urllib.parse import parse_qsl

import numpy as np

MAX_DEPTH = 32      # a table is nested 4 deep ({"dataframe_split": {"data": [[...]]}})
ROWS_ENV, BODY_ENV = "THERMOCOMP_SERVE_MAX_ROWS", "THERMOCOMP_SERVE_MAX_BODY_BYTES"
PARENT_ENV = "THERMOCOMP_SERVE_PARENT"   # `thermocomp serve`'s process: the server ends with it
_STRING = re.compile(rb'"(?:[^"\\]|\\.)*"', re.S)
_NOT_BRACKET = bytes(b for b in range(256) if b not in b"[]{}")


def json_shape(body: bytes) -> tuple[int, int]:
    """``(deepest nesting, most arrays and objects opened at one depth)`` of a JSON body, strings
    skipped, nothing parsed (a parse is what a hostile body costs).  The second is a table's
    rows in MLflow's row formats: the row arrays of ``dataframe_split``, the records of
    ``dataframe_records`` and ``instances`` outnumber everything else at their depth."""
    # a few brackets per row: the depth scan is over them alone
    brackets = np.frombuffer(_STRING.sub(b"", body).translate(None, _NOT_BRACKET), np.uint8)
    opens = (brackets == ord("[")) | (brackets == ord("{"))
    depth = np.cumsum(np.where(opens, 1, -1), dtype=np.int32)
    at = depth[opens]
    at = at[at > 0]
    return int(depth.max(initial=0)), int(np.bincount(at).max()) if len(at) else 0


def count_rows(body: bytes, content_type: str) -> tuple[int, int]:
    """``(nesting depth, rows)`` of a request body (CSV: its lines after the header)."""
    if "csv" in content_type:
        return 0, max(body.count(b"\n") - 1 + (not body.endswith(b"\n")), 0)
    return json_shape(body)


_NUMBER = re.compile(r"[+-]?(\d+\.?\d*|\.\d+)([eE][+-]?\d+)?|[+-]?(nan|inf|infinity)", re.I)
_INTEGER = re.compile(r"[+-]?\d+")


def _cell(text: str):
    """A CSV cell as JSON carries it: a number (an integer as one), a missing value (an empty
    cell, ``nan``) as null, any other text as it is (the model refuses it naming its row)."""
    value = text.strip()
    if not value:
        return None
    if _INTEGER.fullmatch(value):
        return int(value)
    if _NUMBER.fullmatch(value):
        number = float(value)
        return None if number != number else number
    return text


def is_csv(content_type: str) -> bool:
    """Whether a request's ``Content-Type`` is CSV in UTF-8 (another charset: MLflow's 415)."""
    mime, *params = (p.strip().lower() for p in content_type.split(";"))
    return mime == "text/csv" and all(p in ("charset=utf-8", "charset=utf8") for p in params)


def csv_as_split(body: bytes, params: dict | None = None) -> bytes:
    """A CSV block (header first, comma-separated, UTF-8) as the JSON body ``{"dataframe_split":
    ..., "params": params}`` of the same cells (:func:`_cell`), so that CSV and JSON take one path
    to the model (its columns' types, its refusals).  A body that is not such a table: ValueError
    naming the data row (1-based, after the header)."""
    try:
        text = body.decode("utf-8-sig")
    except UnicodeDecodeError as exc:
        raise ValueError(f"CSV body: byte {exc.start} is not UTF-8") from None
    lines = csv.reader(io.StringIO(text, newline=""))
    columns = next(lines, None)
    if not columns:
        raise ValueError("CSV body: no header row (the column names first)")
    data = []
    for row, cells in enumerate(lines, start=1):
        if not cells:              # a blank line (the body's last newline)
            continue
        if len(cells) != len(columns):
            raise ValueError(f"CSV body, data row {row}: {len(cells)} cells under a header of "
                             f"{len(columns)} columns")
        data.append([_cell(c) for c in cells])
    table = {"dataframe_split": {"columns": columns, "data": data}}
    return json.dumps({**table, "params": params} if params else table).encode()


def model_params(model) -> dict[str, str]:
    """The parameters a loaded pyfunc ``model`` declares: name -> MLflow's type (``boolean``,
    ``string``, ``double``, ...), as :func:`query_params` reads them."""
    schema = model.metadata.get_params_schema()
    return {p.name: p.dtype.name for p in schema.params} if schema else {}


_TRUE, _FALSE = ("true", "1"), ("false", "0")


def _param(name: str, text: str, kind: str):
    """The query string's ``name=text`` as the JSON value of MLflow type ``kind``."""
    if kind == "boolean":
        if text.lower() in _TRUE + _FALSE:
            return text.lower() in _TRUE
        raise ValueError(f"query parameter {name}={text!r}: not true or false (true, false, 1, 0)")
    if kind in ("double", "float", "long", "integer"):
        try:
            number = int(text) if kind in ("long", "integer") else float(text)
        except ValueError:
            number = None
        if number is None or not math.isfinite(number):
            raise ValueError(f"query parameter {name}={text!r}: not a finite number ({kind})")
        return number
    return text


def query_params(query: bytes, declared: dict[str, str]) -> dict:
    """The ``params`` a request's query string gives (``session=machine-7&reset=true``,
    percent-encoded UTF-8), each as the JSON value of the type the model ``declared`` for it
    (:func:`model_params`; a boolean as ``true``/``false``/``1``/``0``).  A name the model does
    not declare, one given twice or a value not of its type: ValueError saying which, in one
    line."""
    try:
        pairs = parse_qsl(query.decode("ascii"), keep_blank_values=True, strict_parsing=True,
                          errors="strict")
    except (UnicodeDecodeError, ValueError):
        raise ValueError(f"query string {query.decode('latin-1')!r}: not name=value pairs joined "
                         "by '&' (percent-encoded UTF-8)") from None
    params: dict = {}
    for name, text in pairs:
        if name not in declared:
            raise ValueError(f"query parameter {name!r}: the model takes "
                             f"{', '.join(declared) or 'no parameters'}")
        if name in params:
            raise ValueError(f"query parameter {name!r} given twice")
        params[name] = _param(name, text, declared[name])
    return params


def with_params(body: bytes, params: dict) -> bytes:
    """The JSON request ``body`` with ``params`` (the query string's) in its ``params``; one
    given there too must be the same value."""
    try:
        table = json.loads(body)
    except ValueError:
        raise ValueError("JSON body: not valid JSON") from None
    given = table.get("params") if isinstance(table, dict) else None
    if not isinstance(table, dict) or not isinstance(given or {}, dict):
        raise ValueError("JSON body: not an object with a params object")
    for name, value in params.items():
        if name in (given or {}) and given[name] != value:
            raise ValueError(f"parameter {name!r}: {value!r} in the query string, "
                             f"{given[name]!r} in the body's params")
    return json.dumps({**table, "params": {**(given or {}), **params}}).encode()


class RequestLimits:
    """ASGI middleware around ``app``: the limits of the module doc on every POST."""

    def __init__(self, app, max_body_bytes: int, max_rows: int, params: dict[str, str] | None = None):
        self.app, self.max_body_bytes, self.max_rows = app, int(max_body_bytes), int(max_rows)
        self.params = params or {}       # the model's parameters, for the query string's

    async def __call__(self, scope, receive, send):
        if scope["type"] != "http" or scope["method"] != "POST":
            return await self.app(scope, receive, send)
        headers = dict(scope["headers"])
        declared = headers.get(b"content-length", b"0")
        too_big = (f"request body over serve.max_body_mb ({self.max_body_bytes / 2**20:g} MB): "
                   "send the rows in smaller blocks")
        if not declared.isdigit() or int(declared) > self.max_body_bytes:
            return await _refuse(send, 413, too_big)
        body = bytearray()
        while True:
            message = await receive()
            if message["type"] != "http.request":
                return None                     # the client went away
            body += message.get("body", b"")
            if len(body) > self.max_body_bytes:
                return await _refuse(send, 413, too_big)
            if not message.get("more_body", False):
                break
        body = bytes(body)
        content_type = headers.get(b"content-type", b"").decode("latin-1")
        depth, rows = count_rows(body, content_type)
        if depth > MAX_DEPTH:
            return await _refuse(send, 400, f"JSON nested more than {MAX_DEPTH} deep: not a table "
                                            "of sensor readings")
        if rows > self.max_rows:
            return await _refuse(send, 413, f"{rows} rows over serve.max_rows ({self.max_rows}): "
                                            "send the rows in smaller blocks")
        query, sent = scope.get("query_string", b""), body
        try:
            params = query_params(query, self.params) if query else {}
            if is_csv(content_type):
                body = csv_as_split(body, params)
            elif params and "json" in content_type:   # (another type: MLflow's 415)
                body = with_params(body, params)
        except ValueError as exc:
            return await _refuse(send, 400, str(exc))
        if body is not sent:
            scope = {**scope, "headers": [(k, v) for k, v in scope["headers"]
                                          if k not in (b"content-type", b"content-length")]
                     + [(b"content-type", b"application/json"),
                        (b"content-length", str(len(body)).encode())]}
        replayed = False

        async def replay():
            nonlocal replayed
            if replayed:
                return await receive()
            replayed = True
            return {"type": "http.request", "body": body, "more_body": False}

        return await self.app(scope, replay, one_line_refusals(send, body, from_csv=is_csv(content_type)))


QUOTED = "Failed to predict data '"     # MLflow's prefix of every refusal: the block, quoted
# MLflow's refusal of a value its signature's type does not take: the column, not the row
UNCONVERTED = re.compile(r"Failed to convert column (?P<column>.+?) to type '(?P<type>\w+)'")


def _number(value) -> bool:
    """Whether MLflow's float conversion takes ``value`` (a JSON null is a missing value)."""
    if value is None:
        return True
    try:
        float(value)
    except (TypeError, ValueError):
        return False
    return True


def unconverted_row(message: str, body: bytes, from_csv: bool = False) -> str | None:
    """MLflow's "Failed to convert column X to type 'float64'" as a row's refusal: ``column 'X',
    data row N of the block: value 'v' is not a number`` (N 1-based, as a lab's file is counted),
    found in a ``dataframe_split`` or ``dataframe_records`` body; None for any other answer."""
    found = UNCONVERTED.search(message)
    if found is None:
        return None
    column = found["column"]
    try:
        table = json.loads(body)
        if "dataframe_split" in table:
            split = table["dataframe_split"]
            at = list(split["columns"]).index(column)
            values = [row[at] for row in split["data"]]
        else:
            values = [row.get(column) for row in table["dataframe_records"]]
    except (ValueError, TypeError, KeyError, IndexError, AttributeError):
        return None
    bad = next((i for i, v in enumerate(values) if not _number(v)), None)
    if bad is None:
        return None
    how = ("a decimal point, a missing value as an empty cell" if from_csv
           else "send numbers as JSON numbers, a missing value as null")
    return (f"column {column!r}, data row {bad + 1} of the block: value {values[bad]!r} is not a "
            f"number ({found['type']}; {how})")


def twice_sent(body: bytes) -> str | None:
    """A ``dataframe_split`` (or CSV) block naming a column twice, as its refusal (``column 'X' is
    sent twice in the block: columns 2 and 12 of 12``; MLflow's schema check answered
    ``'DataFrame' object has no attribute 'dtype'``, audit103); None where no name repeats."""
    try:
        columns = list(json.loads(body)["dataframe_split"]["columns"])
    except (ValueError, TypeError, KeyError):
        return None
    first: dict[str, int] = {}
    for at, name in enumerate(map(str, columns), start=1):
        if name in first:
            return (f"column {name!r} is sent twice in the block: columns {first[name]} and {at} "
                    f"of {len(columns)} (send each column once)")
        first[name] = at
    return None


def one_line_refusals(send, body: bytes = b"", from_csv: bool = False):
    """``send`` with an HTTP 400 answer's ``message`` cut to its reason: MLflow's app quotes
    the whole block before it (a sensor column missing from 35 rows: 3 KB on 37 lines, the reason
    last), which a caller's log cannot show in one line; a value that is no number said with its
    row of the request ``body`` (MLflow names the column alone; ``from_csv``: the body came as CSV,
    the hint says how a CSV cell is written), a block naming a column twice said so
    (:func:`twice_sent`); every other answer as it is."""
    held: list = []

    async def cut(message):
        if message["type"] == "http.response.start" and message["status"] == 400:
            held.append(message)
            return None
        if not held or message["type"] != "http.response.body":
            return await send(message)
        held.append(message)
        if message.get("more_body", False):
            return None
        start, *bodies = held
        held.clear()
        answered = b"".join(m.get("body", b"") for m in bodies)
        try:
            answer = json.loads(answered)
        except ValueError:
            answer = None
        if isinstance(answer, dict) and (twice := twice_sent(body)):
            answer["message"] = twice
            answered = json.dumps(answer).encode()
        elif isinstance(answer, dict) and str(answer.get("message", "")).startswith(QUOTED):
            reason = answer["message"].rpartition("Error: ")[2]
            answer["message"] = " ".join(reason.split())
            answered = json.dumps(answer).encode()
        elif isinstance(answer, dict) and (row := unconverted_row(str(answer.get("message", "")),
                                                                  body, from_csv)):
            answer["message"] = row
            answered = json.dumps(answer).encode()
        headers = [(k, str(len(answered)).encode() if k.lower() == b"content-length" else v)
                   for k, v in start.get("headers", [])]
        await send({**start, "headers": headers})
        return await send({"type": "http.response.body", "body": answered})

    return cut


async def _refuse(send, status: int, message: str) -> None:
    content = json.dumps({"error_code": "REQUEST_LIMIT_EXCEEDED" if status == 413
                          else "MALFORMED_REQUEST", "message": message}).encode()
    await send({"type": "http.response.start", "status": status,
                "headers": [(b"content-type", b"application/json"),
                            (b"content-length", str(len(content)).encode()),
                            (b"connection", b"close")]})
    await send({"type": "http.response.body", "body": content})


def scoring_app():
    """MLflow's scoring app for the model its environment names, behind :class:`RequestLimits`."""
    import mlflow.pyfunc
    from mlflow.pyfunc import scoring_server

    from ...base.lifetime import watch_parent

    if os.environ.get(PARENT_ENV):     # a SIGKILLed `thermocomp serve` leaves no server behind
        watch_parent(int(os.environ[PARENT_ENV]))
    # the folder trusted_copy wrote with this environment's own pins: MLflow's check of them
    # against every installed package (~1-1.5 s CPU at each server start) could find nothing
    model = mlflow.pyfunc.load_model(os.environ[scoring_server._SERVER_MODEL_PATH],
                                     suppress_warnings=True)
    return RequestLimits(scoring_server.init(model), int(os.environ[BODY_ENV]), int(os.environ[ROWS_ENV]),
                         model_params(model))


def is_loopback(host: str) -> bool:
    """Whether ``host`` listens on this machine only (``localhost`` or a loopback address)."""
    import ipaddress

    try:
        return host == "localhost" or ipaddress.ip_address(host).is_loopback
    except ValueError:
        return False      # a name that may resolve to any interface


def trusted_copy(load_deployed, uri: str) -> str:
    """A pyfunc folder made by this installed package around the deployed compensator
    ``load_deployed()`` returns (from the model's signed pickle), which
    is what the server loads: the registered model's own code (``model_code.py``, ``code/``,
    ``MLmodel``) is never run (the signature covers the pickle alone).  A pickle whose
    signature does not match is refused here (exit 2), before any server starts."""
    import tempfile

    import mlflow

    from ...base.files import remove_tree, scratch_name
    from .pyfunc import save_compensator

    mlflow.set_tracking_uri(uri)    # the registry follows it (no process-wide registry URI:
                                    # it would outlive this call in a process that goes on)
    # one folder in the temp dir holds the model and whatever MLflow stages to write it (the
    # temp dir pointed there meanwhile): run_server removes it when the server ends, this
    # function when it cannot be written; a signal at any point leaves nothing else behind
    folder, previous = scratch_name("thermocomp-serve-"), tempfile.tempdir
    try:
        folder.mkdir(mode=0o700)
        tempfile.tempdir = str(folder)
        return str(save_compensator(load_deployed(), folder / "model"))
    except BaseException:
        remove_tree(folder)         # a download's workers may still write in it (files.remove_tree)
        raise
    finally:
        tempfile.tempdir = previous


def server_command(model: str, uri: str, *, host: str, port: int, timeout_s: float,
                   max_rows: int, max_body_mb: float) -> tuple[list[str], dict]:
    """``(argv, environment)`` of uvicorn running :func:`scoring_app` on the pyfunc folder
    ``model``, one worker (a session's stream state lives in the serving process)."""
    from mlflow.pyfunc.scoring_server import _SERVER_MODEL_PATH
    from mlflow.utils.file_utils import path_to_local_file_uri

    bin_dir = str(Path(sys.executable).parent)
    env = {**os.environ, "MLFLOW_TRACKING_URI": uri, "MLFLOW_REGISTRY_URI": uri,
           "PATH": os.pathsep.join([bin_dir, os.environ.get("PATH", "")]),
           _SERVER_MODEL_PATH: path_to_local_file_uri(model),
           "MLFLOW_SCORING_SERVER_REQUEST_TIMEOUT": str(math.ceil(timeout_s)),
           ROWS_ENV: str(int(max_rows)), BODY_ENV: str(int(max_body_mb * 2**20))}
    argv = [str(Path(bin_dir) / "uvicorn"), "--host", str(host), "--port", str(port),
            "--workers", "1", "--factory", f"{__name__}:{scoring_app.__name__}"]
    return argv, env


def run_server(argv: list[str], env: dict) -> int:
    """Run the server until it ends or this process is stopped (Ctrl-C, SIGTERM: it stops
    cleanly); its model folder is removed either way.  Its exit status (0 when stopped)."""
    import signal
    import subprocess

    from mlflow.pyfunc.scoring_server import _SERVER_MODEL_PATH
    from mlflow.utils.file_utils import local_file_uri_to_path

    from ...base.files import Terminated, signals_raise

    folder = Path(local_file_uri_to_path(env[_SERVER_MODEL_PATH])).parent
    server = None
    with signals_raise(sigint=True) as signals:
        try:
            sys.stdout.flush()
            sys.stderr.flush()
            # a signal while the child is forked waits until it is ours to stop (connect68:
            # raised inside Popen, it left a server whose parent was gone before the server
            # could watch it, serving on)
            with signals.deferred():
                server = subprocess.Popen(argv, env={**env, PARENT_ENV: str(os.getpid())})
            code = server.wait()
        except (KeyboardInterrupt, Terminated):    # Ctrl-C, SIGTERM: the server stops, cleanly
            if server is None:
                raise
            server.terminate()
            code = server.wait()
        finally:    # the model folder written for it, whatever ended the server; a second
            # signal while it stopped: it is killed, not left
            if server is not None and server.poll() is None:
                server.kill()
                server.wait()
            shutil.rmtree(folder, ignore_errors=True)
    return 0 if code in (0, -signal.SIGTERM, -signal.SIGINT) else code if code > 0 else 1
