"""The TOML configuration of ``microslip frf``: a structure, its contacts, the excitation, the sweep.

The tables and keys, with their types, units, defaults and examples, are declared once in
:mod:`microslip.config.schema`: this module reads a file against them (every table refuses a key it does
not know, naming the table and the keys it accepts, the closest one first when a key looks misspelled, and a
value of the wrong type) and :func:`microslip.config.reference_markdown` renders them as the reference
(``microslip config-reference``). Every number is SI unless it is a string with a unit (``"37.5N"``,
``"2um"``, ``"2kHz"``); paths are relative to the configuration file. ``examples/inclined_block.toml`` is a
complete example.
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from ..common import _checks
from ..common._checks import close_spelling
from ..model import MicroslipModel
from ..common.units import parse_quantity
from ..common.errors import ConfigError
from ..frequency.aft import check_harmonics, check_samples
from ..frequency.analyses.nonlinear_modes import FOLDS
from ..frequency.numerics.continuation import StepControl
from ..frequency.structures.structure import Structure
from .schema import KEYS, REFERENCE, REQUIRED, check_types

try:  # Python >= 3.11
    import tomllib as _toml
except ModuleNotFoundError:  # pragma: no cover - Python 3.10
    try:
        import tomli as _toml
    except ModuleNotFoundError:
        _toml = None

# the keys each table accepts, their types, units, defaults and examples: declared once, in .schema
FREQUENCY_UNITS = ("Hz", "rad/s")
#: what ``[excitation]`` accepts (its keys name harmonics), and keys to suggest a misspelled one from
EXCITATION_ACCEPTS = "static, h<harmonic> such as h1, phase_h<harmonic> such as phase_h1, and scale"
EXCITATION_EXAMPLES = ("static", "h1", "h2", "h3", "phase_h1", "phase_h2", "phase_h3", "scale")


#: the references a contact may be tuned on when the configuration is read ('microslip tune --reference'), their
#: keys (besides kind) and the defaults of the command line
_REFERENCES = {"sphere": "sphere on a plane", "punch": "flat punch with rounded edges"}
_REFERENCE_KEYS = {kind: tuple(k.name for k in REFERENCE.keys if k.name != "kind" and kind in k.applies_to)
                   for kind in _REFERENCES}
_REFERENCE_NEEDS = {kind: tuple(k for k in _REFERENCE_KEYS[kind] if REFERENCE.key(k).default == REQUIRED)
                    for kind in _REFERENCES}
_REFERENCE_DEFAULTS = {k.name: k.default for k in REFERENCE.keys
                       if isinstance(k.default, (int, float)) and not isinstance(k.default, bool)}
_REFERENCE_KINDS = {k.name: {"m": "length", "Pa": "pressure", "": "dimensionless"}[k.unit] for k in REFERENCE.keys
                    if k.type == "quantity"}
_REFERENCE_EXAMPLES = {k.name: k.example for k in REFERENCE.keys}


def _whole(value, what: str, path, default: int) -> int:
    if value is None:
        return default
    if isinstance(value, bool) or not isinstance(value, int) or value < 1:
        raise ConfigError(f"{path}: {what} must be a positive whole number such as {default}, got {value!r}")
    return value


def _contact_models(table: dict, where: str, path, base: Path, files: "ConfigFiles", *, many: bool) -> list:
    """A contact's law: the model file(s) of ``model``, or the model tuned on ``reference`` at ``load``.

    ``reference = {kind = "sphere" | "punch", ...}`` is tuned as ``microslip tune --reference`` tunes it (the same
    defaults, the same code path: :func:`microslip.tune`, through :func:`microslip.mdr` for the punch), with
    ``load`` (required) and ``elements`` (default 4). ``many``: ``model`` may list one file per point.
    """
    if "reference" not in table:
        for key in ("load", "elements"):
            if key in table:
                raise ConfigError(f"{path}: {where} {key} goes with reference = {{kind = ...}} (a contact tuned when "
                                  f"the configuration is read); the model file of model = ... is tuned already")
        names = _get(table, "model", where, path)
        names = names if many and isinstance(names, list) else [names]
        try:
            return [files.model(base / f) for f in names]
        except (ValueError, TypeError) as exc:
            raise ConfigError(f"{path}: {where}: {exc}") from None
    if "model" in table:
        raise ConfigError(f"{path}: {where} gives both model and reference: the contact's law is one of them, a "
                          f"model file or a reference tuned when the configuration is read")
    here = f"{where} reference"
    spec = table["reference"]
    if not isinstance(spec, dict):
        raise ConfigError(f"{path}: {here} must be a table such as {{kind = \"punch\", flat_radius = \"1mm\", "
                          f"edge_radius = \"5mm\"}}, got {spec!r}")
    kind = spec.get("kind")
    if kind == "cylinder":
        raise ConfigError(f"{path}: {here}: a cylinder on a flat has no closed-form tangential law: it is tuned on "
                          f"measured loops (microslip tune LOOPS... --reference cylinder); give that model's file, "
                          f"model = \"cylinder.json\"")
    if kind not in _REFERENCES:
        raise ConfigError(f"{path}: {here} kind must be one of {list(_REFERENCES)}, got {kind!r}")
    accepted = _REFERENCE_KEYS[kind]
    for key in spec:
        if key == "kind" or key in accepted:
            continue
        users = [k for k in _REFERENCES if key in _REFERENCE_KEYS[k]]
        if users:
            raise ConfigError(f"{path}: {here}: {key} does not apply to the {_REFERENCES[kind]} (kind = {kind!r}); "
                              f"it is a key of kind = {users[0]!r}")
        raise ConfigError(f"{path}: {here} has an unknown key {key!r}{close_spelling(key, accepted)} (kind = "
                          f"{kind!r} accepts kind, {', '.join(accepted)})")
    for key in _REFERENCE_NEEDS[kind]:
        if key not in spec:
            raise ConfigError(f"{path}: {here}: kind = {kind!r} needs {key} (e.g. {key} = "
                              f"{_REFERENCE_EXAMPLES[key]}): the {_REFERENCES[kind]} has no default")
    for key, other in (("E2", "nu2"), ("nu2", "E2")):
        if key in spec and other not in spec:
            raise ConfigError(f"{path}: {here}: {key} needs {other}: the second body's material is both or neither "
                              f"(e.g. {other} = {_REFERENCE_EXAMPLES[other]})")
    values = {}
    for key in accepted:
        if key == "mdr_elements":
            values[key] = _whole(spec.get(key), f"{here} mdr_elements", path, _REFERENCE_DEFAULTS[key])
        elif key in spec:
            values[key] = _quantity(spec[key], _REFERENCE_KINDS[key], f"{here} {key}", path)
        elif key in _REFERENCE_DEFAULTS:
            values[key] = _REFERENCE_DEFAULTS[key]
    load = _quantity(_get(table, "load", where, path), "force", f"{where} load", path)
    if not (np.isfinite(load) and load > 0):
        raise ConfigError(f"{path}: {where} load must be a positive force such as \"37.5N\", got {table['load']!r}")
    elements = _whole(table.get("elements"), f"{where} elements", path, 4)
    key = ("tuned", kind, tuple(sorted(values.items())), load, elements)
    return [checked(path, f"{here}: ", files._once, key, lambda: _tune_reference(kind, values, load, elements))]


def _tune_reference(kind: str, values: dict, load: float, elements: int) -> MicroslipModel:
    """``tune`` on the reference, built as 'microslip tune --reference' builds it."""
    from ..reference import RoundedPunch, Sphere, mdr
    from ..tuning import tune

    second = {k: values[k] for k in ("E2", "nu2") if k in values}
    if kind == "sphere":
        reference = Sphere(radius=values["radius"], E=values["E"], nu=values["nu"], mu=values["mu"], **second)
    else:  # the punch's material carried by a sphere whose radius the profile replaces (microslip.mdr's reference)
        material = Sphere(radius=values["edge_radius"], E=values["E"], nu=values["nu"], mu=values["mu"], **second)
        reference = mdr(material, max_load=load, elements=values["mdr_elements"],
                        profile=RoundedPunch(values["flat_radius"], values["edge_radius"])).as_reference()
    return tune(reference, load, elements=elements)


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
    prestress: PrestressTable | None = None
    speed: SpeedTable | None = None
    campbell: CampbellTable | None = None
    #: the ``[continuation]`` keys the file sets (a nonlinear mode keeps its own steps for the others)
    continuation_keys: tuple = ()


@dataclass
class PrestressTable:
    """The ``[prestress]`` table: the friction state of the static step, the modes reported, a damping fitted on them.

    ``modal_damping``: one damping ratio per prestressed mode (``C`` from them,
    :meth:`~microslip.frequency.Prestress.modal_damping`); ``rayleigh_damping``:
    two ratios on the ``rayleigh_modes`` (:meth:`~microslip.frequency.Prestress.rayleigh_damping`).
    """

    friction: str = "released"
    modes: int = 6
    modal_damping: np.ndarray | None = None
    rayleigh_damping: tuple[float, float] | None = None
    rayleigh_modes: tuple[int, int] = (1, 2)


@dataclass
class SpeedTable:
    """The ``[speed]`` table: the stiffness (N/m) at 2 or 3 rotation speeds (rad/s), ``[structure]``'s at the first."""

    at: np.ndarray
    stiffness: list


