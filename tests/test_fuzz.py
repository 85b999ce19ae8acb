"""Every public callable, fuzzed one argument at a time.

Each callable of the public API (the ``__all__`` of every public package and
the public methods of the classes they export) has one entry in ``CASES``: a
valid call. Each argument of it is then replaced, one at a time, by NaN,
inf, a negative value, zero, an empty array, an array of the wrong shape, a
string, a dict, 1e300 and 1e-300 (integers also by 2.5 and 10**12, flags by
``"no"``). The only acceptable outcomes are

* a ``ValueError`` or ``TypeError`` (or a documented subclass such as
  ``TuningError`` or ``LoadLimitError``) whose message names the argument
  replaced, or
* a result in which every float is finite -- but never for NaN, inf, a value
  of the wrong type or a non-integer size, which must be refused.

Each call runs with at most 2 GiB of extra address space and a time limit,
so a size that is attempted instead of refused fails here with a
``MemoryError`` rather than exhausting the machine.
"""

from __future__ import annotations

import dataclasses
import importlib
import inspect
import math
import re
import signal
import warnings
from contextlib import contextmanager
from functools import cache
from typing import Callable, NamedTuple

import matplotlib

matplotlib.use("Agg")

import numpy as np
import pytest
import scipy.io
import scipy.sparse

import microslip
import microslip.fe
import microslip.study
from microslip import (Cylinder, MeasuredContact, MicroslipModel, Sphere, State, Structure, accuracy, fit_backbone,
                       loops, mdr, paths, tune, tune_on_loops)
from microslip.accuracy import PathBatch, reference_run, restriction_mask
from microslip.frequency import HarmonicBalance, StepControl, aft, frequency_point, steady_state
from microslip.reference import AxisymmetricProfile, RoundedPunch, SphereProfile
from microslip.tuning import TargetProblem, tuning_points

# -- the bad values -----------------------------------------------------------------------------------


class Bad(NamedTuple):
    label: str
    value: object
    refuse: bool  # True: only an error naming the argument is right; False: a finite result is right too


def _array_bad(a: np.ndarray) -> list[Bad]:
    k = a.size // 2
    with_nan, with_inf = a.copy(), a.copy()
    with_nan.flat[k], with_inf.flat[k] = np.nan, np.inf
    wrong_shape = np.stack([a, a]) if a.ndim == 1 else a.ravel()
    return [Bad("nan", with_nan, True), Bad("inf", with_inf, True), Bad("negative", -np.abs(a) - 1.0, False),
            Bad("zero", np.zeros_like(a), False), Bad("empty", a[..., :0], False),
            Bad("wrong shape", wrong_shape, False), Bad("string", "abc", True), Bad("dict", {"a": 1}, True),
            Bad("1e300", np.full_like(a, 1e300), False), Bad("1e-300", np.full_like(a, 1e-300), False)]


BAD = {
    "float": [Bad("nan", math.nan, True), Bad("inf", math.inf, True), Bad("-inf", -math.inf, True),
              Bad("negative", -1.0, False), Bad("zero", 0.0, False), Bad("empty", np.empty(0), False),
              Bad("wrong shape", np.ones((2, 3)), False), Bad("string", "abc", True), Bad("dict", {"a": 1}, True),
              Bad("1e300", 1e300, False), Bad("1e-300", 1e-300, False)],
    "int": [Bad("nan", math.nan, True), Bad("inf", math.inf, True), Bad("negative", -1, False),
            Bad("zero", 0, False), Bad("2.5", 2.5, True), Bad("empty", np.empty(0), True),
            Bad("wrong shape", np.ones((2, 3), dtype=int), True), Bad("string", "abc", True),
            Bad("dict", {"a": 1}, True), Bad("1e300", 1e300, True), Bad("1e-300", 1e-300, True),
            Bad("10**12", 10**12, False)],
    "bool": [Bad("string", "no", True), Bad("nan", math.nan, True), Bad("2.5", 2.5, True),
             Bad("dict", {"a": 1}, True), Bad("zero", 0, False)],
    "str": [Bad("empty", "", False), Bad("unknown", "no such thing", False), Bad("float", 1.0, True),
            Bad("nan", math.nan, True), Bad("dict", {"a": 1}, True)],
    "object": [Bad("string", "abc", True), Bad("dict", {"a": 1}, True), Bad("float", 1.0, True),
               Bad("nan", math.nan, True)],
    "mapping": [Bad("string", "abc", True), Bad("float", 1.0, True), Bad("nan", math.nan, True),
                Bad("list", [1.0, 2.0], True)],
    # file names: strings would reach the file system, so only values of the wrong type
    "path": [Bad("float", 1.0, True), Bad("nan", math.nan, True), Bad("dict", {"a": 1}, True)],
}


def _kind(value) -> str:
    if isinstance(value, bool):
        return "bool"
    if isinstance(value, int):
        return "int"
    if isinstance(value, float):
        return "float"
    if isinstance(value, str):
        return "str"
    if isinstance(value, (list, tuple, np.ndarray)) and np.asarray(value).dtype.kind in "iuf":
        return "array"
    return "object"


def _bad_values(value, kind: str) -> list[Bad]:
    """The bad values for an argument of this ``kind`` whose valid value is ``value``."""
    return _array_bad(np.asarray(value, dtype=float)) if kind == "array" else BAD[kind]


# -- the table ------------------------------------------------------------------------------------------


class Lazy:
    """An argument built on first use (shared objects: a tuned model, an MDR reference, loops, ...)."""

    def __init__(self, build: Callable[[], object]):
        self.build = build

    def __repr__(self) -> str:
        return f"Lazy({self.build.__name__})"


def _resolve(value):
    return value.build() if isinstance(value, Lazy) else value


@dataclasses.dataclass
class Case:
    """One valid call of a public callable and how to fuzz it."""

    name: str                                   # "Class.method" or "function" (" [variant]" may follow)
    target: Callable[[], Callable]              # builds the callable (a fresh object when it mutates)
    args: dict                                  # valid keyword arguments
    kinds: dict = dataclasses.field(default_factory=dict)   # argument -> kind, where its value does not say
    skip: dict = dataclasses.field(default_factory=dict)    # argument -> labels not tried (reason at the entry)
    finite: bool = True                         # False: the result may hold NaN, as documented (reason at the entry)
    refused_only: bool = False                  # long-running: only the values it must refuse before work


def case(name, target, /, *, kinds=None, skip=None, finite=True, refused_only=False, **args) -> Case:
    return Case(name, target, args, kinds or {}, skip or {}, finite, refused_only)


# shared objects, built once
SPHERE = Sphere.paper()
N_TOT = 37.5


@cache
def model() -> MicroslipModel:
    return tune(SPHERE, N_TOT, elements=4)


@cache
def reference_model():
    return mdr(SPHERE, max_load=40.0, elements=40)


@cache
def small_family() -> list:
    return paths.default_family(SPHERE, N_TOT, ratios=(0.0, 0.3), phases_deg=(0.0,), amplitudes=(0.5, 2.0),
                                levels=(1.0,), cycles=1, steps_per_cycle=16)


@cache
def report():
    return accuracy(model(), reference_model(), small_family())


@cache
def a_path():
    return paths.loop(SPHERE, 20.0, 1e-6, cycles=1, steps_per_cycle=16)


@cache
def batch():
    return PathBatch(small_family())


@cache
def a_record():
    fine = tune(SPHERE, N_TOT, elements=30)
    t = 1.5e-6 * np.sin(2 * np.pi * np.linspace(0, 4, 4 * 200 + 1))
    T = fine.simulate(t, float(SPHERE.approach(N_TOT)), per_element=False).T
    return loops.Record(t=t, T=T, normal_load=N_TOT, source="sphere")


@cache
def some_loops():
    return loops.analyse(a_record())


@cache
def measured_contact():
    return MeasuredContact.from_loops(some_loops(), SPHERE)


@cache
def fitted():
    return measured_contact().fit


@cache
def loop_tuning():
    return tune_on_loops(some_loops(), SPHERE, elements=3)


@cache
def _cylinder(law: str):
    table = [[0.0, 0.0], [1e-7, 20.0], [2e-7, 50.0]]
    return Cylinder(10e-3, 5e-3, 200e9, 0.3, 0.4, law=table if law == "table" else law)


def jenkins_structure() -> Structure:
    """1 DOF, 1 kg on 1e4 N/m with a Jenkins contact slipping at 1 N: a fresh one for every call."""
    s = Structure(M=[[1.0]], C=[[1.0]], K=[[1e4]])
    s.add_contact(MicroslipModel(kt=[1e4], kn=[1e6], gaps=[0.0], mu=1.0), tangential=0, approach=1e-6)
    return s


@cache
def harmonic_balance():
    return HarmonicBalance(jenkins_structure(), [1.0], 1)


@cache
def a_point():
    return frequency_point(jenkins_structure(), [1.0], 100.0, harmonics=1)


@cache
def a_mode():
    return microslip.nonlinear_modes(jenkins_structure(), 1, (1e-5, 1e-2), harmonics=1)


