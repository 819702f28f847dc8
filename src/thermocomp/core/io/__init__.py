"""Dataset contract, reading, validation and ingest (``shared/spec/DATA_FORMAT.md``)."""

from pathlib import Path

from ...base.log import once_per_run
from .contract import (
                       ContractError,
                       Dataset,
                       match_columns,
                       role,
                       write_dataset,
)
from .read import (
    INGEST_REPORT,
    ReadOptions,
    check_separate,
    folder_splits,
    ingest,
    load_interim,
    read_campaign,
    read_dataset,
    read_manifest,
)

# what the reader says is about a file: said once a stage run, however often it reads the file
once_per_run(Path(__file__).parent)

__all__ = [
    "INGEST_REPORT", "ContractError", "Dataset", "ReadOptions", "check_separate", "folder_splits", "ingest",
    "load_interim",
    "match_columns", "read_campaign", "read_dataset", "read_manifest", "role", "write_dataset",
]
