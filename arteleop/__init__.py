"""arteleop: a simulated platform for studying Augmented Reality in robot teleoperation.

Subpackages follow the data flow: ``operator`` -> ``robot`` -> ``scene`` -> ``ar_features``;
``study`` drives trials and ``analysis`` reads only the files a study writes.
"""

from importlib.metadata import version as _version

from arteleop.blas_kernel import choose_blas_kernel as _choose_blas_kernel
from arteleop.numpy_loops import choose_numpy_loops as _choose_numpy_loops

__version__ = _version("arteleop")
"""The installed package's version, as ``pyproject.toml`` gives it."""

# Before anything loads numpy: the same seed gives the same trial on every x86-64 machine.
_choose_blas_kernel()
_choose_numpy_loops()