@cache
def a_synthesis():
    return a_mode().forced_response([0.5])


@cache
def a_steady_state():
    return steady_state(jenkins_structure(), [1.0], 100.0, steps_per_period=64, harmonics=1, max_periods=20)


@cache
def problem():
    return TargetProblem(SPHERE, (20.0, N_TOT), reference_elements=40, steps_per_cycle=16,
                         family_options=dict(ratios=(0.0,), phases_deg=(0.0,), amplitudes=(1.0,), levels=(1.0,)))


@cache
def sweep():
    return microslip.tuning.element_sweep(problem(), [2], spacings=["force"])


@cache
def points():
    return tuning_points(SPHERE, N_TOT, elements=3)


@cache
def aft_result():
    return aft(model(), [1e-7, 1e-7, 0.0], [float(SPHERE.approach(N_TOT)), 0.0, 0.0], samples=16)


def plane_aft_result():
    return microslip.frequency.aft_plane(model(), [[1e-7, 1e-7, 0.0]] * 2, [float(SPHERE.approach(N_TOT)), 0.0, 0.0],
                                         samples=16)


@cache
def backbone_xy():
    return some_loops().backbone_points()


@cache
def a_branch():
    t = np.linspace(-1.5e-6, 1.5e-6, 200)
    return t, SPHERE.branch(t, N_TOT, -1.5e-6, -15.0)


def _paraboloid(r):
    return r ** 2 / (2 * 5e-3)


# files read by the entries that read files (the tests run in a temporary folder: see ``_in_tmp``)
@cache
def table_file() -> str:
    with open("normal.csv", "w") as f:
        f.write("n [um], N [N]\n0.0, 0.0\n0.1, 10.0\n0.2, 25.0\n")
    return "normal.csv"


@cache
def record_file() -> str:
    r = a_record()
    with open("record.csv", "w") as f:
        f.write("t [m], T [N]\n" + "".join(f"{float(a)!r}, {float(b)!r}\n" for a, b in zip(r.t, r.T)))
    return "record.csv"


@cache
def model_file() -> str:
    return str(model().save("model.json"))


def disk():
    """Eight sectors of 3 DOFs, a Jenkins contact from DOF 1 to the next sector's: a fresh one for every call."""
    from microslip.frequency import CyclicStructure

    K = np.array([[2e6, -1e6, 0.0], [-1e6, 2e6, -1e6], [0.0, -1e6, 1e6]])
    d = CyclicStructure(np.eye(3) * 0.1, None, K, sectors=8, left=[0], right=[2])
    d.add_contact(MicroslipModel([1e4], [1e6], [0.0], 0.5), tangential={1: 1.0, d.next(1): -1.0}, approach=1e-6)
    return d


@cache
def disk_point():
    return frequency_point(disk(), [0.0, 1.0, 0.0], 3000.0, harmonics=1, engine_order=1)


@cache
def whole_disk_point():
    d = disk()
    return frequency_point(d.assembled(), d.travelling_wave([0.0, 1.0, 0.0], 1), 3000.0, harmonics=1,
                           reduction="exact")


def damper():
    from microslip.frequency import UnderPlatformDamper

    return UnderPlatformDamper(0.02, 1e-6, centrifugal_load=300.0)


def damper_with_interface():
    d = damper()
    law = MicroslipModel([1e6], [1e8], [0.0], 0.5)
    d.add_interface(law, points=[(-4e-3, 2e-3), (-2e-3, 4e-3)], angle_deg=135.0,
                    platform=[{"x": 0, "y": 1}, {"x": 0, "y": 1}], name="flat")
    d.add_interface(law, points=[(3e-3, 3e-3)], angle_deg=45.0, platform={"x": 0, "y": 1}, name="curved")
    return d


@cache
def damper_point():
    """A solved response of a structure with :func:`damper_with_interface` attached."""
    s = damper_with_interface().attach(Structure(np.eye(2), None, np.eye(2) * 1e4))
    f = np.zeros(s.ndof)
    f[0] = 1.0
    return frequency_point(s, f, 100.0, harmonics=1, stability=False)


def three_dofs() -> Structure:
    s = Structure(np.eye(3), None, np.array([[2e4, -1e4, 0.0], [-1e4, 2e4, -1e4], [0.0, -1e4, 1e4]]))
    s.add_contact(MicroslipModel(kt=[1e4], kn=[1e6], gaps=[0.0], mu=1.0), tangential=0, approach=1e-6)
    return s


def speed_model(**kwargs):
    K = np.array([[2e4, -1e4, 0.0], [-1e4, 2e4, -1e4], [0.0, -1e4, 1e4]])
    return microslip.frequency.SpeedModel(np.eye(3), None, [K, K + 1e-2 * np.eye(3)], [0.0, 500.0], **kwargs)


@cache
def speed_model_with_contact():
    return speed_model(contacts=three_dofs())


@cache
def a_campbell():
    return microslip.frequency.campbell(speed_model_with_contact(), [0.0, 100.0, 200.0], modes=2, engine_orders=[1])


@cache
def design_curve():
    loads = np.array([100.0, 300.0])
    return microslip.frequency.DesignCurve(loads, np.array([2e-6, 1e-6]), np.array([110.0, 120.0]), [], 0)


@cache
def reduced():
    return microslip.frequency.craig_bampton(three_dofs(), [0], 1)


@cache
def reduced_file() -> str:
    return reduced().save("reduced.npz")


def matrices_file() -> str:
    np.savez("matrices.npz", M=np.eye(2), K=np.array([[2e4, -1e4], [-1e4, 1e4]]))
    return "matrices.npz"


def sector_file() -> str:
    np.savez("sector.npz", M=np.eye(3) * 0.1, K=np.array([[2e6, -1e6, 0.0], [-1e6, 2e6, -1e6], [0.0, -1e6, 1e6]]))
    return "sector.npz"


# microslip.fe: a 3-DOF model (masses in kg, stiffnesses in N/m) in a NumPy .npz file and in one Matrix Market file
# per matrix, and its DOF map in a CSV file
FE_M = np.diag([1.0, 1.0, 0.5])
FE_K = np.array([[2e4, -1e4, 0.0], [-1e4, 2e4, -1e4], [0.0, -1e4, 1e4]])


@cache
def fe_file() -> str:
    np.savez("fe_model.npz", MGG=FE_M, KGG=FE_K, C=FE_K * 1e-4)
    return "fe_model.npz"


@cache
def mtx_file(name: str) -> str:
    scipy.io.mmwrite(f"{name}.mtx", {"M": FE_M, "K": FE_K, "C": FE_K * 1e-4}[name])
    return f"{name}.mtx"


def dof_map():
    return microslip.fe.DofMap([1, 1, 2], ["x", "y", "x"])


@cache
def dof_file() -> str:
    return str(dof_map().to_csv("dofs.csv"))


@cache
def fe_blade():
    return microslip.fe.blade(300)


#: a contact patch: a 2 x 1 grid of 1 cm quads (side a, z = 0, nodes 0-5) under its copy 0.1 µm above (nodes 6-11)
PATCH_POINTS = np.array([[0.01 * i, 0.01 * j, z] for z in (0.0, 1e-7) for i in range(3) for j in range(2)])
PATCH_A = np.array([[0, 2, 3, 1], [2, 4, 5, 3]])
PATCH_B = PATCH_A[:, ::-1] + 6
PATCH_INP = ("*NODE\n" + "".join(f"{k + 1}, {x:.17g}, {y:.17g}, {z:.17g}\n" for k, (x, y, z) in enumerate(PATCH_POINTS))
             + "*ELEMENT, TYPE=S4, ELSET=LOWER\n1, 1, 3, 4, 2\n2, 3, 5, 6, 4\n"
             + "*ELEMENT, TYPE=S4, ELSET=UPPER\n3, 8, 10, 9, 7\n4, 10, 12, 11, 9\n")


def a_patch():
    return microslip.fe.contact_patch(PATCH_POINTS, PATCH_A, PATCH_B, tolerance=1e-6)


@cache
def patch_file() -> str:
    with open("patch.inp", "w") as f:
        f.write(PATCH_INP)
    return "patch.inp"


def patch_structure() -> Structure:
    """The patch's 12 nodes, 3 DOFs each, on springs (a fresh structure: add_patch adds contacts)."""
    dof_map = microslip.fe.DofMap([k for k in range(12) for _ in "xyz"], [c for _ in range(12) for c in "xyz"])
    return Structure(np.eye(36), np.zeros((36, 36)), 1e6 * np.eye(36), dof_map=dof_map)


@cache
def lap_joint():
    return microslip.fe.lap_joint(30, modes=4)


@cache
def table_patch():
    return microslip.fe.patch_from_tables([3, 8], [1e-4, 2e-4], [[0.0, 0.0, 1.0], [0.6, 0.0, 0.8]])


PRESSURE_LAW = microslip.fe.PressureLaw(kn_per_area=1e12, kt_per_area=5e11, mu=0.5, gap=0.0)


