"""Small file helpers: output-path checks, atomic writes, memory checks and provenance.

Every command checks its output paths with :func:`check_output_path` *before* it computes
anything, and every file is written through :func:`atomic_path` / :func:`write_atomic`, so a
failed write (disk full, read-only place) ends with a clean error and leaves the previous file
intact.  Files get the permissions an ordinary ``open()`` would give (``0666 & ~umask``), so a
report written for others can be read by them.
"""

from __future__ import annotations

import contextlib
import functools
import importlib.metadata
import json
import math
import os
import tempfile
import threading
from collections.abc import Callable, Collection, Iterator
from pathlib import Path
from typing import Any, Literal

from .errors import InputError


class OutputPathError(InputError):
    """An output path that cannot be written; the message names the option and what to change."""


def _nearest_existing(path: Path) -> Path:
    p = path
    while not p.exists() and p != p.parent:
        p = p.parent
    return p


def check_output_path(
    path: str | os.PathLike[str],
    *,
    option: str = "--out",
    kind: Literal["dir", "file"] = "dir",
    suffixes: Collection[str] | None = None,
) -> Path:
    """Check before any work that ``path`` can be written as an output ``kind``; return it.

    ``kind="dir"``: an existing directory or a path that can be created (parents included);
    ``kind="file"``: a file name whose suffix is one of ``suffixes`` (e.g. ``(".png", ".pdf")``),
    not an existing directory, in a directory that exists or can be created.  Writability is
    probed by creating (and removing) a temporary file in the nearest existing directory, so
    read-only mounts, ``/proc`` and missing permissions are all caught.  Nothing is created.

    Raises :class:`OutputPathError` (a ``ValueError``) whose message starts with ``option``.
    """
    target = Path(path).expanduser()
    where = f"{option} {path}"
    if kind == "file":
        if target.is_dir():
            example = target / ("out" + (min(suffixes) if suffixes else ""))
            raise OutputPathError(f"{where} is a directory; give a file name such as {example}")
        if suffixes is not None:
            allowed = sorted({s.lower() for s in suffixes})
            if target.suffix.lower() not in allowed:
                shown = f"'{target.suffix}'" if target.suffix else "none"
                raise OutputPathError(f"{where}: unknown file extension {shown}; use one of {', '.join(allowed)}")
        parent = target.parent
    else:
        if target.exists() and not target.is_dir():
            raise OutputPathError(
                f"{where} is an existing file, not a directory; give a directory (it is created if missing)")
        parent = target
    anchor = _nearest_existing(parent)
    if not anchor.is_dir():
        raise OutputPathError(f"{where}: {anchor} is a file, so nothing can be created below it; choose another path")
    try:
        fd, probe = tempfile.mkstemp(prefix=".stochfric-write-check.", dir=anchor)
    except OSError as exc:
        reason = exc.strerror or str(exc)
        raise OutputPathError(
            f"{where}: cannot create files in {anchor} ({reason}); "
            "choose a writable place (e.g. under your home directory)"
        ) from None
    os.close(fd)
    os.unlink(probe)
    return target


_UMASK_LOCK = threading.Lock()


def current_umask() -> int:
    """The process's file-mode creation mask (read without changing it where the OS allows)."""
    try:
        with open("/proc/self/status", encoding="ascii") as fh:
            for line in fh:
                if line.startswith("Umask:"):
                    return int(line.split()[1], 8)
    except (OSError, ValueError, IndexError):
        pass
    with _UMASK_LOCK:  # portable fallback: set and restore
        mask = os.umask(0o022)
        os.umask(mask)
    return mask


def available_memory_bytes() -> int | None:
    """Memory available to new allocations (Linux ``MemAvailable``), or ``None`` if unknown."""
    try:
        with open("/proc/meminfo", encoding="ascii") as fh:
            for line in fh:
                if line.startswith("MemAvailable:"):
                    return int(line.split()[1]) * 1024
    except (OSError, ValueError, IndexError):
        pass
    return None


def format_bytes(n: float) -> str:
    """``1.2 GB``-style text (decimal units)."""
    for unit in ("B", "kB", "MB", "GB", "TB", "PB"):
        if abs(n) < 1000 or unit == "PB":
            return f"{n:.3g} {unit}"
        n /= 1000
    return f"{n:.3g} PB"  # pragma: no cover


class MemoryRequestError(InputError):
    """A request that would not fit into memory; the message gives the estimate and what to change."""


def require_memory(nbytes: float, *, what: str, advice: str, fraction: float = 0.8) -> None:
    """Refuse (``MemoryRequestError``) a request estimated at ``nbytes`` bytes that exceeds
    ``fraction`` of the available memory; ``what`` says what needs it, ``advice`` what to change."""
    avail = available_memory_bytes()
    if avail is None or nbytes <= fraction * avail:
        return
    raise MemoryRequestError(
        f"{what} needs about {format_bytes(nbytes)} of memory, but only {format_bytes(avail)} is available; "
        f"{advice}")


