"""Reading measured height maps (method §1, thesis 3.2 / 3.3).

Instrument files (every format SurfaceTopography knows) are read through
:func:`SurfaceTopography.open_topography`; so are ``.txt`` files with a header SurfaceTopography's
text reader understands (size, unit, height conversion factor).  Plain matrices (``.npy``, ``.csv``,
``.txt`` without such a header) need their physical size and height unit given.  A :class:`Surface`
holds heights in metres, ``z[i, j]`` at ``x = i Δx``, ``y = j Δy`` with ``Δx = ℓx / nx``, and never a
NaN: undefined points are reported and filled by harmonic interpolation or refused.  Checksums (x3p)
and a plausibility check guard against corrupted files (docs/surface_contact.md, "Reading").
"""

from __future__ import annotations

import hashlib
import math
import re
import warnings
from dataclasses import dataclass, field
from importlib import resources
from pathlib import Path
from typing import Any

import numpy as np
import numpy.typing as npt

from stochfric.arrays import FloatArray
from stochfric.errors import InputError
from stochfric.io_utils import regular_file
from stochfric.units import length_to_m

__all__ = [
    "DEFAULT_SURFACE_NAME",
    "HEADER_TEXT_SUFFIXES",
    "MATRIX_SUFFIXES",
    "MIN_GRID_POINTS",
    "SPIKE_SQ",
    "Surface",
    "SurfaceError",
    "default_surface_path",
    "file_sha256",
    "plausibility_warnings",
    "read_surface",
    "surface_from_array",
    "verify_checksums",
]

#: File name of the measured surface shipped with the package (see ``data/NOTICE.md``).
DEFAULT_SURFACE_NAME = "al3d-1.al3d"

#: Suffixes read as plain height matrices with numpy (size and unit must be given), unless the
#: file is one of :data:`HEADER_TEXT_SUFFIXES` and carries a header SurfaceTopography reads.
MATRIX_SUFFIXES = (".npy", ".txt", ".csv")

#: Matrix suffixes first offered to SurfaceTopography's text reader (format ``asc``, which claims
#: ``.txt``, ``.asc``, ``.dat``; the last two always go through SurfaceTopography).  If that reader
#: finds a physical size, a unit or a height conversion factor in the file, the file is read by it
#: (an instrument file); otherwise it is a plain matrix for numpy.  ``.csv`` (comma separated) and
#: ``.npy`` are never offered: SurfaceTopography's text reader splits on whitespace.
HEADER_TEXT_SUFFIXES = (".txt",)

#: SurfaceTopography format identifier of its header-parsing text reader (``AscReader``).
_TEXT_READER_FORMAT = "asc"

#: The summit rule needs two neighbours on each side, so a grid needs at least 5 points.
MIN_GRID_POINTS = 5

#: A point more than this many Sq outside the range of the 3×3-median map is a spike.
SPIKE_SQ = 20.0


class SurfaceError(InputError):
    """Bad surface input: unreadable file, missing size or unit, undefined points, a
    non-uniform grid, a preparation that leaves too few points, no summit.

    The message is one line and says what to change; the command line prints it and
    exits with status 2.
    """


