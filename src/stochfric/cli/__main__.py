"""``python -m stochfric.cli``."""

from . import main

main()