@dataclass
class CampbellTable:
    """The ``[campbell]`` table of ``microslip campbell`` (SI units): the speeds and what to draw."""

    speeds: np.ndarray
    engine_orders: tuple = (1, 2, 3, 4, 5, 6)
    modes: int = 6
    contacts: str = "both"
    nodal_diameters: list | None = None


@dataclass
class ModesTable:
    """The ``[modes]`` table of ``microslip modes`` (SI units)."""

    mode: int = 1
    amplitude: tuple[float, float] = (1e-8, 1e-4)
    dof: int = 0
    compare: bool = True
    nodal_diameter: int | None = None
    folds: str = "stop"


def refuse_unknown(table: dict, where: str, path, keys: dict = KEYS) -> None:
    """Refuse a key ``where`` does not accept, naming it, the table and the accepted keys (the closest first)."""
    accepted = keys[where]
    for key in table:
        if key not in accepted:
            raise ConfigError(f"{path}: {where} has an unknown key {key!r}{close_spelling(key, accepted)} (it accepts "
                              f"{', '.join(accepted)})")


def harmonic_key(key: str) -> int | None:
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


def _dof_key(key, names: list[str], path, where: str, dof_map=None) -> int:
    """One DOF: an index (an integer, or its digits as a table key such as ``"7"``), a name of ``names``, or with a
    DOF map any spelling of ``"node:component"`` (``"1113:2"`` is ``"1113:y"``)."""
    if isinstance(key, str) and key.strip().isdigit():
        key = int(key)
    if isinstance(key, str) and key in names:
        return names.index(key)
    if isinstance(key, int) and not isinstance(key, bool):
        if 0 <= key < len(names):
            return key
        raise ConfigError(f"{path}: {where} names DOF {key}; the structure has {len(names)}")
    if isinstance(key, str) and dof_map is not None and ":" in key:
        try:
            return dof_map.index(key)
        except (ValueError, TypeError) as exc:
            raise ConfigError(f"{path}: {where}: {exc}") from None
    raise ConfigError(f"{path}: {where}: {key!r} is not a DOF{close_spelling(str(key), names)} (an index "
                      f"from 0 to {len(names) - 1}, or one of the names {', '.join(names[:8])}"
                      f"{', ...' if len(names) > 8 else ''})")


