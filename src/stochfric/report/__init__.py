"""The HTML report and the figures of simulations and studies (renders results; computes nothing).

:func:`write_report` writes ``index.html`` with the figures of every study result and, given the
chapter-3 analysis, its sections; :func:`plot_phase_portrait` draws one simulation.
"""

from __future__ import annotations

from stochfric.oscillator.figures import plot_phase_portrait
from stochfric.report.html import write_report

__all__ = ["plot_phase_portrait", "write_report"]
