"""A served model fed a row whose value is no number (journey63): the refusal names the column,
the row of the block and the value, where MLflow's named the column alone."""

from __future__ import annotations

import json

import pandas as pd
import pytest

from test_hostile_stream import _asgi, _split, deployed, scoring  # noqa: F401 (fixtures)
from thermocomp.apps.deploy.server import RequestLimits


@pytest.mark.parametrize("form", ["dataframe_split", "dataframe_records"])
def test_a_text_value_in_a_block_is_refused_with_its_column_and_row(scoring, form):  # noqa: F811
    """'20,6' (a decimal comma) in the third row of a block: HTTP 400 naming T_, row 3, '20,6'."""
    _, app, rows = scoring
    block = rows.head(5).astype(object)
    column = [c for c in block.columns if c.startswith("T_")][1]
    block.loc[2, column] = "20,6"
    if form == "dataframe_split":
        body = _split(block, session="lab", reset=True)
    else:
        body = json.dumps({"dataframe_records": block.to_dict(orient="records"),
                           "params": {"session": "lab", "reset": True}}).encode()
    status, answer, _ = _asgi(RequestLimits(app, max_body_bytes=len(body), max_rows=10), body)
    assert status == 400
    assert answer["message"].startswith(f"column '{column}', data row 3 of the block: value '20,6' "
                                        "is not a number (float64;")
    good = _split(rows.head(5), session="lab", reset=True)
    assert _asgi(RequestLimits(app, max_body_bytes=len(good), max_rows=10), good)[0] == 200


def test_a_time_that_is_no_time_is_refused_with_its_row_of_the_block_not_of_stdin(scoring):  # noqa: F811
    """A logger's timestamps with 'abc' in the third row: the served model's refusal said
    'file <stdin>, column 'time', data row 3: ...' of a request that had no stdin."""
    _, app, rows = scoring
    block = rows.head(5).astype(object)
    block["time"] = [f"2026-12-01T08:0{i}:00" for i in range(5)]
    block.loc[2, "time"] = "abc"
    body = _split(block, session="lab", reset=True)
    status, answer, _ = _asgi(RequestLimits(app, max_body_bytes=len(body), max_rows=10), body)
    assert status == 400 and "<stdin>" not in answer["message"]
    assert answer["message"].startswith("column 'time', data row 3 of the block: value 'abc' is not")


@pytest.mark.parametrize("form", ["json", "csv"])
def test_a_column_sent_twice_is_refused_naming_it_and_where(scoring, form):  # noqa: F811
    """audit103: a block naming a sensor column twice (a lab's export with the channel listed
    twice) answered HTTP 400 "'DataFrame' object has no attribute 'dtype'" (MLflow's schema check);
    now the column and both places, in JSON and in CSV."""
    _, app, rows = scoring
    column = [c for c in rows.columns if c.startswith("T_")][1]
    block = pd.concat([rows.head(4), rows.head(4)[[column]]], axis=1)
    at = [i + 1 for i, c in enumerate(block.columns) if c == column]
    if form == "json":
        body = json.dumps({"dataframe_split": {"columns": list(block.columns),
                                               "data": block.to_numpy(float).tolist()},
                           "params": {"session": "lab", "reset": True}}).encode()
        kind = "application/json"
    else:
        body, kind = block.to_csv(index=False).encode(), "text/csv"
    status, answer, _ = _asgi(RequestLimits(app, max_body_bytes=len(body), max_rows=10), body,
                              content_type=kind)
    assert status == 400
    assert answer["message"] == (f"column '{column}' is sent twice in the block: columns {at[0]} and "
                                 f"{at[1]} of {len(block.columns)} (send each column once)")
