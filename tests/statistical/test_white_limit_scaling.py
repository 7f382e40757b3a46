"""σ(X_gh) of the contact model does not converge as the process's correlation length ℓ → 0 at a
fixed low-frequency level S0 (issue 19, docs/method.md §5.1a, docs/studies.md "White noise as the
limit of the contact process"): σ(X_gh) ∝ ℓ^β with β < 0.

The pinned values are the command's (``stochfric study white-limit``, seed 19, 300 runs):
brake 2720 N, relative path, ℓ = 1e-3 … 1e-5 m: β = −0.200 ± 0.013; S0/100, ℓ = 1e-3 … 1e-6 m:
β = −0.290 ± 0.010.  A rerun (another seed, another stream layout) must land within 3 SE.
"""

from __future__ import annotations

import pytest

from stochfric.studies.white_limit import WhiteLimitConfig, white_limit_study


def _beta(**kw):  # type: ignore[no-untyped-def]
    s = white_limit_study(WhiteLimitConfig(preset="brake", normal_force=2720.0, **kw)).summary
    return s.fit.beta, s.fit.beta_se_reported, s


def test_fast_small_version_sigma_grows_as_l_shrinks() -> None:
    """100 runs, S0/100 (all ℓ far above ℓ* ≈ 5e-8 m), ℓ = 1e-3, 1e-4, 1e-5 m: a few seconds."""
    beta, se, s = _beta(correlation_lengths=(1e-3, 1e-4, 1e-5), runs=100, level_factor=0.01, seed=3)
    assert beta + 3 * se < 0.0, s.fit
    assert abs(beta - (-0.290)) <= 3 * se + 3 * 0.010, s.fit
    for row in s.table:
        # the time step is converged: Δτ and Δτ/4 agree within 3 SE of σ
        assert abs(row.std_difference_over_se) <= 3.0
        assert row.fine.max_path_over_length < 1.0


@pytest.mark.slow
def test_brake_exponent_at_the_preset_level() -> None:
    beta, se, s = _beta(correlation_lengths=(1e-3, 3e-4, 1e-4, 3e-5, 1e-5), runs=300, seed=23)
    assert abs(beta - (-0.200)) <= 3 * max(se, 0.013), s.fit
    assert beta + 3 * se < 0.0


@pytest.mark.slow
def test_brake_exponent_at_a_hundredth_of_the_level() -> None:
    beta, se, s = _beta(correlation_lengths=(1e-3, 1e-4, 1e-5, 1e-6), runs=300, level_factor=0.01, seed=23)
    assert abs(beta - (-0.290)) <= 3 * max(se, 0.010), s.fit
    assert beta + 3 * se < 0.0
    # σ(X_gh) is linear in √S0: at ℓ = 1e-3 m a tenth of the preset level's 2.06e-4
    assert s.table[0].fine.x_gh_std == pytest.approx(2.06e-5, rel=0.1)