N_APP = float(SPHERE.approach(N_TOT))
NO_RISE = ("negative", "zero", "1e300", "1e-300")  # data values that make a curve flat or falling
UNCHECKED = ("nan", "inf", "string", "dict")
T3 = [0.0, 0.5e-6, 1e-6]
F3 = [0.0, 5.0, 10.0]
T3_PLANE = [[0.0, 0.0], [0.5e-6, 0.2e-6], [1e-6, -0.3e-6]]  # a history on the contact plane (m)
X3 = [0.0, 1e-6, 0.0]  # harmonic balance unknowns of the 1-DOF structure with H = 1: c0, a1, b1 (m)
L = Lazy  # short, for the table
#: accuracy targets: math.inf is the documented "no limit" (tests/tuning/test_tune_range.py), not a bad value
NO_LIMIT = {"energy_target": ("inf",), "force_target": ("inf",)}
REFERENCE = SPHERE
MODEL = L(model)
STATE = L(lambda: State(np.zeros(4)))
PATHS = L(small_family)
ARRAY = {"values": "array", "T": "array", "N": "array", "W": "array", "x": "array", "y": "array", "t": "array",
         "kt": "array", "slip_displacements": "array"}
PATH = {"path": "path", "out_dir": "path"}

CASES = [
    # -- microslip.reference -------------------------------------------------------------------
    case("Sphere", lambda: Sphere, radius=5e-3, E=200e9, nu=0.3, mu=0.4),
    case("Sphere.contact_radius", lambda: SPHERE.contact_radius, N=N_TOT),
    case("Sphere.approach", lambda: SPHERE.approach, N=N_TOT),
    case("Sphere.normal_force", lambda: SPHERE.normal_force, n=N_APP),
    case("Sphere.normal_stiffness", lambda: SPHERE.normal_stiffness, N=N_TOT),
    case("Sphere.tangential_stiffness", lambda: SPHERE.tangential_stiffness, N=N_TOT),
    case("Sphere.gross_slip_displacement", lambda: SPHERE.gross_slip_displacement, N=N_TOT),
    case("Sphere.backbone", lambda: SPHERE.backbone, t=T3, N=N_TOT),
    case("Sphere.backbone_displacement", lambda: SPHERE.backbone_displacement, T=F3, N=N_TOT),
    case("Sphere.branch", lambda: SPHERE.branch, t=T3, N=N_TOT, t_reversal=1e-6, T_reversal=12.0),
    case("Sphere.loop", lambda: SPHERE.loop, amplitude=1e-6, N=N_TOT, points=9),
    case("Sphere.dissipation", lambda: SPHERE.dissipation, T_amplitude=5.0, N=N_TOT),
    case("Sphere.raised_load_path", lambda: SPHERE.raised_load_path, T=F3, N=25.0, dN=12.5, T_A=5.0),
    case("Sphere.join_point", lambda: SPHERE.join_point, N=25.0, dN=12.5, T_A=5.0),
    case("Cylinder", lambda: Cylinder, length=10e-3, radius=5e-3, E=200e9, nu=0.3, mu=0.4, law="palmgren"),
    case("Cylinder [table]", lambda: Cylinder, length=10e-3, radius=5e-3, E=200e9, nu=0.3,
         law=[[0.0, 0.0], [1e-7, 10.0], [2e-7, 25.0]]),
    case("Cylinder.from_file", lambda: Cylinder.from_file, kinds=PATH, path=L(table_file), length=10e-3,
         radius=5e-3, E=200e9, nu=0.3, mu=0.4),
    case("Cylinder.with_mu", lambda: Cylinder(10e-3, 5e-3, 200e9, 0.3).with_mu, mu=0.3),
    *[c for law in ("palmgren", "lundberg", "table") for c in (
        case(f"Cylinder.approach [{law}]", lambda law=law: _cylinder(law).approach, N=N_TOT),
        case(f"Cylinder.normal_force [{law}]", lambda law=law: _cylinder(law).normal_force, n=1e-7),
        case(f"Cylinder.normal_stiffness [{law}]", lambda law=law: _cylinder(law).normal_stiffness, N=N_TOT))],
    case("Cylinder.contact_half_width", lambda: _cylinder("palmgren").contact_half_width, N=N_TOT),
    case("SphereProfile", lambda: SphereProfile, radius=5e-3),
    case("SphereProfile.height", lambda: SphereProfile(5e-3).height, r=[0.0, 1e-4]),
    case("SphereProfile.mdr", lambda: SphereProfile(5e-3).mdr, x=[0.0, 1e-4]),
    case("RoundedPunch", lambda: RoundedPunch, flat_radius=1e-3, edge_radius=5e-3),
    case("RoundedPunch.height", lambda: RoundedPunch(1e-3, 5e-3).height, r=[0.0, 2e-3]),
    case("RoundedPunch.mdr", lambda: RoundedPunch(1e-3, 5e-3).mdr, x=[0.0, 2e-3]),
    case("AxisymmetricProfile", lambda: AxisymmetricProfile, shape=_paraboloid, scale=5e-3, breaks=[1e-3]),
    case("AxisymmetricProfile.height", lambda: AxisymmetricProfile(_paraboloid, 5e-3).height, r=[0.0, 1e-4]),
    case("AxisymmetricProfile.mdr", lambda: AxisymmetricProfile(_paraboloid, 5e-3).mdr, x=[0.0, 1e-4]),
    case("microslip.mdr", lambda: mdr, reference=REFERENCE, max_load=40.0, elements=20,
         profile=L(lambda: SphereProfile(5e-3))),
    case("MDRModel.check_approach", lambda: reference_model().check_approach, n=N_APP),
    case("MDRModel.element_normal_forces", lambda: reference_model().element_normal_forces, n=N_APP),
    case("MDRModel.simulate", lambda: reference_model().simulate, t=T3, n=N_APP, state=L(lambda: State(np.zeros(40))),
         per_element=True, work=True),
    case("MDRModel.trial", lambda: reference_model().trial, state=L(lambda: State(np.zeros(40))), t=1e-7, n=N_APP),
    case("MDRModel.approach", lambda: reference_model().approach, N=N_TOT),
    case("MDRContact", lambda: microslip.reference.MDRContact, model=L(reference_model)),
    case("MDRContact.approach", lambda: reference_model().as_reference().approach, N=N_TOT),
    case("MDRContact.normal_force", lambda: reference_model().as_reference().normal_force, n=N_APP),
    case("MDRContact.backbone", lambda: reference_model().as_reference().backbone, t=T3, N=N_TOT),
    case("MDRContact.gross_slip_displacement", lambda: reference_model().as_reference().gross_slip_displacement,
         N=N_TOT),
    case("MDRContact.backbone_displacement", lambda: reference_model().as_reference().backbone_displacement,
         T=F3, N=N_TOT),

    # -- microslip.model ---------------------------------------------------------------------------
    case("MicroslipModel", lambda: MicroslipModel, kt=[1e6, 2e6], kn=[1e8, 1e8], gaps=[0.0, 1e-7], mu=0.4),
    case("MicroslipModel.element_normal_forces", lambda: model().element_normal_forces, n=N_APP),
    case("MicroslipModel.normal_force", lambda: model().normal_force, n=N_APP),
    case("MicroslipModel.slip_force", lambda: model().slip_force, n=N_APP),
    case("MicroslipModel.approach", lambda: model().approach, N=N_TOT),
    case("MicroslipModel.backbone", lambda: model().backbone, t=T3, n=N_APP),
    case("MicroslipModel.initial_state", lambda: model().initial_state, t0=0.0),
    case("MicroslipModel.simulate", lambda: model().simulate, t=T3, n=N_APP, state=STATE, per_element=True,
         work=True),
    case("MicroslipModel.trial", lambda: model().trial, state=STATE, t=1e-7, n=N_APP),
    case("MicroslipModel.simulate [plane]", lambda: model().simulate, t=T3_PLANE, n=N_APP,
         state=L(lambda: State(np.zeros((4, 2)))), per_element=True, work=True),
    case("MicroslipModel.trial [plane]", lambda: model().trial, state=L(lambda: State(np.zeros((4, 2)))),
         t=[1e-7, -2e-7], n=N_APP),
    case("MicroslipModel.initial_state [plane]", lambda: model().initial_state, t0=[1e-7, 0.0]),
    case("MicroslipModel.from_dict", lambda: MicroslipModel.from_dict, kinds={"data": "mapping"},
         data=L(lambda: model().to_dict())),
    case("MicroslipModel.with_provenance", lambda: model().with_provenance, kinds={"provenance": "object"},
         provenance=L(lambda: model().provenance)),
    case("MicroslipModel.save", lambda: model().save, kinds=PATH, path="saved.json"),
    case("MicroslipModel.load", lambda: MicroslipModel.load, kinds=PATH, path=L(model_file)),
    case("State", lambda: State, sliders=[0.0, 1e-7]),

    # -- microslip.accuracy, microslip.paths -------------------------------------------------------
    case("microslip.accuracy", lambda: accuracy, model=MODEL, reference_model=L(reference_model), paths=PATHS,
         progress=False),
    case("accuracy.reference_run", lambda: reference_run, reference_model=L(reference_model), paths=PATHS,
         chunks=1),
    case("accuracy.restriction_mask", lambda: restriction_mask, paths=PATHS, min_load=1.0,
         min_amplitude=0.0),
    case("PathBatch", lambda: PathBatch, paths=PATHS),
    case("PathBatch.n_for", lambda: batch().n_for, model=MODEL),
    case("PathBatch.run", lambda: batch().run, model=MODEL, chunks=2),
    case("PathBatch.per_path", lambda: batch().per_path, kinds=ARRAY,
         values=L(lambda: np.ones(batch().steady_index.size)), how="sum"),
    case("PathBatch.steady_metrics", lambda: batch().steady_metrics, kinds=ARRAY,
         T=L(lambda: np.ones(batch().t.size)), N=L(lambda: np.ones(batch().t.size)),
         W=L(lambda: np.ones(batch().t.size))),
    case("PathBatch.split", lambda: batch().split, kinds=ARRAY, values=L(lambda: np.ones(batch().t.size))),
    case("AccuracyReport.metric", lambda: report().metric, name="energy_error"),
    case("AccuracyReport.error_maps", lambda: report().error_maps, kinds={"metrics": "object"},
         metrics=("energy_error", "force_difference")),
    case("AccuracyReport.param", lambda: report().param, name="amplitude"),
    case("AccuracyReport.where", lambda: report().where, kinds={"mask": "array"}, mask=[True, False, True, False]),
    case("AccuracyReport.restrict", lambda: report().restrict, min_load=1.0, min_amplitude=0.0),
    case("AccuracyReport.worst", lambda: report().worst, name="energy_error"),
    # NaN when no amplitude meets the limit (documented), e.g. limit = 1e-300
    case("AccuracyReport.threshold_amplitude", lambda: report().threshold_amplitude, finite=False, limit=0.5),
    case("AccuracyReport.to_csv", lambda: report().to_csv, kinds=PATH, path="report.csv"),
    case("Path", lambda: paths.Path, kinds={"steady": "object", "params": "mapping"}, t=X3, n=[N_APP] * 3,
         steady=slice(0, 3), N=[N_TOT] * 3, periodic=False, label="path", params={"N_m": N_TOT}),
    case("Path.simulate", lambda: a_path().simulate, model=MODEL, per_element=False),
    case("paths.loop", lambda: paths.loop, reference=REFERENCE, normal_load=20.0, amplitude=1e-6, cycles=1,
         steps_per_cycle=16),
    case("paths.variable_load_cycles", lambda: paths.variable_load_cycles, reference=REFERENCE, mean_load=20.0,
         load_amplitude=5.0, amplitude=1e-6, phase_deg=90.0, cycles=1, steps_per_cycle=16),
    case("paths.paper_fig4", lambda: paths.paper_fig4, reference=REFERENCE, normal_load=25.0, load_step=12.5,
         raised_at=0.5, beyond=1.3, steps=10),
    case("paths.from_arrays", lambda: paths.from_arrays, kinds={"steady": "object"}, t=X3, n=N_APP,
         steady=slice(0, 3), periodic=True, label="path"),
    case("paths.from_arrays [N]", lambda: paths.from_arrays, t=X3, N=[N_TOT] * 3, reference=REFERENCE),
    case("paths.circle", lambda: paths.circle, reference=REFERENCE, radius=1e-6, mean_load=20.0, load_amplitude=5.0,
         phase_deg=90.0, cycles=1, steps_per_cycle=16),
    case("paths.ellipse", lambda: paths.ellipse, reference=REFERENCE, semi_major=1e-6, semi_minor=0.5e-6,
         mean_load=20.0, load_amplitude=5.0, phase_deg=90.0, angle_deg=30.0, cycles=1, steps_per_cycle=16),
    case("paths.figure_eight", lambda: paths.figure_eight, reference=REFERENCE, half_width=1e-6, half_height=0.5e-6,
         mean_load=20.0, load_amplitude=5.0, phase_deg=90.0, angle_deg=30.0, cycles=1, steps_per_cycle=16),
    case("paths.line", lambda: paths.line, reference=REFERENCE, amplitude=1e-6, mean_load=20.0, load_amplitude=5.0,
         phase_deg=90.0, angle_deg=30.0, cycles=1, steps_per_cycle=16),
    case("paths.default_family", lambda: paths.default_family, reference=REFERENCE, normal_load=N_TOT,
         ratios=[0.0, 0.5], phases_deg=[0.0], amplitudes=[1.0], levels=[1.0], cycles=1, steps_per_cycle=16),
]