@dataclass(frozen=True, kw_only=True, eq=False)
class Surface:
    """A height map on a uniform grid, SI units.

    Attributes
    ----------
    heights_m:
        ``z[i, j]`` [m], shape ``(nx, ny)``, finite everywhere.
    physical_size_m:
        ``(ℓx, ℓy)`` [m]; the nominal area is ``A_nom = ℓx ℓy`` (3.14).
    source:
        Where the data came from (a file path or a description).
    n_undefined_filled:
        Number of undefined points that were filled by harmonic interpolation on reading.
    info:
        Free-form provenance (reader, instrument, sha256 of the file, …), JSON-serialisable.
    """

    heights_m: FloatArray
    physical_size_m: tuple[float, float]
    source: str = "array"
    n_undefined_filled: int = 0
    info: dict[str, Any] = field(default_factory=dict)

    def __repr__(self) -> str:
        h = np.asarray(self.heights_m)
        nx, ny = h.shape
        lx, ly = (v * 1e6 for v in self.physical_size_m)
        sq = float(np.std(h)) * 1e6
        return (f"Surface({Path(str(self.source)).name}: {nx} × {ny} points, {lx:.4g} × {ly:.4g} µm, "
                f"Sq = {sq:.4g} µm as stored (form and tilt not removed: prepare() levels it), "
                f"{self.n_undefined_filled} undefined points filled)")

    def __post_init__(self) -> None:
        h = np.asarray(self.heights_m)
        if h.ndim != 2:
            raise SurfaceError(f"a surface needs a 2-D height map, got {h.ndim} dimension(s)")
        if not np.issubdtype(h.dtype, np.number):
            raise SurfaceError(f"heights must be numbers, got dtype {h.dtype}")
        if not np.all(np.isfinite(h)):
            raise SurfaceError(
                f"{int(np.count_nonzero(~np.isfinite(h)))} height(s) are NaN or infinite; "
                "fill them (fill_undefined) before building a Surface"
            )
        if len(self.physical_size_m) != 2:
            raise SurfaceError(f"physical_size_m needs two lengths, got {self.physical_size_m!r}")
        for name, v in zip(("x", "y"), self.physical_size_m, strict=True):
            if not (math.isfinite(float(v)) and float(v) > 0.0):
                raise SurfaceError(f"physical size in {name} must be > 0 m, got {v!r}")
        h = np.ascontiguousarray(h, dtype=np.float64)
        h.setflags(write=False)
        object.__setattr__(self, "heights_m", h)
        object.__setattr__(
            self,
            "physical_size_m",
            (float(self.physical_size_m[0]), float(self.physical_size_m[1])),
        )

    @property
    def nb_grid_pts(self) -> tuple[int, int]:
        """Number of grid points ``(nx, ny)``."""
        nx, ny = self.heights_m.shape
        return int(nx), int(ny)

    @property
    def grid_spacing_m(self) -> tuple[float, float]:
        """Grid spacing ``(Δx, Δy) = (ℓx/nx, ℓy/ny)`` [m]."""
        nx, ny = self.nb_grid_pts
        return self.physical_size_m[0] / nx, self.physical_size_m[1] / ny

    @property
    def nominal_area_m2(self) -> float:
        """Nominal (apparent) area ``A_nom = ℓx ℓy`` [m²] (3.14)."""
        return self.physical_size_m[0] * self.physical_size_m[1]


def default_surface_path() -> Path:
    """Path of the measured surface shipped with the package (``stochfric/data``).

    An Alicona focus-variation measurement (``al3d-1.al3d`` of the SurfaceTopography test
    fixtures, MIT licence, see ``stochfric/data/NOTICE.md``).
    """
    ref = resources.files("stochfric") / "data" / DEFAULT_SURFACE_NAME
    path = Path(str(ref))
    if not path.is_file():  # pragma: no cover - only for a broken installation
        raise SurfaceError(f"the default surface {DEFAULT_SURFACE_NAME} is missing from the package")
    return path


def file_sha256(path: str | Path) -> str:
    """Hex sha256 of a file's bytes (recorded as provenance)."""
    digest = hashlib.sha256()
    with open(path, "rb") as fh:
        for chunk in iter(lambda: fh.read(1 << 20), b""):
            digest.update(chunk)
    return digest.hexdigest()


def surface_from_array(
    heights: npt.ArrayLike,
    *,
    physical_size_m: tuple[float, float],
    fill_undefined: bool = False,
    source: str = "array",
    info: dict[str, Any] | None = None,
) -> Surface:
    """Build a :class:`Surface` from heights in metres; NaN / masked entries are undefined.

    Undefined points are refused with a :class:`SurfaceError` unless ``fill_undefined`` is
    set, in which case they are filled by harmonic interpolation (SurfaceTopography).
    """
    masked = np.ma.masked_invalid(np.ma.asarray(heights, dtype=np.float64))
    return _finish(
        masked,
        physical_size_m=physical_size_m,
        fill_undefined=fill_undefined,
        source=source,
        info=dict(info or {}),
    )