def _plot_dofs(value, names: list[str], path, where: str = "[output] plot", dof_map=None) -> list[int]:
    """``[output] plot`` (or ``where``): DOF indices or names, as indices."""
    if not isinstance(value, list):
        raise ConfigError(f"{path}: {where} must be a list of DOFs (indices or names), got {value!r}")
    return [_dof_key(d, names, path, where, dof_map) for d in value]


def checked(path, where: str, check, *args, **kwargs):
    """``check(*args, **kwargs)``, its error raised as a :class:`ConfigError` prefixed with ``where``."""
    try:
        return check(*args, **kwargs)
    except (ValueError, TypeError) as exc:
        raise ConfigError(f"{path}: {where}{exc}") from None


def _get(table: dict, key: str, where: str, path, hint: str = ""):
    """``table[key]``; a missing key is a :class:`ConfigError` naming it (and ``hint``, what to write)."""
    if key not in table:
        raise ConfigError(f"{path}: {where} needs the key {key!r}{': ' + hint if hint else ''}")
    return table[key]


#: what ``[cyclic] left`` and ``right`` hold, when missing
_SHARED = ("the DOFs this sector shares with the {} one, {} = [] when it shares none (blades joined only through "
           "dampers or a rigid disk)")


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


def _per_dof(value, what: str, path, names: list[str], dof_map, kind: str) -> np.ndarray:
    """One value per DOF: a list of them, or a table ``{dof = value}`` by DOF name or index (the others zero)."""
    if isinstance(value, dict):
        out = np.zeros(len(names))
        for key, v in value.items():
            i = _dof_key(key, names, path, what, dof_map)
            out[i] += _quantity(v, kind, f"{what}[{key!r}]", path)
        return out
    if not isinstance(value, list):
        raise ConfigError(f"{path}: {what} must be a list of numbers (one per DOF) or a table of DOFs, e.g. "
                          f"{{\"{names[0]}\" = 1.0}}, got {value!r}")
    out = _array(value, what, path, kind)
    if out.size != len(names):
        raise ConfigError(f"{path}: {what} has {out.size} value(s); the structure has {len(names)} DOFs (one per DOF, "
                          f"or a table of DOFs such as {{\"{names[-1]}\" = 1.0}})")
    return out


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
                      f"angular frequency (rad/s, rpm) or frequency (Hz, kHz; converted with 2 pi), got {value!r}")


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

    def coordinates(self, path: Path) -> dict:
        """``{node id: [x, y(, z)]}`` (m) from the CSV file ``path`` (columns ``node``, ``x``, ``y``, maybe ``z``)."""
        self.paths.add(Path(path))
        return self._once(("coordinates", str(path)), lambda: _node_coordinates(path))

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


def load_config(path, *, nonlinear: bool = False, campbell: bool = False) -> FrfConfig:
    """Read and check a ``microslip frf`` configuration file.

    With ``nonlinear`` (``microslip modes``) the ``[modes]`` table is required and
    ``[excitation]`` and the range of ``[sweep]`` are optional. With ``campbell``
    (``microslip campbell``) ``[speed]`` is required, ``[excitation]`` and
    ``[sweep]`` are optional and a ``[cyclic]`` sector needs no engine order.

    Raises
    ------
    FileNotFoundError
        No such file (or a file it names is missing).
    ConfigError
        Invalid TOML or contents; the message names the table and key.
    """
    return config_from_data(read_toml(path), path, nonlinear=nonlinear, campbell=campbell)


