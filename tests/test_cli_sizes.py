"""Sizes and numbers a user types are checked before any work (issue 20 §1-§2, the cases found).

Each case used to hang while eating memory or to end in a traceback; now it ends at once with exit 2
and one line ``error: …`` that names the limit and what to change.
"""

from __future__ import annotations

import pytest
from typer.testing import CliRunner

from stochfric.cli import app

CASES = [
    (["simulate", "--preset", "brake", "--tau-end", "inf"], "--tau-end must be a finite number"),
    (["simulate", "--preset", "brake", "--dt", "1e-300"], "steps per run"),
    (["simulate", "--preset", "brake", "--tau-end", "1e300"], "steps per run"),
    (["surface", "--median-radius", "100000"], "larger than the 200×296 map"),
    (["contact", "--material", "brake-pad", "--approach-um", "0.1:0.8:50000000"], "at most 10000"),
    (["friction-process", "--material", "brake-pad", "--realizations", "100000000"], "fewer --realizations"),
    (["study", "damping", "--preset", "brake", "--normal-force", "5600", "--damping-ratio", "0.05:0.25:100000000"],
     "at most 10000 per axis"),
]


@pytest.mark.parametrize(("args", "message"), CASES, ids=lambda a: a[0] if isinstance(a, list) else "")
def test_absurd_sizes_are_refused_at_once(args: list[str], message: str) -> None:
    res = CliRunner().invoke(app, args)
    assert res.exit_code == 2, res.output
    assert "Traceback" not in res.output
    lines = [ln for ln in res.stderr.strip().splitlines() if ln.strip()]
    assert lines[-1].startswith("error:") and message in lines[-1], res.stderr
    # refused before any work: checked by the message, not by a wall time (timings belong in benchmarks/)


@pytest.fixture()
def matrices(tmp_path):  # type: ignore[no-untyped-def]
    import numpy as np

    rng = np.random.default_rng(0)
    np.save(tmp_path / "complex.npy", rng.random((50, 60)) + 1j * rng.random((50, 60)))
    np.save(tmp_path / "metres.npy", rng.random((100, 100)))  # Sq ≈ 0.3 m on a 100 µm map: a unit slip
    np.save(tmp_path / "flat.npy", np.zeros((50, 60)))
    return tmp_path


@pytest.mark.parametrize(("name", "unit", "message"), [
    ("complex.npy", "um", "complex numbers"),
    ("metres.npy", "m", "exceeds the map's lateral size"),
    ("flat.npy", "um", "is flat after the form removal"),
])
def test_implausible_height_maps_are_refused_with_the_reason(matrices, name: str, unit: str, message: str) -> None:  # type: ignore[no-untyped-def]
    res = CliRunner().invoke(app, ["surface", str(matrices / name), "--size-um", "100:100", "--height-unit", unit])
    assert res.exit_code == 2 and "Traceback" not in res.output
    assert message in res.stderr.strip().splitlines()[-1], res.stderr


@pytest.mark.parametrize(("option", "value", "message"), [
    ("--long-surfaces", "0", "long_surfaces must be >= 3 (the ergodicity check"),
    ("--long-surfaces", "2", "long_surfaces must be >= 3"),
    ("--realizations", "1", "realizations must be >= 2"),
])
def test_count_options_name_their_real_minimum(option: str, value: str, message: str) -> None:
    res = CliRunner().invoke(app, ["friction-process", "--material", "brake-pad", option, value])
    assert res.exit_code == 2 and message in res.stderr


def test_a_boolean_is_not_a_seed(tmp_path) -> None:  # type: ignore[no-untyped-def]
    toml = tmp_path / "s.toml"
    toml.write_text('[defaults]\nseed = true\n[[study]]\nkind = "damping"\nnormal_forces = [5600]\n'
                    'damping_ratios = "0.05:0.25:3"\nruns = 2\n', encoding="utf-8")
    res = CliRunner().invoke(app, ["run", str(toml)])
    assert res.exit_code == 2 and "seed must be a number, not the boolean true" in res.stderr


def test_decode_errors_name_the_file(tmp_path) -> None:  # type: ignore[no-untyped-def]
    bad_toml = tmp_path / "bad.toml"
    bad_toml.write_bytes(b"\xff\xfe\x00bad")
    res = CliRunner().invoke(app, ["run", str(bad_toml)])
    assert res.exit_code == 2 and f"{bad_toml} is not UTF-8 text" in res.stderr
    bad_json = tmp_path / "bad.json"
    bad_json.write_bytes(b"\xff\xfe{bad")
    res = CliRunner().invoke(app, ["simulate", "--preset", "brake", "--model", "contact", "--process", str(bad_json)])
    assert res.exit_code == 2 and f"{bad_json} is not a friction-process model file" in res.stderr
    assert "Traceback" not in res.output


def test_random_bytes_in_an_instrument_suffix_are_called_possibly_invalid(tmp_path) -> None:  # type: ignore[no-untyped-def]
    import numpy as np

    f = tmp_path / "rand.al3d"
    f.write_bytes(np.random.default_rng(1).bytes(20000))
    res = CliRunner().invoke(app, ["surface", str(f)])
    assert res.exit_code == 2 and "Traceback" not in res.output
    assert "not a valid .al3d file" in res.stderr or "cannot read" in res.stderr


def test_an_absurd_normal_force_gets_a_coded_hopf_warning() -> None:
    import json

    res = CliRunner().invoke(app, ["study", "damping", "--preset", "brake", "--normal-force", "1e12", "--damping-ratio",
                                   "0.05:0.25:3", "--runs", "1", "--models", "deterministic", "--json"])
    assert res.exit_code == 0, res.output
    data = json.loads(res.stdout[res.stdout.index("{"):])
    assert data["d_hopf"][0] > 1e6
    assert {"code": "hopf-damping-above-one", "count": 1} in data["warnings"]


def test_lyapunov_perturbation_larger_than_the_attractor_is_refused() -> None:
    """issue 20 §3: δ = 1e6 ran and every cell said too-few-transitions; δ must be small against n μ0."""
    res = CliRunner().invoke(app, ["study", "lyapunov", "--preset", "brake", "--perturbation", "1e6"])
    assert res.exit_code == 2
    assert "not small against the attractor" in res.output and "below 3e-05" in res.output
    from stochfric.studies.config import LyapunovConfig
    from stochfric.studies.lyapunov import LyapunovStudy

    LyapunovStudy(LyapunovConfig(normal_forces=(4000.0,), perturbation=1e-4))  # the δ table's largest: accepted
