"""simulate(): ensembles, reproducibility, the contact model, warnings and errors."""

from __future__ import annotations

import warnings
from dataclasses import replace

import numpy as np
import pytest

from stochfric.oscillator.friction_laws import law_III, pressure_law
from stochfric.oscillator.integrate import simulate
from stochfric.oscillator.options import ExecutionOptions, IntegrationOptions, NoiseOptions, OutputOptions
from stochfric.oscillator.parameters import OscillatorParameters, ParameterError, PhysicalParameters
from stochfric.oscillator.presets import brake
from stochfric.oscillator.result import load_result


def _brake(force: float = 5600.0, damping: float = 5e-6) -> tuple[OscillatorParameters, object]:
    pre = brake()
    p = PhysicalParameters(mass=pre.mass, stiffness=pre.stiffness, belt_speed=pre.belt_speed,
                           normal_force=force, damping_ratio=damping,
                           contact_area=pre.contact_area).to_dimensionless()
    return p, pre


def _law(p: OscillatorParameters) -> object:
    assert p.pressure_pa is not None
    return pressure_law(brake().process.mean(p.pressure_pa))


@pytest.mark.parametrize("model", ["white", "contact"])
def test_same_seed_same_numbers_whatever_the_threads_and_batches(model: str) -> None:
    p, pre = _brake()
    sets = [p, p.with_normal_force(2720.0), p.with_normal_force(8000.0)]
    kw = dict(model=model, law=_law, process=pre.process, runs=5, seed=7, integration=IntegrationOptions(tau_end=10.0))
    a = simulate(sets, **kw, execution=ExecutionOptions(workers=1, batch_size=15))
    b = simulate(sets, **kw, execution=ExecutionOptions(workers=2, batch_size=1))
    c = simulate(sets, **kw, execution=ExecutionOptions(workers=2, batch_size=4))
    for r in (b, c):
        np.testing.assert_array_equal(a.x_gh, r.x_gh)
        np.testing.assert_array_equal(a.stick_count, r.stick_count)
    # a parameter set's runs do not depend on the other sets
    d = simulate(sets[1:2], **kw)
    assert not np.array_equal(d.x_gh[0], a.x_gh[1], equal_nan=True)  # spawn key (0, r) ≠ (1, r)
    e = simulate(sets, **kw, noise=NoiseOptions(common_random_numbers=True))
    f = simulate(sets[1:2], **kw, noise=NoiseOptions(common_random_numbers=True))
    np.testing.assert_array_equal(e.x_gh[1], f.x_gh[0])
    # different runs differ, a different seed differs
    assert not np.array_equal(a.x_gh[0, 0], a.x_gh[0, 1], equal_nan=True)
    g = simulate(sets, **{**kw, "seed": 8}, execution=ExecutionOptions(workers=1))
    assert not np.array_equal(a.x_gh, g.x_gh, equal_nan=True)


def test_contact_model_with_a_zero_process_equals_the_deterministic_model() -> None:
    p, pre = _brake()

    class Zero:
        dx = pre.process.dx
        length = pre.process.length
        grid_is_periodic = True

        def generate(self, p: float, rng: np.random.Generator) -> np.ndarray:
            return np.zeros(pre.process.n_points)

        def sigma_zeta(self, p: float) -> float:
            return 0.0

        def to_dict(self) -> dict:
            return {"kind": "zero"}

    for integ in ("euler", "accurate"):
        det = simulate(p, law=_law, integration=IntegrationOptions(integrator=integ, tau_end=20.0))
        con = simulate(p, model="contact", law=_law, process=Zero(), runs=2, seed=1,
                       integration=IntegrationOptions(integrator=integ, tau_end=20.0))
        for r in range(2):
            # Euler: bit-identical; accurate: the process's grid points are extra restart
            # events, so the step sequence differs (agreement to its tolerance)
            np.testing.assert_allclose(con.x_gh[0, r], det.x_gh[0, 0], rtol=0,
                                       atol=0 if integ == "euler" else 1e-10)


def test_contact_accurate_is_step_independent() -> None:
    p, pre = _brake()
    a = simulate(p, model="contact", law=_law, process=pre.process, runs=2, seed=3,
                 integration=IntegrationOptions(integrator="accurate", tau_end=20.0, dt=0.01))
    b = simulate(p, model="contact", law=_law, process=pre.process, runs=2, seed=3,
                 integration=IntegrationOptions(integrator="accurate", tau_end=20.0, dt=0.001, rtol=1e-12,
                                                atol=1e-15, max_step=0.05))
    assert np.array_equal(a.stick_count, b.stick_count)
    scale = np.nanmax(np.abs(a.x_gh))  # cycle amplitude ≈ 2e-3
    np.testing.assert_allclose(a.x_gh, b.x_gh, atol=1e-8 * scale / 1e-3)
    # Euler converges to it
    e = simulate(p, model="contact", law=_law, process=pre.process, runs=2, seed=3,
                 integration=IntegrationOptions(dt=0.0005, tau_end=20.0))
    assert np.nanmax(np.abs(e.x_gh - a.x_gh)) < 0.05 * scale