def read_surface(
    path: str | Path,
    *,
    physical_size_m: tuple[float, float] | None = None,
    height_unit: str | None = None,
    fill_undefined: bool = False,
    channel: int | None = None,
) -> Surface:
    """Read a measured height map from ``path`` and convert it to metres.

    Parameters
    ----------
    path:
        An instrument file (any format of SurfaceTopography) or a plain matrix
        (``.npy``, ``.txt`` whitespace separated, ``.csv`` comma separated).  A ``.txt`` file
        whose header gives a size, a unit or a height conversion factor that SurfaceTopography's
        text reader understands (``# Width: 10 um``, ``# Height: 12 um``, ``# Value units: nm``,
        ``# height conversion factor (-> nm) = 0.5``, Gwyddion/SPIP/Nova/Wyko headers) is read
        by that reader, in its layout (each line of the file is one ``y``, values run along
        ``x``); a ``.txt`` file without one is a plain matrix (line ``i`` is ``x = iΔx``).
    physical_size_m:
        ``(ℓx, ℓy)`` [m]. Required for plain matrices and for instrument files that do not
        store it; refused for files that store it.
    height_unit:
        Unit of the stored heights (``m``, ``mm``, ``um``, ``nm``), optionally with a conversion
        factor, ``FACTOR*UNIT`` (``"0.5*nm"``: each stored value × 0.5 is a height in nm;
        :func:`parse_height_unit`). Required for plain
        matrices and for instrument files without a unit; refused for files that store one
        (SurfaceTopography does not let metadata fixed by the file be overridden).
    fill_undefined:
        Fill undefined (unmeasured) points by harmonic interpolation instead of refusing them.
    channel:
        Channel index for multi-channel files (default: the file's default channel).

    Raises
    ------
    SurfaceError
        Unknown, missing or corrupt file; non-uniform or 1-D data; missing size or unit;
        undefined points without ``fill_undefined``.
    """
    p = _readable_map_file(Path(path))
    info: dict[str, Any] = {"file": p.name, "sha256": file_sha256(p)}
    suffix = p.suffix.lower()
    text_reader = _text_reader_with_header(p) if suffix in HEADER_TEXT_SUFFIXES else None
    if suffix in MATRIX_SUFFIXES and text_reader is None:
        surface = _read_matrix(
            p,
            physical_size_m=physical_size_m,
            height_unit=height_unit,
            fill_undefined=fill_undefined,
            info=info,
        )
    else:
        info["checksum"] = verify_checksums(p)
        surface = _read_instrument(
            p,
            physical_size_m=physical_size_m,
            height_unit=height_unit,
            fill_undefined=fill_undefined,
            channel=channel,
            info=info,
            reader=text_reader,
        )
    surface.info["warnings"] = plausibility_warnings(surface.heights_m, name=p.name)
    return surface


#: The largest height-map file read [bytes]: 4 GiB (a 20000² map of float64 is 3.2 GB); larger is refused
#: before any read, with what to do.
MAX_MAP_FILE_BYTES = 4 * 1024**3


def _readable_map_file(p: Path) -> Path:
    """``p`` if it is a regular, non-empty file of at most :data:`MAX_MAP_FILE_BYTES`; else a SurfaceError that
    says which (checked before any reader opens it: a device or a pipe would block or never end)."""
    try:
        regular_file(p)
    except FileNotFoundError:
        raise SurfaceError(f"no such file: {p}") from None
    except IsADirectoryError:
        raise SurfaceError(f"{p} is a directory; give a height-map file") from None
    except OSError as exc:
        raise SurfaceError(f"{p} is {exc.strerror or exc}; give a height-map file") from None
    size = p.stat().st_size
    if size == 0:
        raise SurfaceError(f"{p} is empty (0 bytes); give a height-map file")
    if size > MAX_MAP_FILE_BYTES:
        raise SurfaceError(f"{p} is {size / 1024**3:.1f} GiB, more than the {MAX_MAP_FILE_BYTES / 1024**3:.0f} GiB a "
                           "height map read here may have; crop or subsample it with the instrument's software")
    return p


