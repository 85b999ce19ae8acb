"""The TOML configuration of ``microslip frf``: a structure, its contacts, the excitation, the sweep.

Every number is SI unless it is a string with a unit (``"37.5N"``, ``"2um"``,
``"2kHz"``). Paths are relative to the configuration file. Example::

    title = "Block on an inclined plane"

    [structure]
    M = [[0.1, 0.0], [0.0, 0.1]]        # kg; or matrices = "model.npz" (arrays M, K, optional C), or
                                        # file = "blade.mat" (.mat v5/v7.3, .npz, .op4: M, K, optional C;
                                        # names = {M = "MGG", K = "KGG"} for other names), or M = "M.mtx",
                                        # K = "K.mtx" (one file per matrix); dof_map = "dofs.csv" (node,
                                        # component per row) lets contacts and forces name DOFs "1204:x"
    K = [[1e7, 0.0], [0.0, 1e7]]        # N/m
    C = [[17.3, 0.0], [0.0, 17.3]]      # N s/m (optional), or rayleigh = [alpha, beta]: C = alpha M + beta K
    dofs = ["x", "y"]                   # optional names of the DOFs

    [[contact]]                         # one table per contact
    model = "contact.json"              # from 'microslip tune' (MicroslipModel.save)
    tangential = [0.866, 0.5]           # t = b_t . q: a DOF index, a list per DOF, or {"0" = 1, "1" = -1};
                                        # two directions for a contact moving on its plane: [dir1, dir2], e.g.
                                        # [{"0" = 1}, {"1" = 1}], ["12:x", "12:y"] or [[1.0, 0.0], [0.0, 1.0]]
    normal = [-0.5, 0.866]              # n = b_n . q + approach (omit to impose the approach)
    preload = "37.5N"                   # static force on the structure along normal, shared between the
                                        # contact and the structure's springs (the report prints what the
                                        # contact carries, N0)
    # approach = "2um"                  # imposed approach at q = 0 (with normal omitted: the normal load is
                                        # then fixed, e.g. approach of the tuned contact at the wanted load)
    # name = "damper"

    # [cyclic]                          # one sector of a bladed disk (CyclicStructure)
    # sectors = 24
    # left = [0]                        # boundary DOFs: right[j] of a sector is left[j] of the next
    # right = [1]
    # engine_order = 3                  # the travelling wave's engine order (or in [sweep])
                                        # contacts may then name the next sector's DOFs: {"next:4" = -1}

    # [[damper]]                        # an under-platform damper (UnderPlatformDamper), one table each
    # mass = 0.01                       # kg
    # inertia = 5e-7                    # kg m^2
    # centrifugal_load = "300N"         # or speed = "1000rad/s" with radius = "0.25m"
    # damping = 50.0                    # 1/s, mass-proportional (optional)
    # retention = "1e3N/m"              # N/m: the features keeping the damper in its pocket, a spring from
                                        # each of X, Y and the arc R to the disk (optional, default 0)
    # [[damper.interface]]              # one table per interface
    # model = "flat.json"               # the contacts' law (a list of files: one per point)
    # points = [[-2e-3, 1.5e-3], [-1e-3, 2.5e-3]]   # m, on the damper from its centre of mass
    # angle = 120                       # degrees: the normal, from the damper into the platform
    # platform = {x = 0, y = 1}         # the platform's DOFs at the points (a list: one per point;
                                        # "next:4" for the next sector's)

    [excitation]                        # amplitudes per DOF (N); "static" for the static force
    h1 = [0.6, 0.0]
    # phase_h1 = [0.0, 90.0]            # degrees: F = amplitude * exp(i phase)
    # scale = 2.0                       # multiplies every harmonic's amplitude (not the static force)

    [sweep]
    omega = [12000, 16500]              # rad/s; or frequency = [1900, 2600] (Hz), or strings with units:
                                        # "60Hz" and "2kHz" mean 2 pi 60 and 2 pi 2000 rad/s wherever written
    harmonics = 7
    # samples = 128                     # AFT samples per period (default 16 H rounded up to 2^k)
    # reduction = "exact"               # "auto" (default), "exact", "modal" or "none": harmonic balance on the
    # modes = 60                        # contact DOFs (see frequency_response); modes for "modal"
    # engine_order = 3                  # with [cyclic]: the excitation's engine order (or in [cyclic])

    [continuation]                      # optional step control (see StepControl)
    # ds_max = 0.05
    # max_angle = 0.1

    # [modes]                           # microslip modes: a nonlinear mode (extended periodic motion concept)
    # mode = 1                          # the linear mode, contacts stuck, it starts from (1: the lowest)
    # amplitude = [1e-8, 1e-4]          # its modal amplitude range, kg^1/2 m (a = sqrt(m) x for a rigid mass m)
    # dof = "x"                         # the DOF whose amplitude the plots also show (default: the first plotted)
    # compare = true                    # also solve [excitation]'s forced response over [sweep] by harmonic
                                        # balance and compare it with the one synthesised from the mode
                                        # ([excitation] and [sweep] omega are optional for microslip modes)
    # nodal_diameter = 3                # with [cyclic]: the mode's nodal diameter (default: its engine_order)

    # [design]                          # microslip design: the damper's peak-response curve
    # loads = ["3N", "20N", "300N"]     # centrifugal loads of the (one) damper: from sliding to stuck
    # dof = 2                           # the DOF whose peak is read

    [output]
    # plot = [0]                        # DOFs to plot, indices or names ("x"; default: all, up to 6)
    # harmonic = 1                      # plotted amplitude: a harmonic, or omit for max |q - q0|
    # frequency_unit = "Hz"             # of the plots and the report: "Hz" (default) or "rad/s"

Every table refuses a key it does not know, naming the table and the keys it
accepts (with the closest one when a key looks misspelled).
"""