def config_from_data(data: dict, path, *, nonlinear: bool = False, files: ConfigFiles | None = None,
                     campbell: bool = False) -> FrfConfig:
    """Check and build a configuration from the contents of a TOML file (:func:`read_toml`).

    Parameters
    ----------
    data : dict
        The file's tables and keys.
    path : str or Path
        The file they come from: other files are relative to its folder, and
        messages name it.
    nonlinear, campbell : bool, default False
        As in :func:`load_config`.
    files : ConfigFiles, optional
        Where to read the files the configuration names (default: read them now).
    """
    path = Path(path)
    files = ConfigFiles() if files is None else files
    if not isinstance(data, dict):
        raise ConfigError(f"{path}: the configuration must be a table of tables, got {type(data).__name__}")
    base = path.parent
    refuse_unknown(data, "the file", path)
    check_types(data, "the file", path)

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
    ndof = structure.ndof
    names = _dof_names(st["dofs"], ndof, path) if "dofs" in st else (
        structure.dof_map.names if structure.dof_map is not None else [f"q{i}" for i in range(ndof)])
    engine_order = None
    if "cyclic" in data:
        structure, engine_order = _cyclic(_table(data["cyclic"], "[cyclic]", path), structure, names, path, files)

    # -- contacts ----------------------------------------------------------------------
    for i, c in enumerate(_tables(data, "contact", path)):
        where = f"[[contact]] {i + 1}"
        _table(c, "[[contact]]", path, where)
        model, = _contact_models(c, where, path, base, files, many=False)
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
    for k, d in enumerate(dampers):
        structure = checked(path, f"[[damper]] {k + 1}: ", d.attach, structure)
    names = names + [f"damper{k} {axis}" for k in range(len(dampers)) for axis in ("X", "Y", "R")]

    # -- excitation ----------------------------------------------------------------------
    optional = nonlinear or campbell  # [excitation] and [sweep]'s range
    ex = data.get("excitation", {}) if optional else _get(data, "excitation", "the file", path)
    if not isinstance(ex, dict):
        raise ConfigError(f"{path}: [excitation] must be a table, got {ex!r}")
    force = {}
    scale = 1.0
    if "scale" in ex:
        scale = checked(path, "", _checks.positive_scalar, "[excitation] scale",
                         _quantity(ex["scale"], "dimensionless", "[excitation] scale", path), allow_zero=True)
    for key, value in ex.items():
        if key == "scale":
            continue
        if key == "phase_static":
            raise ConfigError(f"{path}: [excitation] phase_static: a static force has no phase (give a signed "
                              f"static force instead)")
        if key.startswith("phase_") and harmonic_key(key[6:]) is not None:
            continue
        h = harmonic_key(key)
        if h is None:
            raise ConfigError(f"{path}: [excitation] has an unknown key "
                              f"{key!r}{close_spelling(key, EXCITATION_EXAMPLES)} "
                              f"(it accepts {EXCITATION_ACCEPTS})")
        amp = _per_dof(value, f"[excitation] {key}", path, names[:ndof], bare.dof_map, "force").astype(complex)
        amp = np.concatenate([amp, np.zeros(structure.ndof - ndof)])  # the dampers are not excited
        if f"phase_{key}" in ex:
            phase = _per_dof(ex[f"phase_{key}"], f"[excitation] phase_{key}", path, names[:ndof], bare.dof_map,
                             "dimensionless")
            amp = amp * np.exp(1j * np.radians(np.concatenate([phase, np.zeros(structure.ndof - ndof)])))
        force[h] = amp if h == 0 else scale * amp
    for key in ex:
        if key.startswith("phase_") and key[6:] not in ex:
            raise ConfigError(f"{path}: [excitation] {key} has no amplitude {key[6:]!r}")

    # -- sweep ---------------------------------------------------------------------------
    sw = _table(data.get("sweep", {}) if optional else _get(data, "sweep", "the file", path), "[sweep]", path)
    if "omega" in sw and "frequency" in sw or not (optional or "omega" in sw or "frequency" in sw):
        raise ConfigError(f"{path}: [sweep] needs exactly one of omega (rad/s) or frequency (Hz)")
    if "omega" in sw:
        omega = _frequency_range(sw["omega"], "[sweep] omega", path, "rad/s")
    elif "frequency" in sw:
        omega = _frequency_range(sw["frequency"], "[sweep] frequency", path, "Hz")
    else:
        omega = None
    harmonics = checked(path, "", check_harmonics, sw.get("harmonics", 5), name="[sweep] harmonics")
    for h in force:
        if h > harmonics:
            raise ConfigError(f"{path}: [excitation] h{h} is a harmonic above [sweep] harmonics = {harmonics}; "
                              f"raise harmonics to {h} or more, or remove h{h}")
    from ..frequency.structures.cyclic import CyclicStructure
    from ..frequency.reduction.choice import choose_reduction, cyclic_reduction

    if "engine_order" in sw:
        if not isinstance(structure, CyclicStructure):
            raise ConfigError(f"{path}: [sweep] engine_order needs a [cyclic] table (one sector of a bladed disk)")
        if engine_order is not None:
            raise ConfigError(f"{path}: the engine order is given twice, in [cyclic] and in [sweep]: keep one")
        engine_order = checked(path, "", _checks.positive_int, "[sweep] engine_order", sw["engine_order"],
                                minimum=0)
    elif isinstance(structure, CyclicStructure) and engine_order is None and not campbell:
        raise ConfigError(f"{path}: a [cyclic] sector needs its engine order: engine_order in [cyclic] or [sweep]")
    samples = sw.get("samples")
    if samples is not None:
        samples = checked(path, "[sweep] ", check_samples, samples, harmonics)

    reduction = sw.get("reduction", "auto")
    modes = sw.get("modes")

    if isinstance(structure, CyclicStructure):  # a sector is always condensed, in each harmonic's diameter
        checked(path, "[sweep] ", cyclic_reduction, structure, reduction, modes)
    else:
        checked(path, "[sweep] ", choose_reduction, structure, harmonics, reduction, modes)

    # -- continuation and output -----------------------------------------------------------
    cont = dict(_table(data.get("continuation", {}), "[continuation]", path))
    if cont.get("chord_error") is True:
        raise ConfigError(f"{path}: [continuation] chord_error must be a positive number (the target) or false (no "
                          f"chord rule), got true (e.g. chord_error = 1e-4)")
    if cont.get("chord_error") is False:
        cont["chord_error"] = None  # the turn rule
    control = checked(path, "[continuation] ", StepControl, **cont)
    out = _table(data.get("output", {}), "[output]", path)
    frequency_unit = out.get("frequency_unit", "Hz")
    if frequency_unit not in FREQUENCY_UNITS:
        raise ConfigError(f"{path}: [output] frequency_unit must be one of {', '.join(FREQUENCY_UNITS)}, "
                          f"got {frequency_unit!r}")
    plot_dofs = (_plot_dofs(out["plot"], names[:ndof], path, dof_map=bare.dof_map) if "plot" in out
                 else list(range(min(ndof, 6))))
    harmonic = out.get("harmonic")
    if harmonic is not None:
        harmonic = checked(path, "", _checks.positive_int, "[output] harmonic", harmonic, minimum=0)
        if harmonic > harmonics:
            raise ConfigError(f"{path}: [output] harmonic must be at most [sweep] harmonics = {harmonics} "
                              f"(or omitted for max |q - q0|), got {harmonic}")
    design_loads = design_dof = None
    if "design" in data:
        design = _table(data["design"], "[design]", path)
        if len(dampers) != 1:
            raise ConfigError(f"{path}: [design] needs exactly one [[damper]] (its load is varied), got {len(dampers)}")
        design_loads = _array(_get(design, "loads", "[design]", path), "[design] loads", path)
        design_dof = _dof_key(_get(design, "dof", "[design]", path), names[:ndof], path, "[design] dof",
                              bare.dof_map)
    mode_table = None
    if nonlinear:
        mode_table = _modes_table(_table(_get(data, "modes", "the file", path), "[modes]", path), names[:ndof],
                                  plot_dofs, path)
        if engine_order is not None and mode_table.nodal_diameter is None:
            mode_table.nodal_diameter = engine_order
        elif engine_order is None and mode_table.nodal_diameter is not None:
            raise ConfigError(f"{path}: [modes] nodal_diameter needs a [cyclic] table (one sector of a bladed disk)")
    prestress = None
    if "prestress" in data:
        prestress = prestress_table(_table(data["prestress"], "[prestress]", path), ndof, path)
        if isinstance(structure, CyclicStructure) and (prestress.modal_damping is not None
                                                       or prestress.rayleigh_damping is not None):
            raise ConfigError(f"{path}: [prestress] modal_damping and rayleigh_damping are for a structure that is "
                              f"not cyclic (a sector's prestressed modes depend on the nodal diameter)")
    speed = _speed_table(data["speed"], bare, st, base, path, files) if "speed" in data else None
    if campbell and speed is None:
        raise ConfigError(f"{path}: microslip campbell needs a [speed] table: the stiffness at 2 or 3 rotation "
                          f"speeds, e.g. at = [\"0rpm\", \"6000rpm\"] and K = [\"K6000.mtx\"]")
    if campbell and dampers:
        raise ConfigError(f"{path}: microslip campbell does not take a [[damper]] table yet (its load m r Omega^2 "
                          f"follows the speed: build a SpeedModel(..., damper=, radius=) in Python)")
    campbell_table = (_campbell_table(data.get("campbell", {}), speed, bare, path) if "campbell" in data or campbell
                      else None)
    return FrfConfig(str(data.get("title", path.stem)), structure, force, omega, harmonics, samples, control,
                     plot_dofs, harmonic, names, reduction, modes, frequency_unit, engine_order, bare, dampers,
                     design_loads, design_dof, mode_table, prestress, speed, campbell_table, tuple(cont))