def test_path_coordinate_is_recorded_and_matters() -> None:
    p, pre = _brake()
    m = simulate(p, model="contact", law=_law, process=pre.process, runs=2, seed=1,
                 integration=IntegrationOptions(tau_end=20.0))
    r = simulate(p, model="contact", law=_law, process=pre.process, runs=2, seed=1,
                 noise=NoiseOptions(path_coordinate="relative"), integration=IntegrationOptions(tau_end=20.0))
    assert m.path_coordinate == "mass" and r.path_coordinate == "relative"
    assert m.to_dataset().attrs["path_coordinate"] == "mass"
    assert not np.array_equal(m.x_gh, r.x_gh, equal_nan=True)
    # relative sliding distance per cycle exceeds the mass's own path (belt moves too)
    assert np.all(r.diagnostics["path"] > m.diagnostics["path"])


def test_process_never_repeats_and_short_slip_warning(monkeypatch: pytest.MonkeyPatch) -> None:
    """A run whose path exceeds the process length gets further independent segments instead of
    the periodic continuation (no ``process-exhausted``); its numbers are those of an unbounded
    realisation: the same whether it starts with 1 or 16 segments."""
    import stochfric.oscillator.integrate as integrate_module

    p, pre = _brake()
    short = replace(pre.process, length=0.01, dx=0.01 / 16)
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # returned in the result, never emitted as Python warnings
        res = simulate(p, model="contact", law=_law, process=short, runs=3, seed=1)
    assert "process-exhausted" not in {w.code for w in res.warnings}
    segments = res.diagnostics["process_segments"]
    path_m = res.diagnostics["path"] * p.length_scale
    assert np.all(segments * short.length > path_m)  # every run read a fresh realisation throughout
    assert np.max(segments) > 1
    monkeypatch.setattr(integrate_module, "FIRST_SEGMENTS", 16)
    wide = simulate(p, model="contact", law=_law, process=short, runs=3, seed=1)
    np.testing.assert_array_equal(wide.x_gh, res.x_gh)
    np.testing.assert_array_equal(wide.stick_count, res.stick_count)
    acc = simulate(p, model="contact", law=_law, process=short, runs=2, seed=1,
                   integration=IntegrationOptions(integrator="accurate", tau_end=20.0))
    monkeypatch.setattr(integrate_module, "FIRST_SEGMENTS", 1)
    acc1 = simulate(p, model="contact", law=_law, process=short, runs=2, seed=1,
                    integration=IntegrationOptions(integrator="accurate", tau_end=20.0))
    np.testing.assert_array_equal(acc.x_gh, acc1.x_gh)
    assert np.max(acc1.diagnostics["process_segments"]) > 1
    coarse = replace(pre.process, dx=0.05 / 5)  # 1 cm grid: slip paths (≈ 5 mm) are shorter
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        r2 = simulate(p.with_normal_force(720.0), model="contact", law=_law, process=coarse,
                      runs=2, seed=1)
    assert "slip-shorter-than-grid" in {w.code for w in r2.warnings}


@pytest.mark.parametrize(
    ("kwargs", "fragment"),
    [
        ({"model": "white"}, "needs the intensity"),
        ({"model": "white", "noise": NoiseOptions(sigma_zeta=0.1),
          "integration": IntegrationOptions(integrator="accurate")}, "SDE"),  # type: ignore[arg-type]
        ({"integration": IntegrationOptions(integrator="milstein")}, "strong order-1"),  # type: ignore[arg-type]
        ({"model": "contact"}, "friction-process model"),
        ({"model": "fluid"}, "unknown model"),
        ({"integration": IntegrationOptions(dt=0.5)}, "steps per period"),
        ({"integration": IntegrationOptions(dt=-1.0)}, "positive"),
        ({"runs": 0}, "positive integer"),
        ({"noise": NoiseOptions(path_coordinate="belt")}, "path coordinate"),  # type: ignore[arg-type]
        ({"x0": (float("nan"), 0.0)}, "finite"),
    ],
)
def test_bad_input_is_refused_with_a_message(kwargs: dict, fragment: str) -> None:
    with pytest.raises(ParameterError, match=fragment):
        simulate(OscillatorParameters(gamma0=1.0, n=10.0), **kwargs)


def test_white_noise_needs_pressure_for_the_sigma_rule() -> None:
    with pytest.raises(ParameterError, match="pressure"):
        simulate(OscillatorParameters(gamma0=1.0, n=1.0), model="white",
                 process=brake().process)