def verify_checksums(path: str | Path) -> str:
    """Verify the checksums a file format carries; return what was checked.

    ``.x3p`` (ISO 5436-2): the zip CRC-32 of every entry, the MD5 of the binary point data
    against ``MD5ChecksumPointData`` in ``main.xml`` and the MD5 of ``main.xml`` against
    ``md5checksum.hex`` (where present).  Other formats carry no checksum: ``"none"``.

    Raises
    ------
    SurfaceError
        A checksum does not match (the file is corrupt); the message names the file.
    """
    p = Path(path)
    if p.suffix.lower() != ".x3p":
        return "none"
    import re
    import zipfile

    try:
        with zipfile.ZipFile(p) as zf:
            bad = zf.testzip()  # reads every entry and checks its CRC-32
            if bad is not None:
                raise SurfaceError(f"{p.name} is corrupt: the CRC-32 of its entry {bad!r} does not match")
            names = set(zf.namelist())
            main = zf.read("main.xml") if "main.xml" in names else None
            checked = ["zip CRC-32"]
            if main is not None and "md5checksum.hex" in names:
                expected = zf.read("md5checksum.hex").decode("ascii", "replace").split()
                if expected and expected[0].lower() != hashlib.md5(main).hexdigest():
                    raise SurfaceError(f"{p.name} is corrupt: the MD5 of main.xml does not match md5checksum.hex")
                checked.append("main.xml MD5")
            if main is not None:
                text = main.decode("utf-8", "replace")
                link = re.search(r"<PointDataLink>\s*([^<]+?)\s*</PointDataLink>", text)
                md5 = re.search(r"<MD5ChecksumPointData>\s*([0-9A-Fa-f]{32})\s*</MD5ChecksumPointData>", text)
                if link and md5 and link.group(1) in names:
                    if hashlib.md5(zf.read(link.group(1))).hexdigest() != md5.group(1).lower():
                        raise SurfaceError(
                            f"{p.name} is corrupt: the MD5 of its point data ({link.group(1)}) does not "
                            "match MD5ChecksumPointData in main.xml"
                        )
                    checked.append("point-data MD5")
    except SurfaceError:
        raise
    except (zipfile.BadZipFile, OSError, KeyError, EOFError) as exc:  # zlib errors are OSError-like
        raise SurfaceError(f"{p.name} is corrupt: {_one_line(exc)}") from None
    except Exception as exc:  # zlib.error and friends: any failure to decompress is corruption
        raise SurfaceError(f"{p.name} is corrupt: {_one_line(exc)}") from None
    return ", ".join(checked)