def apply_prestress(cfg: FrfConfig, force: dict, friction: str | None = None):
    """``(prestress, table, dynamic force)``: the configuration's ``[prestress]`` solved on ``cfg.structure``.

    ``friction`` (``"released"`` or ``"stuck"``, e.g. a command line's) overrides the table's, or prestresses a
    configuration without one. The static load is ``force[0]`` (N, ``[excitation] static``); the damping the
    table asks for is fitted on the prestressed modes. Without a prestress: ``(None, None, force)``; else the
    force without its static part (the prestress carries it).
    """
    from dataclasses import replace as _replace

    from ..frequency import prestress

    table = cfg.prestress
    if friction is not None:
        table = PrestressTable(friction=friction) if table is None else _replace(table, friction=friction)
    if table is None:
        return None, None, force
    static = force.get(0)
    p = prestress(cfg.structure, None if static is None else np.real(static), friction=table.friction,
                  reduction=cfg.reduction, modes=cfg.modes)
    if table.modal_damping is not None:
        p = p.with_damping(p.modal_damping(table.modal_damping))
    elif table.rayleigh_damping is not None:
        p = p.with_damping(p.rayleigh_damping(table.rayleigh_damping, modes=table.rayleigh_modes))
    return p, table, {h: v for h, v in force.items() if h != 0}


def prestress_table(table: dict, ndof: int, path) -> PrestressTable:
    """``[prestress]`` checked (its keys refused by the caller when unknown): see :class:`PrestressTable`."""
    from ..frequency.analyses.prestressed import FRICTION_STATES

    out = PrestressTable(modes=min(PrestressTable.modes, ndof))
    if "friction" in table:
        out.friction = table["friction"]
        if out.friction not in FRICTION_STATES:
            raise ConfigError(f"{path}: [prestress] friction must be one of {', '.join(map(repr, FRICTION_STATES))}, "
                              f"got {out.friction!r}")
    if "modes" in table:
        out.modes = checked(path, "", _checks.positive_int, "[prestress] modes", table["modes"])
    if "modal_damping" in table and "rayleigh_damping" in table:
        raise ConfigError(f"{path}: [prestress] give either modal_damping or rayleigh_damping, not both")
    if "rayleigh_modes" in table and "rayleigh_damping" not in table:
        raise ConfigError(f"{path}: [prestress] rayleigh_modes goes with rayleigh_damping = [ratio1, ratio2]")
    if "modal_damping" in table:
        value = table["modal_damping"]
        if not isinstance(value, list) or not value:
            raise ConfigError(f"{path}: [prestress] modal_damping must be a list of damping ratios, one per prestressed "
                              f"mode from the lowest, e.g. [0.01, 0.02], got {value!r}")
        out.modal_damping = checked(path, "", _checks.positive_array, "[prestress] modal_damping", value, ndim=1,
                                    allow_zero=True)
        out.modes = max(out.modes, out.modal_damping.size)
    if "rayleigh_damping" in table:
        value = table["rayleigh_damping"]
        if not isinstance(value, list) or len(value) != 2:
            raise ConfigError(f"{path}: [prestress] rayleigh_damping must be two damping ratios [ratio1, ratio2] (on "
                              f"rayleigh_modes, default the first two), got {value!r}")
        out.rayleigh_damping = tuple(checked(path, "", _checks.positive_array, "[prestress] rayleigh_damping", value,
                                             ndim=1, allow_zero=True).tolist())
        modes = table.get("rayleigh_modes", [1, 2])
        if not isinstance(modes, list) or len(modes) != 2:
            raise ConfigError(f"{path}: [prestress] rayleigh_modes must be two mode numbers such as [1, 2], got "
                              f"{modes!r}")
        out.rayleigh_modes = tuple(checked(path, "", _checks.positive_int, f"[prestress] rayleigh_modes[{i}]", m)
                                   for i, m in enumerate(modes))
        if out.rayleigh_modes[0] == out.rayleigh_modes[1]:
            raise ConfigError(f"{path}: [prestress] rayleigh_modes must be two different modes, got {modes!r}")
        out.modes = max(out.modes, *out.rayleigh_modes)
    if out.modes > ndof:
        raise ConfigError(f"{path}: [prestress] asks for {out.modes} prestressed modes; the structure has {ndof} DOFs")
    return out


