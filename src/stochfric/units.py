"""Unit conversions at the boundaries (I/O, CLI, plots).  SI inside the package.

Only the few conversions the package needs; each is a multiplication by a named
constant so a reader sees the unit in the name (``MICROMETRE``, ``MEGAPASCAL``).
"""

from __future__ import annotations

from stochfric.errors import InputError

METRE = 1.0
MILLIMETRE = 1e-3
MICROMETRE = 1e-6
NANOMETRE = 1e-9
PASCAL = 1.0
KILOPASCAL = 1e3
MEGAPASCAL = 1e6
GIGAPASCAL = 1e9

_LENGTH = {"m": METRE, "mm": MILLIMETRE, "um": MICROMETRE, "µm": MICROMETRE, "nm": NANOMETRE}
_PRESSURE = {"Pa": PASCAL, "kPa": KILOPASCAL, "MPa": MEGAPASCAL, "GPa": GIGAPASCAL}


def length_to_m(value: float, unit: str) -> float:
    """Convert a length in ``unit`` (m, mm, um/µm, nm) to metres."""
    try:
        return float(value) * _LENGTH[unit]
    except KeyError:
        raise InputError(f"unknown length unit {unit!r}; use one of {sorted(_LENGTH)}") from None


def pressure_to_pa(value: float, unit: str) -> float:
    """Convert a pressure in ``unit`` (Pa, kPa, MPa, GPa) to pascal."""
    try:
        return float(value) * _PRESSURE[unit]
    except KeyError:
        raise InputError(f"unknown pressure unit {unit!r}; use one of {sorted(_PRESSURE)}") from None
