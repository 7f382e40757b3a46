"""The ``surface`` and ``contact`` commands through a local Typer app."""

from __future__ import annotations

import json
import os
from pathlib import Path

import numpy as np
import pytest
import typer
from typer.testing import CliRunner

from stochfric.cli.surface import parse_approach_um, parse_size_um, register
from stochfric.contact.asperity import ContactError, read_contact_result
from stochfric.surface.io import SurfaceError, default_surface_path

SHARED = Path(__file__).resolve().parents[2] / "shared" / "data" / "topographies"


@pytest.fixture(scope="module")
def app() -> typer.Typer:
    a = typer.Typer()
    register(a)
    return a


def _run(app: typer.Typer, *args: str) -> tuple[int, str, str]:
    result = CliRunner().invoke(app, list(args))
    return result.exit_code, result.stdout, result.stderr


def test_surface_json_on_default_surface(app: typer.Typer) -> None:
    code, out, _ = _run(app, "surface", "--json", "--material", "brake-pad")
    assert code == 0
    d = json.loads(out)
    assert d["grid"] == [200, 296]
    assert d["physical_size_m"] == pytest.approx([8.76054e-05, 1.29655992e-04])
    assert d["sq_m"] == pytest.approx(0.2898e-6, rel=1e-3)  # PROVENANCE.md, detrended
    assert d["raw_sq_m"] == pytest.approx(7.688e-6, rel=1e-3)
    assert d["n_summits"] > 100
    assert d["summit_height_std_m"] > 0 and d["summit_radius_mean_m"] > 0
    gamma = (
        d["material"]["e_star_pa"]
        / d["material"]["hardness_used_pa"]
        * (d["summit_height_std_m"] / d["summit_radius_mean_m"]) ** 0.5
    )
    assert d["plasticity_index"] == pytest.approx(gamma)
    assert d["plasticity_verdict"] == "elastic"
    assert d["preparation"]["default_surface"] is True
    assert d["preparation"]["sha256"].startswith("13a832361afb3489")
    assert d["fine"]["grid"] == [200, 296]


def test_surface_fine_vs_coarse_and_plots(app: typer.Typer, tmp_path: Path) -> None:
    code, out, _ = _run(
        app, "surface", str(default_surface_path()), "--step", "2", "--median-radius", "1",
        "--detrend", "quadratic", "--summit-rule", "8-neighbour", "--plot", str(tmp_path), "--json",
    )  # fmt: skip
    assert code == 0
    d = json.loads(out)
    assert d["grid"] == [100, 148]
    assert d["fine"]["grid"] == [200, 296]
    assert d["preparation"]["median_radius"] == 1
    assert d["preparation"]["detrend"] == "quadratic"
    assert d["preparation"]["summit_rule"] == "8-neighbour"
    assert "plasticity_index" not in d
    assert sorted(p.name for p in tmp_path.iterdir()) == [
        "fine_vs_coarse.png", "pdfs.png", "surface.png",
    ]  # fmt: skip


def test_surface_text_output(app: typer.Typer) -> None:
    code, out, _ = _run(app, "surface", "--material", "dc04")
    assert code == 0
    assert "grid 200x296" in out
    assert "plasticity index (dc04)" in out


def test_contact_json_on_default_surface(app: typer.Typer, tmp_path: Path) -> None:
    nc = tmp_path / "c.nc"
    code, out, _ = _run(app, "contact", "--material", "brake-pad", "--json", "--output", str(nc))
    assert code == 0
    d = json.loads(out)
    for key in ("approach_m", "contact_area_m2", "pressure_pa", "n_contacts", "mu"):
        assert len(d[key]) == 12
    assert d["preparation"]["detrend"] == "plane"
    assert d["preparation"]["step"] == 1
    assert np.all(np.diff(d["contact_area_m2"]) > 0)
    assert d["n_contacts"][0] >= 1
    back = read_contact_result(nc)
    np.testing.assert_allclose(back.mu, d["mu"])


def test_surface_and_contact_write_into_out_dir(app: typer.Typer, tmp_path: Path) -> None:
    """--out DIR everywhere (issue 32): the result files and the figures go there; --output is deprecated."""
    code, out, _ = _run(app, "surface", "--out", str(tmp_path / "s"))
    assert code == 0 and f"output    {tmp_path / 's' / 'surface.json'}" in out
    assert json.loads((tmp_path / "s" / "surface.json").read_text())["grid"] == [200, 296]
    assert (tmp_path / "s" / "surface.png").is_file()
    code, out, _ = _run(app, "contact", "--material", "brake-pad", "--approach-um", "0.3:0.6:2", "--out",
                        str(tmp_path / "c"))
    assert code == 0
    saved = json.loads((tmp_path / "c" / "contact.json").read_text())
    np.testing.assert_allclose(read_contact_result(tmp_path / "c" / "contact.nc").mu, saved["mu"])
    assert (tmp_path / "c" / "contact.png").is_file()
    code, _, err = _run(app, "contact", "--material", "brake-pad", "--approach-um", "0.3:0.6:2", "--output",
                        str(tmp_path / "x.nc"))
    assert code == 0 and "warning [deprecated-option]: --output FILE is deprecated; use --out DIR" in err
    code, _, err = _run(app, "contact", "--material", "brake-pad", "--output", str(tmp_path / "y.nc"), "--out",
                        str(tmp_path / "d"))
    assert code == 2 and err.startswith("error: give --out DIR")


