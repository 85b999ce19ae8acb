"""The 3D blade-sector example run quick, as users run it: exported as DMIG, read back, reduced, spun up."""

import sys

import numpy as np
import pytest

from _paths import EXAMPLES

sys.path.insert(0, str(EXAMPLES))

pytest.importorskip("pyNastran")
pytest.importorskip("skfem")
import blade_sector_3d  # noqa: E402


def test_blade_sector_example_quick(tmp_path):
    out = blade_sector_3d.main(tmp_path, quick=True)
    assert (tmp_path / "blade_sector_3d.png").stat().st_size > 20_000
    # the punch file read back is what was exported: pyNastran's 16-character double-precision fields carry
    # 10 significant digits for a negative value (11 for a positive one), so each entry within 1e-9 of the
    # largest (measured 1.4e-10)
    dofs, free, basis = out["dofs"], out["free"], out["basis"]
    grid = {(n + 1, c): basis.nodal_dofs[c - 1, n] for n in range(basis.nodal_dofs.shape[1]) for c in (1, 2, 3)}
    rows = np.array([grid[(int(n), "xyz".index(c) + 1)] for n, c in zip(dofs.nodes, dofs.components)])
    assert set(rows.tolist()) == set(free.tolist())
    for read, exported in ((out["at_rest"].K, out["K0"]), (out["at_rest"].M, out["M"]),
                           (out["at_speed"].K, out["K0"] + blade_sector_3d.SPEED ** 2 * out["K1"])):
        exported = exported.tocsr()[rows][:, rows].toarray()
        assert np.abs(read.toarray() - exported).max() <= 1e-9 * np.abs(exported).max()
    # the speed model reproduces the matrices at the given speeds exactly (Lagrange weights 1 and 0)
    model = out["model"]
    assert np.array_equal(model.stiffness(blade_sector_3d.SPEED), model.matrices[1])
    # the damper's load follows m r Omega^2
    assert out["load"] == pytest.approx(blade_sector_3d.DAMPER_MASS * model.radius * blade_sector_3d.SPEED ** 2,
                                        rel=1e-12)
    # the damper lowers the peak below the undamped blade's (whose peak is set by 2e-7 s of damping alone)
    assert out["response"].peak(6)[1] < 0.5 * out["no_damper"].peak(6)[1]
    assert np.all(np.isfinite(out["curve"].peak_amplitude))