def plausibility_warnings(
    heights_m: npt.ArrayLike, *, name: str = "the height map", spike_sq: float = SPIKE_SQ
) -> list[dict[str, Any]]:
    """Plausibility check of a height map [m]: isolated spikes, as warnings (docs/surface_contact.md).

    A point is a spike when its plane-detrended height lies more than ``spike_sq`` × Sq above
    the maximum or below the minimum of the 3×3-median-filtered, plane-detrended map (Sq: RMS
    of the plane-detrended map).  Returns a list of ``{"code", "message", ...}`` dictionaries
    (empty when the map is plausible).
    """
    from scipy import ndimage

    z = np.asarray(heights_m, dtype=np.float64)
    if z.ndim != 2 or min(z.shape) < 3:
        return []
    if not np.all(np.isfinite(z)):
        n_bad = int(np.count_nonzero(~np.isfinite(z)))
        return [{"code": "non-finite-heights", "count": n_bad,
                 "message": f"{name}: {n_bad} height(s) are NaN or infinite; the file is corrupt "
                            "or has undefined points (--fill-undefined)"}]  # fmt: skip
    nx, ny = z.shape
    ii, jj = np.meshgrid(np.arange(nx, dtype=np.float64), np.arange(ny, dtype=np.float64), indexing="ij")
    design = np.stack([np.ones(z.size), ii.ravel(), jj.ravel()], axis=1)
    with np.errstate(all="ignore"):
        coef, *_ = np.linalg.lstsq(design, z.ravel(), rcond=None)
        r = z - (design @ coef).reshape(z.shape)
        sq = float(np.sqrt(np.mean(r * r)))
    if not (math.isfinite(sq) and sq > 0.0):
        return []
    m = ndimage.median_filter(r, size=3, mode="nearest")
    excess = np.maximum(r - m.max(), m.min() - r) / sq
    spikes = excess > spike_sq
    n = int(np.count_nonzero(spikes))
    if n == 0:
        return []
    worst = float(excess.max())
    i, j = (int(v) for v in np.unravel_index(int(np.argmax(excess)), z.shape))
    return [
        {
            "code": "implausible-spike",
            "count": n,
            "worst_excess_sq": worst,
            "worst_index": [i, j],
            "message": (
                f"{name}: {n} isolated spike(s) more than {spike_sq:g} Sq outside the height range "
                f"of the 3x3-median-filtered map (worst {worst:.3g} Sq at point ({i}, {j})); the "
                "file may be corrupt - check it against the instrument's original, or remove the "
                "spikes (--median-radius 1) before trusting Sq, summits or mu"
            ),
        }
    ]


# --------------------------------------------------------------------------------------
# internals


def parse_height_unit(text: str) -> tuple[float, str]:
    """``"nm"`` → ``(1.0, "nm")``; ``"0.5*nm"`` or ``"0.5 nm"`` → ``(0.5, "nm")``: a height unit with an
    optional conversion factor (each stored value × factor is a height in the unit; e.g. an instrument
    that stores volts or radians).  SurfaceError for a factor that is not a positive finite number or an
    unknown unit."""
    raw = str(text).strip()
    m = re.fullmatch(r"(?P<f>[-+0-9.eE]+)\s*(?:\*\s*|\s+)(?P<u>\S+)", raw)
    if m is None:
        if "*" in raw:
            raise SurfaceError(f"height unit {raw!r}: write FACTOR*UNIT with a positive number and a length unit, "
                               "e.g. 0.5*nm")
        _unit_factor(raw, "height unit")
        return 1.0, raw
    try:
        factor = float(m.group("f"))
    except ValueError:
        raise SurfaceError(f"height unit {raw!r}: {m.group('f')!r} is not a number; write FACTOR*UNIT, e.g. "
                           "0.5*nm") from None
    if not (math.isfinite(factor) and factor > 0.0):
        raise SurfaceError(f"height unit {raw!r}: the conversion factor must be a positive finite number "
                           f"(got {factor:g})")
    _unit_factor(m.group("u"), "height unit")
    return factor, m.group("u")


def _unit_factor(unit: str, what: str) -> float:
    try:
        return length_to_m(1.0, unit)
    except ValueError as exc:
        raise SurfaceError(f"{what}: {exc}") from None


def _text_reader_with_header(p: Path) -> Any:
    """SurfaceTopography's text reader on ``p`` if it finds a size, a unit or a height conversion
    factor in the file (any channel); ``None`` for a plain matrix or a file that reader cannot read
    (the numpy reader then decides, with today's messages).  The header is parsed by SurfaceTopography
    only: whatever its text reader understands counts, nothing else."""
    from SurfaceTopography import open_topography

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        try:
            reader = open_topography(str(p), format=_TEXT_READER_FORMAT)
            channels = list(reader.channels)
        except Exception:  # not a text matrix SurfaceTopography reads: a case for numpy
            return None
    for ch in channels:
        if (ch.physical_sizes is not None or ch.unit is not None
                or getattr(ch, "height_scale_factor", None) is not None):  # fmt: skip
            return reader
    return None