from __future__ import annotations

from dataclasses import dataclass, field, fields
from pathlib import Path

import numpy as np

from ..common import _checks
from ..model import MicroslipModel
from ..common.units import parse_quantity
from .aft import check_harmonics, check_samples
from .continuation import StepControl
from .structure import Structure

try:  # Python >= 3.11
    import tomllib as _toml
except ModuleNotFoundError:  # pragma: no cover - Python 3.10
    try:
        import tomli as _toml
    except ModuleNotFoundError:
        _toml = None

_CONTROL_KEYS = {f.name for f in fields(StepControl)}
#: the keys each table accepts
KEYS = {
    "the file": ("title", "structure", "cyclic", "contact", "damper", "excitation", "sweep", "design", "continuation",
                 "output", "modes"),
    "[modes]": ("mode", "amplitude", "dof", "compare", "nodal_diameter"),
    "[cyclic]": ("sectors", "left", "right", "engine_order"),
    "[[damper]]": ("mass", "inertia", "centrifugal_load", "speed", "radius", "damping", "retention", "interface"),
    "[[damper.interface]]": ("model", "points", "angle", "platform", "name"),
    "[design]": ("loads", "dof"),
    "[structure]": ("M", "K", "C", "rayleigh", "dofs", "matrices", "file", "dof_map", "names"),
    "[[contact]]": ("model", "tangential", "normal", "preload", "approach", "name"),
    "[sweep]": ("omega", "frequency", "harmonics", "samples", "reduction", "modes", "engine_order"),
    "[continuation]": tuple(sorted(_CONTROL_KEYS)),
    "[output]": ("plot", "harmonic", "frequency_unit"),
}
FREQUENCY_UNITS = ("Hz", "rad/s")
#: what ``[excitation]`` accepts (its keys name harmonics), and keys to suggest a misspelled one from
EXCITATION_ACCEPTS = "static, h<harmonic> such as h1, phase_h<harmonic> such as phase_h1, and scale"
EXCITATION_EXAMPLES = ("static", "h1", "h2", "h3", "phase_h1", "phase_h2", "phase_h3", "scale")


class ConfigError(ValueError):
    """A configuration file that cannot be used; the message names the file and the key."""


@dataclass
class FrfConfig:
    """What ``microslip frf`` needs, read from a TOML file (SI units)."""

    title: str
    structure: Structure
    force: dict
    omega: tuple[float, float]
    harmonics: int
    samples: int | None
    control: StepControl
    plot_dofs: list[int]
    harmonic: int | None
    dof_names: list[str] = field(default_factory=list)
    reduction: str = "auto"
    modes: int | None = None
    frequency_unit: str = "Hz"
    engine_order: int | None = None
    bare: Structure | None = None
    dampers: list = field(default_factory=list)
    design_loads: np.ndarray | None = None
    design_dof: int | None = None
    nonlinear_mode: ModesTable | None = None


@dataclass
class ModesTable:
    """The ``[modes]`` table of ``microslip modes`` (SI units)."""

    mode: int = 1
    amplitude: tuple[float, float] = (1e-8, 1e-4)
    dof: int = 0
    compare: bool = True
    nodal_diameter: int | None = None


def _known(table: dict, where: str, path, keys: dict = KEYS) -> None:
    """Refuse a key ``where`` does not accept, naming it, the table and the accepted keys (the closest first)."""
    accepted = keys[where]
    for key in table:
        if key not in accepted:
            raise ConfigError(f"{path}: {where} has an unknown key {key!r}{_close(key, accepted)} (it accepts "
                              f"{', '.join(accepted)})")


def _close(key: str, accepted) -> str:
    """``"; did you mean 'x'?"`` for the accepted key closest to ``key`` (case ignored), else ``""``."""
    import difflib

    lowered = {a.lower(): a for a in accepted}
    close = difflib.get_close_matches(str(key).lower(), list(lowered), n=1, cutoff=0.6)
    return f"; did you mean {lowered[close[0]]!r}?" if close else ""


