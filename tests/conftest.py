"""Shared test configuration."""

from __future__ import annotations

import os

os.environ.setdefault("MPLBACKEND", "Agg")

from pathlib import Path

import pytest

#: The real measured topographies (../shared/data/topographies beside the checkout).
SHARED_TOPOGRAPHIES = Path(__file__).resolve().parents[2] / "shared" / "data" / "topographies"

#: Every shared file and whether it has undefined points (PROVENANCE.md).
SHARED_FILES: dict[str, bool] = {
    "al3d-1.al3d": False,
    "frt-1.frt": True,
    "mnt-1.mnt": False,
    "opd-1.opd": True,
    "plu-1.plu": False,
    "sur-2.sur": True,
    "x3p-2.x3p": False,
}


def _shared_file(name: str) -> Path:
    """Path of a shared topography; skip without ../shared, but FAIL under CI (CI has it)."""
    path = SHARED_TOPOGRAPHIES / name
    if not path.is_file():
        if os.environ.get("CI"):
            pytest.fail(f"{path} is missing: CI must run with ../shared beside the checkout")
        pytest.skip(f"shared topographies not found at {SHARED_TOPOGRAPHIES}")
    return path


@pytest.fixture(scope="session")
def shared_file() -> object:
    """``shared_file(name) -> Path`` of a shared topography (fails under CI when missing)."""
    return _shared_file


@pytest.fixture(scope="session")
def shared_files() -> dict[str, bool]:
    """Every shared file name → whether it has undefined points."""
    return dict(SHARED_FILES)


def pytest_sessionstart(session: pytest.Session) -> None:
    """Under CI (env CI set) the real topographies must be there: no test may skip silently."""
    if os.environ.get("CI") and not (SHARED_TOPOGRAPHIES / "PROVENANCE.md").is_file():
        pytest.exit(
            f"CI runs with ../shared beside the checkout, but {SHARED_TOPOGRAPHIES} is missing: "
            "the real-data tests would skip silently",
            returncode=1,
        )