def _pid_alive(pid: int) -> bool:
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:  # another user's live process
        return True
    return True


def remove_stale_temporaries(target: Path) -> list[Path]:
    """Remove the temporary files :func:`atomic_path` left next to ``target`` when its writer was
    killed (``kill -9``, power loss: no ``finally`` ran): ``.<name>.<pid>-*.tmp`` whose process is
    gone.  Temporaries of live writers are kept.  Returns the removed paths."""
    removed: list[Path] = []
    prefix = f".{target.name}."
    try:
        siblings = list(target.parent.iterdir())
    except OSError:
        return removed
    for p in siblings:
        name = p.name
        if not (name.startswith(prefix) and name.endswith(".tmp")):
            continue
        pid_text = name[len(prefix):].split("-", 1)[0]
        if not pid_text.isdigit() or int(pid_text) == os.getpid() or _pid_alive(int(pid_text)):
            continue
        with contextlib.suppress(OSError):
            p.unlink()
            removed.append(p)
    return removed


@contextlib.contextmanager
def atomic_path(path: str | os.PathLike[str]) -> Iterator[Path]:
    """Yield a temporary path next to ``path``; on success it replaces ``path`` atomically.

    A crash, Ctrl-C or a failed write (disk full) leaves the previous file (if any) untouched
    and no half-written file behind.  The new file gets mode ``0666 & ~umask``, like a file made
    by ``open()`` (``mkstemp`` alone would leave it ``0600``, unreadable for anyone else).
    """
    target = Path(path)
    target.parent.mkdir(parents=True, exist_ok=True)
    remove_stale_temporaries(target)
    fd, tmp = tempfile.mkstemp(prefix=f".{target.name}.{os.getpid()}-", suffix=".tmp", dir=target.parent)
    os.close(fd)
    tmp_path = Path(tmp)
    try:
        yield tmp_path
        with open(tmp_path, "rb+") as fh:  # the data reach the disk before the rename
            os.fsync(fh.fileno())
        os.chmod(tmp_path, 0o666 & ~current_umask())
        os.replace(tmp_path, target)
    finally:
        if tmp_path.exists():
            tmp_path.unlink()


def write_atomic(path: str | os.PathLike[str], writer: Callable[[Path], object]) -> Path:
    """Call ``writer(tmp_path)`` and move the result to ``path`` atomically."""
    with atomic_path(path) as tmp:
        writer(tmp)
    return Path(path)


def write_bytes_atomic(path: str | os.PathLike[str], data: bytes | memoryview) -> Path:
    """Write ``data`` to ``path`` atomically with plain Python I/O (a full disk is a clean ``OSError``)."""
    return write_atomic(path, lambda p: p.write_bytes(data))


def write_netcdf_atomic(path: str | os.PathLike[str], dataset: Any) -> Path:
    """Write an xarray ``dataset`` to NetCDF-4 (h5netcdf) at ``path`` atomically.

    The file is built in memory and then written with Python I/O: when HDF5 itself writes to a
    full disk it raises from its close handler and can crash the interpreter (exit 139), losing
    the error message; this way a full disk is an ``OSError`` and the previous file stays.
    """
    data = dataset.to_netcdf(None, engine="h5netcdf")
    return write_bytes_atomic(path, bytes(data))


def write_text_atomic(path: str | os.PathLike[str], text: str) -> Path:
    """Write ``text`` to ``path`` atomically (UTF-8)."""
    return write_atomic(path, lambda p: p.write_text(text, encoding="utf-8"))


def write_json_atomic(path: str | os.PathLike[str], payload: Any) -> Path:
    """Write ``payload`` as indented, key-sorted JSON to ``path`` atomically (UTF-8)."""
    return write_text_atomic(path, json.dumps(payload, indent=2, sort_keys=True) + "\n")


def package_versions() -> dict[str, str]:
    """Versions of stochfric and the numerical packages that shaped a result.

    Read once per process (``importlib.metadata`` costs milliseconds a call, which studies
    that record versions per grid cell would otherwise pay every time); a fresh copy each call.
    """
    return dict(_package_versions())


@functools.cache
def _package_versions() -> tuple[tuple[str, str], ...]:
    out: dict[str, str] = {}
    for name in ("stochfric", "numpy", "scipy", "numba", "xarray", "SurfaceTopography"):
        try:
            out[name] = importlib.metadata.version(name)
        except importlib.metadata.PackageNotFoundError:  # pragma: no cover
            out[name] = "not installed"
    return tuple(out.items())


#: The largest input text file read (TOML, JSON: machines, materials, process models, study files) [bytes].
MAX_TEXT_FILE_BYTES = 64 * 1024**2