def _raw_lateral_units(reader: Any, ch: Any) -> tuple[str, str] | None:
    """Lateral units ``(x, y)`` of the physical size a SurfaceTopography *text* file stores without
    a height unit (``# Width: 10 um`` but no ``# Value units``): its text reader then leaves the
    size in those units and reports no unit.  ``None`` for other readers or a size without a unit."""
    from SurfaceTopography.IO.Text import AscReader

    if not isinstance(reader, AscReader):
        return None
    raw = (getattr(ch, "info", None) or {}).get("raw_metadata") or {}
    ux, uy = raw.get("xunit"), raw.get("yunit")
    if ux is None and uy is None:
        return None
    ux = ux if ux is not None else uy  # one lateral unit applies to both directions (as SurfaceTopography)
    uy = uy if uy is not None else ux
    return str(AscReader._normalize_unit(str(ux))), str(AscReader._normalize_unit(str(uy)))  # e.g. μm -> µm


def _read_matrix(
    p: Path,
    *,
    physical_size_m: tuple[float, float] | None,
    height_unit: str | None,
    fill_undefined: bool,
    info: dict[str, Any],
) -> Surface:
    missing = [
        name for name, value in (("physical size", physical_size_m), ("height unit", height_unit)) if value is None
    ]
    if missing:
        raise SurfaceError(
            f"{p.name} is a plain matrix without {' and '.join(missing)}; "
            "give them explicitly (command line: --size-um LX:LY --height-unit UNIT)"
        )
    assert physical_size_m is not None and height_unit is not None
    scale, base_unit = parse_height_unit(height_unit)
    factor = scale * _unit_factor(base_unit, "height unit")
    try:
        if p.suffix.lower() == ".npy":
            raw = np.load(p, allow_pickle=False)
        else:
            delimiter = "," if p.suffix.lower() == ".csv" else None
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                raw = np.genfromtxt(p, delimiter=delimiter, dtype=np.float64, comments="#")
    except Exception as exc:  # any reader failure is a corrupt file for the user
        raise SurfaceError(f"cannot read {p.name} as a height matrix: {_one_line(exc)}") from None
    raw = np.asarray(raw)
    if raw.ndim != 2 or min(raw.shape) < 2:
        raise SurfaceError(
            f"{p.name} does not hold a 2-D height matrix (shape {raw.shape}); "
            "line scans and xyz point lists are not supported"
        )
    if not np.issubdtype(raw.dtype, np.number):
        raise SurfaceError(f"{p.name} holds {raw.dtype} data, not heights")
    if np.iscomplexobj(raw):
        raise SurfaceError(f"{p.name} holds complex numbers; heights are real (save the real part, or the "
                           "modulus if that is what was measured)")
    info.update({"reader": "numpy", "height_unit": base_unit, "height_conversion_factor": scale})
    return surface_from_array(
        raw.astype(np.float64) * factor,
        physical_size_m=physical_size_m,
        fill_undefined=fill_undefined,
        source=str(p),
        info=info,
    )


