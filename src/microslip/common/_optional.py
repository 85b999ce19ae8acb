"""Optional dependencies, imported only where they are needed, with the extra that installs them (private)."""

from __future__ import annotations

import importlib

#: module -> the package that provides it on PyPI
_PROVIDERS = {"h5py": "h5py", "pyNastran.op4.op4": "pyNastran", "pyNastran.bdf.bdf": "pyNastran",
              "ansys.mapdl.reader": "ansys-mapdl-reader", "skfem": "scikit-fem", "dask.distributed":
              "dask[distributed]", "xarray": "xarray", "zarr": "zarr", "pandas": "pandas", "pyarrow": "pyarrow"}


def require(module: str, purpose: str, extra: str):
    """Import ``module`` or raise an ImportError naming the package and ``pip install microslip[<extra>]``."""
    try:
        return importlib.import_module(module)
    except ImportError:
        package = _PROVIDERS.get(module, module.split(".")[0])
        raise ImportError(f"{purpose} needs the package {package}, which is not installed: "
                          f"pip install microslip[{extra}]") from None