def _speed_table(table, bare: Structure, st: dict, base: Path, path, files: ConfigFiles) -> SpeedTable:
    """``[speed]`` checked: 2 or 3 speeds, and the stiffness at each but the first (``[structure]``'s)."""
    table = _table(table, "[speed]", path)
    at = _get(table, "at", "[speed]", path)
    if isinstance(at, (str, bytes)) or not isinstance(at, list) or len(at) not in (2, 3):
        raise ConfigError(f"{path}: [speed] at must be a list of 2 or 3 rotation speeds, [structure] K's first, "
                          f"e.g. [\"0rpm\", \"6000rpm\"], got {at!r}")
    speeds = np.array([_angular_frequency(v, f"[speed] at[{i}]", path, "rad/s") for i, v in enumerate(at)])
    K = _get(table, "K", "[speed]", path)
    if isinstance(K, str) or not isinstance(K, list) or (K and not isinstance(K[0], (str, list))):
        raise ConfigError(f"{path}: [speed] K must be a list of the stiffness matrices at at[1:] (file names or "
                          f"inline matrices), got {K!r}")
    if K and all(isinstance(row, list) and row and not isinstance(row[0], (list, str)) for row in K):
        K = [K]  # one inline matrix, a list of rows of numbers
    if len(K) != speeds.size - 1:
        raise ConfigError(f"{path}: [speed] K must hold one matrix per speed after the first ({speeds.size - 1}: "
                          f"[structure] K is at at[0]), got {len(K)}")
    mats = [bare.K]
    for i, value in enumerate(K):
        what = f"[speed] K[{i}]"
        if isinstance(value, str):
            file = base / value
            if not file.is_file():
                raise FileNotFoundError(f"{path}: {what} file {str(file)!r} does not exist")
            from ..fe.files import read_matrix

            name = (st.get("names") or {}).get("K", "K")
            files.paths.add(file)
            A = checked(path, f"{what}: ", files._once, ("matrix", str(file), name), lambda: read_matrix(file, name))
        else:
            A = _matrix(value, what, path)
        if A.shape != bare.K.shape:
            raise ConfigError(f"{path}: {what} has shape {A.shape}; [structure] K has {bare.K.shape}")
        mats.append(A)
    return SpeedTable(speeds, mats)


def _campbell_table(table, speed: SpeedTable | None, bare: Structure, path) -> CampbellTable:
    """``[campbell]`` checked (the speeds' range, the points, engine orders, modes, systems, diameters)."""
    table = _table(table, "[campbell]", path)
    if "speeds" in table:
        value = table["speeds"]
        if isinstance(value, (str, bytes)) or not isinstance(value, list) or len(value) != 2:
            raise ConfigError(f"{path}: [campbell] speeds must be a range [start, end] of rotation speeds, e.g. "
                              f"[\"0rpm\", \"8000rpm\"], got {value!r}")
        lo, hi = (_angular_frequency(v, f"[campbell] speeds[{i}]", path, "rad/s") for i, v in enumerate(value))
    elif speed is not None:
        lo, hi = 0.0, float(speed.at.max())
    else:
        raise ConfigError(f"{path}: [campbell] needs speeds = [start, end] without a [speed] table")
    if not 0.0 <= lo < hi:
        raise ConfigError(f"{path}: [campbell] speeds must rise from a start >= 0, got {lo!r} to {hi!r} rad/s")
    points = _whole(table.get("points"), "[campbell] points", path, 41)
    if points < 2:
        raise ConfigError(f"{path}: [campbell] points must be at least 2, got {points}")
    points = checked(path, "", _checks.size, "[campbell] points", points)
    out = CampbellTable(np.linspace(lo, hi, points))
    if "engine_orders" in table:
        value = table["engine_orders"]
        if not isinstance(value, list) or not value:
            raise ConfigError(f"{path}: [campbell] engine_orders must be a list of whole numbers >= 1, got {value!r}")
        out.engine_orders = tuple(checked(path, "", _checks.positive_int, f"[campbell] engine_orders[{i}]", e)
                                  for i, e in enumerate(value))
    out.modes = (checked(path, "", _checks.positive_int, "[campbell] modes", table["modes"]) if "modes" in table
                 else min(6, bare.ndof))
    if "contacts" in table:
        out.contacts = checked(path, "", _checks.one_of, "[campbell] contacts", table["contacts"],
                               ("both", "stuck", "free"))
    if "nodal_diameters" in table:
        value = table["nodal_diameters"]
        if not isinstance(value, list) or not value:
            raise ConfigError(f"{path}: [campbell] nodal_diameters must be a list of whole numbers >= 0, got "
                              f"{value!r}")
        out.nodal_diameters = [checked(path, "", _checks.positive_int, f"[campbell] nodal_diameters[{i}]", d,
                                       minimum=0) for i, d in enumerate(value)]
    return out


def _modes_table(table: dict, names: list[str], plot_dofs: list[int], path) -> ModesTable:
    """``[modes]`` checked: the mode, its amplitude range, the DOF shown, whether to compare, what a fold does."""
    out = ModesTable(dof=plot_dofs[0] if plot_dofs else 0)
    if "mode" in table:
        out.mode = checked(path, "", _checks.positive_int, "[modes] mode", table["mode"])
        if out.mode > len(names):
            raise ConfigError(f"{path}: [modes] mode must be at most the number of DOFs ({len(names)}), got "
                              f"{out.mode}")
    if "amplitude" in table:
        value = table["amplitude"]
        if isinstance(value, (str, bytes)) or not hasattr(value, "__len__") or len(value) != 2:
            raise ConfigError(f"{path}: [modes] amplitude must be a list [start, end] of modal amplitudes "
                              f"(kg^1/2 m), got {value!r}")
        lo, hi = (checked(path, "", _checks.positive_scalar, f"[modes] amplitude[{i}]", v)
                  for i, v in enumerate(value))
        if not lo < hi:
            raise ConfigError(f"{path}: [modes] amplitude must rise from start to end, got {lo!r} >= {hi!r}")
        out.amplitude = (lo, hi)
    if "dof" in table:
        out.dof = _plot_dofs([table["dof"]], names, path, "[modes] dof")[0]
    if "compare" in table:
        out.compare = checked(path, "", _checks.flag, "[modes] compare", table["compare"])
    if "nodal_diameter" in table:
        out.nodal_diameter = checked(path, "", _checks.positive_int, "[modes] nodal_diameter",
                                      table["nodal_diameter"], minimum=0)
    if "folds" in table:
        out.folds = checked(path, "", _checks.one_of, "[modes] folds", table["folds"], FOLDS)
    return out


