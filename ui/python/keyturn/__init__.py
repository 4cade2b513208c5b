"""keyturn: ISS keypoint-distribution shape descriptors, datasets and models (docs/python.md).

The computing is the extension keyturn._keyturn (the project's C++ libraries, pybind11); this
package adds Open3D output (to_open3d) and the type stubs (__init__.pyi)."""
import os

# OpenMP threads that sleep while they wait, unless the user chose otherwise: libgomp reads the
# policy once, when the extension loads it, and its default spinning took the cores reconstruct()
# needed on a busy machine (docs/benchmarks.md, "OpenMP threads that wait passively"). Only a
# process that loaded libgomp before importing keyturn keeps its own.
os.environ.setdefault("OMP_WAIT_POLICY", "PASSIVE")

from ._keyturn import (  # noqa: E402  (after the policy)
    Classification,
    Cloud,
    Dataset,
    Description,
    Error,
    Features,
    Model,
    OrganizedShapeLostWarning,
    Reconstruction,
    View,
    __version__,
    describe,
    features_of,
    from_open3d,
    load_cloud,
    parameters,
    reconstruct,
    save_cloud,
    train,
)
from ._open3d import to_open3d

__all__ = [
    "Classification",
    "Cloud",
    "Dataset",
    "Description",
    "Error",
    "Features",
    "Model",
    "OrganizedShapeLostWarning",
    "Reconstruction",
    "View",
    "__version__",
    "describe",
    "features_of",
    "from_open3d",
    "load_cloud",
    "parameters",
    "reconstruct",
    "save_cloud",
    "to_open3d",
    "train",
]

# The public names are keyturn.X (reprs, help(), pickles), not keyturn._keyturn.X.
for _name in __all__:
    _obj = globals()[_name]
    if isinstance(_obj, type) or callable(_obj):
        try:
            _obj.__module__ = __name__
        except (AttributeError, TypeError):
            pass
del _name, _obj
