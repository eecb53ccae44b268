"""Writes docs/reference/commands.md and docs/reference/study-file.md from the command line's and
the study file's own definitions (arteleop/cli/reference.py); tests/test_docs.py checks that the
committed pages are what it writes.

    python docs/make_reference.py
"""

from __future__ import annotations

from pathlib import Path

from arteleop.cli.reference import command_reference, study_file_reference

REFERENCE = Path(__file__).resolve().parent / "reference"


def main() -> None:
    for name, text in (("commands.md", command_reference()),
                       ("study-file.md", study_file_reference())):  # fmt: skip
        (REFERENCE / name).write_text(text, encoding="utf-8")
        print(f"wrote {REFERENCE / name}")


if __name__ == "__main__":
    main()
