"""``--help`` in panels: every command's options grouped as Input, Physics, Numerics and execution,
Output (issue 32 §4), drawn with rich boxes but without rich *markup*, so that units in brackets
(``[kg]``) and ranges such as ``A:B:NUM`` print as written.

Which panel an option belongs to is one table, :data:`PANELS`, keyed by the flag (the same flag means
the same thing in every command).  An option missing from it would land in "Other options";
``tests/test_cli_help_panels.py`` checks that no command has one.  The text of each line is click's
own help record (names, metavar, help, ``[default: …]``), so what is shown is what the option does.
"""

from __future__ import annotations

import io
import shutil
from collections.abc import Iterable
from typing import Any

from typer.core import TyperCommand

__all__ = ["PANELS", "PANEL_ORDER", "PanelCommand", "panel_of", "use_panels"]

INPUT, PHYSICS, NUMERICS, OUTPUT, OTHER = "Input", "Physics", "Numerics and execution", "Output", "Other options"
#: Panels in the order they are shown.
PANEL_ORDER = (INPUT, PHYSICS, NUMERICS, OUTPUT, OTHER)

_INPUT = """file files --median-radius --step --detrend --fill-undefined --summit-rule --size-um --height-unit
--height-factor --cutoff-um --outliers --outlier-k --outlier-sq --quantised --max-undefined --rough-check --resample
--process"""
_PHYSICS = """--preset --machine --allow-extrapolation --model --friction-law --mu0 --normal-force --damping-coefficient
--forcing-amplitude --mass --stiffness --belt-speed --contact-area --damping-ratio --gamma0 --n --q --eta --omega0
--x0 --sigma-zeta --white-intensity --process-level --material --approach-um --method --contact-model --models
--pressures-mpa --forces --risk-level --risk-levels --phase-force --phase-damping --lengths --persson-corrected
--bem-pixel-area"""
_NUMERICS = """--tau-end --dt --integrator --runs --seed --path-coordinate --white-stream --process-length --workers
--bem-refine --bem-frame --realizations --long-surfaces --length-factor --window-shift-um --approach-rule --surrogate
--validation-budget --summit-budget --window-tiles --accept-not-credible --amplitude --max-area-fraction --pressure-rule
--variance-rule --sigma-zeta-rule --quick --refine --run-budget --no-refine --executor --scheduler --damping-points
--no-normal-force-study --path-surfaces --bem-solver --tolerance --max-iterations --time-limit-s --stick-window
--confidence --p-detect --phase-runs --max-runs-per-cell --target-steps --refine-risk-level --perturbation
--steps-per-cell --dt-max --level-factor --fit-min-length --checkpoint --pressure-points"""
_OUTPUT = "--out --output --plot --json --report --save-every --version"

#: Flag (or argument name) → panel.
PANELS: dict[str, str] = {
    name: panel
    for panel, names in ((INPUT, _INPUT), (PHYSICS, _PHYSICS), (NUMERICS, _NUMERICS), (OUTPUT, _OUTPUT))
    for name in names.split()
}


def panel_of(param: Any) -> str:
    """The panel of a click parameter: by its first flag (an option) or its name (an argument)."""
    for key in (*getattr(param, "opts", ()), param.name):
        if key in PANELS:
            return PANELS[key]
    return OTHER


def _records(command: Any, ctx: Any) -> dict[str, list[tuple[str, str]]]:
    grouped: dict[str, list[tuple[str, str]]] = {p: [] for p in PANEL_ORDER}
    for param in command.get_params(ctx):
        if getattr(param, "hidden", False):
            continue
        record = param.get_help_record(ctx)
        if record is None:  # an argument without typer's help record: its name and its help
            record = (param.human_readable_name, getattr(param, "help", None) or "")
        panel = OUTPUT if "--help" in getattr(param, "opts", ()) else panel_of(param)
        grouped[panel].append((record[0], record[1] or ""))
    return {k: v for k, v in grouped.items() if v}


def render_help(command: Any, ctx: Any, width: int | None = None) -> str:
    """The whole ``--help`` text of ``command``: usage, description, then one box per panel."""
    from rich.console import Console
    from rich.panel import Panel
    from rich.table import Table
    from rich.text import Text

    width = width or min(max(shutil.get_terminal_size((100, 24)).columns, 60), 120)
    buf = io.StringIO()
    console = Console(file=buf, width=width, force_terminal=False, color_system=None, highlight=False,
                      emoji=False, markup=False)
    pieces = command.collect_usage_pieces(ctx)
    console.print(Text("Usage: " + " ".join([ctx.command_path, *pieces])))
    if command.help:
        console.print()
        for para in _paragraphs(command.help):
            console.print(Text(para), style="")
    for panel, rows in _records(command, ctx).items():
        table = Table.grid(padding=(0, 2), expand=True)
        table.add_column(no_wrap=True, max_width=max(24, width // 3))
        table.add_column(ratio=1)
        for names, text in rows:
            table.add_row(Text(names), Text(text))
        console.print(Panel(table, title=Text(panel), title_align="left", border_style="", padding=(0, 1)))
    return buf.getvalue()


def _paragraphs(text: str) -> Iterable[str]:
    import inspect

    for block in inspect.cleandoc(text).split("\n\n"):
        block = block.strip()
        if block.startswith("\b"):  # click's "do not rewrap" marker: keep the lines
            yield block.lstrip("\b").strip("\n")
        else:
            yield " ".join(line.strip() for line in block.splitlines())


class PanelCommand(TyperCommand):
    """A typer command whose ``--help`` shows its options in panels (:func:`render_help`)."""

    def format_help(self, ctx: Any, formatter: Any) -> None:
        formatter.write(render_help(self, ctx))  # the terminal's width (click's formatter caps it at 80)


def use_panels(typer_app: Any) -> None:
    """Give every command of ``typer_app`` (and of its sub-applications) :class:`PanelCommand`."""
    for info in typer_app.registered_commands:
        if info.cls is None or info.cls is TyperCommand:
            info.cls = PanelCommand
    for group in typer_app.registered_groups:
        if group.typer_instance is not None:
            use_panels(group.typer_instance)
