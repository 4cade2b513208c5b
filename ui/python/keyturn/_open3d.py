"""keyturn clouds as Open3D point clouds, a reconstruction as an Open3D triangle mesh (Open3D is
imported only when asked for)."""
from typing import Any

import numpy as np

from ._keyturn import Cloud, Reconstruction


def to_open3d(cloud: Any, *, tensor: bool = False) -> Any:
    """A keyturn.Cloud (or an N × 3 / H × W × 3 array) as an Open3D point cloud of its valid points.

    tensor=False: an o3d.geometry.PointCloud (float64 points). tensor=True: an
    o3d.t.geometry.PointCloud (float32 "positions", and the cloud's "amplitude" and
    "confidence", N × 1, when it has them). Open3D keeps no pixel grid: NaN points (a frame's
    holes) are left out; keyturn.describe(..., shape=(H, W)) needs the grid back, so keep the
    keyturn.Cloud of a frame you mean to describe.

    A keyturn.Reconstruction gives its surface: an o3d.geometry.TriangleMesh (float64 vertices,
    vertex normals computed), or with tensor=True an o3d.t.geometry.TriangleMesh (float32
    "positions", int32 "indices"). Its fused cloud is to_open3d(reconstruction.points)."""
    import open3d as o3d  # an optional dependency: python3-open3d

    if isinstance(cloud, Reconstruction):
        vertices, triangles = cloud.vertices, cloud.triangles
        if tensor:
            return o3d.t.geometry.TriangleMesh(o3d.core.Tensor(np.ascontiguousarray(vertices, dtype=np.float32)),
                                               o3d.core.Tensor(np.ascontiguousarray(triangles, dtype=np.int32)))
        mesh = o3d.geometry.TriangleMesh(o3d.utility.Vector3dVector(vertices.astype(np.float64)),
                                         o3d.utility.Vector3iVector(triangles.astype(np.int32)))
        mesh.compute_vertex_normals()
        return mesh

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
