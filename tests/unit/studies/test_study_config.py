"""Config validation (pydantic) and the TOML run file: clear messages."""

from __future__ import annotations

from pathlib import Path

import pytest
from pydantic import ValidationError

from stochfric.studies.config import DampingConfig, LyapunovConfig
from stochfric.studies.errors import StudyError
from stochfric.studies.run_config import load_run_file, parse_run_file

GOOD = """
[defaults]
preset = "sheet"
seed = 3

[execution]
executor = "processes"
workers = 2

[output]
dir = "out"

[[study]]
kind = "damping"
normal_forces = [1400]
damping_ratios = "0.1:0.2:3"
runs = 2

[[study]]
kind = "lyapunov"
preset = "brake"
eta = [1.0, 1.2]
"""


def test_defaults_and_grids(tmp_path: Path) -> None:
    f = tmp_path / "s.toml"
    f.write_text(GOOD)
    rf = load_run_file(f)
    assert rf.execution.executor == "processes" and rf.execution.workers == 2
    d, ly = rf.study
    assert isinstance(d, DampingConfig) and isinstance(ly, LyapunovConfig)
    assert d.preset == "sheet" and d.seed == 3 and d.damping_ratios == (0.1, 0.15, 0.2)
    assert ly.preset == "brake" and ly.eta == (1.0, 1.2) and ly.perturbation == 1e-6


@pytest.mark.parametrize(
    ("text", "needle"),
    [
        ("[[study]]\nkind = 'damping'\ndampng = 0.1\n", "study[0].dampng: Extra inputs are not permitted"),
        ("[[study]]\nkind = 'dumping'\n", "study[0]"),
        ("[[study]]\nkind = 'damping'\ndamping_ratios = '0.3:0.1:x'\n", "START and STOP must be numbers"),
        ("[[study]]\nkind = 'damping'\ndamping_ratios = [0.2, 0.1]\n", "increasing"),
        ("[[study]]\nkind = 'damping'\nruns = 0\n", "study[0].runs: Input should be greater than or equal to 1"),
        ("[[study]]\nkind = 'forcing'\npreset = 'car'\n", "study[0].preset"),
        ("[[study]]\nkind = 'damping'\nmodels = ['white', 'white']\n", "listed twice"),
        ("[[study]]\nruns = 3\n", "needs kind"),
        ("[execution]\nexecutor = 'serial'\n", "no [[study]]"),
        ("[execution]\nexecuter = 'serial'\n[[study]]\nkind = 'damping'\n", "execution.executer"),
        ("study = 3\n", "array of tables"),
        ("[[study]]\nkind = 'damping'\nwhite_intensity = 'pink'\n",
         "study[0].white_intensity: Input should be 'sigma_mu', 'spectral_level' or 'thesis'"),
        ("[defaults]\npath_coordinate = 'global'\n[[study]]\nkind = 'forcing'\n",
         "study[0].path_coordinate: Input should be 'mass', 'relative' or 'position'"),
        ("[[study]]\nkind = 'damping'\nphase_damping_ratios = [0.1, 1.1]\n", "study[0].phase_damping_ratios"),
        ("[[study]]\nkind = 'damping'\nphase_runs = -1\n", "study[0].phase_runs"),
        ("[[study]]\nkind = 'forcing'\nphase_normal_force = 1000\n", "study[0].phase_normal_force: Extra inputs"),
        ("[[study]]\nkind = 'damping'\nintegrator = 'milstein'\n",
         "study[0].integrator: Input should be 'euler' or 'accurate'"),
        # a name no integrator has: told this field's choices, not every integrator of the package
        ("[[study]]\nkind = 'lyapunov'\nintegrator = 'rk4'\n",
         "study[0].integrator: Input should be 'euler' or 'accurate'"),
        ("[[study]]\nkind = 'forcing'\nsde_integrator = 'heun'\n",
         "study[0].sde_integrator: Input should be 'euler' or 'milstein'"),
        ("[[study]]\nkind = 'forcing'\nintegrator = 3\n", "study[0].integrator: Input should be 'euler' or 'accurate'"),
    ],
)
def test_errors_are_clear(tmp_path: Path, text: str, needle: str) -> None:
    f = tmp_path / "bad.toml"
    f.write_text(text)
    with pytest.raises(StudyError) as ei:
        load_run_file(f)
    assert needle in str(ei.value)
    assert "bad.toml" in str(ei.value)


def test_not_toml_and_missing(tmp_path: Path) -> None:
    f = tmp_path / "x.toml"
    f.write_text("this is = = not toml")
    with pytest.raises(StudyError, match="not valid TOML"):
        load_run_file(f)
    with pytest.raises(StudyError, match="cannot read"):
        load_run_file(tmp_path / "missing.toml")
    with pytest.raises(StudyError):
        parse_run_file({"study": [1]})


def test_config_is_frozen_and_hashable_dict() -> None:
    c = DampingConfig(runs=2)
    with pytest.raises(ValidationError):
        c.runs = 3  # type: ignore[misc]
    h = c.hash_config()
    assert h["runs"] == 2 and h["kind"] == "damping"


def test_a_toml_file_with_a_name_not_in_the_glossary_is_refused_naming_the_field(tmp_path: Path) -> None:
    """No compatibility layer (issue 21): another field name is an unknown field, named in one line."""
    f = tmp_path / "old.toml"
    f.write_text("""
[[study]]
kind = "damping"
normal_force_n = [4000, 5600]
""")
    with pytest.raises(StudyError, match=r"study\[0\]\.normal_force_n: Extra inputs are not permitted"):
        load_run_file(f)


def test_model_choices_in_toml() -> None:
    rf = parse_run_file({"defaults": {"white_intensity": "spectral_level", "path_coordinate": "relative"},
                         "study": [{"kind": "damping", "phase_normal_force": 1400, "phase_damping_ratios": "0.05:0.2:4",
                                    "phase_runs": 2, "save_every": 5},
                                   {"kind": "lyapunov", "white_intensity": "sigma_mu"}]})
    d, ly = rf.study
    assert isinstance(d, DampingConfig)
    assert d.white_intensity == "spectral_level" and d.path_coordinate == "relative"
    assert d.phase_normal_force == 1400.0 and d.phase_damping_ratios == (0.05, 0.1, 0.15, 0.2)
    assert d.phase_runs == 2 and d.save_every == 5
    assert ly.white_intensity == "sigma_mu" and ly.path_coordinate == "relative"
    assert DampingConfig().white_intensity == "sigma_mu" and DampingConfig().path_coordinate == "mass"
    # both change the numbers, so both are in the checkpoint key
    assert d.hash_config()["white_intensity"] == "spectral_level"
