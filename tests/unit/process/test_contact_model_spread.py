"""μ at prescribed pressures by a choice of contact model and the spread between them (issue 31;
stochfric.process.contact_models)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from stochfric.contact.asperity import asperity_contact, default_approach_m
from stochfric.contact.bem import PERIMETER_CORRECTION
from stochfric.contact.materials import get_material
from stochfric.errors import AnalysisError
from stochfric.friction_process.model_function import ModelFunction
from stochfric.friction_process.tabulated import TabulatedProcessModel
from stochfric.process.analysis_config import AnalysisConfig
from stochfric.process.contact_models import (
    STATISTICAL_CONTACT_MODELS,
    LoadControl,
    contact_model_spread,
    gw_at_pressures,
    parse_contact_models,
    process_model_for,
)
from stochfric.process.ensemble import SurrogateOptions, ensemble_contact
from stochfric.random import as_seed_sequence, spawn_seed_sequences
from stochfric.surface.summits import summits_of
from synthetic_maps import as_surface, gaussian_heights  # tests/synthetic_maps.py

PAD = get_material("brake-pad")


@pytest.fixture(scope="module")
def surface():  # type: ignore[no-untyped-def]
    return as_surface(gaussian_heights((96, 96), 2.0, 3))


def test_parse_contact_models() -> None:
    assert parse_contact_models("all") == STATISTICAL_CONTACT_MODELS
    assert parse_contact_models("persson, GW") == ("gw", "persson")  # the report's order, any case
    assert parse_contact_models(["bem-plastic"]) == ("bem-plastic",)
    with pytest.raises(AnalysisError, match=r"unknown contact model.*'hertz'"):
        parse_contact_models("gw,hertz")
    with pytest.raises(AnalysisError, match="no contact model"):
        parse_contact_models(" , ")


def test_gw_at_pressures_inverts_the_approach_controlled_sums(surface) -> None:  # type: ignore[no-untyped-def]
    """Load control of GW: at the pressures GW gives at known approaches, the approaches and areas come back."""
    summits = summits_of(surface)
    u = default_approach_m(summits, num=6) * 1.013  # off the summit heights (the default grid sits on some)
    gw = asperity_contact(surface, summits, PAD, u)
    frac, count, u_back = gw_at_pressures(surface.heights_m, surface.grid_spacing_m, PAD, gw.pressure_pa,
                                          rule="thesis")
    np.testing.assert_allclose(u_back, u, rtol=1e-8)
    np.testing.assert_allclose(frac, gw.area_fraction, rtol=1e-7)
    np.testing.assert_array_equal(count, gw.n_contacts)


def test_surrogates_are_the_analysis_ensemble(surface) -> None:  # type: ignore[no-untyped-def]
    """The spread solves the very surrogates of analyse(): realisation r of the ensemble stream of the same seed.
    GW of realisation 1 at the pressure the approach-controlled ensemble gives it at u_k has μ of that ensemble."""
    cfg = AnalysisConfig(realizations=3, seed=11, surrogate="phase")
    u = default_approach_m(summits_of(surface), num=4)
    s_ens = spawn_seed_sequences(as_seed_sequence(11), 4)[0]
    ens = ensemble_contact(surface, PAD, u, realizations=3, seed=s_ens, options=SurrogateOptions(method="phase"))
    k = 2
    p_1 = float(ens.normal_force_n[1, k] / ens.nominal_area_m2)
    spread = contact_model_spread(surface, PAD, [p_1], "gw", cfg)
    assert spread.surrogates["gw"].mu[1, 0] == pytest.approx(float(ens.mu[1, k]), rel=1e-7)


def test_numbers_do_not_depend_on_workers(surface) -> None:  # type: ignore[no-untyped-def]
    cfg = AnalysisConfig(realizations=4, seed=5, surrogate="phase")
    a = contact_model_spread(surface, PAD, [1e6, 4e6], "gw,persson", cfg, workers=1)
    b = contact_model_spread(surface, PAD, [1e6, 4e6], "gw,persson", cfg, workers=2)
    for m in ("gw", "persson"):
        np.testing.assert_array_equal(a.surrogates[m].mu, b.surrogates[m].mu)
        np.testing.assert_array_equal(a.windows[m].mu, b.windows[m].mu)


def test_spread_statistics_and_split(surface) -> None:  # type: ignore[no-untyped-def]
    cfg = AnalysisConfig(realizations=6, seed=2, surrogate="phase")
    p = np.array([0.5e6, 1e6, 2e6, 4e6])
    s = contact_model_spread(surface, PAD, p, "gw,persson", cfg)
    gw, pe = s.surrogate_statistics("gw"), s.surrogate_statistics("persson")
    np.testing.assert_allclose(gw["mu_mean"], s.surrogates["gw"].mu.mean(axis=0))
    env = s.envelope()
    np.testing.assert_allclose(env["mu_max"], np.maximum(gw["mu_mean"], pe["mu_mean"]))
    split = s.uncertainty_split()
    np.testing.assert_allclose(split["model_half_width"], 0.5 * np.abs(gw["mu_mean"] - pe["mu_mean"]))
    share = split["model_share_of_variance"]
    assert np.all((share >= 0) & (share <= 1))
    # Persson: μ = τ κ/(E* ḡ) at small load, per sample
    from stochfric.contact.persson import PERSSON_KAPPA, rms_gradient

    frame = LoadControl().frame_for("thesis")
    assert frame == 2
    d = s.to_dict()
    assert d["models"] == ["gw", "persson"] and d["ratio_gw_to_bem"] is None
    assert d["per_model"]["persson"]["mean_contacts"] is None
    assert math.isfinite(d["plasticity_index"]) and d["recommended_models"]
    win = s.window_statistics("gw")
    assert win is not None and win["mu_mean_ci95"].shape == (4, 2)
    # one sample by hand: the Persson μ of the first measured window at the lowest pressure
    t = s.window_tiles
    assert t is not None
    n = surface.nb_grid_pts[0] // t
    h = surface.heights_m[:n, :n][frame:-frame, frame:-frame]
    g = rms_gradient(h, (h.shape[0] * 1e-6, h.shape[1] * 1e-6))
    x = math.sqrt(2) * p[0] / (PAD.e_star_pa * g)
    assert s.windows["persson"].mu[0, 0] == pytest.approx(PAD.shear_strength_pa * math.erf(x) / p[0], rel=1e-9)
    assert PERSSON_KAPPA == pytest.approx(math.sqrt(8 / math.pi))


def test_bad_pressures_and_hardness(surface) -> None:  # type: ignore[no-untyped-def]
    cfg = AnalysisConfig(realizations=2, seed=0, surrogate="phase")
    with pytest.raises(AnalysisError, match="pressures must be"):
        contact_model_spread(surface, PAD, [0.0, 1e6], "gw", cfg)
    with pytest.raises(AnalysisError, match="at or above the hardness"):
        contact_model_spread(surface, PAD, [1e6, 2 * PAD.hardness], "bem-plastic", cfg)
    with pytest.raises(AnalysisError, match="unknown boundary-element solver"):
        LoadControl(bem_solver="abaqus")


def test_bem_models_on_the_same_samples(surface, tmp_path) -> None:  # type: ignore[no-untyped-def]
    """The elastic boundary-element model carries the load on more area than GW at equal load (asperity
    interaction and the full elastic field; thesis Fig. 3.12–3.14, docs/contact_models.md), and the plastic cap
    never lowers the area."""
    pytest.importorskip("tamaas")
    cfg = AnalysisConfig(realizations=2, seed=4, surrogate="phase")
    s = contact_model_spread(surface, PAD, [1e6, 3e6], "gw,bem,bem-plastic", cfg)
    for m in ("bem", "bem-plastic"):
        assert np.all((s.surrogates[m].area_fraction > 0) & (s.surrogates[m].area_fraction < 1))
        assert np.all(s.surrogates[m].iterations >= 1)
    assert np.all(s.surrogates["bem-plastic"].area_fraction >= s.surrogates["bem"].area_fraction * (1 - 1e-6))
    # the pixel count carries the load on more area than GW; the perimeter correction (the default) takes off
    # less than a pixel per contact pixel, and on this coarse map (correlation length 2 points) about as much
    # as the count exceeds GW: GW/BEM 1.01-1.05 corrected (docs/contact_models.md)
    pixels = contact_model_spread(surface, PAD, [1e6, 3e6], "gw,bem", cfg, control=LoadControl(bem_area="pixels"))
    ratio = pixels.ratio("gw", "bem")
    assert ratio is not None and np.all(ratio < 1.0)
    counted, corrected = pixels.surrogates["bem"].area_fraction, s.surrogates["bem"].area_fraction
    assert np.all(corrected < counted) and np.all(corrected > counted * (1 - 4 * PERIMETER_CORRECTION))
    assert s.control.bem_area == "corrected" and pixels.control.bem_area == "pixels"
    # each keeps the other estimator's μ: the two runs hold the same pair, and the grid's share is half its gap
    np.testing.assert_allclose(s.surrogates["bem"].mu_other, pixels.surrogates["bem"].mu, rtol=1e-12)
    np.testing.assert_allclose(pixels.surrogates["bem"].mu_other, s.surrogates["bem"].mu, rtol=1e-12)
    half = s.uncertainty_split()["discretisation_half_width"]
    gap = 0.5 * (pixels.surrogates["bem"].mu.mean(axis=0) - s.surrogates["bem"].mu.mean(axis=0))
    assert half is not None and np.all(gap > 0)
    np.testing.assert_allclose(half, np.maximum(gap, 0.5 * np.abs(s.surrogates["bem-plastic"].mu.mean(axis=0)
                                                               - s.surrogates["bem-plastic"].mu_other.mean(axis=0))))
    assert s.surrogates["gw"].mu_other is None
    from stochfric.process.contact_models import ContactModelSpread
    from stochfric.process.pipeline import write_spread

    again = ContactModelSpread.load(write_spread(s, tmp_path, figures=False)["contact_models_file"])
    np.testing.assert_array_equal(again.surrogates["bem"].mu_other, s.surrogates["bem"].mu_other)
    assert again.surrogates["gw"].mu_other is None
    np.testing.assert_array_equal(again.uncertainty_split()["discretisation_half_width"], half)
    assert contact_model_spread(surface, PAD, [1e6], "gw", cfg).uncertainty_split()["discretisation_half_width"] \
        is None


def test_process_model_takes_the_chosen_model(surface) -> None:  # type: ignore[no-untyped-def]
    from stochfric.friction_process.model_function import ModelFunction

    cfg = AnalysisConfig(realizations=8, seed=3, surrogate="phase")
    p = np.geomspace(0.5e6, 5e6, 6)
    s = contact_model_spread(surface, PAD, p, "gw,persson", cfg)
    gw_model = TabulatedProcessModel(
        name="m", mu_mean=ModelFunction(a=0.0, b=1.0, c=0.4), mu_std=ModelFunction(a=0.0, b=1.0, c=0.05),
        dx=1e-5, length=1e-3, pressures_pa=(1e6, 3e6), table_frequencies=(1e3, 2e3, 3e3),
        table_psd=((1.0, 0.5, 0.2), (1.0, 0.5, 0.2)), fitted_range_pa=(1e6, 3e6))
    new, record = process_model_for(gw_model, s, "persson")
    pe = s.surrogate_statistics("persson")
    np.testing.assert_allclose([new.mu_mean(float(v)) for v in p], pe["mu_mean"], rtol=0.02)
    assert new.contact_model == "persson" and new.fitted_range_pa == (p.min(), p.max())
    assert TabulatedProcessModel.from_dict(new.to_dict()).contact_model == "persson"
    assert record["reference"] == "gw" and len(record["mu_mean_ratio_to_reference"]) == p.size
    same, rec = process_model_for(gw_model, s, "gw")
    assert same is gw_model and rec == {"contact_model": "gw"}


def test_the_path_at_three_pressures_holds_the_one_at_the_middle(surface) -> None:  # type: ignore[no-untyped-def]
    """The path per model is solved at the lowest, middle and highest pressure in one warm-started solve per
    window; its middle slice equals a path solved at that pressure alone (GW exactly, the boundary-element
    solution within its tolerance), and the model record checks the correlation length at each pressure."""
    pytest.importorskip("tamaas")
    cfg = AnalysisConfig(realizations=6, seed=4, surrogate="phase", long_surfaces=3, length_factor=2)
    p = np.geomspace(1e6, 8e6, 5)
    three = contact_model_spread(surface, PAD, p, "gw,bem", cfg, path_surfaces=2)
    for m in ("gw", "bem"):
        path = three.paths[m]
        np.testing.assert_allclose(path.pressures_pa, [1e6, np.sqrt(8e12), 8e6])
        assert path.mu.shape[0] == 2 and path.mu.shape[2] == 3 and path.pressure_pa == pytest.approx(np.sqrt(8e12))
    one = contact_model_spread(surface, PAD, p, "gw,bem", cfg, path_surfaces=2, path_pressure_pa=np.sqrt(8e12))
    np.testing.assert_allclose(three.paths["gw"].mu[:, :, 1], one.paths["gw"].mu[:, :, 0], rtol=1e-9)
    np.testing.assert_allclose(three.paths["bem"].mu[:, :, 1], one.paths["bem"].mu[:, :, 0], rtol=1e-3)
    assert one.paths["bem"].pressures_pa.size == 1
    gw_model = TabulatedProcessModel(
        name="m", mu_mean=ModelFunction(a=0.0, b=1.0, c=0.4), mu_std=ModelFunction(a=0.0, b=1.0, c=0.05),
        dx=1e-5, length=1e-3, pressures_pa=(1e6, 8e6), table_frequencies=(1e3, 2e3, 3e3),
        table_psd=((1.0, 0.5, 0.2), (1.0, 0.5, 0.2)), fitted_range_pa=(1e6, 8e6))
    _new, record = process_model_for(gw_model, three, "bem")
    assert [c["pressure_pa"] for c in record["path_check"]] == three.paths["bem"].pressures_pa.tolist()
    assert all(set(c["correlation_length_m"]) == {"gw", "bem"} for c in record["path_check"])