CASES += [
    # -- microslip.tuning ------------------------------------------------------------------------
    case("microslip.tune", lambda: tune, reference=REFERENCE, normal_load=N_TOT, elements=4),
    case("microslip.tune [forces]", lambda: tune, reference=REFERENCE, normal_load=N_TOT, forces=[5.0, 10.0, 15.0]),
    # a load range other than the one of the stored points starts a search of minutes
    case("microslip.tune [load_range]", lambda: tune, refused_only=True, skip=NO_LIMIT,
         reference=REFERENCE, normal_load=N_TOT,
         load_range=(7.5, N_TOT), elements=6, energy_target=0.02, force_target=0.02),
    case("microslip.tuning_points", lambda: tuning_points, reference=REFERENCE, normal_load=N_TOT, elements=4),
    case("microslip.tuning_points [displacements]", lambda: tuning_points, reference=REFERENCE, normal_load=N_TOT,
         displacements=L(lambda: np.array([0.3, 0.6, 1.0]) * float(SPHERE.gross_slip_displacement(N_TOT))),
         kinds={"displacements": "array"}),
    case("tuning.model_from_points", lambda: microslip.tuning.model_from_points, reference=REFERENCE,
         points=L(points)),
    case("tuning.tangential_stiffnesses", lambda: microslip.tuning.tangential_stiffnesses, kinds=ARRAY,
         t=L(lambda: points().t), T=L(lambda: points().T)),
    case("tuning.normal_parameters", lambda: microslip.tuning.normal_parameters, kinds=ARRAY, reference=REFERENCE,
         kt=L(lambda: microslip.tuning.tangential_stiffnesses(points().t, points().T)),
         slip_displacements=L(lambda: points().t[::-1]), normal_load=N_TOT),
    # each of these searches for minutes once its arguments are accepted
    case("microslip.tune_to_target", lambda: microslip.tune_to_target, refused_only=True, skip=NO_LIMIT,
         reference=REFERENCE,
         load_range=(20.0, N_TOT), elements=3, energy_target=0.02, force_target=0.02, min_amplitude=0.5),
    case("microslip.smallest_elements", lambda: microslip.smallest_elements, refused_only=True, skip=NO_LIMIT,
         reference=REFERENCE, load_range=(20.0, N_TOT), energy_target=0.9, force_target=0.9, min_amplitude=0.5,
         max_elements=4, spacing="force", start=2),
    case("tuning.element_sweep", lambda: microslip.tuning.element_sweep, refused_only=True, problem=L(problem),
         elements=[2, 3], spacings=["force"]),
    case("TargetProblem", lambda: TargetProblem, kinds={"family_options": "mapping"}, skip=NO_LIMIT,
         reference=REFERENCE,
         load_range=(20.0, N_TOT), energy_target=0.02, force_target=0.02, min_amplitude=0.5, steps_per_cycle=16,
         reference_elements=40, family_options=dict(ratios=(0.0,), phases_deg=(0.0,), amplitudes=(1.0,),
                                                    levels=(1.0,)), dense=False),
    case("TargetProblem.report", lambda: problem().report, model=MODEL),
    case("TargetProblem.amplitude_report", lambda: problem().amplitude_report, model=MODEL),
    case("TargetProblem.worst", lambda: problem().worst, model=MODEL),
    case("TargetProblem.score", lambda: problem().score, model=MODEL),
    case("TargetProblem.normalised", lambda: problem().normalised, energy_error=0.01, force_difference=0.01),
    case("TargetProblem.result", lambda: problem().result, model=MODEL, points=L(points), spacing="force",
         evaluations=1),
    case("TargetProblem.tune_fractions", lambda: problem().tune_fractions, fractions=[0.3, 0.6, 1.0]),
    case("TargetProblem.tune_points", lambda: problem().tune_points, kinds={"points": "object"}, points=L(points)),
    case("TargetProblem.tune_spacing", lambda: problem().tune_spacing, spacing="force", elements=3),
    case("ElementSweep.smallest", lambda: sweep().smallest, spacing="force"),

    # -- microslip.measured, microslip.loops -------------------------------------------------------
    # points that do not rise are a TuningError about the data ("the backbone points do not rise"), not naming x, y
    case("microslip.fit_backbone", lambda: fit_backbone, kinds=ARRAY, skip={"x": ("1e-300",), "y": NO_RISE},
         x=L(lambda: backbone_xy()[0]), y=L(lambda: backbone_xy()[1]), knots=8),
    # NaN, inf and strings are not refused yet (inverse([nan]) returns 3e-26): left out until FittedBackbone
    # checks its input
    case("FittedBackbone.__call__", lambda: fitted(), x=T3),
    case("FittedBackbone.slope", lambda: fitted().slope, x=T3),
    case("FittedBackbone.inverse", lambda: fitted().inverse, T=F3),
    case("MeasuredContact.backbone", lambda: measured_contact().backbone, t=T3, N=N_TOT),
    case("MeasuredContact.backbone_displacement", lambda: measured_contact().backbone_displacement, T=F3, N=N_TOT),
    case("MeasuredContact.gross_slip_displacement", lambda: measured_contact().gross_slip_displacement, N=N_TOT),
    case("MeasuredContact.approach", lambda: measured_contact().approach, N=N_TOT),
    case("MeasuredContact.normal_force", lambda: measured_contact().normal_force, n=N_APP),
    case("MeasuredContact.branch", lambda: measured_contact().branch, t=T3, N=N_TOT, t_reversal=1e-6,
         T_reversal=12.0),
    # a Masing tolerance the loops cannot meet is a TuningError describing the loops (it names the record)
    case("MeasuredContact.from_loops", lambda: MeasuredContact.from_loops, skip={"masing_tolerance": ("1e-300",)},
         loops=L(some_loops), normal=REFERENCE, mu=0.4, normal_load=N_TOT, knots=8, masing_tolerance=0.1),
    # data that are no branch (t constant; T flat, falling or without microslip) are a LoopError or TuningError
    # naming the record (source), not t or T
    case("MeasuredContact.from_branch", lambda: MeasuredContact.from_branch, kinds=ARRAY,
         skip={"t": ("zero", "1e300", "1e-300"), "T": NO_RISE}, t=L(lambda: a_branch()[0]),
         T=L(lambda: a_branch()[1]), normal=REFERENCE, normal_load=N_TOT, mu=0.4, knots=8, source="branch"),
    # as from_loops; and mu = 1e300 never slips: the Masing error of the elastic predicted loops is inf
    case("microslip.tune_on_loops", lambda: tune_on_loops, skip={"masing_tolerance": ("1e-300",), "mu": ("1e300",)},
         loops=L(some_loops), normal=REFERENCE, elements=3, mu=0.4, normal_load=N_TOT, masing_tolerance=0.1),
    case("microslip.validate", lambda: microslip.validate, model=MODEL, normal=REFERENCE, loops=L(some_loops)),
    case("LoopTuning.transition", lambda: loop_tuning().transition, N=20.0, dN=10.0, at=0.5, points=30),
    case("LoopTuning.validation_at", lambda: loop_tuning().validation_at, normal_load=N_TOT),
    # it draws and writes figures once its arguments are accepted
    case("LoopTuning.report", lambda: loop_tuning().report, refused_only=True, kinds=PATH, out_dir="report",
         stem="report", title="title"),
    # a source that is not a string is not refused yet: left out until Record checks it
    case("Record", lambda: loops.Record, kinds=ARRAY, t=L(lambda: a_record().t), T=L(lambda: a_record().T), normal_load=N_TOT, source="record"),
    case("Record.analyse", lambda: a_record().analyse, threshold=0.1),
    case("loops.analyse", lambda: loops.analyse, record=L(a_record), threshold=0.1, stick_fraction=0.1,
         slip_fraction=0.1, steady_tolerance=0.05, noise_correction=True),
    case("loops.find_reversals", lambda: loops.find_reversals, kinds=ARRAY, t=L(lambda: a_record().t),
         threshold=1e-7),
    case("loops.read", lambda: loops.read, kinds={**PATH, "columns": "mapping", "units": "mapping"},
         path=L(record_file), columns={"t": "t", "T": "T"}, units={"t": "m"}, normal_load=N_TOT),
    case("Loops.cycle_bounds", lambda: some_loops().cycle_bounds, cycle=1),
    # steady_mean, branch and backbone_points do not check their argument yet (AttributeError, IndexError for
    # branch(2.5)): left out until they do
    case("Loops.steady_mean", lambda: some_loops().steady_mean, name="energy"),
    case("Loops.branch", lambda: some_loops().branch, number=1),
    case("Loops.backbone_points", lambda: some_loops().backbone_points, cycles=[1, 2]),

    # -- microslip.frequency -----------------------------------------------------------------------
    case("Structure", lambda: Structure, M=[[1.0]], C=[[1.0]], K=[[1e4]]),
    case("Structure.add_contact", lambda: jenkins_structure().add_contact, model=MODEL, tangential=0,
         approach=1e-6, name="wall"),
    case("Structure.add_contact [normal]", lambda: Structure(np.eye(2), None, np.eye(2)).add_contact, model=MODEL,
         tangential=0, normal=1, preload=1.0, approach=1e-6),
    case("Structure.force_vector", lambda: jenkins_structure().force_vector, force=[1.0], name="force"),
    # an array force is not checked yet (NaN, inf, strings give zero displacement): left out until it is
    case("microslip.static_solution", lambda: microslip.frequency.static_solution,
         skip={"force": ("nan", "inf", "string", "dict")}, structure=L(jenkins_structure), force=[1.0],
         tolerance=1e-10),
    # a force of 1e300 N overflows the work per cycle (force times displacement) to inf; at 1e-300 rad/s every mode
    # lies above the harmonics, so Hill's method resolves no Floquet exponent: leading_exponent is NaN by definition
    case("microslip.frequency_point", lambda: frequency_point, skip={"force": ("1e300",), "omega": ("1e-300",)},
         structure=L(jenkins_structure), force=[1.0], omega=100.0, harmonics=1, samples=16, max_periods=100),
    # a curve takes seconds once its arguments are accepted
    case("microslip.frequency_response", lambda: microslip.frequency_response, refused_only=True,
         structure=L(jenkins_structure), force=[1.0], omega=(90.0, 110.0), harmonics=1, samples=16, progress=False,
         max_periods=100),
    # a mode takes a second once its arguments are accepted
    case("microslip.nonlinear_modes", lambda: microslip.nonlinear_modes, refused_only=True,
         structure=L(jenkins_structure), mode=1, amplitude=(1e-5, 1e-3), harmonics=1, samples=16, progress=False,
         max_periods=100),
    case("NonlinearModes.frequency", lambda: a_mode().frequency, unit="Hz"),
    case("NonlinearModes.amplitude", lambda: a_mode().amplitude, dof=0, harmonic=1),
    case("NonlinearModes.shape", lambda: a_mode().shape, point=0),
    case("NonlinearModes.columns", lambda: a_mode().columns, dofs=[0]),
    case("NonlinearModes.forced_response", lambda: a_mode().forced_response, force=[0.5], omega=(100.0, 160.0),
         points=50),
    case("SynthesizedResponse.amplitude", lambda: a_synthesis().amplitude, dof=0, harmonic=1),
    case("SynthesizedResponse.peak", lambda: a_synthesis().peak, dof=0, harmonic=1),
    case("microslip.steady_state", lambda: steady_state, structure=L(jenkins_structure), force=[1.0], omega=100.0,
         steps_per_period=64, harmonics=1, tolerance=1e-7, max_periods=20, progress=False, start=L(a_point)),
    case("frequency.aft", lambda: aft, model=MODEL, t=[1e-7, 1e-7, 0.0], n=[N_APP, 0.0, 0.0], samples=16,
         max_periods=100),
    case("frequency.aft_plane", lambda: microslip.frequency.aft_plane, model=MODEL, t=[[1e-7, 1e-7, 0.0]] * 2,
         n=[N_APP, 0.0, 0.0], samples=16, max_periods=100),
    case("frequency.aft_batch", lambda: microslip.frequency.aft_batch, models=L(lambda: [model(), model()]),
         t=[[1e-7, 1e-7, 0.0]] * 2, n=[[N_APP, 0.0, 0.0]] * 2, samples=16, max_periods=100),
    # cycle_work does not check its arrays yet (NaN, strings, mismatched lengths give a number): left out until
    # it does
    case("frequency.cycle_work", lambda: microslip.frequency.cycle_work,
         skip={"force": ("nan", "inf", "string", "dict"), "displacement": ("nan", "inf", "string", "dict")},
         force=[0.0, 1.0, 0.0], displacement=[0.0, 0.0, 1e-6]),
    case("frequency.default_samples", lambda: microslip.frequency.default_samples, harmonics=5),
    case("frequency.time_samples", lambda: microslip.frequency.time_samples, coefficients=[0.0, 1e-6, 0.0], samples=16),
    case("StepControl", lambda: StepControl, ds_initial=0.02, ds_min=1e-7, ds_max=0.05, max_angle=0.1,
         target_iterations=3, max_iterations=12, max_points=5000, tolerance=1e-9),
    case("HarmonicBalance", lambda: HarmonicBalance, structure=L(jenkins_structure), force=[1.0], harmonics=1,
         samples=16, max_periods=100),
    case("HarmonicBalance.local", lambda: harmonic_balance().local, x=X3),
    case("HarmonicBalance.dynamic_stiffness", lambda: harmonic_balance().dynamic_stiffness, omega=100.0),
    case("HarmonicBalance.evaluate", lambda: harmonic_balance().evaluate, x=X3, omega=100.0, jacobian=True),
    case("HarmonicBalance.evaluate_reference", lambda: harmonic_balance().evaluate_reference, x=X3, omega=100.0,
         jacobian=True),
    case("FrequencyResponse.amplitude", lambda: a_point().amplitude, dof=0, harmonic=1),
    case("FrequencyResponse.peak", lambda: a_point().peak, dof=0, harmonic=1),
    case("FrequencyResponse.peak_on_edge", lambda: a_point().peak_on_edge, dof=0, harmonic=1),
    case("FrequencyResponse.time_history", lambda: a_point().time_history, point=0, dof=0, samples=16),
    case("FrequencyResponse.columns", lambda: a_point().columns, dofs=[0]),
    case("FrequencyResponse.to_csv", lambda: a_point().to_csv, kinds=PATH, path="frf.csv", dofs=[0]),
    case("SteadyState.amplitude", lambda: a_steady_state().amplitude, dof=0, harmonic=1),
    case("AFTResult.dissipation", lambda: aft_result().dissipation, t=[1e-7, 1e-7, 0.0]),
    case("PlaneAFTResult.dissipation", lambda: plane_aft_result().dissipation, t=[[1e-7, 1e-7, 0.0]] * 2),
    case("Structure.add_static_force", lambda: jenkins_structure().add_static_force, force=[1.0]),
    case("FrequencyResponse.dof_coefficients", lambda: a_point().dof_coefficients, dof=0),
    case("FrequencyResponse.sector_coefficients", lambda: disk_point().sector_coefficients, dof=1, sector=2),
    case("CyclicStructure", lambda: microslip.frequency.CyclicStructure, M=np.eye(3) * 0.1, C=None,
         K=[[2e6, -1e6, 0.0], [-1e6, 2e6, -1e6], [0.0, -1e6, 1e6]], sectors=8, left=[0], right=[2]),
    # in the global Cartesian frame: two nodes (x, y) and one between them, the right node the left one turned by 45 deg
    case("CyclicStructure [cartesian]", lambda: microslip.frequency.CyclicStructure, M=np.eye(6) * 0.1, C=None,
         K=np.kron([[2e6, -1e6, 0.0], [-1e6, 2e6, -1e6], [0.0, -1e6, 1e6]], np.eye(2)), sectors=8, left=[[0, 1]],
         right=[[4, 5]], frame="cartesian", axis=[0.0, 0.0, 1.0], point=[0.0, 0.0],
         coordinates=[[[0.1, 0.0]], [[0.1 * np.cos(np.pi / 4), 0.1 * np.sin(np.pi / 4)]]], nodes=[[2, 3]]),
    case("CyclicStructure.add_contact", lambda: disk().add_contact, model=MODEL, tangential=1, approach=1e-6),
    case("CyclicStructure.next", lambda: disk().next, dof=1),
    case("CyclicStructure.phase", lambda: disk().phase, harmonic=1, engine_order=1),
    case("CyclicStructure.constraint", lambda: disk().constraint, phi=0.5),
    case("CyclicStructure.matrices", lambda: disk().matrices, phi=0.5),
    case("microslip.contact_cycle", lambda: microslip.frequency.contact_cycle, result=L(a_point), contact=0, point=0,
         samples=16),
    case("CyclicStructure.travelling_wave", lambda: disk().travelling_wave, force=[0.0, 1.0, 0.0], engine_order=3),
    case("CyclicStructure.assembled", lambda: disk().assembled, stiffness_scale=np.linspace(0.98, 1.02, 8),
         scaled_dofs=[0, 1]),
    case("frequency.blade_scatter", lambda: microslip.frequency.blade_scatter, sectors=8, std=0.02, seed=1, sample=0),
    case("frequency.mistuned_disk", lambda: microslip.frequency.mistuned_disk, sector=L(disk),
         scatter=np.linspace(-0.02, 0.02, 8), blade_dofs=[0, 1]),
    case("frequency.blade_peaks", lambda: microslip.frequency.blade_peaks, result=L(whole_disk_point), sector=L(disk),
         dof=1, harmonic=1),
    case("frequency.amplification_factor", lambda: microslip.frequency.amplification_factor,
         result=L(whole_disk_point), tuned=L(disk_point), sector=L(disk), dof=1, harmonic=1),
    case("UnderPlatformDamper", lambda: microslip.frequency.UnderPlatformDamper, mass=0.02, inertia=1e-6,
         centrifugal_load=300.0, retention=1e3),
    case("UnderPlatformDamper.add_interface", lambda: damper().add_interface,
         kinds={"platform": "object", "points": "array"}, models=L(lambda: MicroslipModel([1e6], [1e8], [0.0], 0.5)),
         points=[[-4e-3, 2e-3], [-2e-3, 4e-3]], angle_deg=135.0, platform=[{"x": 0, "y": 1}, {"x": 0, "y": 1}],
         name="flat"),
    case("UnderPlatformDamper.add_interface [radians]", lambda: damper().add_interface,
         kinds={"platform": "object", "points": "array"}, models=L(lambda: MicroslipModel([1e6], [1e8], [0.0], 0.5)),
         points=[[-4e-3, 2e-3], [-2e-3, 4e-3]], angle=2.356, platform=[{"x": 0, "y": 1}, {"x": 0, "y": 1}],
         name="flat"),
    case("UnderPlatformDamper.static_balance", lambda: damper_with_interface().static_balance, result=L(damper_point)),
    case("UnderPlatformDamper.attach", lambda: damper_with_interface().attach,
         structure=L(lambda: Structure(np.eye(2), None, np.eye(2) * 1e4))),
    case("microslip.craig_bampton", lambda: microslip.frequency.craig_bampton, structure=L(three_dofs), keep=[0],
         modes=1),
    case("CraigBampton.expand", lambda: reduced().expand, u=[1e-6, 0.0]),
    case("Structure.from_files", lambda: Structure.from_files, kinds=PATH, path=L(matrices_file)),
    case("CyclicStructure.from_files", lambda: microslip.frequency.CyclicStructure.from_files, kinds=PATH,
         path=L(sector_file), sectors=8, left=[0], right=[2]),
    case("Structure.dof_index", lambda: jenkins_structure().dof_index, dof=0),
    case("microslip.damper_design_curve", lambda: microslip.frequency.damper_design_curve, refused_only=True,
         kinds={"damper": "object", "force": "array"}, structure=L(lambda: Structure(np.eye(2), None, np.eye(2) * 1e4)),
         damper=L(damper_with_interface), loads=[100.0, 300.0], force=[1.0, 0.0], omega=(50.0, 150.0), dof=0),
    case("DesignCurve.to_csv", lambda: design_curve().to_csv, kinds=PATH, path="design.csv"),
    case("SpeedModel", lambda: microslip.frequency.SpeedModel, M=np.eye(2), C=None,
         stiffness=[np.diag([2e4, 1e4]), np.diag([2.1e4, 1.2e4])], speeds=[0.0, 500.0]),
    case("SpeedModel.weights", lambda: speed_model().weights, omega_rot=300.0),
    case("SpeedModel.stiffness", lambda: speed_model().stiffness, omega_rot=300.0),
    case("SpeedModel.at", lambda: speed_model_with_contact().at, omega_rot=300.0, contacts=True, damper=True),
    case("microslip.campbell", lambda: microslip.frequency.campbell, model=L(speed_model_with_contact),
         speeds=[0.0, 100.0, 200.0], modes=2, engine_orders=[1, 2], contacts="both"),
    case("frequency.excited_diameter", lambda: microslip.frequency.excited_diameter, engine_order=5, sectors=8),
    case("CampbellDiagram.hertz", lambda: a_campbell().hertz, system="stuck"),
    case("CampbellDiagram.to_csv", lambda: a_campbell().to_csv, kinds=PATH, path="campbell.csv"),
    case("microslip.damper_speed_curve", lambda: microslip.frequency.damper_speed_curve, refused_only=True,
         kinds={"force": "array"}, model=L(lambda: speed_model(damper=damper_with_interface(), radius=0.2)),
         speeds=[100.0, 200.0], force=[1.0, 0.0, 0.0], omega=(50.0, 150.0), dof=0),
    case("CraigBampton.save", lambda: reduced().save, kinds=PATH, path="saved.npz"),
    case("CraigBampton.load", lambda: microslip.frequency.CraigBampton.load, kinds=PATH, path=L(reduced_file)),

    # -- microslip.fe ------------------------------------------------------------------------------
    # one node's three DOFs: node ids of zero are valid, so zero nodes must give a map
    case("DofMap", lambda: microslip.fe.DofMap, kinds={"components": "object"}, nodes=[1, 1, 1],
         components=["x", "y", "rz"]),
    case("DofMap.from_names", lambda: microslip.fe.DofMap.from_names, kinds={"names": "object"},
         names=["1:x", "1:y", "2:x"]),
    case("DofMap.from_csv", lambda: microslip.fe.DofMap.from_csv, kinds=PATH, path=L(dof_file)),
    case("DofMap.to_csv", lambda: dof_map().to_csv, kinds=PATH, path="dofs_out.csv"),
    case("DofMap.index", lambda: dof_map().index, name="1:y"),
    case("DofMap.rows", lambda: dof_map().rows, node=1),
    # the smallest blade (about 400 DOFs, 0.04 s): every accepted bad value builds one
    case("fe.blade", lambda: microslip.fe.blade, dofs=300, span=0.06, chord=0.02, platform_width=0.04,
         platform_height=0.004, shank_width=0.012, shank_height=0.015, thickness=0.003, contact_width=0.004,
         contact_nodes=3, E=2e11, nu=0.3, rho=8190.0),
    case("FEBlade.position", lambda: fe_blade().position, node=1),
    case("fe.natural_frequencies", lambda: microslip.fe.natural_frequencies, M=FE_M, K=FE_K, count=2),
    case("fe.natural_frequencies [sparse]", lambda: microslip.fe.natural_frequencies,
         kinds={"M": "object", "K": "object"}, M=L(lambda: scipy.sparse.csr_matrix(FE_M)),
         K=L(lambda: scipy.sparse.csr_matrix(FE_K)), count=2),
    case("fe.read_matrix", lambda: microslip.fe.read_matrix, kinds=PATH, path=L(fe_file), name="KGG",
         symmetry_tolerance=1e-6),
    case("fe.read_matrices", lambda: microslip.fe.read_matrices,
         kinds={**PATH, "dof_map": "path", "names": "mapping"}, path=L(fe_file), dof_map=L(dof_file),
         names={"M": "MGG", "K": "KGG"}, symmetry_tolerance=1e-6),
    case("fe.read_matrices [per matrix]", lambda: microslip.fe.read_matrices,
         kinds={"M": "path", "K": "path", "C": "path"}, M=L(lambda: mtx_file("M")), K=L(lambda: mtx_file("K")),
         C=L(lambda: mtx_file("C"))),
    # contact patches: node ids of zero are valid; shifted or scaled positions still pair (or are refused)
    case("fe.contact_patch", lambda: microslip.fe.contact_patch, mesh_or_points=PATCH_POINTS, surface_a=PATCH_A,
         surface_b=PATCH_B, tolerance=1e-6),
    case("fe.patch_from_mesh", lambda: microslip.fe.patch_from_mesh, kinds=PATH, path=L(patch_file),
         set_a="LOWER", set_b="UPPER", tolerance=1e-6),
    case("fe.add_patch", lambda: microslip.fe.add_patch, kinds={"dofs": "mapping"}, structure=L(patch_structure),
         patch=L(a_patch), law=PRESSURE_LAW, dofs={k: (3 * k, 3 * k + 1, 3 * k + 2) for k in range(12)},
         name="patch"),
    case("fe.add_patch [relative]", lambda: microslip.fe.add_patch, kinds={"dofs": "mapping"},
         structure=L(lambda: Structure(np.eye(6), np.zeros((6, 6)), np.eye(6))), patch=L(table_patch),
         law=PRESSURE_LAW, dofs={3: (0, 1, 2), 8: (3, 4, 5)}, relative=True),
    # the lap joint: each build takes seconds, so only the values it must refuse before meshing
    case("fe.lap_joint", lambda: microslip.fe.lap_joint, refused_only=True, contacts=30, modes=4, length=0.24,
         width=0.03, thickness=0.012, overlap=0.12, bolt_load=1e4, washer=3.0, E=2e11, nu=0.3, rho=7850.0),
    case("frequency.jointed_structure", lambda: microslip.frequency.jointed_structure, joint=L(lap_joint),
         law=PRESSURE_LAW, damping_ratio=1e-3),
    # interface tables: node ids of zero and negative areas are refused, a zero normal has no unit length
    case("fe.patch_from_tables", lambda: microslip.fe.patch_from_tables, nodes_a=[3, 8], area=[1e-4, 2e-4],
         normal=[[0.0, 0.0, 1.0], [0.6, 0.0, 0.8]], nodes_b=[13, 18], tangent1=[[1.0, 0.0, 0.0], [0.8, 0.0, -0.6]],
         tangent2=[[0.0, 1.0, 0.0], [0.0, 1.0, 0.0]]),
    case("PressureLaw", lambda: microslip.fe.PressureLaw, kn_per_area=1e12, kt_per_area=5e11, mu=0.5, gap=0.0),
    case("PressureLaw.model", lambda: PRESSURE_LAW.model, area=1e-4),
]


