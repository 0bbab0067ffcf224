"""SI records as a pandas DataFrame that carries its units (``attrs["units"]``)."""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

from granudb.lazy import pandas as pd
from granudb.vocabulary.listings import units_of


def records_frame(records: Sequence[dict[str, Any]], columns: Sequence[str]) -> Any:
    """A DataFrame of ``records`` with ``columns`` in order and their units in
    ``attrs["units"]``."""
    frame = pd.DataFrame.from_records(list(records), columns=list(columns))
    frame.attrs["units"] = units_of(columns)
    return frame
