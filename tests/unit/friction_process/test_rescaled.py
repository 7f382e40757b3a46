"""The path-rescaled band-limited process of the white-limit study (issue 19): reference checks."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from stochfric.friction_process.band_limited import BandLimitedProcessModel
from stochfric.friction_process.rescaled import (
    FftBandLimitedProcessModel,
    band_correlation_length,
    low_frequency_psd,
    rescaled_process,
)
from stochfric.friction_process.spectral import one_sided_psd
from stochfric.oscillator.presets import brake, sheet

P = 1.7e5  # Pa (brake 2720 N on 0.016 m²)


def _plain(model: FftBandLimitedProcessModel) -> BandLimitedProcessModel:
    fields = {f.name: getattr(model, f.name) for f in dataclasses.fields(BandLimitedProcessModel)}
    return BandLimitedProcessModel(**fields)


@pytest.mark.parametrize("preset", [brake, sheet])
def test_fft_realisation_equals_the_spectral_sum(preset) -> None:  # type: ignore[no-untyped-def]
    m = rescaled_process(preset().process, 1e-4, 0.02)
    a = m.generate(P, np.random.default_rng(11))
    b = _plain(m).generate(P, np.random.default_rng(11))
    assert a.shape == (m.n_points,)
    np.testing.assert_allclose(a, b, rtol=0, atol=1e-12 * float(np.abs(b).max()))


def test_preset_correlation_lengths() -> None:
    # flat band of K = 39 harmonics over 0.05 m: ℓ = 0.05/(4·39); sheet K = 33, falling to 1/2: 0.02/(2·33·1.5)
    assert band_correlation_length(brake().process) == pytest.approx(0.05 / 156, rel=1e-12)
    assert band_correlation_length(sheet().process) == pytest.approx(0.02 / 99, rel=1e-12)


@pytest.mark.parametrize("preset", [brake, sheet])
@pytest.mark.parametrize("ell", [1e-3, 1e-4, 1e-5, 1e-6])
def test_rescaling_keeps_the_level_and_sets_the_correlation_length(preset, ell) -> None:  # type: ignore[no-untyped-def]
    base = preset().process
    m = rescaled_process(base, ell, 0.1)
    assert m.grid_is_periodic and m.length >= 0.1
    assert band_correlation_length(m) == pytest.approx(ell, rel=1e-12)
    for p in (1e5, 1e6):
        assert low_frequency_psd(m, p) == pytest.approx(low_frequency_psd(base, p), rel=1e-12)
        # S0 = 4 σ² ℓ: the variance grows as 1/ℓ
        assert m.variance(p) * 4 * ell == pytest.approx(low_frequency_psd(base, p), rel=1e-9)
        assert m.variance(p) / base.variance(p) == pytest.approx(band_correlation_length(base) / ell, rel=1e-9)
    assert m.mean(P) == base.mean(P) and m.spectrum_shape == base.spectrum_shape


@pytest.mark.parametrize("ell", [1e-3, 1e-5])
def test_a_realisation_has_the_level_and_variance(ell) -> None:  # type: ignore[no-untyped-def]
    """Amplitudes are deterministic (random phases only): the periodogram of one realisation at the
    band's lowest harmonic is S(f_1) and its grid variance is σ_ℓ², both exactly."""
    m = rescaled_process(sheet().process, ell, 0.05)
    x = m.generate(P, np.random.default_rng(3))
    f, s = one_sided_psd(x, m.dx)
    k = int(np.argmin(np.abs(f - 1.0 / m.length)))
    assert s[k] == pytest.approx(low_frequency_psd(m, P), rel=1e-8)
    assert float(np.mean(x**2)) == pytest.approx(m.variance(P), rel=1e-8)
    # the measured integral scale S(f_1)/(4 var) is ℓ
    assert s[k] / (4.0 * float(np.mean(x**2))) == pytest.approx(ell, rel=1e-8)


def test_level_factor_and_errors() -> None:
    base = brake().process
    m = rescaled_process(base, 1e-4, 0.01, level_factor=0.01)
    assert low_frequency_psd(m, P) == pytest.approx(0.01 * low_frequency_psd(base, P), rel=1e-12)
    for bad in (0.0, -1e-4, float("nan")):
        with pytest.raises(ValueError, match="correlation length"):
            rescaled_process(base, bad, 0.1)
    with pytest.raises(ValueError, match="process length"):
        rescaled_process(base, 1e-4, 0.0)
    with pytest.raises(ValueError, match="level factor"):
        rescaled_process(base, 1e-4, 0.1, level_factor=0.0)
    with pytest.raises(ValueError, match="grid points"):
        rescaled_process(base, 1e-9, 1.0)
    with pytest.raises(ValueError, match="length = n"):
        FftBandLimitedProcessModel(name="x", mu_mean=base.mu_mean, mu_std=base.mu_std, dx=0.3, length=1.0)
    assert m.to_dict()["evaluation"] == "fft"