# -- design studies --------------------------------------------------------------------------------------
@cache
def study_file() -> str:
    """The smallest study (examples/inclined_block_study.toml) beside its base configuration, in a new folder."""
    import shutil
    import tempfile
    from pathlib import Path

    from _paths import REPO

    folder = Path(tempfile.mkdtemp(prefix="fuzz-study-"))
    for name in ("inclined_block.toml", "sphere_4_elements.json", "inclined_block_study.toml"):
        shutil.copy(REPO / "examples" / name, folder / name)
    study = folder / "inclined_block_study.toml"
    study.write_text(study.read_text().replace('["25N", "37.5N", "50N"]', '["25N"]')
                     .replace('[["0.3N", "0N"], ["0.6N", "0N"]]', '[["0.3N", "0N"]]'))
    return str(study)


@cache
def a_study():
    return microslip.study.load_study(study_file())


@cache
def a_sweep():
    """The one-case study solved on an in-process cluster of one worker."""
    import tempfile

    from dask.distributed import Client, LocalCluster

    with LocalCluster(n_workers=1, threads_per_worker=1, processes=False, dashboard_address=":0") as cluster, \
            Client(cluster) as client:
        return microslip.sweep(a_study(), client, out=tempfile.mkdtemp(prefix="fuzz-sweep-"), report=False)


