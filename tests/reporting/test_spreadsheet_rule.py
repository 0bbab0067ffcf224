"""The spreadsheet rule applied to a whole frame (``spreadsheet_frame``, the runs CSV beside
a report) prefixes exactly the cells the one-cell rule (``spreadsheet_cell``) prefixes."""

import pandas as pd

from granudb.vocabulary.escaping import FORMULA_STARTS, spreadsheet_cell, spreadsheet_frame


def test_frame_rule_and_cell_rule_prefix_the_same_cells() -> None:
    near = ["", "x", "a=b", " =x", "\n=x", "é=", "＝x", "[x", "\\x", "'=x", "^x", "*x"]
    texts = [*(start + "1" for start in FORMULA_STARTS), *FORMULA_STARTS, *near]
    frame = pd.DataFrame(
        {"object": pd.Series(texts, dtype=object), "string": pd.Series(texts, dtype="string")}
    )
    out = spreadsheet_frame(frame)
    expected = [spreadsheet_cell(t) for t in texts]
    assert out["object"].tolist() == expected
    assert out["string"].tolist() == expected
    assert sum(e != t for e, t in zip(expected, texts, strict=True)) == 2 * len(FORMULA_STARTS)
