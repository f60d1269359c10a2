"""Trajectory evaluation with the numbers of ``rslam eval`` (evo 1.38.1's, see docs/src/metrics.md).

``est`` and ``gt`` are each a trajectory file (TUM, Replica traj.txt, KITTI, EuRoC; detected
from the content), a ROS 2 bag folder (a pose topic of it: ``est_topic``, ``gt_topic``), an Nx8 array of TUM rows ``t tx ty tz qx qy qz qw``, or an Nx4x4 array of
camera-to-world matrices (no timestamps: matched by index). Note the order: estimate first, as
``rslam eval EST GT`` (evo takes the ground truth first).
"""

import json

from rslam._rslam import evaluate_json

__all__ = ["ate", "evaluate"]


def evaluate(est, gt, *, align="se3", max_diff=0.01, t_offset=0.0, format=None, rate=20.0,
             delta=1.0, delta_unit="f", all_pairs=False, est_topic=None, gt_topic=None):
    """Everything ``rslam eval EST GT --json`` prints, as a dict.

    Keys: ``ate``, ``rpe_trans``, ``rpe_rot_deg`` (each rmse, mean, median, std, min, max, sse,
    n), ``sr``, ``sr_path_ratio``, ``tracked_fraction`` and path lengths, ``pairs``,
    ``max_pairs``, ``alignment`` (rotation rows, translation, scale) and ``options``.

    Args:
        est, gt: trajectory file paths or arrays (see the module help).
        align: 'se3' (RGB-D, default), 'sim3' (monocular) or 'none'.
        max_diff: largest timestamp difference of an associated pair, seconds (inclusive).
        t_offset: added to the estimate's timestamps, seconds.
        format: force the file format ('tum', 'replica', 'kitti', 'euroc', 'colmap').
        rate: frame rate of Replica traj.txt and COLMAP images.txt files, Hz.
        delta, delta_unit, all_pairs: the RPE pairs ('f' frames, 'm' metres, 'deg' degrees).
        est_topic, gt_topic: the pose topic of a bag ('/odom'; '/tf:base_link' for a TF
            topic's transforms to a frame); None reads the bag's one pose topic.

    Raises:
        ValueError: no association, a degenerate alignment, a malformed file or option.
        OSError: a file that cannot be read.
    """
    return json.loads(evaluate_json(est, gt, align, max_diff, t_offset, format, rate, delta,
                                    delta_unit, all_pairs, est_topic, gt_topic))


def ate(est, gt, *, align="se3", max_diff=0.01, t_offset=0.0, format=None, rate=20.0):
    """Absolute trajectory error of ``est`` against ``gt``, in metres, as ``rslam eval``.

    Association by nearest timestamp within ``max_diff``, Umeyama alignment on positions
    (``align``: 'se3', 'sim3' or 'none'), then the per-pose position error.

    Returns:
        dict with ``rmse``, ``mean``, ``median``, ``std``, ``min``, ``max``, ``sse``, ``n``
        (the error statistics, as evo prints them), ``pairs`` and ``alignment`` (``rotation``
        3x3 rows, ``translation``, ``scale``).
    """
    result = evaluate(est, gt, align=align, max_diff=max_diff, t_offset=t_offset, format=format,
                      rate=rate)
    return dict(result["ate"], pairs=result["pairs"], alignment=result["alignment"])