def _harmonic_key(key: str) -> int | None:
    """The harmonic an ``[excitation]`` key names: 0 for ``static``, ``h`` for ``h<h>`` (h >= 1), else None."""
    if key == "static":
        return 0
    if key.startswith("h") and key[1:].isdigit() and int(key[1:]) >= 1:
        return int(key[1:])
    return None


def _tables(data: dict, key: str, path) -> list:
    """The tables of an array of tables ``[[key]]`` (none if absent)."""
    value = data.get(key, [])
    if isinstance(value, dict):
        raise ConfigError(f"{path}: {key} must be an array of tables, written [[{key}]] (one per {key}), "
                          f"got a single table [{key}]")
    if not isinstance(value, list):
        raise ConfigError(f"{path}: {key} must be an array of tables, written [[{key}]], got {value!r}")
    return value


def _dof_names(value, ndof: int, path) -> list[str]:
    """``[structure] dofs``: one distinct, non-empty name per DOF."""
    if not isinstance(value, list) or not all(isinstance(v, str) and v.strip() for v in value):
        raise ConfigError(f"{path}: [structure] dofs must be a list of names (non-empty strings), one per DOF, "
                          f"got {value!r}")
    if len(value) != ndof:
        raise ConfigError(f"{path}: [structure] dofs names {len(value)} DOFs, the matrices have {ndof}")
    seen = set()
    for name in value:
        if name in seen:
            raise ConfigError(f"{path}: [structure] dofs names {name!r} twice; each DOF needs its own name")
        seen.add(name)
    return list(value)


def _plot_dofs(value, names: list[str], path, where: str = "[output] plot") -> list[int]:
    """``[output] plot`` (or ``where``): DOF indices or names, as indices."""
    if not isinstance(value, list):
        raise ConfigError(f"{path}: {where} must be a list of DOFs (indices or names), got {value!r}")
    out = []
    for d in value:
        if isinstance(d, str) and d in names:
            out.append(names.index(d))
        elif isinstance(d, int) and not isinstance(d, bool) and 0 <= d < len(names):
            out.append(d)
        elif isinstance(d, int) and not isinstance(d, bool):
            raise ConfigError(f"{path}: {where} names DOF {d}; the structure has {len(names)}")
        else:
            raise ConfigError(f"{path}: {where}: {d!r} is not a DOF{_close(str(d), names)} (an index "
                              f"from 0 to {len(names) - 1}, or one of the names {', '.join(names[:8])}"
                              f"{', ...' if len(names) > 8 else ''})")
    return out


def _checked(path, where: str, check, *args, **kwargs):
    """``check(*args, **kwargs)``, its error raised as a :class:`ConfigError` prefixed with ``where``."""
    try:
        return check(*args, **kwargs)
    except (ValueError, TypeError) as exc:
        raise ConfigError(f"{path}: {where}{exc}") from None


def _get(table: dict, key: str, where: str, path):
    if key not in table:
        raise ConfigError(f"{path}: {where} needs the key {key!r}")
    return table[key]


def _quantity(value, kind: str, what: str, path) -> float:
    try:
        return parse_quantity(value, kind, name=what)
    except (ValueError, TypeError) as exc:
        raise ConfigError(f"{path}: {exc}") from None


def _array(value, what: str, path, kind: str = "force") -> np.ndarray:
    try:
        return np.array([_quantity(v, kind, what, path) for v in value], dtype=float)
    except TypeError:
        raise ConfigError(f"{path}: {what} must be a list of numbers, got {value!r}") from None


# units of a frequency in [sweep]: rad/s as they are, Hz and kHz times 2 pi
_FREQUENCY_KINDS = {"angular frequency": 1.0, "frequency": 2 * np.pi}


def _angular_frequency(value, what: str, path, bare: str) -> float:
    """An angular frequency (rad/s) from a number in ``bare`` units (``rad/s`` or ``Hz``) or a string with a unit.

    ``"60Hz"`` is ``2 pi 60`` rad/s wherever it is written; a unit that is not a
    frequency is refused.
    """
    native = "angular frequency" if bare == "rad/s" else "frequency"
    kinds = [native] + [k for k in _FREQUENCY_KINDS if k != native]
    for kind in kinds:
        try:
            return parse_quantity(value, kind, name=what, default_unit=bare if kind == native else None) \
                * _FREQUENCY_KINDS[kind]
        except (ValueError, TypeError):
            continue
    raise ConfigError(f"{path}: {what} must be a frequency: a number ({bare}) or a string with a unit of "
                      f"angular frequency (rad/s) or frequency (Hz, kHz; converted with 2 pi), got {value!r}")