def _read_instrument(
    p: Path,
    *,
    physical_size_m: tuple[float, float] | None,
    height_unit: str | None,
    fill_undefined: bool,
    channel: int | None,
    info: dict[str, Any],
    reader: Any = None,
) -> Surface:
    """Read ``p`` through SurfaceTopography (``reader``: an already opened reader of ``p``, else the
    format is detected).  Size, unit and height conversion factor stored in the file are used and
    recorded in ``info``; ``physical_size_m`` / ``height_unit`` complete what the file lacks and are
    refused for what it stores."""
    # Imported here: SurfaceTopography registers its readers at import time, and importing
    # stochfric should do no work.
    from SurfaceTopography import open_topography
    from SurfaceTopography.Exceptions import CannotDetectFileFormat

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        if reader is None:
            try:
                reader = open_topography(str(p))
            except CannotDetectFileFormat:
                raise SurfaceError(
                    f"cannot read {p.name}: no SurfaceTopography reader recognises this file "
                    "(unknown format or corrupt file)"
                ) from None
            except Exception as exc:
                raise SurfaceError(f"cannot read {p.name}: {_one_line(exc)}") from None
        channels = reader.channels
        if channel is None:
            ch = reader.default_channel
        else:
            if not 0 <= channel < len(channels):
                raise SurfaceError(f"{p.name} has {len(channels)} channel(s); channel {channel} does not exist")
            ch = channels[channel]
        uniform = getattr(ch, "is_uniform", True) is not False
        if ch.dim != 2:
            kind = "line scan" if uniform else "non-uniform line scan"
            raise SurfaceError(
                f"{p.name} holds a {kind} ({ch.dim}-D data); a 2-D height map on a uniform grid is needed"
            )
        if not uniform:
            raise SurfaceError(f"{p.name} is not on a uniform grid; resample it first")
        file_unit = ch.unit
        if file_unit is not None and height_unit is not None:
            raise SurfaceError(
                f"{p.name} stores its length unit ({file_unit}); a height unit can only be given for files without one"
            )
        if ch.physical_sizes is not None and physical_size_m is not None:
            raise SurfaceError(f"{p.name} stores its physical size; a size can only be given for files without one")
        file_sizes = None if ch.physical_sizes is None else [float(v) for v in ch.physical_sizes]
        if file_sizes is not None and len(file_sizes) != 2:
            raise SurfaceError(
                f"{p.name} stores its physical size in one direction only ({file_sizes[0]:g}); a height map "
                "needs both (in a text file: a Width and a Height line)"
            )
        scale, given_unit = parse_height_unit(height_unit) if height_unit is not None else (1.0, None)
        unit = file_unit if file_unit is not None else given_unit
        if unit is None:
            raise SurfaceError(f"{p.name} does not store a length unit, or is not a valid {p.suffix} file (its "
                               "reader found no unit in it); if the file is valid, give the unit (command line: "
                               "--height-unit)")
        factor = _unit_factor(str(unit), f"{p.name}")
        kwargs: dict[str, Any] = {}
        if ch.physical_sizes is None:
            if physical_size_m is None:
                raise SurfaceError(
                    f"{p.name} does not store its physical size; give it (command line: --size-um LX:LY)"
                )
            kwargs["physical_sizes"] = (physical_size_m[0] / factor, physical_size_m[1] / factor)
        if file_unit is None:
            kwargs["unit"] = str(unit)
        try:
            topo = reader.topography(channel_index=ch.index, **kwargs)
        except Exception as exc:
            raise SurfaceError(f"cannot read {p.name}: {_one_line(exc)}") from None
        if topo.dim != 2 or not topo.is_uniform:
            raise SurfaceError(f"{p.name} is not a height map on a uniform 2-D grid")
        heights = np.ma.asarray(topo.heights(), dtype=np.float64)
        sizes = topo.physical_sizes
        # A size stored without a height unit is in the file's lateral unit(s) where the file names
        # them (a text header "Width: 10 um"), else in the unit of the heights (SurfaceTopography).
        lateral = _raw_lateral_units(reader, ch) if file_sizes is not None and file_unit is None else None
        if lateral is None:
            size_factors = (factor, factor)
            size_units = None if file_sizes is None else [str(unit), str(unit)]
        else:
            size_factors = (_unit_factor(lateral[0], f"{p.name} (its lateral unit)"),
                            _unit_factor(lateral[1], f"{p.name} (its lateral unit)"))  # fmt: skip
            size_units = list(lateral)
        file_scale = getattr(ch, "height_scale_factor", None)
    info.update(
        {
            "reader": type(reader).__name__,
            "file_unit": None if file_unit is None else str(file_unit),
            "height_unit": str(unit),
            "file_physical_size": file_sizes,
            "file_size_units": size_units,
            "file_height_scale_factor": None if file_scale is None else float(file_scale),
            "height_conversion_factor": scale,
        }
    )
    return _finish(
        np.ma.masked_invalid(heights * (factor * scale)),
        physical_size_m=(float(sizes[0]) * size_factors[0], float(sizes[1]) * size_factors[1]),
        fill_undefined=fill_undefined,
        source=str(p),
        info=info,
    )


