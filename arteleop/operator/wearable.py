"""The wearable: one IMU per arm segment at 100 Hz plus a pinch-grip sensor, with sensor errors.

An IMU reports its own orientation in an earth frame (z up, fixed heading). It is strapped to its
segment with an unknown mounting rotation ``q_segment_sensor``, and the operator's torso faces
``torso_heading_rad`` about earth z. So, for segment k::

    q_earth_sensor = q_drift_k(t) * Rz(torso_heading) * q_torso_segment * q_segment_sensor * q_noise
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
from numpy.typing import ArrayLike, NDArray
from scipy.signal import lfilter
from scipy.spatial.transform import Rotation

from arteleop.errors import ConfigurationError


@dataclass(frozen=True)
class ImuErrorConfig:
    """Sensor errors; set any of them to 0 to switch it off.

    Attributes:
        noise_deg_rms: RMS angle of the orientation error (deg). About 1 deg for the MPU9150
            with sensor fusion.
        noise_correlation_s: Correlation time of that error (s). Fusion filters leave a slowly
            wandering error rather than independent jitter per sample, so the error is a
            first-order Gauss-Markov process; 0 makes it white.
        heading_drift_deg_per_sqrt_s: Random-walk intensity of each sensor's heading bias
            (deg / sqrt(s)): after t seconds the bias has a standard deviation of this times
            sqrt(t). Magnetometer-aided fusion keeps it slow.
        drop_probability: Chance that a packet (one sample of all sensors) starts a loss.
        drop_burst_max: A loss spans 1 to this many consecutive samples, uniformly.
    """

    noise_deg_rms: float = 1.0
    noise_correlation_s: float = 0.2
    heading_drift_deg_per_sqrt_s: float = 0.1
    drop_probability: float = 0.01
    drop_burst_max: int = 3

    def __post_init__(self) -> None:
        if min(self.noise_deg_rms, self.noise_correlation_s, self.heading_drift_deg_per_sqrt_s) < 0:
            raise ConfigurationError(
                "ImuErrorConfig: noise_deg_rms, noise_correlation_s and "
                "heading_drift_deg_per_sqrt_s must be >= 0"
            )
        if not 0 <= self.drop_probability < 1 or self.drop_burst_max < 1:
            raise ConfigurationError(
                f"ImuErrorConfig: drop_probability={self.drop_probability} must be in [0, 1) and "
                f"drop_burst_max={self.drop_burst_max} >= 1"
            )

    @classmethod
    def ideal(cls) -> ImuErrorConfig:
        """No noise, no drift, no dropped samples."""
        return cls(noise_deg_rms=0.0, heading_drift_deg_per_sqrt_s=0.0, drop_probability=0.0)


def _default_mounting() -> tuple[tuple[float, float, float, float], ...]:
    # Straps are never aligned with the bones: a few tens of degrees off, differently per sensor.
    angles = ((20.0, -10.0, 35.0), (-15.0, 25.0, -40.0), (10.0, 30.0, 15.0))
    return tuple(
        tuple(Rotation.from_euler("xyz", a, degrees=True).as_quat(scalar_first=True).tolist())
        for a in angles
    )  # type: ignore[return-value]


@dataclass(frozen=True)
class WearableConfig:
    """How the wearable sits on the operator.

    Attributes:
        rate_hz: Sample rate of the IMUs and the grip sensor (Hz).
        mounting_wxyz: ``q_segment_sensor`` for upper arm, forearm and hand.
        torso_heading_rad: Heading of the operator's torso in the IMUs' earth frame.
        errors: Sensor errors.
    """

    rate_hz: float = 100.0
    mounting_wxyz: tuple[tuple[float, float, float, float], ...] = field(
        default_factory=_default_mounting
    )
    torso_heading_rad: float = 0.0
    errors: ImuErrorConfig = field(default_factory=ImuErrorConfig)

    def __post_init__(self) -> None:
        if self.rate_hz <= 0:
            raise ConfigurationError(f"WearableConfig.rate_hz must be > 0, got {self.rate_hz}")
        if np.asarray(self.mounting_wxyz).shape != (3, 4):
            raise ConfigurationError(
                "WearableConfig.mounting_wxyz needs 3 quaternions (w, x, y, z)"
            )


@dataclass(frozen=True)
class WearableSignals:
    """What the wearable emitted: kept samples only (dropped packets are absent).

    Attributes:
        time_s: (N,) sample times (s).
        sensor_quat_wxyz: (N, 3, 4) orientation of each IMU in the earth frame.
        grip: (N,) pinch grip, 0 open .. 1 pinched.
        dropped: Number of packets lost.
    """

    time_s: NDArray[np.float64]
    sensor_quat_wxyz: NDArray[np.float64]
    grip: NDArray[np.float64]
    dropped: int


class WearableSimulator:
    """IMU model with state: mounting, torso heading, drift and noise processes, packet loss.

    The orientation error is a first-order Gauss-Markov process per axis and sensor, and the
    heading bias a random walk; their states carry over between calls, so a trial can be
    simulated sample by sample (:meth:`sample`) or in one block (:meth:`run`).
    """

    def __init__(self, config: WearableConfig, rng: np.random.Generator) -> None:
        self.config = config
        self._rng = rng
        err = config.errors
        self._dt = 1.0 / config.rate_hz
        self._mounting = Rotation.from_quat(
            np.asarray(config.mounting_wxyz, dtype=np.float64), scalar_first=True
        ).as_matrix()
        self._sigma = np.radians(err.noise_deg_rms) / np.sqrt(3.0)  # per axis: RMS angle / sqrt(3)
        corr = err.noise_correlation_s * config.rate_hz
        self._a = float(np.exp(-1.0 / corr)) if corr > 0 else 0.0
        self._noise = rng.standard_normal((3, 3)) * self._sigma  # start in the stationary law
        self._bias = np.zeros(3)
        self._drop_left = 0
        self.dropped = 0
        self.samples = 0

    def run(
        self, segments_torso: Rotation, n: int
    ) -> tuple[NDArray[np.float64], NDArray[np.bool_]]:
        """IMU quaternions (n, 3, 4) for n postures (3n rotations), and which packets arrived."""
        err = self.config.errors
        bias = np.zeros((n, 3))
        if err.heading_drift_deg_per_sqrt_s > 0:
            step = np.radians(err.heading_drift_deg_per_sqrt_s) * np.sqrt(self._dt)
            bias = self._bias + np.cumsum(self._rng.standard_normal((n, 3)) * step, axis=0)
            self._bias = bias[-1]
        noise = np.zeros((n, 3, 3))
        if err.noise_deg_rms > 0:
            innovation = (
                self._rng.standard_normal((n, 3, 3)) * self._sigma * np.sqrt(1 - self._a**2)
            )
            noise = lfilter(
                [1.0], [1.0, -self._a], innovation, axis=0, zi=self._a * self._noise[None]
            )[0]
            self._noise = noise[-1]
        keep = self._arrivals(n)
        # q_earth_sensor = Rz(heading + bias) * q_torso_segment * q_segment_sensor * noise,
        # composed as matrices: one scipy call per factor instead of one per product.
        heading = self.config.torso_heading_rad + bias.reshape(-1, 1)
        segment_sensor = (segments_torso.as_matrix().reshape(n, 3, 3, 3) @ self._mounting).reshape(
            -1, 3, 3
        )
        sensor = (
            Rotation.from_euler("z", heading).as_matrix()
            @ segment_sensor
            @ Rotation.from_rotvec(noise.reshape(-1, 3)).as_matrix()
        )
        quats = Rotation.from_matrix(sensor, assume_valid=True).as_quat(
            scalar_first=True, canonical=True
        )
        return quats.reshape(n, 3, 4), keep

    def sample(self, segments_torso: Rotation) -> NDArray[np.float64] | None:
        """(3, 4) IMU quaternions for one posture, or None if the packet is lost."""
        quats, keep = self.run(segments_torso, 1)
        return quats[0] if keep[0] else None

    def _arrivals(self, n: int) -> NDArray[np.bool_]:
        err = self.config.errors
        keep = np.ones(n, dtype=bool)
        if err.drop_probability <= 0:
            self.samples += n
            return keep
        starts = self._rng.random(n) < err.drop_probability
        bursts = self._rng.integers(1, err.drop_burst_max + 1, n)
        for i in range(n):
            self.samples += 1
            if self._drop_left == 0 and starts[i] and self.samples > 1:  # the first one anchors
                self._drop_left = int(bursts[i])
            if self._drop_left > 0:
                self._drop_left -= 1
                keep[i] = False
        self.dropped += int(n - keep.sum())
        return keep


def simulate_wearable(
    segments_torso: Rotation,
    grip: ArrayLike,
    config: WearableConfig,
    rng: np.random.Generator,
    start_time_s: float = 0.0,
) -> WearableSignals:
    """Turn segment orientations (N postures x 3, torso frame) into the wearable's signals."""
    grip = np.asarray(grip, dtype=np.float64)
    n = len(grip)
    if len(segments_torso) != 3 * n:
        raise ConfigurationError(
            f"{len(segments_torso)} segment rotations for {n} grip samples; need 3 per sample"
        )
    sim = WearableSimulator(config, rng)
    quats, keep = sim.run(segments_torso, n)
    time = start_time_s + np.arange(n) / config.rate_hz
    return WearableSignals(time[keep], quats[keep], grip[keep], sim.dropped)
