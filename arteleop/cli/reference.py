"""The reference pages of docs/reference/, made from the command line's and the study file's own
definitions so that they cannot drift from them: ``python docs/make_reference.py`` writes them,
and a test checks that the committed pages are what this module makes."""

from __future__ import annotations

import contextlib
import io
import os
from collections.abc import Iterator

HELP_COLUMNS = 100
"""The width the help texts are laid out at."""


@contextlib.contextmanager
def _columns(width: int) -> Iterator[None]:
    """Lay out help as a terminal ``width`` characters wide would show it."""
    before = os.environ.get("COLUMNS")
    os.environ["COLUMNS"] = str(width)
    try:
        yield
    finally:
        if before is None:
            del os.environ["COLUMNS"]
        else:
            os.environ["COLUMNS"] = before


def _help(argv: list[str]) -> str:
    from arteleop.cli.main import main

    # A text stream with an encoding, as a terminal's or a pipe's: the help draws its boxes.
    buffer = io.BytesIO()
    out = io.TextIOWrapper(buffer, encoding="utf-8")
    with _columns(HELP_COLUMNS), contextlib.redirect_stdout(out):
        try:
            main([*argv, "--help"])
        except SystemExit:
            pass
    out.flush()
    text = buffer.getvalue().decode("utf-8")
    return "\n".join(line.rstrip() for line in text.strip().splitlines()) + "\n"


def command_names() -> list[str]:
    """Every command, as typed after ``arteleop``."""
    from arteleop.cli.main import COMMANDS, GROUPS

    names = list(COMMANDS)
    for group, commands in GROUPS.items():
        names += [f"{group} {name}" for name in commands]
    return names


def command_reference() -> str:
    """docs/reference/commands.md: the overview, then each command's ``--help``."""
    from arteleop.cli.main import OVERVIEW

    lines = [
        "# Commands",
        "",
        "Every command of `arteleop`, with its options as `arteleop COMMAND --help` prints them.",
        "This page is made by `python docs/make_reference.py` from the commands' own",
        "definitions; a test fails when it is out of date.",
        "",
        "```",
        OVERVIEW,
        "```",
    ]
    for name in command_names():
        lines += ["", f"## `arteleop {name}`", "", "```", _help(name.split()).rstrip(), "```"]
    return "\n".join(lines) + "\n"


def study_file_reference() -> str:
    """docs/reference/study-file.md: every key of a study definition, with its default and
    meaning, as ``arteleop study init`` writes them."""
    from arteleop.study import StudyConfig, study_text
    from arteleop.study.study_constants import OPERATOR_PARAMS_KEYS

    return "\n".join([
        "# Study files",
        "",
        "A study is defined in a TOML file; `arteleop study init FILE` writes the default one, and",
        "`arteleop study run FILE --out RUN_DIR` runs it. Every key is optional: a missing key takes",
        "the default shown below. An unknown key, a value of the wrong type or out of range, a",
        "duplicate participant id, or a start or target the arm cannot reach or the head camera",
        "cannot see is refused before anything runs, with the file, the line and the key.",
        "`[[conditions]]` (network delay crossed with cues; see",
        "[A delay study](../guides/delay-study.md)) and `[[participants]]` (named participants in",
        "place of the simulated cohort) are tables of their own, shown commented at the end.",
        "",
        "This page is made by `python docs/make_reference.py` from the definitions themselves; a",
        "test fails when it is out of date.",
        "",
        "```toml",
        study_text(StudyConfig()).rstrip(),
        "```",
        "",
        "## A pointing study",
        "",
        'With `task = "pointing"` (a Fitts study under lag, run with simulated participants; see',
        "[Analysing data](../guides/analysing-data.md#a-pointing-study)), the `[pointing]` table",
        "designs the trials and the `[[conditions]]` are the lags, each a `round_trip_ms` with",
        "`cues = []`. The keys of the pick-and-place its trials do not read (practice, the",
        "served pages' texts, the start and target, the camera's registration, the hand filter,",
        "`timeout_s`) are refused unless left at their defaults. The `[pointing]` defaults:",
        "",
        "```toml",
        _pointing_table(),
        "```",
        "",
        "## The simulated participant's constants: a sensitivity run",
        "",
        "Every constant of the simulated participant has a value and a source",
        "([the operator model](../explanation/operator-model.md)), fixed before a study runs. To",
        "see how far a study's answer rests on one (an assumption's above all), run the study again",
        "with the constant at half and at twice its value, in an `[operator_params]` table; a",
        "file written from such a study says each changed constant beside the model's value, and",
        "`arteleop analyze` pools its run with the model's only with `--allow-different-designs`.",
        "A study may change these, the plain numbers of `OperatorParams`:",
        "",
        "```toml",
        "[operator_params]",
        "max_look_s = 3.0  # the model's: 1.5",
        "```",
        "",
        ", ".join(f"`{key}`" for key in OPERATOR_PARAMS_KEYS) + ".",
    ]) + "\n"  # fmt: skip


def _pointing_table() -> str:
    """The ``[pointing]`` table as a pointing study's file writes it, with its defaults."""
    from arteleop.study import StudyConfig, study_text
    from arteleop.study.definition import ConditionSpec

    text = study_text(StudyConfig(task="pointing", conditions=(ConditionSpec(),)))
    return text[text.index("[pointing]") :].split("\n\n", 1)[0]
