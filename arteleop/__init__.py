"""arteleop: a simulated platform for studying Augmented Reality in robot teleoperation.

Subpackages follow the data flow: ``operator`` -> ``robot`` -> ``scene`` -> ``ar_features``;
``study`` drives trials and ``analysis`` reads only the files a study writes.
"""

from arteleop.blas_kernel import choose_blas_kernel as _choose_blas_kernel

__version__ = "0.1.0"

# Before anything loads numpy: the same seed gives the same trial on every x86-64 machine.
_choose_blas_kernel()