CASES += [
    # a study's cases are solved on Dask: only the values it must refuse before any work
    case("microslip.sweep", lambda: microslip.sweep, refused_only=True, kinds={"study": "path", "out": "path"},
         study=L(study_file), out="sweep-out", workers=1, progress=False, retry_failed=False, report=False),
    case("study.load_study", lambda: microslip.study.load_study, kinds=PATH, path=L(study_file)),
    case("Study.configuration", lambda: a_study().configuration, case=L(lambda: a_study().cases()[0])),
    case("SweepResult.column", lambda: a_sweep().column, name="peak x (m)"),
    case("SweepResult.curve", lambda: a_sweep().curve, index=0),
    case("SweepResult.measure", lambda: a_sweep().measure, dof="x"),
    # a study without mistuning has no amplification: only the values it must refuse
    case("SweepResult.amplification", lambda: a_sweep().amplification, refused_only=True, dof="x"),
    case("SweepResult.to_csv", lambda: a_sweep().to_csv, kinds=PATH, path="summary.csv"),
]


def a_prestress():
    return microslip.frequency.prestress(jenkins_structure(), [1.0], friction="released")


def two_dof_prestress():
    s = Structure(M=np.eye(2), C=None, K=[[2e4, -1e4], [-1e4, 1e4]])
    s.add_contact(MicroslipModel(kt=[1e4], kn=[1e6], gaps=[0.0], mu=1.0), tangential=1, approach=1e-6)
    return microslip.frequency.prestress(s, [0.0, 1.0], friction="stuck")


