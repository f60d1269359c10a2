"""rslam: GPU image corruptions and RGB-D perturbations for SLAM data loaders.

A drop-in for ``imagecorruptions`` (``corrupt``, ``get_corruption_names``), seeded and on the GPU
(lavapipe, Mesa's CPU Vulkan driver, when there is no GPU); ``Perturber`` applies any
``rslam perturb`` spec to frames in memory with the bytes ``rslam perturb`` writes;
``render`` draws a scene along poses; ``rslam.eval.ate`` gives the numbers of ``rslam eval``.

One GPU context per process, created on first use; the GIL is released while the GPU works.
"""

from rslam._rslam import (
    Perturber,
    __version__,
    corrupt,
    get_corruption_names,
    gpu_adapter,
    perturbation_names,
    render,
    scene_poses,
)
from rslam import eval

__all__ = [
    "Perturber",
    "corrupt",
    "eval",
    "get_corruption_names",
    "gpu_adapter",
    "perturbation_names",
    "render",
    "scene_poses",
    "__version__",
]