def _frequency_range(value, what: str, path, bare: str) -> tuple[float, float]:
    if isinstance(value, (str, bytes)) or not hasattr(value, "__len__"):
        raise ConfigError(f"{path}: {what} must be a list [start, end], got {value!r}")
    if len(value) != 2:
        raise ConfigError(f"{path}: [sweep] the range must have 2 values (start, end), got {len(value)}")
    return tuple(_angular_frequency(v, f"{what}[{i}]", path, bare) for i, v in enumerate(value))


def _matrix(value, what: str, path) -> np.ndarray:
    try:
        A = np.array(value, dtype=float)
    except (TypeError, ValueError):
        raise ConfigError(f"{path}: {what} must be a matrix (a list of rows of numbers)") from None
    return A


def _direction(value, what: str, path):
    if isinstance(value, list) and any(isinstance(v, dict) for v in value):  # two directions, each a table
        return [_direction(v, f"{what}[{i}]", path) for i, v in enumerate(value)]
    if isinstance(value, dict):
        try:  # keys: DOF indices ("0") or names with a DOF map ("1204:x")
            return {(int(k) if k.strip().lstrip("-").isdigit() else k): float(v) for k, v in value.items()}
        except (ValueError, TypeError):
            raise ConfigError(f"{path}: {what} keys must be DOF indices or names and values numbers, "
                              f"got {value!r}") from None
    return value


class ConfigFiles:
    """The files a configuration names, each read once: contact models, ``.npz`` matrices, FE matrix files.

    :func:`config_from_data` reads through it, so building many configurations
    that differ in a few values (a design study) reads each file once, and the
    object, pickled with what it has read, carries them to other processes.
    """

    def __init__(self):
        self._read: dict = {}
        #: the files read so far
        self.paths: set[Path] = set()

    def _once(self, key, read):
        if key not in self._read:
            self._read[key] = read()
        return self._read[key]

    def model(self, path: Path) -> MicroslipModel:
        """The contact model saved in ``path`` (:meth:`MicroslipModel.load`)."""
        self.paths.add(Path(path))
        return self._once(("model", str(path)), lambda: MicroslipModel.load(path))

    def arrays(self, path: Path) -> dict:
        """The arrays ``M``, ``C``, ``K`` found in the ``.npz`` file ``path``."""
        def read():
            from ..fe.files import NpzArrays

            with NpzArrays(path) as arrays:  # a damaged file is a FileFormatError naming it
                return {k: arrays.get(k) for k in ("M", "C", "K") if k in arrays.names}

        self.paths.add(Path(path))
        return self._once(("npz", str(path)), read)

    def matrices(self, file, **kwargs):
        """:func:`microslip.fe.read_matrices` of ``file`` and ``kwargs``."""
        from ..fe import read_matrices

        key = ("fe", str(file), tuple(sorted((k, str(v)) for k, v in kwargs.items())))
        self.paths.update(Path(v) for v in (file, *kwargs.values()) if isinstance(v, Path))
        return self._once(key, lambda: read_matrices(file, **kwargs))


def read_toml(path) -> dict:
    """The contents of the TOML file ``path``.

    Raises
    ------
    FileNotFoundError
        No such file.
    ConfigError
        Not valid TOML.
    """
    path = Path(path)
    if not path.is_file():
        raise FileNotFoundError(f"configuration file {str(path)!r} does not exist")
    if _toml is None:  # pragma: no cover - Python 3.10 without tomli
        raise ConfigError("reading TOML needs Python >= 3.11 or the 'tomli' package (pip install tomli)")
    try:
        return _toml.loads(path.read_text(encoding="utf-8"))
    except _toml.TOMLDecodeError as exc:
        raise ConfigError(f"{path}: not valid TOML: {exc}") from None
    except UnicodeDecodeError as exc:
        raise ConfigError(f"{path}: not a text file (UTF-8): {exc}") from None


def load_config(path, *, nonlinear: bool = False) -> FrfConfig:
    """Read and check a ``microslip frf`` configuration file.

    With ``nonlinear`` (``microslip modes``) the ``[modes]`` table is required and
    ``[excitation]`` and the range of ``[sweep]`` are optional.

    Raises
    ------
    FileNotFoundError
        No such file (or a file it names is missing).
    ConfigError
        Invalid TOML or contents; the message names the table and key.
    """
    return config_from_data(read_toml(path), path, nonlinear=nonlinear)


