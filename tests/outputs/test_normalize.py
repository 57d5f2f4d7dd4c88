"""normalize: one dtype per column and nulls for missing values, the same whether a column is converted or
already of its kind (a sweep's chunks come from its workers of their kinds: they are kept as they are)."""

import numpy as np
import pandas as pd
import pytest

from flyopt.outputs import results


def _converted(frame):
    """Every column through the conversion, none kept as it is: what normalize gave before it kept any."""
    out = frame.copy()
    for name in frame.columns:
        out[name] = results._of_kind(frame[name], results.column_kind(name, frame[name]), name)
    return out


FRAMES = {
    "of their kinds": pd.DataFrame(
        {
            "point": np.arange(4, dtype=np.int64),
            "mass": [1.0, np.nan, 3.5, 4.0],
            "feasible": [True, False, True, True],
            "best_material": pd.Series(["cast_iron", None, "steel", "steel"], dtype="str"),
            "iterations": np.array([3, -1, 5, 7], dtype=np.int64),
        }
    ),
    "empty text in a text column": pd.DataFrame(
        {"message": pd.Series(["", "ok", None, ""], dtype="str"), "mass": [1.0, 2.0, 3.0, 4.0]}
    ),
    "object text, None, NaN and empty": pd.DataFrame(
        {"status": pd.Series(["designed", None, np.nan, ""], dtype=object)}
    ),
    "whole numbers in a number's column": pd.DataFrame({"mass": np.array([1, 2, 3], dtype=np.int64)}),
    "words in a flag's column": pd.DataFrame({"feasible": ["true", "false", "True"]}),
    "a count as floats": pd.DataFrame({"n_feasible": [1.0, 2.0, 0.0]}),
    "no rows": pd.DataFrame({"best_material": pd.Series([], dtype="str"), "mass": pd.Series([], dtype=float)}),
    "text of nulls only": pd.DataFrame({"binding": pd.Series([None, None], dtype="str")}),
    "text in Python's storage": pd.DataFrame(
        {"best_material": pd.Series(["cast_iron", None], dtype=pd.StringDtype("python", na_value=np.nan))}
    ),
}


@pytest.mark.parametrize("name", FRAMES)
def test_a_column_kept_is_what_its_conversion_gives(name):
    frame = FRAMES[name]
    got = results.normalize(frame.copy())
    pd.testing.assert_frame_equal(got, _converted(frame), check_exact=True)
    for column in got.columns:
        kind = results.column_kind(column, got[column])
        assert {"float": "float64", "bool": "bool", "str": str(results._text_dtype())}.get(
            kind, str(got[column].dtype)
        ) == str(got[column].dtype)


def test_empty_text_and_minus_one_become_nulls():
    frame = results.normalize(FRAMES["empty text in a text column"].copy())
    assert frame["message"].isna().tolist() == [True, False, True, True]
    counts = results.normalize(FRAMES["of their kinds"].copy())["iterations"]
    assert str(counts.dtype) == "Int64" and counts.isna().tolist() == [False, True, False, False]
