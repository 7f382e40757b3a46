"""Every preparation option of issue 18 refuses bad values cleanly: exit 2, one line, no traceback.

Zero, negative, NaN, infinite, out-of-range and non-numeric values of --outlier-k, --outlier-sq,
--max-undefined, --cutoff-um, --quantised, --detrend (on ``surface``, the fastest command that
shares the option group with ``contact`` and ``friction-process``).
"""

from __future__ import annotations

import pytest
from typer.testing import CliRunner

from stochfric.cli import app

CASES = [
    *[("--outlier-k", v) for v in ("0", "-1", "nan", "inf", "2", "x")],
    *[("--outlier-sq", v) for v in ("0", "-1", "nan", "inf", "1", "x")],
    *[("--max-undefined", v) for v in ("0", "-0.1", "nan", "inf", "1.5", "x")],
    *[("--cutoff-um", v) for v in ("0", "-5", "nan", "inf", "1e9", "x")],
    ("--quantised", "smooth"),
    ("--detrend", "cubic"),
]


@pytest.mark.parametrize(("option", "value"), CASES)
def test_bad_preparation_values_are_refused_in_one_line(option: str, value: str) -> None:
    extra = ["--detrend", "gaussian"] if option == "--cutoff-um" else []
    res = CliRunner().invoke(app, ["surface", *extra, option, value])
    assert res.exit_code == 2, (option, value, res.output)
    assert "Traceback" not in res.output
    lines = [ln for ln in res.stderr.strip().splitlines() if ln.strip()]
    assert lines and (lines[-1].startswith("error:") or "Invalid value" in res.stderr), res.stderr


def test_gaussian_filter_without_cutoff_is_refused() -> None:
    res = CliRunner().invoke(app, ["surface", "--detrend", "gaussian"])
    assert res.exit_code == 2 and "--cutoff-um" in res.stderr and "Traceback" not in res.output