CASES += [
    case("microslip.prestress", lambda: microslip.prestress, structure=L(jenkins_structure), load=[1.0],
         friction="released", reduction="none", modes=None, tolerance=1e-10),
    case("Prestress.modes", lambda: a_prestress().modes, n=1),
    case("Prestress.modal_damping", lambda: a_prestress().modal_damping, ratios=[0.01], modes=1),
    case("Prestress.rayleigh_damping", lambda: two_dof_prestress().rayleigh_damping, ratios=[0.01, 0.02],
         modes=(1, 2)),
    case("Prestress.with_damping", lambda: a_prestress().with_damping, C=[[2.0]]),
    case("Prestress.to_csv", lambda: a_prestress().to_csv, kinds=PATH, path="prestress.csv"),
]

CASE = {c.name: c for c in CASES}
assert len(CASE) == len(CASES), "two entries of CASES share a name"

# -- what is not fuzzed, and why ----------------------------------------------------------------------

#: methods that draw (matplotlib checks its own arguments) and solver steps that work on arrays the solver built
NOT_FUZZED = {
    "AccuracyReport.plot": "draws", "AccuracyReport.plot_amplitude": "draws", "FittedBackbone.plot": "draws",
    "FrequencyResponse.plot": "draws", "LoopTuning.plot_branch": "draws", "LoopTuning.plot_elements": "draws",
    "LoopTuning.plot_normal": "draws", "LoopTuning.plot_transition": "draws", "Validation.plot": "draws",
    "Response.plot": "draws", "Path.plot": "draws", "Record.plot": "draws", "Loops.plot": "draws",
    "TargetTuning.plot": "draws", "ElementSweep.plot": "draws",
    "HarmonicBalance.solve": "a step of the solver on its own Jacobian (NaN for a singular one, by design)",
    "HarmonicBalance.augmented": "a step of the solver on its own Jacobian",
    "HarmonicBalance.curve_quantities": "a step of the solver on its own solutions",
    "DesignCurve.plot": "draws",
    "CampbellDiagram.plot": "draws",
    "SpeedCurve.plot": "draws",
    "ContactCycle.plot": "draws",
    "frequency.plot_contact_cycles": "draws",
    "NonlinearModes.plot": "draws",
    "SynthesizedResponse.plot": "draws",
    "SweepResult.plot": "draws",
    "ContactReference": "a protocol: what a reference provides, nothing to call",
    "NonlinearModes.synthesize": "the deprecated name of NonlinearModes.forced_response, fuzzed under that name",
    "Prestress.plot": "draws",
}

