"""``python -m stochfric.cli``."""

from .app import main

main()
