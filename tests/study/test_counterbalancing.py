"""Orders of conditions: the balance properties that make each scheme what it is."""

from __future__ import annotations

import itertools
from collections import Counter

import pytest

from arteleop.errors import StudyDefinitionError
from arteleop.study import cyclic_sequences, participant_orders, williams_sequences


@pytest.mark.parametrize("n", [2, 3, 4, 5, 6, 7])
def test_williams_square_balances_positions_and_carry_over(n: int) -> None:
    rows = williams_sequences(n)
    assert len(rows) == (n if n % 2 == 0 else 2 * n)
    copies = len(rows) // n
    for row in rows:
        assert sorted(row) == list(range(n))
    for position in range(n):  # each condition equally often at each position
        assert Counter(row[position] for row in rows) == dict.fromkeys(range(n), copies)
    follows = Counter(pair for row in rows for pair in itertools.pairwise(row))
    # Each condition directly follows each other one equally often: once per square.
    assert follows == dict.fromkeys(itertools.permutations(range(n), 2), copies)


def test_williams_five_conditions_is_the_ten_sequence_design() -> None:
    rows = williams_sequences(5)
    assert rows[0] == (0, 1, 4, 2, 3)
    assert rows[5] == (3, 2, 4, 1, 0)  # the mirror of the first row


def test_cyclic_orders_rotate_and_do_not_balance_carry_over() -> None:
    rows = cyclic_sequences(5)
    assert rows[:3] == [(0, 1, 2, 3, 4), (1, 2, 3, 4, 0), (2, 3, 4, 0, 1)]
    follows = Counter(pair for row in rows for pair in itertools.pairwise(row))
    assert follows[(0, 1)] == 4 and follows[(1, 0)] == 0


def test_participants_cycle_through_the_sequences_and_random_is_seeded() -> None:
    orders = participant_orders("williams", 5, 22, seed=0)
    assert orders[10] == orders[0] and orders[21] == orders[1]
    first = participant_orders("random", 5, 22, seed=3)
    assert first == participant_orders("random", 5, 22, seed=3)
    assert first != participant_orders("random", 5, 22, seed=4)
    assert all(sorted(o) == list(range(5)) for o in first)


def test_an_unknown_scheme_is_refused_with_the_valid_ones() -> None:
    with pytest.raises(
        StudyDefinitionError, match=r"^order = 'latin'; expected one of williams, cyclic, random\.$"
    ):
        participant_orders("latin", 5, 22, seed=0)