def config_from_data(data: dict, path, *, nonlinear: bool = False, files: ConfigFiles | None = None) -> FrfConfig:
    """Check and build a configuration from the contents of a TOML file (:func:`read_toml`).

    Parameters
    ----------
    data : dict
        The file's tables and keys.
    path : str or Path
        The file they come from: other files are relative to its folder, and
        messages name it.
    nonlinear : bool, default False
        As in :func:`load_config`.
    files : ConfigFiles, optional
        Where to read the files the configuration names (default: read them now).
    """
    path = Path(path)
    files = ConfigFiles() if files is None else files
    if not isinstance(data, dict):
        raise ConfigError(f"{path}: the configuration must be a table of tables, got {type(data).__name__}")
    base = path.parent
    _known(data, "the file", path)

    # -- structure -------------------------------------------------------------------
    st = _table(_get(data, "structure", "the file", path), "[structure]", path)
    fe_files = _structure_files(st, base, path, files)
    if fe_files is not None:
        mats = {"M": fe_files.M, "K": fe_files.K, **({"C": fe_files.C} if fe_files.C is not None else {})}
    elif "matrices" in st:
        npz = base / st["matrices"]
        if not npz.is_file():
            raise FileNotFoundError(f"{path}: [structure] matrices file {str(npz)!r} does not exist")
        try:
            mats = dict(files.arrays(npz))
        except ValueError as exc:  # a damaged file (FileFormatError)
            raise ConfigError(f"{path}: [structure] matrices: {exc}") from None
        for key in ("M", "K"):
            if key not in mats:
                raise ConfigError(f"{path}: [structure] matrices file {str(npz)!r} holds no array {key!r}")
    else:
        mats = {k: _matrix(_get(st, k, "[structure]", path), f"[structure] {k}", path) for k in ("M", "K")}
        if "C" in st:
            mats["C"] = _matrix(st["C"], "[structure] C", path)
    if "rayleigh" in st:
        if "C" in mats:
            raise ConfigError(f"{path}: [structure] give either C or rayleigh, not both")
        rayleigh = st["rayleigh"]
        if isinstance(rayleigh, str) or not hasattr(rayleigh, "__len__") or len(rayleigh) != 2:
            raise ConfigError(f"{path}: [structure] rayleigh must be a list [alpha, beta] (1/s, s) giving "
                              f"C = alpha M + beta K, got {rayleigh!r}")
        alpha, beta = (_quantity(v, "dimensionless", f"[structure] rayleigh[{i}]", path)
                       for i, v in enumerate(rayleigh))
        mats["C"] = alpha * mats["M"] + beta * mats["K"]
    try:
        structure = Structure(mats["M"], mats.get("C"), mats["K"],
                              dof_map=fe_files.dof_map if fe_files is not None else None)
    except (ValueError, TypeError) as exc:
        raise ConfigError(f"{path}: [structure] {exc}") from None
    engine_order = None
    if "cyclic" in data:
        structure, engine_order = _cyclic(_table(data["cyclic"], "[cyclic]", path), structure, path)
    ndof = structure.ndof
    names = _dof_names(st["dofs"], ndof, path) if "dofs" in st else (
        structure.dof_map.names if structure.dof_map is not None else [f"q{i}" for i in range(ndof)])

    # -- contacts ----------------------------------------------------------------------
    for i, c in enumerate(_tables(data, "contact", path)):
        where = f"[[contact]] {i + 1}"
        _table(c, "[[contact]]", path, where)
        model_path = base / _get(c, "model", where, path)
        try:
            model = files.model(model_path)
        except (ValueError, TypeError) as exc:
            raise ConfigError(f"{path}: {where}: {exc}") from None
        kwargs = {"tangential": _next_keys(_direction(_get(c, "tangential", where, path), f"{where} tangential",
                                                      path), structure, f"{where} tangential", path),
                  "normal": _next_keys(_direction(c.get("normal"), f"{where} normal", path), structure,
                                       f"{where} normal", path), "name": c.get("name")}
        if "preload" in c:
            kwargs["preload"] = _quantity(c["preload"], "force", f"{where} preload", path)
        if "approach" in c:
            kwargs["approach"] = _quantity(c["approach"], "length", f"{where} approach", path)
        try:
            structure.add_contact(model, **kwargs)
        except (ValueError, TypeError) as exc:
            raise ConfigError(f"{path}: {where}: {exc}") from None

    # -- dampers ------------------------------------------------------------------------
    bare = structure  # without the dampers: what the design curve attaches its damper to
    dampers = [_damper(d, k, structure, base_dir=base, path=path, files=files) for k, d in enumerate(_tables(data, "damper", path))]
    for d in dampers:
        structure = d.attach(structure)
    names = names + [f"damper{k} {axis}" for k in range(len(dampers)) for axis in ("X", "Y", "R")]

    # -- excitation ----------------------------------------------------------------------
    ex = data.get("excitation", {}) if nonlinear else _get(data, "excitation", "the file", path)
    if not isinstance(ex, dict):
        raise ConfigError(f"{path}: [excitation] must be a table, got {ex!r}")
    force = {}
    scale = 1.0
    if "scale" in ex:
        scale = _checked(path, "", _checks.positive_scalar, "[excitation] scale",
                         _quantity(ex["scale"], "dimensionless", "[excitation] scale", path), allow_zero=True)
    for key, value in ex.items():
        if key == "scale":
            continue
        if key == "phase_static":
            raise ConfigError(f"{path}: [excitation] phase_static: a static force has no phase (give a signed "
                              f"static force instead)")
        if key.startswith("phase_") and _harmonic_key(key[6:]) is not None:
            continue
        h = _harmonic_key(key)
        if h is None:
            raise ConfigError(f"{path}: [excitation] has an unknown key {key!r}{_close(key, EXCITATION_EXAMPLES)} "
                              f"(it accepts {EXCITATION_ACCEPTS})")
        amp = _array(value, f"[excitation] {key}", path).astype(complex)
        if amp.size != ndof:
            raise ConfigError(f"{path}: [excitation] {key} has {amp.size} value(s); the structure has {ndof} DOFs "
                              f"(one amplitude per DOF, N)")
        amp = np.concatenate([amp, np.zeros(structure.ndof - ndof)])  # the dampers are not excited
        if f"phase_{key}" in ex:
            amp = amp * np.exp(1j * np.radians(_array(ex[f"phase_{key}"], f"[excitation] phase_{key}", path,
                                                      "dimensionless")))
        force[h] = amp if h == 0 else scale * amp
    for key in ex:
        if key.startswith("phase_") and key[6:] not in ex:
            raise ConfigError(f"{path}: [excitation] {key} has no amplitude {key[6:]!r}")

    # -- sweep ---------------------------------------------------------------------------
    sw = _table(data.get("sweep", {}) if nonlinear else _get(data, "sweep", "the file", path), "[sweep]", path)
    if "omega" in sw and "frequency" in sw or not (nonlinear or "omega" in sw or "frequency" in sw):
        raise ConfigError(f"{path}: [sweep] needs exactly one of omega (rad/s) or frequency (Hz)")
    if "omega" in sw:
        omega = _frequency_range(sw["omega"], "[sweep] omega", path, "rad/s")
    elif "frequency" in sw:
        omega = _frequency_range(sw["frequency"], "[sweep] frequency", path, "Hz")
    else:
        omega = None
    harmonics = _checked(path, "", check_harmonics, sw.get("harmonics", 5), name="[sweep] harmonics")
    for h in force:
        if h > harmonics:
            raise ConfigError(f"{path}: [excitation] h{h} is a harmonic above [sweep] harmonics = {harmonics}; "
                              f"raise harmonics to {h} or more, or remove h{h}")
    from .cyclic import CyclicStructure
    from .cyclic_balance import cyclic_reduction
    from .reduced import choose_reduction

    if "engine_order" in sw:
        if not isinstance(structure, CyclicStructure):
            raise ConfigError(f"{path}: [sweep] engine_order needs a [cyclic] table (one sector of a bladed disk)")
        if engine_order is not None:
            raise ConfigError(f"{path}: the engine order is given twice, in [cyclic] and in [sweep]: keep one")
        engine_order = _checked(path, "", _checks.positive_int, "[sweep] engine_order", sw["engine_order"],
                                minimum=0)
    elif isinstance(structure, CyclicStructure) and engine_order is None:
        raise ConfigError(f"{path}: a [cyclic] sector needs its engine order: engine_order in [cyclic] or [sweep]")
    samples = sw.get("samples")
    if samples is not None:
        samples = _checked(path, "[sweep] ", check_samples, samples, harmonics)

    reduction = sw.get("reduction", "auto")
    modes = sw.get("modes")

    if isinstance(structure, CyclicStructure):  # a sector is always condensed, in each harmonic's diameter
        _checked(path, "[sweep] ", cyclic_reduction, structure, reduction, modes)
    else:
        _checked(path, "[sweep] ", choose_reduction, structure, harmonics, reduction, modes)

    # -- continuation and output -----------------------------------------------------------
    cont = _table(data.get("continuation", {}), "[continuation]", path)
    control = _checked(path, "[continuation] ", StepControl, **cont)
    out = _table(data.get("output", {}), "[output]", path)
    frequency_unit = out.get("frequency_unit", "Hz")
    if frequency_unit not in FREQUENCY_UNITS:
        raise ConfigError(f"{path}: [output] frequency_unit must be one of {', '.join(FREQUENCY_UNITS)}, "
                          f"got {frequency_unit!r}")
    plot_dofs = _plot_dofs(out["plot"], names[:ndof], path) if "plot" in out else list(range(min(ndof, 6)))
    harmonic = out.get("harmonic")
    if harmonic is not None:
        harmonic = _checked(path, "", _checks.positive_int, "[output] harmonic", harmonic, minimum=0)
        if harmonic > harmonics:
            raise ConfigError(f"{path}: [output] harmonic must be at most [sweep] harmonics = {harmonics} "
                              f"(or omitted for max |q - q0|), got {harmonic}")
    design_loads = design_dof = None
    if "design" in data:
        design = _table(data["design"], "[design]", path)
        if len(dampers) != 1:
            raise ConfigError(f"{path}: [design] needs exactly one [[damper]] (its load is varied), got {len(dampers)}")
        design_loads = _array(_get(design, "loads", "[design]", path), "[design] loads", path)
        design_dof = _checked(path, "", _checks.positive_int, "[design] dof", _get(design, "dof", "[design]", path),
                              minimum=0)
        if design_dof >= ndof:
            raise ConfigError(f"{path}: [design] dof names DOF {design_dof}; the structure has {ndof}")
    mode_table = None
    if nonlinear:
        mode_table = _modes_table(_table(_get(data, "modes", "the file", path), "[modes]", path), names[:ndof],
                                  plot_dofs, path)
        if engine_order is not None and mode_table.nodal_diameter is None:
            mode_table.nodal_diameter = engine_order
        elif engine_order is None and mode_table.nodal_diameter is not None:
            raise ConfigError(f"{path}: [modes] nodal_diameter needs a [cyclic] table (one sector of a bladed disk)")
    return FrfConfig(str(data.get("title", path.stem)), structure, force, omega, harmonics, samples, control,
                     plot_dofs, harmonic, names, reduction, modes, frequency_unit, engine_order, bare, dampers,
                     design_loads, design_dof, mode_table)