def _cyclic(table: dict, structure: Structure, names: list[str], path, files: ConfigFiles):
    """The sector as a :class:`CyclicStructure`, and the engine order; the boundaries' DOFs as everywhere (an index,
    a name of ``[structure] dofs`` or of the DOF map), a list for one node's DOFs; its frame, axis and coordinates."""
    from ..frequency.structures.cyclic import CyclicStructure

    def dofs(key, value):
        if isinstance(value, (str, int)):
            value = [value]
        if not isinstance(value, list):
            raise ConfigError(f"{path}: [cyclic] {key} must be a list of DOFs (indices or names; a list of a node's "
                              f"DOFs for one node), got {value!r}")
        return [tuple(_dof_key(d, names, path, f"[cyclic] {key}[{j}]", structure.dof_map) for d in v)
                if isinstance(v, list) else _dof_key(v, names, path, f"[cyclic] {key}", structure.dof_map)
                for j, v in enumerate(value)]

    frame = {}
    if "frame" in table:
        frame["frame"] = table["frame"]
    if "axis" in table:
        frame["axis"] = _numbers(table["axis"], "[cyclic] axis", path, "dimensionless")
    if "point" in table:
        frame["point"] = _numbers(table["point"], "[cyclic] point", path, "length")
    if "nodes" in table:
        frame["nodes"] = dofs("nodes", table["nodes"])
    if "coordinates" in table:
        frame["coordinates"] = _coordinates(table["coordinates"], path, files)

    sectors = checked(path, "", _checks.positive_int, "[cyclic] sectors", _get(table, "sectors", "[cyclic]", path),
                       minimum=3)
    engine_order = None
    if "engine_order" in table:
        engine_order = checked(path, "", _checks.positive_int, "[cyclic] engine_order", table["engine_order"],
                                minimum=0)
    disk = checked(path, "[cyclic] ", CyclicStructure, structure.M, structure.C, structure.K, sectors=sectors,
                    left=dofs("left", _get(table, "left", "[cyclic]", path, _SHARED.format("previous", "left"))),
                    right=dofs("right", _get(table, "right", "[cyclic]", path, _SHARED.format("next", "right"))),
                    dof_map=structure.dof_map, **frame)
    return disk, engine_order


def _numbers(value, what: str, path, kind: str) -> np.ndarray:
    """A list of numbers (or strings with units of ``kind``)."""
    if not isinstance(value, list):
        raise ConfigError(f"{path}: {what} must be a list of numbers, got {value!r}")
    return _array(value, what, path, kind)


def _coordinates(value, path, files: ConfigFiles):
    """``[cyclic] coordinates``: a CSV file of node positions, a table ``{node id: [x, y(, z)]}``, or the left and
    right nodes' positions ``[[[x, y(, z)], ...], [...]]`` (m; strings with a length unit)."""
    what = "[cyclic] coordinates"
    if isinstance(value, str):
        file = Path(path).parent / value
        if not file.is_file():
            raise FileNotFoundError(f"{path}: {what} file {str(file)!r} does not exist")
        return files.coordinates(file)
    if isinstance(value, dict):
        out = {}
        for key, xyz in value.items():
            if not str(key).strip().isdigit():
                raise ConfigError(f"{path}: {what} keys must be node ids, got {key!r}")
            out[int(key)] = _numbers(xyz, f"{what}[{key!r}]", path, "length")
        return out
    if not (isinstance(value, list) and all(isinstance(side, list) and all(isinstance(x, list) for x in side)
                                            for side in value)):
        raise ConfigError(f"{path}: {what} must be a file name, a table {{node id = [x, y, z]}} or the left and "
                          f"right nodes' positions [[[x, y, z], ...], [[x, y, z], ...]] (m), got {value!r}")
    return [[_numbers(x, what, path, "length") for x in side] for side in value]


def _node_coordinates(file) -> dict:
    """``{node id: [x, y(, z)]}`` (m) from a CSV file with a header naming ``node``, ``x``, ``y`` and optionally ``z``
    (other columns ignored; a node on several rows, as in a DOF map, must have one position)."""
    import csv

    with open(file, newline="", encoding="utf-8-sig") as fh:
        lines = [(no, line) for no, line in enumerate(fh, start=1)
                 if line.strip() and not line.lstrip().startswith("#")]
    rows = list(csv.reader(line for _, line in lines))
    header = [h.strip().lower() for h in rows[0]] if rows else []
    missing = [c for c in ("node", "x", "y") if c not in header]
    if missing:
        raise ConfigError(f"{file}: the first line must be a header naming the columns node, x, y (and z) of the "
                          f"[cyclic] coordinates; missing {', '.join(missing)}")
    cols = [header.index(c) for c in ("node", "x", "y", "z") if c in header]
    out: dict = {}
    for (no, _), cells in zip(lines[1:], rows[1:]):
        try:
            node = int(cells[cols[0]])
            xyz = [float(cells[c]) for c in cols[1:]]
        except (ValueError, IndexError):
            raise ConfigError(f"{file}: line {no}: expected a node id and its coordinates (m), got {cells}") from None
        if out.setdefault(node, xyz) != xyz:
            raise ConfigError(f"{file}: line {no}: node {node} at {xyz} m, but at {out[node]} m on an earlier line")
    return out


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
            key = checked(path, f"{what}: ", lambda r: structure.next(structure.dof_index(r)), rest)
        out[key] = value
    return out


