"""Sizes and numbers a user types are checked before any work (issue 20 §1-§2, the cases found).

Each case used to hang while eating memory or to end in a traceback; now it ends at once with exit 2
and one line ``error: …`` that names the limit and what to change.
"""

from __future__ import annotations

import time

import pytest
from typer.testing import CliRunner

from stochfric.cli.app import app

CASES = [
    (["simulate", "--preset", "brake", "--tau-end", "inf"], "--tau-end must be a finite number"),
    (["simulate", "--preset", "brake", "--dt", "1e-300"], "steps per run"),
    (["simulate", "--preset", "brake", "--tau-end", "1e300"], "steps per run"),
    (["surface", "--median-radius", "100000"], "larger than the 200×296 map"),
    (["contact", "--material", "brake-pad", "--approach-um", "0.1:0.8:50000000"], "at most 10000"),
    (["friction-process", "--material", "brake-pad", "--realizations", "100000000"], "fewer --realizations"),
    (["study", "damping", "--preset", "brake", "--normal-force", "5600", "--damping", "0.05:0.25:100000000"],
     "at most 10000 per axis"),
]


@pytest.mark.parametrize(("args", "message"), CASES, ids=lambda a: a[0] if isinstance(a, list) else "")
def test_absurd_sizes_are_refused_at_once(args: list[str], message: str) -> None:
    t0 = time.perf_counter()
    res = CliRunner().invoke(app, args)
    assert res.exit_code == 2, res.output
    assert "Traceback" not in res.output
    lines = [ln for ln in res.stderr.strip().splitlines() if ln.strip()]
    assert lines[-1].startswith("error:") and message in lines[-1], res.stderr
    assert time.perf_counter() - t0 < 30.0
