"""A transform graph: frames as nodes, rigid transforms with uncertainty as edges.

An edge ``parent -> child`` holds ``T_parent_child`` (:class:`UncertainTransform`) and a kind
(:class:`EdgeKind`). A query between any two frames walks the edges, forwards or backwards
(inverted), and composes them with their covariances. Queries remember their path, with each
run of ``fixed`` edges along it multiplied once, and their last answer, given again while no
edge along the path has been set since; so a repeated query multiplies only the edges that
changed. Changing the graph's shape (an edge added or removed, or a fixed edge given a new
value) forgets what was remembered.
"""

from __future__ import annotations

import json
import operator
from collections import deque
from collections.abc import Iterator
from dataclasses import dataclass
from enum import StrEnum
from functools import reduce
from itertools import pairwise
from pathlib import Path

import numpy as np
from numpy.typing import ArrayLike, NDArray

from arteleop.errors import FrameGraphError
from arteleop.files import write_atomic
from arteleop.frames.uncertain_transform import UncertainTransform

GRAPH_FORMAT_VERSION = 1


class EdgeKind(StrEnum):
    """What an edge's transform is and how it changes."""

    FIXED = "fixed"  # never changes while the graph is used (rigid mounts, the table)
    DYNAMIC = "dynamic"  # changes every tick (joints, tracked bodies)
    CALIBRATION = "calibration"  # estimated once by a calibration, with its covariance
    TEMPORARY = "temporary"  # a measurement that closes a loop for a while (a seen marker)
    FUSION = "fusion"  # the combination of several estimates of one transform


@dataclass(frozen=True)
class Edge:
    """``transform`` is ``T_parent_child``."""

    parent: str
    child: str
    kind: EdgeKind
    transform: UncertainTransform