def regular_file(path: str | os.PathLike[str], max_bytes: int | None = None) -> Path:
    """``path`` after checking that it is a regular file (of at most ``max_bytes``): checked before any reader
    opens it, since a device or pipe (``/dev/zero``) would never end.  Raises :class:`FileNotFoundError`,
    :class:`IsADirectoryError` or an :class:`OSError` whose ``strerror`` says what is wrong (not a regular
    file; too large), so that each caller words its own message."""
    import errno
    import stat

    p = Path(path)
    st = p.stat()
    if stat.S_ISDIR(st.st_mode):
        raise IsADirectoryError(errno.EISDIR, "Is a directory", str(p))
    if not stat.S_ISREG(st.st_mode):
        raise OSError(errno.EINVAL, "not a regular file (a device, pipe or socket)", str(p))
    if max_bytes is not None and st.st_size > max_bytes:
        raise OSError(errno.EFBIG, f"{st.st_size} bytes, more than the {max_bytes} such a file may have", str(p))
    return p


def read_text_checked(path: str | os.PathLike[str], max_bytes: int = MAX_TEXT_FILE_BYTES) -> str:
    """The UTF-8 text of ``path`` after :func:`regular_file`.  Raises :class:`OSError` (``strerror`` says
    which) or :class:`UnicodeDecodeError`, as ``Path.read_text`` does, so callers keep their messages."""
    return regular_file(path, max_bytes).read_text(encoding="utf-8")


def json_ready(obj: Any) -> Any:
    """``obj`` with tuples as lists, numpy scalars as Python numbers and NaN/inf as None (strict JSON)."""
    if isinstance(obj, dict):
        return {k: json_ready(v) for k, v in obj.items()}
    if isinstance(obj, list | tuple):
        return [json_ready(v) for v in obj]
    if isinstance(obj, float) or type(obj).__name__.startswith("float"):  # numpy floats without importing numpy
        return float(obj) if math.isfinite(float(obj)) else None
    if type(obj).__module__ == "numpy" and hasattr(obj, "item"):  # numpy integers and booleans
        return obj.item()
    return obj


# --- reading saved results back -----------------------------------------------------------------------

#: The first bytes of an HDF5 file (NetCDF-4, what :func:`write_netcdf_atomic` writes).
HDF5_SIGNATURE = b"\x89HDF\r\n\x1a\n"


class ResultFileError(InputError):
    """A file that is not the saved result it was given as; the message names it and what to give instead."""


def result_file(path: str | os.PathLike[str], what: str) -> Path:
    """``path`` as an existing regular file, for reading the saved ``what`` (e.g. ``"simulation result
    (simulation.nc)"``).  A missing path is a :class:`FileNotFoundError`, a directory a
    :class:`ResultFileError` listing the result files in it; both name ``path`` and what to give."""
    p = Path(path).expanduser()
    if p.is_dir():
        inside = sorted(q.name for q in p.iterdir() if q.suffix in (".nc", ".json") and not q.name.startswith("."))
        hint = f"; it holds {', '.join(inside)}" if inside else "; it holds no .nc or .json file"
        raise ResultFileError(f"{path} is a directory, not a file: give the file of the {what}{hint}")
    try:
        return regular_file(p)
    except FileNotFoundError:
        where = "" if p.parent.is_dir() else f" (the folder {p.parent} does not exist either)"
        raise FileNotFoundError(f"no file {path}{where}: give the path of a saved {what}") from None
    except OSError as exc:
        raise ResultFileError(f"{path} is {exc.strerror or exc}: give the file of a saved {what}") from None


def read_netcdf(path: str | os.PathLike[str], what: str) -> Any:
    """The NetCDF-4 file of the saved ``what`` as an :class:`xarray.Dataset`, read fully into memory.
    Not a NetCDF-4 file: :class:`ResultFileError` naming ``path`` (no traceback from inside HDF5)."""
    import xarray as xr

    p = result_file(path, what)
    with p.open("rb") as fh:
        head = fh.read(len(HDF5_SIGNATURE))
    if head != HDF5_SIGNATURE:
        raise ResultFileError(f"{path} is not a NetCDF-4 file, so not a {what}")
    try:
        with xr.open_dataset(p, engine="h5netcdf") as ds:
            return ds.load()
    except (OSError, ValueError, KeyError, TypeError) as exc:
        raise ResultFileError(f"{path}: cannot read it as the NetCDF-4 file of a {what} ({exc})") from None


def read_json_file(path: str | os.PathLike[str], what: str) -> Any:
    """The JSON value in the file of the saved ``what`` (NaN allowed, as the writers keep it).  Not UTF-8
    JSON: :class:`ResultFileError` naming ``path`` and the place of the fault."""
    p = result_file(path, what)
    try:
        return json.loads(p.read_text(encoding="utf-8"))
    except UnicodeDecodeError as exc:
        raise ResultFileError(f"{path} is not a {what} (not UTF-8 text: byte {exc.start}, {exc.reason})") from None
    except json.JSONDecodeError as exc:
        raise ResultFileError(f"{path} is not a {what} (not JSON: {exc.msg} at line {exc.lineno}, "
                              f"column {exc.colno})") from None