def _check_height_scale(heights: FloatArray, physical_size_m: tuple[float, float], name: str) -> None:
    """Refuse a map whose RMS roughness (after a plane fit) exceeds its lateral size: mean slopes far
    beyond 1 are no measured micro-topography but heights in the wrong unit (m for µm: ×10⁶)."""
    nx, ny = heights.shape
    xx, yy = np.meshgrid(np.arange(nx) / max(nx, 1), np.arange(ny) / max(ny, 1), indexing="ij")
    design = np.stack([np.ones(heights.size), xx.ravel(), yy.ravel()], axis=1)
    coef, *_ = np.linalg.lstsq(design, heights.ravel(), rcond=None)
    h = heights.ravel() - design @ coef
    sq = float(np.sqrt(np.mean(h * h)))
    side = float(min(physical_size_m))
    if math.isfinite(sq) and sq > side:
        raise SurfaceError(
            f"{name}: Sq = {sq:.3g} m exceeds the map's lateral size {side:.3g} m; the heights are probably in "
            f"another unit than read (give --height-unit, e.g. um if they are micrometres)"
        )


def _finish(
    masked: np.ma.MaskedArray[Any, Any],
    *,
    physical_size_m: tuple[float, float],
    fill_undefined: bool,
    source: str,
    info: dict[str, Any],
) -> Surface:
    """Report, fill or refuse undefined points; return a NaN-free :class:`Surface`."""
    if masked.ndim != 2:
        raise SurfaceError(f"a surface needs a 2-D height map, got {masked.ndim} dimension(s)")
    mask = np.ma.getmaskarray(masked)
    n_undefined = int(np.count_nonzero(mask))
    info["n_undefined"] = n_undefined
    info["undefined_fraction"] = n_undefined / mask.size if mask.size else 0.0
    name = Path(source).name if source != "array" else "the height map"
    if n_undefined:
        from stochfric.surface.prepare_checks import undefined_border_fraction

        info["undefined_border_fraction"] = undefined_border_fraction(mask)
        fraction = n_undefined / mask.size
        if not fill_undefined:
            raise SurfaceError(
                f"{name} has {n_undefined} undefined point(s) ({100 * fraction:.3g} % of "
                f"{mask.size}); fill them by harmonic interpolation (--fill-undefined) or "
                "crop the measurement"
            )
        if n_undefined == mask.size:
            raise SurfaceError(f"{name} has no defined point at all")
        filled = _fill_harmonic(masked, physical_size_m)
    else:
        filled = np.ma.getdata(masked).astype(np.float64)
    _check_height_scale(filled, physical_size_m, name)
    return Surface(
        heights_m=filled,
        physical_size_m=physical_size_m,
        source=source,
        n_undefined_filled=n_undefined,
        info=info,
    )


def _fill_harmonic(masked: np.ma.MaskedArray[Any, Any], physical_size_m: tuple[float, float]) -> FloatArray:
    """Harmonic interpolation of the masked points (SurfaceTopography, non-periodic)."""
    from SurfaceTopography import Topography

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        topo = Topography(masked, physical_size_m, unit="m", periodic=False)
        filled = np.ma.getdata(topo.interpolate_undefined_data().heights())
    out = np.asarray(filled, dtype=np.float64)
    if not np.all(np.isfinite(out)):  # pragma: no cover - SurfaceTopography guarantees this
        raise SurfaceError("harmonic interpolation left undefined points")
    return out


def _one_line(exc: BaseException) -> str:
    text = " ".join(str(exc).split())
    if len(text) > 200:
        text = text[:197] + "..."
    return f"{type(exc).__name__}: {text}" if text else type(exc).__name__