def test_contact_explicit_range_and_text(app: typer.Typer) -> None:
    code, out, _ = _run(app, "contact", "--material", "dc04", "--approach-um", "0.1:0.8:8")
    assert code == 0
    assert out.count("\n") >= 10
    code, out, _ = _run(app, "contact", "--material", "dc04", "--approach-um", "0.1:0.8:8",
                        "--json")  # fmt: skip
    d = json.loads(out)
    np.testing.assert_allclose(d["approach_m"], np.linspace(0.1e-6, 0.8e-6, 8))
    assert d["preparation"]["approach"] == "given"


def test_contact_halfspace(app: typer.Typer, tmp_path: Path) -> None:
    pytest.importorskip("ContactMechanics")
    code, out, err = _run(
        app, "contact", "--material", "brake-pad", "--method", "halfspace", "--step", "4",
        "--approach-um", "0.2:0.6:3", "--json", "--plot", str(tmp_path),
    )  # fmt: skip
    assert code == 0, err
    d = json.loads(out)
    assert d["method"] == "halfspace"
    assert len(d["asperity"]["area_ratio_halfspace_to_asperity"]) == 3
    assert (tmp_path / "contact.png").is_file()


@pytest.mark.parametrize(
    ("args", "message"),
    [
        (["surface", "{garbage}"], "no SurfaceTopography reader"),
        (["surface", "{npy}"], "plain matrix without physical size and height unit"),
        (["surface", "{holes}", "--size-um", "100:100", "--height-unit", "um"], "undefined"),
        (["surface", "--step", "60"], "step 60 leaves"),
        (["surface", "--detrend", "cubic"], "unknown detrend mode"),
        (["surface", "{flat}", "--size-um", "100", "--height-unit", "um"], "no summit"),
        (["surface", "{missing}"], "no such file"),
        (["surface", "{line}"], "line scan"),
        (["contact", "--material", "steel"], "unknown material"),
        (["contact", "--material", "dc04", "--approach-um", "0:1:3"], "0 < START"),
        (["contact", "--material", "dc04", "--approach-um", "1:2"], "START:STOP:NUM"),
        (["contact", "{flat}", "--material", "dc04", "--size-um", "100:100", "--height-unit", "um"], "is flat"),
    ],
)
def test_bad_input_gives_one_line_and_exit_2(app: typer.Typer, tmp_path: Path, args: list[str], message: str) -> None:
    garbage = tmp_path / "garbage.bin"
    garbage.write_bytes(b"\x00\x01 not a topography " * 30)
    npy = tmp_path / "h.npy"
    np.save(npy, np.random.default_rng(0).normal(size=(20, 20)))
    holes = tmp_path / "holes.npy"
    h = np.random.default_rng(1).normal(size=(20, 20))
    h[3, 3] = np.nan
    np.save(holes, h)
    flat = tmp_path / "flat.npy"
    np.save(flat, np.zeros((20, 20)))
    line = tmp_path / "line.xyz"
    x = np.sort(np.random.default_rng(2).uniform(size=30))
    np.savetxt(line, np.c_[x, x**2])
    paths = {"garbage": garbage, "npy": npy, "holes": holes, "flat": flat, "line": line,
             "missing": tmp_path / "missing.x3p"}  # fmt: skip
    argv = [a.format(**paths) for a in args]
    code, out, err = _run(app, *argv)
    assert code == 2
    assert err.startswith("error: ")
    assert message in err
    assert err.count("\n") == 1  # one line, no traceback
    assert "Traceback" not in err + out


def test_fill_undefined_flag(app: typer.Typer, tmp_path: Path) -> None:
    holes = tmp_path / "holes.npy"
    h = np.random.default_rng(1).normal(size=(30, 30))
    h[3, 3] = np.nan
    np.save(holes, h)
    code, out, err = _run(app, "surface", str(holes), "--size-um", "100:100", "--height-unit",
                          "um", "--fill-undefined", "--json")  # fmt: skip
    assert code == 0, err
    d = json.loads(out)
    assert d["preparation"]["n_undefined_filled"] == 1
    assert d["physical_size_m"] == pytest.approx([1e-4, 1e-4])


@pytest.mark.skipif(not (SHARED / "opd-1.opd").is_file(), reason="shared topographies absent")
def test_instrument_file_with_undefined_points(app: typer.Typer) -> None:
    code, _, err = _run(app, "surface", str(SHARED / "opd-1.opd"))
    assert code == 2 and "--fill-undefined" in err


