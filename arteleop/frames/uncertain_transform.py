"""Rigid transforms with uncertainty: SE(3) poses with a 6x6 covariance in se(3).

Convention (one, used everywhere): a transform's uncertainty is a perturbation on the **left**,
``T = exp(xi) * T_mean`` with ``xi ~ N(0, covariance)``, and ``xi = (v, w)`` in pinocchio's
order: translation part first (m), rotation part second (rad). The perturbation so lives in the
frame the transform maps into (for ``T_a_b``, frame a). With it:

- composition ``T_a_c = T_a_b T_b_c``: ``Sigma_a_c = Sigma_a_b + Ad(T_a_b) Sigma_b_c Ad(T_a_b)^T``;
- inverse: ``Sigma_b_a = Ad(T_b_a) Sigma_a_b Ad(T_b_a)^T``;
- fusion of two estimates x, y of one transform:
  ``Sigma = (Sigma_x^-1 + Sigma_y^-1)^-1``, ``T = exp(Sigma Sigma_y^-1 log(T_y T_x^-1)) T_x``.

All to first order; the tests check them against Monte Carlo sampling. The group operations
(``exp``, ``log``, the adjoint) are pinocchio's.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
import pinocchio as pin
from numpy.typing import ArrayLike, NDArray

from arteleop.errors import FrameGraphError


@dataclass(frozen=True, eq=False)
class UncertainTransform:
    """``T_a_b`` (4x4, m) with an optional 6x6 covariance of its left perturbation (m, rad).

    ``covariance`` None means known exactly (the same as zeros, cheaper to compose).
    """

    T: NDArray[np.float64]
    covariance: NDArray[np.float64] | None = None

    def __post_init__(self) -> None:
        T = np.array(self.T, dtype=np.float64)
        if T.shape != (4, 4) or not np.isfinite(T).all():
            raise FrameGraphError(f"a transform must be a finite 4x4 matrix, got shape {T.shape}")
        R = T[:3, :3]
        if np.abs(R.T @ R - np.eye(3)).max() > 1e-6 or np.linalg.det(R) < 0:
            raise FrameGraphError("a transform's rotation block is not a rotation matrix")
        if np.abs(T[3] - (0, 0, 0, 1)).max() > 1e-12:
            raise FrameGraphError(f"a transform's last row must be 0 0 0 1, got {T[3].tolist()}")
        T.flags.writeable = False
        object.__setattr__(self, "T", T)
        if self.covariance is not None:
            C = np.array(self.covariance, dtype=np.float64)
            if C.shape != (6, 6) or not np.isfinite(C).all() or np.abs(C - C.T).max() > 1e-9:
                raise FrameGraphError(
                    f"a covariance must be a finite symmetric 6x6 matrix, got shape {C.shape}"
                )
            if np.linalg.eigvalsh(C).min() < -1e-12:
                raise FrameGraphError("a covariance must be positive semi-definite")
            C.flags.writeable = False
            object.__setattr__(self, "covariance", C)

    @classmethod
    def _trusted(
        cls, T: NDArray[np.float64], covariance: NDArray[np.float64] | None = None
    ) -> UncertainTransform:
        """Built from the results of operations on checked transforms: no checks (they cost
        more than the operation)."""
        result = object.__new__(cls)
        object.__setattr__(result, "T", T)
        object.__setattr__(result, "covariance", covariance)
        return result

    @property
    def se3(self) -> pin.SE3:
        return pin.SE3(self.T)

    def __matmul__(self, other: UncertainTransform) -> UncertainTransform:
        """``T_a_c`` from ``self = T_a_b`` and ``other = T_b_c``."""
        T = self.T @ other.T
        if other.covariance is None:
            return UncertainTransform._trusted(T, self.covariance)
        Ad = self.se3.action
        C = Ad @ other.covariance @ Ad.T
        if self.covariance is not None:
            C = C + self.covariance
        return UncertainTransform._trusted(T, (C + C.T) / 2)

    def inverse(self) -> UncertainTransform:
        """``T_b_a`` from ``self = T_a_b``."""
        inv = self.se3.inverse()
        if self.covariance is None:
            return UncertainTransform._trusted(inv.homogeneous)
        Ad = inv.action
        C = Ad @ self.covariance @ Ad.T
        return UncertainTransform._trusted(inv.homogeneous, (C + C.T) / 2)

    def sample(self, rng: np.random.Generator, n: int) -> NDArray[np.float64]:
        """``n`` transforms (n, 4, 4) drawn from this distribution."""
        C = np.zeros((6, 6)) if self.covariance is None else self.covariance
        xi = rng.multivariate_normal(np.zeros(6), C, size=n)
        mean = self.se3
        return np.array([(pin.exp6(x) * mean).homogeneous for x in xi])


def left_error(T: ArrayLike, T_mean: ArrayLike) -> NDArray[np.float64]:
    """``log(T T_mean^-1)``: the left perturbation (v, w) that takes ``T_mean`` to ``T``."""
    return pin.log6(pin.SE3(np.asarray(T)) * pin.SE3(np.asarray(T_mean)).inverse()).vector


def fuse(x: UncertainTransform, y: UncertainTransform) -> UncertainTransform:
    """The information-weighted combination of two independent estimates of one transform.

    Both need a covariance, and an invertible one.
    """
    if x.covariance is None or y.covariance is None:
        raise FrameGraphError("fusing two estimates needs a covariance on both")
    try:
        info_x, info_y = np.linalg.inv(x.covariance), np.linalg.inv(y.covariance)
        C = np.linalg.inv(info_x + info_y)
    except np.linalg.LinAlgError:
        raise FrameGraphError(
            "fusing two estimates needs invertible covariances (a zero variance says the "
            "estimate is exact: use it alone)"
        ) from None
    step = C @ info_y @ left_error(y.T, x.T)
    return UncertainTransform._trusted((pin.exp6(step) * x.se3).homogeneous, (C + C.T) / 2)


def mean_transform(
    transforms: Sequence[ArrayLike] | NDArray[np.float64],
    max_iterations: int = 50,
    tolerance: float = 1e-12,
) -> UncertainTransform:
    """The mean of several measured transforms (n, 4, 4), with the covariance of that mean.

    The mean is the point whose left errors to the measurements average to zero (the
    Karcher mean, found by Gauss-Newton). The covariance is that of the errors divided by n:
    the uncertainty of the mean of n independent measurements, not of one. With one
    measurement, there is no spread to estimate: the covariance is None.
    """
    Ts = np.asarray(transforms, dtype=np.float64).reshape(-1, 4, 4)
    if len(Ts) == 0:
        raise FrameGraphError("the mean of no transforms: give at least one measurement")
    mean = pin.SE3(Ts[0])
    for _ in range(max_iterations):
        errors = np.array([left_error(T, mean.homogeneous) for T in Ts])
        step = errors.mean(axis=0)
        mean = pin.exp6(step) * mean
        if np.linalg.norm(step) < tolerance:
            break
    if len(Ts) == 1:
        return UncertainTransform._trusted(mean.homogeneous)
    errors = np.array([left_error(T, mean.homogeneous) for T in Ts])
    return UncertainTransform._trusted(mean.homogeneous, np.cov(errors, rowvar=False) / len(Ts))