def _modes_table(table: dict, names: list[str], plot_dofs: list[int], path) -> ModesTable:
    """``[modes]`` checked: the mode, its amplitude range, the DOF shown, whether to compare."""
    out = ModesTable(dof=plot_dofs[0] if plot_dofs else 0)
    if "mode" in table:
        out.mode = _checked(path, "", _checks.positive_int, "[modes] mode", table["mode"])
        if out.mode > len(names):
            raise ConfigError(f"{path}: [modes] mode must be at most the number of DOFs ({len(names)}), got "
                              f"{out.mode}")
    if "amplitude" in table:
        value = table["amplitude"]
        if isinstance(value, (str, bytes)) or not hasattr(value, "__len__") or len(value) != 2:
            raise ConfigError(f"{path}: [modes] amplitude must be a list [start, end] of modal amplitudes "
                              f"(kg^1/2 m), got {value!r}")
        lo, hi = (_checked(path, "", _checks.positive_scalar, f"[modes] amplitude[{i}]", v)
                  for i, v in enumerate(value))
        if not lo < hi:
            raise ConfigError(f"{path}: [modes] amplitude must rise from start to end, got {lo!r} >= {hi!r}")
        out.amplitude = (lo, hi)
    if "dof" in table:
        out.dof = _plot_dofs([table["dof"]], names, path, "[modes] dof")[0]
    if "compare" in table:
        out.compare = _checked(path, "", _checks.flag, "[modes] compare", table["compare"])
    if "nodal_diameter" in table:
        out.nodal_diameter = _checked(path, "", _checks.positive_int, "[modes] nodal_diameter",
                                      table["nodal_diameter"], minimum=0)
    return out


