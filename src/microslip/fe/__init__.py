"""Finite-element models: matrices from files, DOF maps, a scikit-fem blade.

* :func:`read_matrices`, :func:`read_matrix` -- mass, stiffness and damping matrices from Matrix
  Market, MATLAB (v5 and v7.3), NumPy ``.npz`` and Nastran OP4 files, checked (square, finite,
  symmetric, same size); a truncated, damaged or inconsistent file raises :class:`FileFormatError`
  (a ``ValueError`` naming the file and, for a text format, the line);
* :class:`DofMap` -- the node and component of every matrix row, names such as ``"1204:x"``;
* :func:`blade` -- a plane-stress blade with a platform, meshed and assembled with scikit-fem
  (:class:`FEBlade`);
* :func:`lap_joint` -- a bolted lap joint of two plates meshed with scikit-fem (3D), reduced to relative
  interface coordinates plus tied-interface modes (:class:`LapJoint`);
* :func:`natural_frequencies` -- the lowest natural frequencies of ``M``, ``K``;
* :func:`contact_patch`, :func:`patch_from_mesh`, :func:`patch_from_tables`, :func:`add_patch` -- node-to-node
  contacts between two surfaces of a mesh or from a reduced model's interface tables (tributary areas,
  normals, tangents; a law per unit area, :class:`PressureLaw`).

Nothing here imports from the rest of :mod:`microslip` except :mod:`microslip.common` and (for the
contact laws of patches) :mod:`microslip.model`. h5py, scikit-fem and meshio are optional
(``pip install microslip[fe]``) and imported only by the readers and the model that need them.
"""

from .blade import FEBlade, blade
from .dof_map import DofMap
from .files import FEMatrices, FileFormatError, read_matrices, read_matrix
from .joints import LapJoint, lap_joint
from .modal import natural_frequencies
from .patches import ContactPatch, PressureLaw, add_patch, contact_patch, patch_from_mesh, patch_from_tables

__all__ = ["ContactPatch", "DofMap", "FEBlade", "FEMatrices", "FileFormatError", "LapJoint", "PressureLaw", "add_patch", "blade",
           "contact_patch", "lap_joint", "natural_frequencies", "patch_from_mesh", "patch_from_tables", "read_matrices",
           "read_matrix"]
