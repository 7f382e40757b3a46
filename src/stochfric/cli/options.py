"""What the commands share: the choices offered on the command line and the one-line error exit.

Each choice is one :class:`~enum.StrEnum` (typer shows its values and refuses others); the values
are the names the library uses (glossary: docs/glossary.md).
"""

from __future__ import annotations

from enum import StrEnum

import typer

__all__ = [
    "AmplitudeChoice", "IntegratorChoice", "LawChoice", "MethodChoice", "ModelChoice", "PathChoice",
    "PresetChoice", "PressureRuleChoice", "ProcessLevelChoice", "SigmaZetaChoice", "SummitRuleChoice",
    "SurrogateChoice", "VarianceRuleChoice", "WhiteIntensityChoice", "fail",
]  # fmt: skip

# simulate (method §5)
ModelChoice = StrEnum("ModelChoice", "deterministic white contact")
LawChoice = StrEnum("LawChoice", [("I", "I"), ("II", "II"), ("III", "III"), ("pressure", "pressure")])
IntegratorChoice = StrEnum("IntegratorChoice", "euler accurate milstein")
PresetChoice = StrEnum("PresetChoice", "brake sheet")
WhiteIntensityChoice = StrEnum("WhiteIntensityChoice", "sigma_mu spectral_level thesis")
ProcessLevelChoice = StrEnum("ProcessLevelChoice", "sigma_mu psd_level")
PathChoice = StrEnum("PathChoice", "mass relative position")
# surface, contact (method §1–§2)
SummitRuleChoice = StrEnum("SummitRuleChoice", [("thesis", "thesis"), ("eight", "8-neighbour")])
MethodChoice = StrEnum("MethodChoice", "asperity halfspace")
# friction-process (method §3–§4)
SurrogateChoice = StrEnum("SurrogateChoice", "phase iaaft")
AmplitudeChoice = StrEnum("AmplitudeChoice", "tukey hann raw")  # surface.synthesis.amplitude_spectrum
PressureRuleChoice = StrEnum("PressureRuleChoice", "nearest interpolate")  # spectrum between analysed p
VarianceRuleChoice = StrEnum("VarianceRuleChoice", "sigma_mu tabulated")
SigmaZetaChoice = StrEnum("SigmaZetaChoice", "sigma_mu spectral_level")


def fail(message: str) -> typer.Exit:
    """Print ``error: message`` on stderr and return the exit to raise (status 2)."""
    typer.echo(f"error: {message}", err=True)
    return typer.Exit(code=2)
