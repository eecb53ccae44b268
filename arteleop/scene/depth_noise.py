"""Kinect-360-like depth errors: axial noise growing with z**2 and disparity quantisation."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from arteleop.errors import ConfigurationError


@dataclass(frozen=True)
class DepthNoiseConfig:
    """Depth error model of a structured-light sensor.

    Attributes:
        enabled: Add Gaussian axial noise ``sigma(z) = axial_coeff_per_m * z**2`` (m).
        axial_coeff_per_m: 1.425e-3 /m gives about 1.4 mm at 1 m, as measured on the Kinect 360
            (Nguyen, Izadi & Lovell, 3DIMPVT 2012).
        quantize: Round depth to the sensor's disparity steps.
        baseline_m: Projector-to-camera baseline; 7.5 cm on the Kinect 360.
        subpixel: Disparity resolution in pixels; the Kinect reports 1/8 pixel.
    """

    enabled: bool = True
    axial_coeff_per_m: float = 1.425e-3
    quantize: bool = True
    baseline_m: float = 0.075
    subpixel: float = 1.0 / 8.0

    def __post_init__(self) -> None:
        for name in ("axial_coeff_per_m", "baseline_m", "subpixel"):
            if not getattr(self, name) > 0:
                raise ConfigurationError(
                    f"DepthNoiseConfig.{name} must be > 0, got {getattr(self, name)}"
                )

    def sigma_m(self, z_m: NDArray[np.float64] | float) -> NDArray[np.float64]:
        """Standard deviation (m) of the axial noise at depth ``z_m``."""
        return self.axial_coeff_per_m * np.square(z_m)

    def quantization_step_m(self, z_m: float, focal_px: float) -> float:
        """Depth step (m) between two adjacent disparity levels at depth ``z_m``."""
        return z_m**2 * self.subpixel / (self.baseline_m * focal_px)


def apply_depth_noise(
    depth_m: NDArray[np.float32],
    focal_px: float,
    config: DepthNoiseConfig,
    rng: np.random.Generator,
) -> NDArray[np.float32]:
    """Return a noisy copy of ``depth_m`` (0 marks invalid pixels and stays 0)."""
    # In place where it can be: a 640x480 frame passes through here 30 times a second, and the
    # temporaries cost more than the arithmetic. The operations and their order are those of
    # the plain formulas, so the numbers are the same to the bit (a test compares them).
    z = depth_m.astype(np.float64)
    invalid = ~(z > 0)
    if config.enabled:
        noisy = rng.standard_normal(z.shape)
        noisy *= config.sigma_m(z)
        noisy += z
        noisy[invalid] = 0.0
        z = noisy
    if config.quantize:
        bf = config.baseline_m * focal_px  # disparity (px) times depth (m)
        disparity = np.where(invalid, 1.0, z)
        np.divide(bf, disparity, out=disparity)
        disparity /= config.subpixel
        np.round(disparity, out=disparity)
        disparity *= config.subpixel
        invalid |= disparity <= 0
        np.maximum(disparity, config.subpixel, out=disparity)
        z = np.divide(bf, disparity, out=disparity)
        z[invalid] = 0.0
    return z.astype(np.float32)