def _cyclic(table: dict, structure: Structure, path):
    """The sector as a :class:`CyclicStructure`, and the engine order."""
    from .cyclic import CyclicStructure

    def dofs(key):
        value = _get(table, key, "[cyclic]", path)
        if isinstance(value, (str, int)):
            value = [value]
        return [_checked(path, f"[cyclic] {key}: ", structure.dof_index, v) for v in value]

    sectors = _checked(path, "", _checks.positive_int, "[cyclic] sectors", _get(table, "sectors", "[cyclic]", path),
                       minimum=3)
    engine_order = None
    if "engine_order" in table:
        engine_order = _checked(path, "", _checks.positive_int, "[cyclic] engine_order", table["engine_order"],
                                minimum=0)
    disk = _checked(path, "[cyclic] ", CyclicStructure, structure.M, structure.C, structure.K, sectors=sectors,
                    left=dofs("left"), right=dofs("right"), dof_map=structure.dof_map)
    return disk, engine_order


def _next_keys(spec, structure: Structure, what: str, path):
    """A direction whose ``"next:j"`` keys name the next sector's DOF ``j`` (a cyclic structure only)."""
    if not isinstance(spec, dict) or not any(isinstance(k, str) and k.startswith("next:") for k in spec):
        return spec
    if not hasattr(structure, "next"):
        raise ConfigError(f"{path}: {what} names a next-sector DOF, which needs a [cyclic] table")
    out = {}
    for key, value in spec.items():
        if isinstance(key, str) and key.startswith("next:"):
            rest = key[5:]
            rest = int(rest) if rest.strip().isdigit() else rest
            key = _checked(path, f"{what}: ", lambda r: structure.next(structure.dof_index(r)), rest)
        out[key] = value
    return out


