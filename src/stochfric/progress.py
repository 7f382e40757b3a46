"""The two progress-callback signatures of the package, named once (docs/glossary.md).

* :data:`Progress` — ``progress(done, total)``: one stage, e.g. the realisations of the surrogate
  ensemble (``process.ensemble``) or the tasks of one study (``studies.base``).
* :data:`StagedProgress` — ``progress(stage, done, total)``: work in named stages, e.g. the
  statistical contact analysis (``process.statistics.analyse``) or the studies of ``reproduce``.

Callbacks report only; they never change a number.
"""

from __future__ import annotations

from collections.abc import Callable

#: ``progress(done, total)``
Progress = Callable[[int, int], None]

#: ``progress(stage, done, total)``
StagedProgress = Callable[[str, int, int], None]

__all__ = ["Progress", "StagedProgress"]
