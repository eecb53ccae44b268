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
from arteleop.transforms import (
    matrices_to_quats,
    quats_to_matrices,
    rotations_z,
    rotvecs_to_matrices,
)


@dataclass(frozen=True)
class ImuErrorConfig:
    """Sensor errors; set any of them to 0 to switch it off.

    Attributes:
        noise_deg_rms: RMS angle of the orientation error (deg). About 1 deg for the MPU9150
            with sensor fusion.
        noise_correlation_s: Correlation time of that error (s). A fusion filter leaves a slowly
            wandering error rather than independent jitter per sample, so the error is a
            first-order Gauss-Markov process; 0 makes it white. 3 s: the accelerometer time
            constant of the VQF fusion filter (Laidig & Seel, Information Fusion 91, 2023),
            below which the gyroscope's integrated drift is kept and above which the
            accelerometer's correction acts; the gyroscope's own white noise (0.005 deg/s per
            sqrt Hz, InvenSense's MPU-6050/9150 data) adds only hundredths of a degree.
        heading_drift_deg_per_sqrt_s: Random-walk intensity of each sensor's heading bias
            (deg / sqrt(s)): after t seconds the bias has a standard deviation of this times
            sqrt(t). Magnetometer-aided fusion keeps it slow.
        drop_probability: Chance that a packet (one sample of all sensors) starts a loss.
        drop_burst_max: A loss spans 1 to this many consecutive samples, uniformly.
    """

    noise_deg_rms: float = 1.0
    noise_correlation_s: float = 3.0
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


BLOCK_SAMPLES = 512
"""The simulator draws its errors this many samples at a time, whatever the calls ask for: the
per-sample work in the loop is then two matrix products and a conversion, and a trial
simulated one sample at a time equals one simulated in a single block."""


class WearableSimulator:
    """IMU model with state: mounting, torso heading, drift and noise processes, packet loss.

    The orientation error is a first-order Gauss-Markov process per axis and sensor, and the
    heading bias a random walk. They depend on the random generator alone, not on the motion,
    so they are drawn ahead in blocks of :data:`BLOCK_SAMPLES`; a trial can be simulated sample
    by sample (:meth:`sample`) or in one block (:meth:`run`), with the same result.
    """

    def __init__(self, config: WearableConfig, rng: np.random.Generator) -> None:
        self.config = config
        self._rng = rng
        err = config.errors
        self._dt = 1.0 / config.rate_hz
        self._mounting = quats_to_matrices(config.mounting_wxyz)
        self._sigma = np.radians(err.noise_deg_rms) / np.sqrt(3.0)  # per axis: RMS angle / sqrt(3)
        corr = err.noise_correlation_s * config.rate_hz
        self._a = float(np.exp(-1.0 / corr)) if corr > 0 else 0.0
        self._noise = rng.standard_normal((3, 3)) * self._sigma  # start in the stationary law
        self._bias = np.zeros(3)
        self._drop_left = 0
        self._drawn = 0  # samples drawn ahead so far
        # The current block: earth_torso (B, 3, 3, 3), segment_sensor_noisy (B, 3, 3, 3), keep.
        self._block: tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.bool_]] | None
        self._block, self._used = None, 0
        self.dropped = 0
        self.samples = 0

    def run(
        self, segments_torso: ArrayLike, n: int
    ) -> tuple[NDArray[np.float64], NDArray[np.bool_]]:
        """IMU quaternions (n, 3, 4) for n postures (``R_torso_segment``, (n, 3, 3, 3)), and
        which packets arrived."""
        parts = []
        left = n
        while left > 0:
            if self._block is None or self._used == len(self._block[2]):
                self._block, self._used = self._draw_block(), 0
            take = min(left, len(self._block[2]) - self._used)
            parts.append(tuple(x[self._used : self._used + take] for x in self._block))
            self._used += take
            left -= take
        earth_torso, segment_sensor, keep = (
            (parts[0][k] if len(parts) == 1 else np.concatenate([p[k] for p in parts]))
            for k in range(3)
        )
        segments = np.asarray(segments_torso, dtype=np.float64).reshape(n, 3, 3, 3)
        # q_earth_sensor = Rz(heading + bias) * q_torso_segment * q_segment_sensor * noise
        quats = matrices_to_quats(earth_torso @ segments @ segment_sensor)
        self.samples += n
        self.dropped += int(n - keep.sum())
        return quats, keep

    def sample(self, segments_torso: ArrayLike) -> NDArray[np.float64] | None:
        """(3, 4) IMU quaternions for one posture (``R_torso_segment``, (3, 3, 3)), or None if
        the packet is lost."""
        quats, keep = self.run(segments_torso, 1)
        return quats[0] if keep[0] else None

    def _draw_block(
        self,
    ) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.bool_]]:
        """The next :data:`BLOCK_SAMPLES` samples' errors, as the rotations they multiply."""
        err = self.config.errors
        n = BLOCK_SAMPLES
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
        earth_torso = rotations_z(self.config.torso_heading_rad + bias)
        return earth_torso, self._mounting @ rotvecs_to_matrices(noise), keep

    def _arrivals(self, n: int) -> NDArray[np.bool_]:
        err = self.config.errors
        keep = np.ones(n, dtype=bool)
        if err.drop_probability <= 0:
            return keep
        starts = self._rng.random(n) < err.drop_probability
        bursts = self._rng.integers(1, err.drop_burst_max + 1, n)
        for i in range(n):
            self._drawn += 1
            if self._drop_left == 0 and starts[i] and self._drawn > 1:  # the first one anchors
                self._drop_left = int(bursts[i])
            if self._drop_left > 0:
                self._drop_left -= 1
                keep[i] = False
        return keep


def simulate_wearable(
    segments_torso: ArrayLike,
    grip: ArrayLike,
    config: WearableConfig,
    rng: np.random.Generator,
    start_time_s: float = 0.0,
) -> WearableSignals:
    """Turn segment orientations (``R_torso_segment``, (N, 3, 3, 3)) into the wearable's
    signals."""
    grip = np.asarray(grip, dtype=np.float64)
    n = len(grip)
    segments_torso = np.asarray(segments_torso, dtype=np.float64)
    if segments_torso.shape != (n, 3, 3, 3):
        raise ConfigurationError(
            f"segment rotations of shape {segments_torso.shape} for {n} grip samples; need "
            f"({n}, 3, 3, 3): three segments' rotation matrices per sample"
        )
    sim = WearableSimulator(config, rng)
    quats, keep = sim.run(segments_torso, n)
    time = start_time_s + np.arange(n) / config.rate_hz
    return WearableSignals(time[keep], quats[keep], grip[keep], sim.dropped)
