"""The surrogate checks on the shared instrument files, as a user runs them (issue 18 acceptance).

For every file in ``../shared/data/topographies`` (or the folders given), run
``stochfric friction-process FILE --material brake-pad --fill-undefined --json`` once with the
default surrogate rule (``auto``) and once with random phases (``--surrogate phase``), and print
one row per run: the preparation's verdict (refused or not), the summit check (z of the summit
count, β̄ and σ_S), the measured-window check (max |z| against its threshold), μ's range and the
gate's verdict with its exit status.  Usage::

    python benchmarks/eval_files.py [--realizations 100] [--long-surfaces 10] [--seed 1] [DIR ...]

The table in docs/statistical_contact.md ("Verdicts on the shared files") comes from this script.
"""

from __future__ import annotations

import argparse
import json
import subprocess
import sys
import time
from pathlib import Path

SHARED = Path(__file__).resolve().parents[1].parent / "shared" / "data" / "topographies"


def run(path: Path, surrogate: str, args: argparse.Namespace) -> tuple[int, dict | None, str, float]:
    cmd = ["stochfric", "friction-process", str(path), "--material", args.material, "--fill-undefined",
           "--realizations", str(args.realizations), "--long-surfaces", str(args.long_surfaces),
           "--seed", str(args.seed), "--surrogate", surrogate, "--json"]
    t0 = time.perf_counter()
    res = subprocess.run(cmd, capture_output=True, text=True, check=False)
    seconds = time.perf_counter() - t0
    data = json.loads(res.stdout) if res.stdout.strip().startswith("{") else None
    last = res.stderr.strip().splitlines()[-1] if res.stderr.strip() else ""
    return res.returncode, data, last, seconds


def row(name: str, surrogate: str, rc: int, data: dict | None, last: str, seconds: float) -> str:
    if data is None:
        return f"| {name} | {surrogate} | refused | | | | | {rc} | {last[:90]} |"
    sc, wc, cr = data["surrogate_check"], data["window_check"], data["credibility"]
    z = sc["z"]
    summit = "pass" if all(abs(z[k]) < sc["limit"] for k in z) else "FAIL"
    window = "n/a" if wc is None else f"{wc['max_abs_z']:.2f} / {wc['threshold']:.2f} " + (
        "pass" if wc["consistent"] else "FAIL")
    mu = [v for v in data["mu_mean"] if v is not None]
    verdict = "credible" if cr["credible"] else ", ".join(r["code"] for r in cr["reasons"])
    used = data["surrogate_choice"].split(" ")[0]
    return (f"| {name} | {surrogate} → {used} | {z['summit_count']:+.1f} {z['summit_radius_mean_m']:+.1f} "
            f"{z['summit_height_std_m']:+.1f} {summit} | {window} | {min(mu):.3g} … {max(mu):.3g} | {verdict} | {rc} "
            f"| {seconds:.0f} s |")


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("dirs", nargs="*", type=Path, default=[SHARED])
    ap.add_argument("--realizations", type=int, default=100)
    ap.add_argument("--long-surfaces", type=int, default=10)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--material", default="brake-pad")
    ap.add_argument("--surrogates", default="auto,phase")
    args = ap.parse_args()
    files = sorted(p for d in args.dirs for p in d.iterdir() if p.suffix not in (".md", ".txt") and p.is_file())
    print("| file | surrogate | summit check z (count β̄ σ_S) | window check max|z| / threshold | E[μ] | gate | exit "
          "| time |")
    print("|---|---|---|---|---|---|---|---|")
    for path in files:
        for surrogate in args.surrogates.split(","):
            rc, data, last, seconds = run(path, surrogate, args)
            print(row(path.stem, surrogate, rc, data, last, seconds), flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
