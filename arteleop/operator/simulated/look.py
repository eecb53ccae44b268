"""One look of the synthetic operator: glance after glance at an error until it is sure either
way (:mod:`arteleop.operator.simulated.belief`)."""

from __future__ import annotations

from arteleop.operator.simulated.belief import averaging_saturated
from arteleop.operator.simulated.traits import OperatorTraits


class Look:
    """A look's glances and what looks have come to cost the person (s).

    Glances go on until the probability that the error is within the criterion reaches the
    person's confidence (accept) or falls to ``1 - confidence`` (correct), or the look ends
    unsure: looking longer no longer helps (the averaged noise is small beside what lasts, or a
    remembered mark's drift grows), or the look has lasted ``max_look_s``. A look that ends
    unsure accepts an error judged within the criterion, else corrects: a correction of an
    error within it makes the person no surer, and the next look averages afresh. (Until 0.4 a
    look cut at ``max_look_s`` corrected whatever it judged: a person whose glances stayed noisy
    beside the criterion nudged the hand by that noise, look after look, until urgency had
    loosened the criterion; 19 looks in one 70 s trial of the delay example.)
    """

    def __init__(self, traits: OperatorTraits, max_look_s: float) -> None:
        self.traits = traits
        self.max_look_s = max_look_s
        self.cost_s = 3 * traits.glance_s
        """What a look costs, from experience (s)."""
        self.start_s = 0.0
        self.next_glance_s = 0.0
        """When the next glance is due (s), in a look or during a movement."""
        self._glances = 0
        self._first_variance_m2 = 0.0  # the believed variance at the look's first glance

    def start(self, time_s: float) -> None:
        self.start_s = self.next_glance_s = time_s
        self._glances = 0

    def glanced(self, time_s: float, duration_s: float) -> None:
        """A glance begins at ``time_s`` (s) and takes ``duration_s`` (s): it is judged, and the
        next begins, when it is over."""
        self._glances += 1
        self.next_glance_s = time_s + duration_s

    def verdict(
        self, time_s: float, sure: float, variance_m2: float, judged_within: bool
    ) -> bool | None:
        """After a glance, over at ``time_s`` (s), that leaves the person ``sure`` (a
        probability) that the error is within the criterion, believing its judgement's variance
        ``variance_m2``, the judged error itself within the criterion or not
        (``judged_within``): True to accept, False to correct, None to look again."""
        confidence = self.traits.confidence
        looked = time_s - self.start_s
        glances = self._glances
        if glances == 1:
            self._first_variance_m2 = variance_m2
        saturated = averaging_saturated(self._first_variance_m2, variance_m2, glances)
        accept = sure >= confidence
        ended_unsure = saturated or looked >= self.max_look_s
        if not (accept or sure <= 1.0 - confidence or ended_unsure):
            return None
        self.cost_s = 0.5 * self.cost_s + 0.5 * looked
        return accept or (ended_unsure and judged_within)