def test_parsers() -> None:
    np.testing.assert_allclose(parse_approach_um("1:12:12"), np.arange(1, 13) * 1e-6)
    assert parse_size_um("5300:5300") == pytest.approx((5.3e-3, 5.3e-3))
    assert parse_size_um("10") == pytest.approx((1e-5, 1e-5))
    with pytest.raises(ContactError):
        parse_approach_um("2:1:3")
    with pytest.raises(ContactError):
        parse_approach_um("1:2:0")
    with pytest.raises(SurfaceError):
        parse_size_um("a:b")
    with pytest.raises(SurfaceError):
        parse_size_um("1:-2")


# ---------------------------------------------------------------- every shared file (issue 9 §1, §6)

ALL_SHARED = ["al3d-1.al3d", "frt-1.frt", "mnt-1.mnt", "opd-1.opd", "plu-1.plu", "sur-2.sur", "x3p-2.x3p"]


def _shared(name: str) -> Path:
    path = SHARED / name
    if not path.is_file():
        if os.environ.get("CI"):
            pytest.fail(f"{path} is missing (CI is set: the shared instrument files must be present)")
        pytest.skip(f"{path} not available")
    return path


@pytest.mark.parametrize("name", ALL_SHARED)
def test_every_shared_file_runs_surface_and_contact(app: typer.Typer, name: str) -> None:
    """surface + contact (brake-pad, dc04) on each real file; the default range is sensible; frt-1, a
    part outline, is refused by both as not a rough surface."""
    path = str(_shared(name))
    code, out, err = _run(app, "surface", path, "--fill-undefined", "--material", "brake-pad", "--json")
    if name.startswith("frt-1"):
        assert code == 2 and "not a rough surface (part outline" in err
        code, out, err = _run(app, "contact", path, "--fill-undefined", "--material", "dc04", "--json")
        assert code == 2 and "not a rough surface" in err
        return
    assert code == 0, err
    s = json.loads(out)
    assert s["n_summits"] >= 10 and s["summit_height_std_m"] > 0
    assert isinstance(s["warnings"], list)
    for material in ("brake-pad", "dc04"):
        code, out, err = _run(app, "contact", path, "--fill-undefined", "--material", material, "--json")
        assert code == 0, err
        d = json.loads(out)
        mu = np.array(d["mu"], dtype=float)
        assert np.all(np.isfinite(mu)) and np.all(mu > 0)
        # the surface-derived default range starts at 20 contacts and ends inside the
        # non-interaction range (A_c/A_nom <= 0.1) or at half the summits
        assert d["n_contacts"][0] == 20 and d["n_contacts"][-1] > 20
        assert max(d["area_fraction"]) <= 0.1 * (1 + 1e-9)
        assert np.all(np.array(d["area_fraction"]) <= 1.0)
        codes = {w["code"] for w in d["warnings"]}
        # every warning is on stderr too, one line each
        assert err.count("warning: [") == len(d["warnings"])
        if material == "dc04" and d["plasticity_index"] > 1:
            assert "plastic" in codes


def test_contact_warnings_of_issue_9(app: typer.Typer) -> None:
    """plu-1 with the pad: μ ≫ 1; mnt-1 at approaches below its 20-contact default start: few contacts;
    the default surface pushed 100–200 µm: A_c > A_nom."""
    code, out, err = _run(app, "contact", str(_shared("plu-1.plu")), "--material", "brake-pad", "--json")
    assert code == 0
    d = json.loads(out)
    assert max(d["mu"]) > 1
    assert "mu-above-one" in {w["code"] for w in d["warnings"]}
    assert "warning: [mu-above-one] plu-1.plu: mu > 1" in err
    code, out, err = _run(app, "contact", str(_shared("mnt-1.mnt")), "--material", "brake-pad", "--json",
                          "--approach-um", "0.001:0.01:4")
    d = json.loads(out)
    few = [w for w in d["warnings"] if w["code"] == "few-contacts"]
    assert few and all(d["n_contacts"][i] < 10 for i in few[0]["indices"])
    code, out, err = _run(app, "contact", "--material", "brake-pad", "--approach-um", "100:200:3")
    assert code == 0
    assert "warning: [area-fraction-above-one]" in err
    assert "use smaller approaches" in err


def test_contact_rejects_a_corrupt_x3p_and_warns_on_a_corrupt_plu(app: typer.Typer, tmp_path: Path) -> None:
    data = bytearray(_shared("x3p-2.x3p").read_bytes())
    data[len(data) // 2] ^= 0xFF
    bad = tmp_path / "bad.x3p"
    bad.write_bytes(bytes(data))
    code, _, err = _run(app, "contact", str(bad), "--material", "dc04")
    assert code == 2 and "error: bad.x3p is corrupt" in err
    data = bytearray(_shared("plu-1.plu").read_bytes())
    for k in range(4):
        data[len(data) // 2 + k] ^= 0xFF
    bad = tmp_path / "bad.plu"
    bad.write_bytes(bytes(data))
    code, out, err = _run(app, "surface", str(bad), "--json")
    assert code == 0
    assert "warning: [implausible-spike] bad.plu" in err
    assert json.loads(out)["warnings"][0]["code"] == "implausible-spike"
