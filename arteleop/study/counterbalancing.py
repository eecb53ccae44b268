"""Orders of conditions for a within-subject study.

A sequence is a tuple of condition indices (0..n-1). Participant k takes sequence
``k % len(sequences)`` of a scheme, so a scheme is balanced over any multiple of its count.
"""

from __future__ import annotations

import numpy as np

from arteleop.errors import StudyDefinitionError


def williams_sequences(n: int) -> list[tuple[int, ...]]:
    """Williams' balanced Latin square (Williams, Aust. J. Sci. Res. 1949).

    Every condition appears once at every position and directly follows every other condition
    equally often: n sequences for even n; for odd n no single square does it, so the square
    and its mirror image, 2n sequences.
    """
    if n < 1:
        raise StudyDefinitionError(f"A Latin square needs at least one condition, got {n}.")
    # First row 0, 1, n-1, 2, n-2, ...; row r adds r to every entry (mod n).
    first = [0]
    low, high = 1, n - 1
    for k in range(1, n):
        if k % 2:
            first.append(low)
            low += 1
        else:
            first.append(high)
            high -= 1
    rows = [tuple((c + r) % n for c in first) for r in range(n)]
    if n % 2:
        rows += [tuple(reversed(row)) for row in rows]
    return rows


def cyclic_sequences(n: int) -> list[tuple[int, ...]]:
    """The n rotations of 0..n-1 (e.g. 12345, 23451, ...): each position once per condition,
    but each condition always follows the same one (no carry-over balance)."""
    if n < 1:
        raise StudyDefinitionError(f"A cyclic order needs at least one condition, got {n}.")
    return [tuple((c + r) % n for c in range(n)) for r in range(n)]


def participant_orders(
    scheme: str, n_conditions: int, n_participants: int, seed: int
) -> list[tuple[int, ...]]:
    """One sequence of condition indices per participant, by ``scheme`` (see
    :attr:`StudyConfig.order <arteleop.study.StudyConfig>`)."""
    if scheme == "williams":
        rows = williams_sequences(n_conditions)
    elif scheme == "cyclic":
        rows = cyclic_sequences(n_conditions)
    elif scheme == "listed":
        raise StudyDefinitionError("Listed orders come from StudyConfig.orders, not a scheme.")
    elif scheme == "random":
        rng = np.random.default_rng([seed, 2])  # a stream of its own, apart from the cohort's
        return [tuple(int(c) for c in rng.permutation(n_conditions)) for _ in range(n_participants)]
    else:
        raise StudyDefinitionError(f"order = {scheme!r}; expected one of williams, cyclic, random.")
    return [rows[k % len(rows)] for k in range(n_participants)]
