"""Errors of the analysis package.

The analysis imports nothing else from arteleop, so that a lab can run it on its own CSVs; its
errors therefore derive from ValueError rather than from arteleop's root exception.
"""

from __future__ import annotations


class AnalysisInputError(ValueError):
    """A study file is invalid; the message names the file, the column and the value."""
