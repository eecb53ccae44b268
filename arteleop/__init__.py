"""arteleop: a simulated platform for studying Augmented Reality in robot teleoperation.

Subpackages follow the data flow: ``operator`` -> ``robot`` -> ``scene`` -> ``ar_features``;
``study`` drives trials and ``analysis`` reads only the files a study writes.
"""

__version__ = "0.1.0"