#: classes whose objects the package builds and returns (their constructors are not an entry point)
RESULTS = {"AccuracyReport", "AFTResult", "PlaneAFTResult", "Contact", "ElementSweep", "FittedBackbone", "FrequencyResponse",
           "LoadValidation", "LoopTuning", "Loops", "MDRModel", "MeasuredContact", "ReferenceRun", "Response",
           "SteadyState", "Step", "TargetTuning", "TuningPoints", "Validation", "CraigBampton", "DamperContact",
           "DesignCurve", "CampbellDiagram", "SpeedCurve", "FEBlade", "FEMatrices", "ContactCycle", "NonlinearModes",
           "SynthesizedResponse", "SweepResult", "Study", "Case", "Mistuning", "ContactPatch", "Prestress",
           "PrestressedModes", "LapJoint"}

PUBLIC_MODULES = ("microslip", "microslip.frequency", "microslip.loops", "microslip.paths", "microslip.reference",
                  "microslip.tuning", "microslip.measured", "microslip.accuracy", "microslip.fe", "microslip.study")


def public_callables() -> dict:
    """``{name: callable}`` for every public function, class and public method with arguments to fuzz."""
    out, seen = {}, set()
    for module_name in PUBLIC_MODULES:
        module = importlib.import_module(module_name)
        short = module_name.replace("microslip.", "")
        for attr in module.__all__:
            obj = getattr(module, attr)
            if inspect.ismodule(obj) or not callable(obj) or id(obj) in seen:
                continue
            seen.add(id(obj))
            if not inspect.isclass(obj):
                out[f"{short}.{attr}"] = obj
                continue
            if issubclass(obj, BaseException) or obj.__name__ in NOT_FUZZED:
                continue
            if obj.__name__ not in RESULTS:
                out[obj.__name__] = obj
            for name, member in vars(obj).items():
                if name.startswith("_") and name != "__call__":
                    continue
                func = member.__func__ if isinstance(member, (classmethod, staticmethod)) else member
                if inspect.isfunction(func) and _arguments(func):
                    out[f"{obj.__name__}.{name}"] = func
    return out


def _arguments(func) -> list:
    return [p for p in inspect.signature(func).parameters.values() if p.name not in ("self", "cls")]


def test_every_public_callable_is_fuzzed():
    covered = {c.name.split(" [")[0] for c in CASES}
    missing = sorted(set(public_callables()) - covered - set(NOT_FUZZED))
    assert not missing, f"public callables without an entry in CASES (or a reason in NOT_FUZZED): {missing}"
    unknown = sorted(covered - set(public_callables()))
    assert not unknown, f"entries of CASES that are not public callables: {unknown}"


# -- running one call ------------------------------------------------------------------------------------

MEMORY = 2 << 30  # bytes of address space a call may add
SECONDS = 20      # a call that takes longer has attempted a size it should have refused


class TooSlow(Exception):
    pass


@contextmanager
def _limits():
    """At most ``MEMORY`` more bytes of address space and ``SECONDS`` of time (where the system allows it)."""
    try:
        import resource
        with open("/proc/self/statm") as f:
            used = int(f.read().split()[0]) * resource.getpagesize()
    except (ImportError, OSError):  # not Linux: no limit
        yield
        return
    soft, hard = resource.getrlimit(resource.RLIMIT_AS)
    limit = used + MEMORY if hard == resource.RLIM_INFINITY else min(used + MEMORY, hard)

    def alarm(signum, frame):
        raise TooSlow(f"took more than {SECONDS} s")

    previous = signal.signal(signal.SIGALRM, alarm)
    resource.setrlimit(resource.RLIMIT_AS, (limit, hard))
    signal.setitimer(signal.ITIMER_REAL, SECONDS)
    try:
        yield
    finally:
        signal.setitimer(signal.ITIMER_REAL, 0)
        signal.signal(signal.SIGALRM, previous)
        resource.setrlimit(resource.RLIMIT_AS, (soft, hard))


def _call(c: Case, arg: str | None = None, value=None):
    fn = c.target()
    kwargs = {k: _resolve(v) for k, v in c.args.items()}
    if arg is not None:
        kwargs[arg] = value
    with _limits(), warnings.catch_warnings():
        warnings.simplefilter("ignore")  # warnings are not errors here: a warned result must still be finite
        return fn(**kwargs)


def _non_finite(x, where: str = "result", seen=None) -> str | None:
    """Where a NaN or an infinity hides in ``x`` (numbers, arrays, containers, the package's objects), or None."""
    seen = set() if seen is None else seen
    if x is None or isinstance(x, (bool, np.bool_, str, bytes, int, np.integer)):
        return None
    if isinstance(x, (float, complex, np.floating, np.complexfloating)):
        return None if np.isfinite(x) else f"{where} = {x!r}"
    if isinstance(x, np.ndarray):
        if x.dtype.kind in "fc":
            bad = np.argwhere(~np.isfinite(x))
            return f"{where}[{', '.join(map(str, bad[0]))}] = {x[tuple(bad[0])]!r}" if bad.size else None
        if x.dtype.kind != "O":
            return None
    if id(x) in seen:
        return None
    seen.add(id(x))
    if isinstance(x, dict):
        items = x.items()
    elif isinstance(x, (list, tuple, np.ndarray)):
        items = enumerate(x)
    elif hasattr(x, "toarray"):  # scipy.sparse
        items = [("data", x.data)]
    elif dataclasses.is_dataclass(x) and not isinstance(x, type):
        items = ((f.name, getattr(x, f.name)) for f in dataclasses.fields(x))
    elif type(x).__module__.startswith("microslip") and hasattr(x, "__dict__"):
        items = vars(x).items()
    else:
        return None
    for key, value in items:
        found = _non_finite(value, f"{where}[{key!r}]" if isinstance(x, (dict, list, tuple)) else f"{where}.{key}",
                            seen)
        if found:
            return found
    return None


_UNIT_AFTER_NUMBER = re.compile(r"(\d|inf|nan)\s*(N|m|J|s|Pa)\b")


def _names(message: str, arg: str) -> bool:
    """True when ``message`` names the argument ``arg`` (not merely a unit after a number, as in ``15 N``)."""
    return re.search(rf"(?<!\w){re.escape(arg)}(?!\w)", _UNIT_AFTER_NUMBER.sub("", message)) is not None


# -- the tests ---------------------------------------------------------------------------------------------


@pytest.fixture(scope="module", autouse=True)
def _in_tmp(tmp_path_factory):
    """The calls that write or read files do it in a temporary folder."""
    with pytest.MonkeyPatch.context() as mp:
        mp.chdir(tmp_path_factory.mktemp("fuzz"))
        yield


@pytest.mark.parametrize("name", [c.name for c in CASES if not c.refused_only])
def test_the_valid_call_succeeds_with_a_finite_result(name):
    c = CASE[name]
    result = _call(c)
    assert _non_finite(result) is None or not c.finite, _non_finite(result)


def _fuzzed():
    for c in CASES:
        for arg, value in c.args.items():
            kind = c.kinds.get(arg) or _kind(value)
            for label, refuse in ((b.label, b.refuse) for b in _bad_values(np.zeros(2), kind)):
                if label in c.skip.get(arg, ()) or (c.refused_only and not refuse):
                    continue
                yield pytest.param(c.name, arg, label, id=f"{c.name}-{arg}-{label}")


@pytest.mark.parametrize(("name", "arg", "label"), list(_fuzzed()))
def test_a_bad_argument_is_refused_by_name_or_gives_a_finite_result(name, arg, label):
    c = CASE[name]
    kind = c.kinds.get(arg) or _kind(c.args[arg])
    bad = next(b for b in _bad_values(_resolve(c.args[arg]), kind) if b.label == label)
    call = f"{name}({arg}={label})"
    try:
        result = _call(c, arg, bad.value)
    except (ValueError, TypeError) as exc:
        assert _names(str(exc), arg), f"{call} raised {type(exc).__name__} without naming {arg!r}: {exc}"
        return
    except Exception as exc:  # noqa: BLE001 - any other exception is the defect reported
        pytest.fail(f"{call} raised {type(exc).__name__}: {exc}")
    assert not bad.refuse, f"{call} was accepted: {_show(result)}"
    if c.finite:
        where = _non_finite(result)
        assert where is None, f"{call} returned a non-finite value: {where}"


def _show(x) -> str:
    text = repr(x)
    return text if len(text) < 200 else text[:197] + "..."
