"""keyturn clouds as Open3D point clouds (Open3D is imported only when asked for)."""
from typing import Any

import numpy as np

from ._keyturn import Cloud


def to_open3d(cloud: Any, *, tensor: bool = False) -> Any:
    """A keyturn.Cloud (or an N × 3 / H × W × 3 array) as an Open3D point cloud of its valid points.

    tensor=False: an o3d.geometry.PointCloud (float64 points). tensor=True: an
    o3d.t.geometry.PointCloud (float32 "positions", and the cloud's "amplitude" and
    "confidence", N × 1, when it has them). Open3D keeps no pixel grid: NaN points (a frame's
    holes) are left out; keyturn.describe(..., shape=(H, W)) needs the grid back, so keep the
    keyturn.Cloud of a frame you mean to describe."""
    import open3d as o3d  # an optional dependency: python3-open3d

    if isinstance(cloud, Cloud):
        points = np.asarray(cloud).reshape(-1, 3)
        channels = {"amplitude": cloud.amplitude, "confidence": cloud.confidence}
    else:
        points = np.asarray(cloud, dtype=np.float32)
        if points.ndim not in (2, 3) or points.shape[-1] != 3:
            raise ValueError(f"to_open3d: points must be an N × 3 or H × W × 3 array, not shape {points.shape}")
        points = points.reshape(-1, 3)
        channels = {}
    valid = np.isfinite(points).all(axis=1)
    if not tensor:
        return o3d.geometry.PointCloud(o3d.utility.Vector3dVector(points[valid].astype(np.float64)))
    out = o3d.t.geometry.PointCloud(o3d.core.Tensor(np.ascontiguousarray(points[valid], dtype=np.float32)))
    for name, values in channels.items():
        if values is not None:
            column = np.ascontiguousarray(np.asarray(values, dtype=np.float32).reshape(-1)[valid].reshape(-1, 1))
            out.point[name] = o3d.core.Tensor(column)
    return out