def test_result_round_trip_through_netcdf(tmp_path) -> None:
    p, pre = _brake()
    res = simulate([p, p.with_normal_force(8000.0)], model="white", law=_law, process=pre.process, runs=3, seed=11,
                   integration=IntegrationOptions(tau_end=10.0), output=OutputOptions(save_trajectory=True))
    path = res.to_netcdf(tmp_path / "sub" / "sim.nc")
    ds = load_result(path)
    np.testing.assert_array_equal(ds["x_gh"].values, res.x_gh)
    np.testing.assert_array_equal(ds["stick_count"].values, res.stick_count)
    assert ds["x1"].shape == (2, 3, res.trajectory.shape[2])
    assert ds.attrs["model"] == "white" and ds.attrs["seed_entropy"] == "11"
    np.testing.assert_allclose(ds["normal_force_n"].values, [5600.0, 8000.0])
    assert ds["sigma_zeta"].values[0] == pytest.approx(pre.process.std(350000.0))
    assert not list(tmp_path.glob("sub/.*tmp"))  # atomic write left nothing behind
    with pytest.raises(ValueError, match="not a stochfric"):
        (tmp_path / "other.nc").write_bytes(b"")
        import xarray as xr

        xr.Dataset({"a": ("x", [1.0])}).to_netcdf(tmp_path / "other.nc", engine="h5netcdf")
        load_result(tmp_path / "other.nc")


def test_event_buffer_overflow_is_reported() -> None:
    r = simulate(OscillatorParameters(gamma0=1.0, n=10.0), law=law_III(), output=OutputOptions(max_events=2))
    assert any("max_events" in w.message for w in r.warnings)
    assert r.stick_count[0, 0] == 6 and np.isfinite(r.x_gh[0, 0]).sum() == 2


@pytest.mark.parametrize("neighbour", ["forced", "constant-law"])
@pytest.mark.parametrize(("model", "integrator"), [("deterministic", "euler"), ("white", "euler"),
                                                   ("white", "milstein"), ("contact", "euler")])
def test_fast_passes_give_identical_numbers(model: str, integrator: str, neighbour: str) -> None:
    """The batch kernel's fast pass shares the arithmetic of the full step: an unforced lane gives
    the same bits alone (no forcing terms), in a group with forced lanes (with the forcing terms
    q cos x3 of kernels._forcing_terms) and in a group with a constant law (law II in the rational
    form p0/(1 + 0·v) + 0 + 0·v²).  (Contact: the fast pass reads μ̂ from per-lane segment caches, the
    full step gathers.)"""
    from stochfric.oscillator.friction_laws import law_II
    from stochfric.oscillator.kernels import LOCKSTEP

    p, pre = _brake(2720.0)
    runs = LOCKSTEP // 2
    other = p.replace(q=1e-4, eta=1.3) if neighbour == "forced" else p.replace(eta=0.5)  # a marker
    constant = law_II()

    def law(q: OscillatorParameters) -> object:
        return constant if (neighbour == "constant-law" and q.eta == 0.5) else _law(q)

    kw = dict(model=model, law=law, process=pre.process, runs=runs, seed=9,
              integration=IntegrationOptions(integrator=integrator, tau_end=20.0),
              output=OutputOptions(save_trajectory=True))
    alone = simulate([p], **kw, execution=ExecutionOptions(workers=1))
    # shares its lock-step group with `other`
    mixed = simulate([p, other], **kw, execution=ExecutionOptions(workers=1, batch_size=2 * runs))
    np.testing.assert_array_equal(alone.x_gh[0], mixed.x_gh[0])
    np.testing.assert_array_equal(alone.trajectory[0], mixed.trajectory[0])
    assert alone.stick_count.sum() > 0
    assert mixed.stick_count[1].sum() > 0


@pytest.mark.parametrize("model", ["deterministic", "white", "contact"])
def test_forced_ensembles_do_not_depend_on_the_grouping(model: str) -> None:
    """Forcing terms are computed once per distinct (q, x30, η) of neighbouring lanes and carried
    from step to step: the numbers of a forced multi-η ensemble are the same whether its
    trajectories share lock-step groups (default batches) or run one per batch."""
    p, pre = _brake(4000.0)
    sets = [p.replace(q=1e-4, eta=eta) for eta in (0.3, 0.9, 0.9, 1.7)] + [p]
    kw = dict(model=model, law=_law, process=pre.process, runs=7, seed=5,
              integration=IntegrationOptions(tau_end=30.0, dt=0.003),
              output=OutputOptions(save_trajectory=True, save_every=25))
    a = simulate(sets, **kw, execution=ExecutionOptions(workers=1))
    b = simulate(sets, **kw, execution=ExecutionOptions(workers=2, batch_size=1))
    np.testing.assert_array_equal(a.x_gh, b.x_gh)
    np.testing.assert_array_equal(a.trajectory, b.trajectory)
    assert a.stick_count.sum() > 0