def _damper(table: dict, k: int, structure: Structure, *, base_dir: Path, path, files: ConfigFiles):
    """An :class:`UnderPlatformDamper` from a ``[[damper]]`` table and its ``[[damper.interface]]`` tables."""
    from ..frequency.structures.damper import UnderPlatformDamper

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
        kwargs["damping"] = number("damping", "rate")
    if "retention" in table:
        kwargs["retention"] = number("retention", "stiffness")
    mass = _quantity(_get(table, "mass", where, path), "mass", f"{where} mass", path)
    inertia = _quantity(_get(table, "inertia", where, path), "moment of inertia", f"{where} inertia", path)
    d = checked(path, f"{where}: ", UnderPlatformDamper, mass, inertia, **kwargs)
    for i, face in enumerate(_get(table, "interface", where, path)):
        here = f"{where} interface {i + 1}"
        _table(face, "[[damper.interface]]", path, here)
        models = _contact_models(face, here, path, base_dir, files, many=True)
        points = np.array([[_quantity(v, "length", f"{here} points", path) for v in row]
                           for row in _get(face, "points", here, path)])
        angle = _angle(_get(face, "angle", here, path), f"{here} angle", path)
        platform = _get(face, "platform", here, path)
        platform = [platform] if isinstance(platform, dict) else platform
        plats = [{axis: _platform_dof(p.get(axis) if isinstance(p, dict) else None, structure, f"{here} platform",
                                      path) for axis in ("x", "y")} for p in platform]
        for p, dofs in zip(platform, plats):
            if dofs["x"] == dofs["y"]:
                raise ConfigError(f"{path}: {here} platform: x = {p['x']!r} and y = {p['y']!r} are the same DOF: "
                                  f"the platform's circumferential (x) and radial (y) DOFs at a point must differ")
        checked(path, f"{here}: ", d.add_interface, models if len(models) > 1 else models[0], points=points,
                 angle_deg=angle, platform=plats if len(plats) > 1 else plats[0], name=face.get("name"))
    return d


#: an interface angle's units (factor to degrees); a bare number is in degrees
_ANGLE_UNITS = {"deg": 1.0, "°": 1.0, "rad": 180.0 / np.pi}
_ANGLE = re.compile(r"\s*([-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?)\s*(\S*)\s*")


def _angle(value, what: str, path) -> float:
    """An interface normal's angle (degrees): a number in degrees, or a string with ``deg`` or ``rad``.

    A bare number of magnitude up to ``2 pi`` that is not whole could be either
    unit (``angle = 2.1`` meant as 120 degrees is a normal 2.1 degrees from x):
    it is refused, and its unit asked for.
    """
    if isinstance(value, str):
        match = _ANGLE.fullmatch(value)
        if match is None or match[2] not in _ANGLE_UNITS:
            raise ConfigError(f"{path}: {what} must be an angle: a number (degrees) or a string with a unit, "
                              f"\"120deg\" or \"2.1rad\", got {value!r}")
        return float(match[1]) * _ANGLE_UNITS[match[2]]
    degrees = _quantity(value, "dimensionless", what, path)
    if 0 < abs(degrees) <= 2 * np.pi and degrees != round(degrees):
        raise ConfigError(f"{path}: {what} = {value!r} is read in degrees (a normal {degrees:g}° from x), but it "
                          f"looks like radians ({np.degrees(degrees):.4g}°): write its unit, \"{value!r}deg\" or "
                          f"\"{value!r}rad\"")
    return degrees


def _platform_dof(value, structure: Structure, what: str, path):
    """A platform DOF: an index or name, or ``"next:j"`` for the next sector's."""
    if value is None:
        raise ConfigError(f"{path}: {what} must give the DOFs x and y of the platform, e.g. {{x = 0, y = 1}}")
    if isinstance(value, str) and value.startswith("next:"):
        return _next_keys({value: 1.0}, structure, what, path).popitem()[0]
    return checked(path, f"{what}: ", structure.dof_index, value)


def _table(value, where: str, path, label: str | None = None) -> dict:
    """A TOML table checked: a table, with known keys only."""
    if not isinstance(value, dict):
        raise ConfigError(f"{path}: {label or where} must be a table, got {value!r}")
    refuse_unknown(value, where, path)
    check_types(value, where, path, label)
    return value


def _structure_files(st: dict, base: Path, path, files: ConfigFiles):
    """The matrices read from ``file = ...`` or ``M = "M.mtx"``-style file names (FEMatrices), or None."""
    by_file = "file" in st
    by_name = any(isinstance(st.get(k), str) for k in ("M", "K", "C"))
    if not (by_file or by_name):
        for k in ("dof_map", "format"):
            if k in st:
                raise ConfigError(f"{path}: [structure] {k} goes with matrices read from files (file = ... or "
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

    if "format" in st and not isinstance(st["format"], str):
        raise ConfigError(f"{path}: [structure] format must be a string such as \"harwell-boeing\", got "
                          f"{st['format']!r}")
    try:
        return files.matrices(base / st["file"] if by_file else None, dof_map=dof_map, names=st.get("names"),
                              **kwargs, **({"format": st["format"]} if "format" in st else {}))
    except OneMatrixFile as exc:
        raise ConfigError(f"{path}: [structure] file = {st['file']!r} is a {exc.kind} file, which holds a single "
                          f"matrix: say which matrix each file is, M = \"M{exc.path.suffix}\", K = "
                          f"\"K{exc.path.suffix}\" (and C = ... if any) instead of file = ...") from None
    except (ValueError, TypeError) as exc:
        raise ConfigError(f"{path}: [structure] {exc}") from None
