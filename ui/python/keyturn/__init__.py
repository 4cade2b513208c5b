"""keyturn: ISS keypoint-distribution shape descriptors, datasets and models (docs/python.md).

The computing is the extension keyturn._keyturn (the project's C++ libraries, pybind11); this
package adds Open3D output (to_open3d) and the type stubs (__init__.pyi)."""
from ._keyturn import (
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
