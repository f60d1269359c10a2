"""Type stubs of the compiled module (see the docstrings for behaviour)."""

import os
from typing import Optional, Sequence, Tuple, Union

import numpy as np
import numpy.typing as npt

__version__: str

Camera = Union[str, Sequence[float]]
"""'replica', 'tum', "W,H,FX,FY,CX,CY" or (w, h, fx, fy, cx, cy)."""

Depth = Union[npt.NDArray[np.float32], npt.NDArray[np.uint16]]

def corrupt(
    image: npt.NDArray[np.uint8],
    severity: int = 1,
    corruption_name: Optional[str] = None,
    corruption_number: int = -1,
    seed: int = 0,
) -> npt.NDArray[np.uint8]:
    """Corrupts ``image`` like ``imagecorruptions.corrupt``, on the GPU; same shape out."""

def get_corruption_names(subset: str = "common") -> list[str]:
    """'common', 'validation', 'all', 'noise', 'blur', 'weather' or 'digital'."""

class Perturber:
    """Image and depth corruptions of a ``--perturb`` spec for frames in memory."""

    def __init__(self, spec: str, seed: int = 0, camera: Optional[Camera] = None) -> None: ...
    def apply(
        self,
        rgb: npt.NDArray[np.uint8],
        depth: Optional[Depth] = None,
        frame_index: int = 0,
        depth_scale: Optional[float] = None,
    ) -> Tuple[npt.NDArray[np.uint8], Optional[Depth]]:
        """One frame as frame ``frame_index`` of its sequence."""
    def apply_batch(
        self,
        rgbs: npt.NDArray[np.uint8],
        depths: Optional[Depth] = None,
        frame_indices: Optional[Sequence[int]] = None,
        depth_scale: Optional[float] = None,
    ) -> Tuple[npt.NDArray[np.uint8], Optional[Depth]]:
        """N frames (NxHxWx3, NxHxW) at once; frame_indices default to 0..N-1."""
    def severities(self, frame_index: int) -> dict[str, int]:
        """The severity each corruption gives this frame (0 = clean)."""
    @property
    def spec(self) -> str: ...
    @property
    def seed(self) -> int: ...
    @property
    def camera(self) -> Optional[Tuple[int, int, float, float, float, float]]: ...

def render(
    scene: str,
    poses: npt.ArrayLike,
    camera: Optional[Camera] = None,
    perturb: Optional[str] = None,
    seed: int = 0,
    rate: float = 20.0,
    capture_scale: Optional[float] = None,
    capture_depth: str = "expected",
    capture_min_opacity: float = 0.5,
) -> Tuple[npt.NDArray[np.uint8], npt.NDArray[np.float32]]:
    """(rgb NxHxWx3 uint8, depth NxHxW float32 metres) along Nx4x4 camera-to-world poses."""

def scene_poses(scene: str) -> npt.NDArray[np.float64]:
    """A built-in scene's default camera path, Nx4x4 camera-to-world."""

def evaluate_json(
    est: Union[str, os.PathLike, npt.ArrayLike],
    gt: Union[str, os.PathLike, npt.ArrayLike],
    align: str = "se3",
    max_diff: float = 0.01,
    t_offset: float = 0.0,
    format: Optional[str] = None,
    rate: float = 20.0,
    delta: float = 1.0,
    delta_unit: str = "f",
    all_pairs: bool = False,
    est_topic: Optional[str] = None,
    gt_topic: Optional[str] = None,
) -> str:
    """The ``rslam eval --json`` object as text; use ``rslam.eval``."""

def gpu_adapter() -> str:
    """The GPU adapter in use (created now if not yet)."""

def perturbation_names() -> list[str]:
    """Every name a spec accepts."""