class TransformGraph:
    """Frames and the transforms between them; see the module docstring."""

    def __init__(self) -> None:
        self._edges: dict[tuple[str, str], Edge] = {}
        self._neighbours: dict[str, set[str]] = {}
        self._paths: dict[tuple[str, str], list[tuple[str, str, bool] | UncertainTransform]] = {}
        # Each edge's stamp: a counter value, new whenever the edge is set. A query's answer is
        # kept with the stamps of the edges it read, and reused while they are unchanged.
        self._stamps: dict[tuple[str, str], int] = {}
        self._counter = 0
        self._answers: dict[tuple[str, str], tuple[tuple[int, ...], UncertainTransform]] = {}

    # -- building -------------------------------------------------------------------------------
    def set(
        self,
        parent: str,
        child: str,
        T_parent_child: ArrayLike | UncertainTransform,
        kind: EdgeKind | str = EdgeKind.DYNAMIC,
        covariance: ArrayLike | None = None,
    ) -> None:
        """Add the edge ``parent -> child`` or give it a new transform (4x4, m) and kind."""
        kind = _kind(kind, f"edge {parent} -> {child}")
        if parent == child:
            raise FrameGraphError(f"edge {parent} -> {child}: a frame cannot be its own parent")
        if (child, parent) in self._edges:
            raise FrameGraphError(
                f"edge {parent} -> {child}: the graph has it as {child} -> {parent}; set it in "
                "that direction (with the inverse transform)"
            )
        transform = _transform(T_parent_child, covariance, f"edge {parent} -> {child}")
        old = self._edges.get((parent, child))
        self._edges[(parent, child)] = Edge(parent, child, kind, transform)
        self._counter += 1
        self._stamps[(parent, child)] = self._counter
        if old is None:
            self._neighbours.setdefault(parent, set()).add(child)
            self._neighbours.setdefault(child, set()).add(parent)
            self._paths.clear()
            self._answers.clear()
        elif old.kind is EdgeKind.FIXED or kind is EdgeKind.FIXED:
            self._paths.clear()  # products of fixed runs may hold the old value
            self._answers.clear()

    def remove(self, parent: str, child: str) -> None:
        """Remove the edge ``parent -> child`` (e.g. a temporary one); frames left without
        edges are removed too."""
        if (parent, child) not in self._edges:
            raise FrameGraphError(f"no edge {parent} -> {child} to remove")
        del self._edges[(parent, child)]
        del self._stamps[(parent, child)]
        for a, b in ((parent, child), (child, parent)):
            self._neighbours[a].discard(b)
            if not self._neighbours[a]:
                del self._neighbours[a]
        self._paths.clear()
        self._answers.clear()

    # -- reading --------------------------------------------------------------------------------
    @property
    def frames(self) -> list[str]:
        return sorted(self._neighbours)

    def edges(self) -> Iterator[Edge]:
        return iter(self._edges.values())

    def edge(self, parent: str, child: str) -> Edge:
        try:
            return self._edges[(parent, child)]
        except KeyError:
            raise FrameGraphError(f"no edge {parent} -> {child}") from None

    def path(self, a: str, b: str) -> list[str]:
        """The frames from ``a`` to ``b``, both included (the fewest edges)."""
        for frame in (a, b):
            if frame not in self._neighbours:
                raise FrameGraphError(
                    f"no frame '{frame}' in the graph; its frames are {self.frames}"
                )
        previous: dict[str, str | None] = {a: None}
        todo = deque([a])
        while todo and b not in previous:
            frame = todo.popleft()
            for other in sorted(self._neighbours[frame]):
                if other not in previous:
                    previous[other] = frame
                    todo.append(other)
        if b not in previous:
            raise FrameGraphError(
                f"no path from '{a}' to '{b}': '{a}' is connected to "
                f"{sorted(self._component(a))} and '{b}' to {sorted(self._component(b))}; an "
                "edge between the two (a calibration, a seen marker) would connect them"
            )
        frames = [b]
        while frames[-1] != a:
            frames.append(previous[frames[-1]])  # type: ignore[arg-type]
        return frames[::-1]

    def lookup(self, a: str, b: str) -> UncertainTransform:
        """``T_a_b`` with its covariance, composed along the path from ``a`` to ``b``."""
        steps = self._paths.get((a, b))
        if steps is None:
            steps = self._paths[(a, b)] = self._compile(self.path(a, b))
            self._answers.pop((a, b), None)
        stamps = self._stamps
        read = tuple(stamps[step[:2]] for step in steps if type(step) is tuple)
        answer = self._answers.get((a, b))
        if answer is not None and answer[0] == read:
            return answer[1]
        transforms = []
        for step in steps:
            if type(step) is tuple:
                parent, child, forward = step
                step = self._edges[(parent, child)].transform
                step = step if forward else step.inverse()
            transforms.append(step)
        if any(t.covariance is not None for t in transforms):
            result = reduce(operator.matmul, transforms)
        else:  # no covariance on the path (most queries): plain matrix products
            T = reduce(np.matmul, [t.T for t in transforms]) if transforms else np.eye(4)
            result = UncertainTransform._trusted(T)
        self._answers[(a, b)] = (read, result)
        return result

    def T(self, a: str, b: str) -> NDArray[np.float64]:
        """``T_a_b`` (4x4, m) without its covariance."""
        return self.lookup(a, b).T

    # -- files ----------------------------------------------------------------------------------
    def to_json(self) -> str:
        edges = [
            {
                "parent": e.parent, "child": e.child, "kind": e.kind.value,
                "T": np.round(e.transform.T, 15).tolist(),
                "covariance": None if e.transform.covariance is None
                else e.transform.covariance.tolist(),
            }
            for e in self._edges.values()
        ]  # fmt: skip
        return json.dumps({"format_version": GRAPH_FORMAT_VERSION, "edges": edges}, indent=1)

    def save(self, path: Path) -> None:
        write_atomic(Path(path), self.to_json())

    @classmethod
    def from_json(cls, text: str, source: str = "the graph") -> TransformGraph:
        try:
            data = json.loads(text)
        except json.JSONDecodeError as e:
            raise FrameGraphError(f"{source}: not JSON (line {e.lineno}: {e.msg})") from None
        if not isinstance(data, dict) or data.get("format_version") != GRAPH_FORMAT_VERSION:
            raise FrameGraphError(
                f"{source}: expected an object with format_version {GRAPH_FORMAT_VERSION} and "
                "a list of edges"
            )
        graph = cls()
        edges = data.get("edges")
        if not isinstance(edges, list):
            raise FrameGraphError(f"{source}: 'edges' must be a list")
        for i, edge in enumerate(edges):
            try:
                parent, child, T = edge["parent"], edge["child"], edge["T"]
                name = f"{source}, edge {i} ({parent} -> {child})"
                kind = _kind(edge["kind"], name)
            except (KeyError, TypeError) as e:
                raise FrameGraphError(
                    f"{source}, edge {i}: needs parent, child, kind and T (a 4x4 list); "
                    f"missing: {e}"
                ) from None
            transform = _transform(T, edge.get("covariance"), name)
            try:
                graph.set(parent, child, transform, kind)
            except FrameGraphError as e:  # the edge against the others: a loop, a duplicate
                raise FrameGraphError(f"{source}, edge {i}: {e}") from None
        return graph

    @classmethod
    def load(cls, path: Path) -> TransformGraph:
        path = Path(path)
        try:
            text = path.read_text()
        except OSError as e:
            raise FrameGraphError(f"{path}: cannot read the graph file ({e.strerror})") from None
        return cls.from_json(text, str(path))

    def to_dot(self) -> str:
        """The graph in Graphviz's DOT language: an arrow per edge, labelled with its kind."""
        lines = ["digraph transforms {"]
        for e in self._edges.values():
            style = "" if e.kind is EdgeKind.FIXED else ", style=dashed"
            lines.append(f'  "{e.parent}" -> "{e.child}" [label="{e.kind.value}"{style}];')
        lines.append("}")
        return "\n".join(lines) + "\n"

    # -- inside ---------------------------------------------------------------------------------
    def _compile(self, frames: list[str]) -> list[tuple[str, str, bool] | UncertainTransform]:
        """The path's steps: (parent, child, forward) for an edge read at query time, and one
        product for each run of fixed edges."""
        steps: list[tuple[str, str, bool] | UncertainTransform] = []
        run: UncertainTransform | None = None
        for a, b in pairwise(frames):
            forward = (a, b) in self._edges
            edge = self._edges[(a, b) if forward else (b, a)]
            if edge.kind is EdgeKind.FIXED:
                step = edge.transform if forward else edge.transform.inverse()
                run = step if run is None else run @ step
                continue
            if run is not None:
                steps.append(run)
                run = None
            steps.append((edge.parent, edge.child, forward))
        if run is not None:
            steps.append(run)
        return steps

    def _component(self, frame: str) -> set[str]:
        seen = {frame}
        todo = [frame]
        while todo:
            for other in self._neighbours[todo.pop()]:
                if other not in seen:
                    seen.add(other)
                    todo.append(other)
        return seen


def _transform(
    T: ArrayLike | UncertainTransform, covariance: ArrayLike | None, where: str
) -> UncertainTransform:
    if isinstance(T, UncertainTransform):
        return T
    try:
        return UncertainTransform(np.asarray(T, dtype=np.float64), covariance)
    except (FrameGraphError, ValueError, TypeError) as e:
        raise FrameGraphError(f"{where}: {e}") from None


def _kind(kind: EdgeKind | str, where: str) -> EdgeKind:
    try:
        return EdgeKind(kind)
    except ValueError:
        raise FrameGraphError(
            f"{where}: kind '{kind}' is not one of {[k.value for k in EdgeKind]}"
        ) from None
