"""Benchmark: ``stochfric friction-process`` with its default settings on real and thesis-size maps.

Each case runs the command line in a fresh subprocess and reports the wall time and the peak
resident memory of that process (``os.wait4``), plus the figures a user reads first: summit
counts of the measured map and its surrogates, the largest |z| of μ(u), the ergodicity verdict.

Cases (default settings: 100 realisations, 10 long surfaces × 10 lengths, 12 approaches):

* ``plu``    — plu-1.plu, 768 × 576 points (shared real data);
* ``thesis`` — a synthetic Gaussian self-affine map of the thesis's size, 1700 × 1700 points,
  5.3 × 5.3 mm (Hurst 0.8, Sq 0.5 µm), written to ``.npy`` and read through SurfaceTopography;
* ``files``  — all seven shared files (undefined points filled).

Targets (issues 9, 18): 1700², 100 realisations < 3 min on 2 cores with peak RSS < 4 GiB (the peak of
the main process and of its worker processes, each measured); plu-1 < 30 s.  Exit status 3 (the
gate: not credible) is a finished run.

Run:  python benchmarks/bench_process_files.py [plu] [thesis] [files]
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
import tempfile
import threading
import time
from pathlib import Path

import numpy as np
import psutil

SHARED = Path(__file__).resolve().parents[2] / "shared" / "data" / "topographies"
FILES = {
    "al3d-1.al3d": False, "frt-1.frt": True, "mnt-1.mnt": False, "opd-1.opd": True,
    "plu-1.plu": False, "sur-2.sur": True, "x3p-2.x3p": False,
}  # fmt: skip


def thesis_size_map(path: Path, n: int = 1700, seed: int = 1700) -> Path:
    """A Gaussian self-affine map (H = 0.8, roll-off below 1/50 px, Sq = 0.5 µm) as ``.npy`` [m]."""
    rng = np.random.default_rng(seed)
    kx = np.fft.fftfreq(n)[:, None]
    ky = np.fft.rfftfreq(n)[None, :]
    k = np.hypot(kx, ky)
    k[0, 0] = 1.0
    psd = np.maximum(k, 0.02) ** (-2.0 * (1.0 + 0.8))
    psd[0, 0] = 0.0
    coef = np.sqrt(psd) * (rng.standard_normal(psd.shape) + 1j * rng.standard_normal(psd.shape))
    z = np.fft.irfft2(coef, s=(n, n))
    np.save(path, z * (0.5e-6 / z.std()))
    return path


def _sample_tree_rss(pid: int, peak: list[int], every_s: float = 0.1) -> None:
    """Largest summed RSS of process ``pid`` and all its descendants (worker processes), sampled."""
    try:
        root = psutil.Process(pid)
        while root.is_running() and root.status() != psutil.STATUS_ZOMBIE:
            total = 0
            for p in [root, *root.children(recursive=True)]:
                try:
                    total += p.memory_info().rss
                except psutil.Error:
                    pass
            peak[0] = max(peak[0], total)
            time.sleep(every_s)
    except psutil.Error:
        return


def run_case(args: list[str]) -> dict[str, object]:
    """Run ``stochfric friction-process ARGS --json`` in a subprocess: time, peak RSS, summary."""
    cmd = [sys.executable, "-c", "from stochfric.cli import main; main()", "friction-process", *args, "--json"]
    with tempfile.TemporaryFile("w+") as out, tempfile.TemporaryFile("w+") as err:
        t0 = time.perf_counter()
        proc = subprocess.Popen(cmd, stdout=out, stderr=err, text=True)
        tree_peak = [0]
        sampler = threading.Thread(target=_sample_tree_rss, args=(proc.pid, tree_peak), daemon=True)
        sampler.start()
        _pid, status, usage = os.wait4(proc.pid, 0)
        sampler.join(timeout=1.0)
        wall = time.perf_counter() - t0
        proc.returncode = os.waitstatus_to_exitcode(status)
        out.seek(0)
        err.seek(0)
        stdout, stderr = out.read(), err.read()
    res: dict[str, object] = {"wall_s": round(wall, 1), "peak_rss_mib": round(usage.ru_maxrss / 1024, 1),
                              "peak_tree_rss_mib": round(tree_peak[0] / 2**20, 1), "rc": proc.returncode}  # fmt: skip
    if proc.returncode not in (0, 3):  # 3: finished, not credible (the gate)
        res["error"] = stderr.strip().splitlines()[-1] if stderr.strip() else "?"
        return res
    d = json.loads(stdout)
    sc, erg, wc = d["surrogate_check"], d["ergodicity"], d["window_check"]
    res.update(
        grid=d["surface"]["grid"],
        surrogate=d["surrogate_choice"].split(" ")[0],
        window_check_max_z=None if wc is None else round(wc["max_abs_z"], 2),
        gate=d["credibility"]["credible"] or [r["code"] for r in d["credibility"]["reasons"]],
        summits_measured=sc["measured"]["summit_count"],
        summits_surrogates=f"{sc['ensemble_mean']['summit_count']:.0f} ± {sc['ensemble_std']['summit_count']:.0f}",
        z_summits={k: round(v, 2) for k, v in sc["z"].items()},
        max_abs_mu_z=None if sc["max_abs_mu_z"] is None else round(sc["max_abs_mu_z"], 2),
        credible=sc["credible"],
        ergodicity_max_z=round(erg["max_abs_z"], 2),
        ergodic=erg["consistent"],
        warnings=len(d.get("warnings", [])),
    )
    return res


def main(argv: list[str]) -> None:
    cases = argv or ["plu", "thesis"]
    print(f"machine: {os.cpu_count()} cores; python {sys.version.split()[0]}")
    if "plu" in cases:
        print("plu-1 768x576:", json.dumps(run_case([str(SHARED / "plu-1.plu"), "--material", "brake-pad",
                                                   "--seed", "1"])))  # fmt: skip
    if "thesis" in cases:
        with tempfile.TemporaryDirectory() as tmp:
            path = thesis_size_map(Path(tmp) / "thesis1700.npy")
            for surrogate in ("quilt", "auto"):  # the new method's cost; auto picks phase on this Gaussian map
                print(f"synthetic 1700x1700, --surrogate {surrogate}:", json.dumps(run_case([
                    str(path), "--size-um", "5300:5300", "--height-unit", "m", "--material", "brake-pad",
                    "--seed", "1", "--surrogate", surrogate])))  # fmt: skip
    if "files" in cases:
        for name, fill in FILES.items():
            extra = ["--fill-undefined"] if fill else []
            print(f"{name}:", json.dumps(run_case([str(SHARED / name), "--material", "brake-pad", *extra,
                                                  "--seed", "1"])))  # fmt: skip


if __name__ == "__main__":
    main(sys.argv[1:])
