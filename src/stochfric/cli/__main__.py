"""``python -m stochfric.cli``."""

from .application import main

main()