def _damper(table: dict, k: int, structure: Structure, *, base_dir: Path, path, files: ConfigFiles):
    """An :class:`UnderPlatformDamper` from a ``[[damper]]`` table and its ``[[damper.interface]]`` tables."""
    from .damper import UnderPlatformDamper

    where = f"[[damper]] {k + 1}"
    _table(table, "[[damper]]", path, where)
    number = lambda key, kind: _quantity(table[key], kind, f"{where} {key}", path)  # noqa: E731
    kwargs = {}
    if "centrifugal_load" in table:
        kwargs["centrifugal_load"] = number("centrifugal_load", "force")
    if "speed" in table:
        kwargs["speed"] = _angular_frequency(table["speed"], f"{where} speed", path, "rad/s")
    if "radius" in table:
        kwargs["radius"] = number("radius", "length")
    if "damping" in table:
        kwargs["damping"] = number("damping", "dimensionless")
    if "retention" in table:
        kwargs["retention"] = number("retention", "stiffness")
    mass = _quantity(_get(table, "mass", where, path), "dimensionless", f"{where} mass", path)
    inertia = _quantity(_get(table, "inertia", where, path), "dimensionless", f"{where} inertia", path)
    d = _checked(path, f"{where}: ", UnderPlatformDamper, mass, inertia, **kwargs)
    for i, face in enumerate(_get(table, "interface", where, path)):
        here = f"{where} interface {i + 1}"
        _table(face, "[[damper.interface]]", path, here)
        names = _get(face, "model", here, path)
        names = names if isinstance(names, list) else [names]
        try:
            models = [files.model(base_dir / f) for f in names]
        except (ValueError, TypeError) as exc:
            raise ConfigError(f"{path}: {here}: {exc}") from None
        points = np.array([[_quantity(v, "length", f"{here} points", path) for v in row]
                           for row in _get(face, "points", here, path)])
        angle = np.radians(_quantity(_get(face, "angle", here, path), "dimensionless", f"{here} angle", path))
        platform = _get(face, "platform", here, path)
        platform = [platform] if isinstance(platform, dict) else platform
        plats = [{axis: _platform_dof(p.get(axis) if isinstance(p, dict) else None, structure, f"{here} platform",
                                      path) for axis in ("x", "y")} for p in platform]
        _checked(path, f"{here}: ", d.add_interface, models if len(models) > 1 else models[0], points=points,
                 angle=angle, platform=plats if len(plats) > 1 else plats[0], name=face.get("name"))
    return d


def _platform_dof(value, structure: Structure, what: str, path):
    """A platform DOF: an index or name, or ``"next:j"`` for the next sector's."""
    if value is None:
        raise ConfigError(f"{path}: {what} must give the DOFs x and y of the platform, e.g. {{x = 0, y = 1}}")
    if isinstance(value, str) and value.startswith("next:"):
        return _next_keys({value: 1.0}, structure, what, path).popitem()[0]
    return _checked(path, f"{what}: ", structure.dof_index, value)


def _table(value, where: str, path, label: str | None = None) -> dict:
    """A TOML table checked: a table, with known keys only."""
    if not isinstance(value, dict):
        raise ConfigError(f"{path}: {label or where} must be a table, got {value!r}")
    _known(value, where, path)
    return value


def _structure_files(st: dict, base: Path, path, files: ConfigFiles):
    """The matrices read from ``file = ...`` or ``M = "M.mtx"``-style file names (FEMatrices), or None."""
    by_file = "file" in st
    by_name = any(isinstance(st.get(k), str) for k in ("M", "K", "C"))
    if not (by_file or by_name):
        if "dof_map" in st:
            raise ConfigError(f"{path}: [structure] dof_map goes with matrices read from files (file = ... or "
                              f"M = \"M.mtx\", ...)")
        return None
    if by_file and by_name:
        raise ConfigError(f"{path}: [structure] give either file = ... or one file per matrix, not both")
    inline = [k for k in ("M", "K") if k in st and not isinstance(st[k], str)]
    if by_name and inline:
        named = [k for k in ("M", "K", "C") if isinstance(st.get(k), str)]
        raise ConfigError(f"{path}: [structure] {named[0]} is a file name ({st[named[0]]!r}) but {inline[0]} is "
                          f"written inline: give M and K both as files (M = \"M.mtx\", K = \"K.mtx\") or both "
                          f"as matrices")
    kwargs = {k: base / st[k] for k in ("M", "K", "C") if isinstance(st.get(k), str)}
    dof_map = base / st["dof_map"] if "dof_map" in st else None
    from ..fe.files import OneMatrixFile

    try:
        return files.matrices(base / st["file"] if by_file else None, dof_map=dof_map, names=st.get("names"),
                              **kwargs)
    except OneMatrixFile as exc:
        raise ConfigError(f"{path}: [structure] file = {st['file']!r} is a {exc.kind} file, which holds a single "
                          f"matrix: say which matrix each file is, M = \"M{exc.path.suffix}\", K = "
                          f"\"K{exc.path.suffix}\" (and C = ... if any) instead of file = ...") from None
    except (ValueError, TypeError) as exc:
        raise ConfigError(f"{path}: [structure] {exc}") from None
