"""The study file of ``microslip sweep``: a base configuration and the values to vary, checked before any work.

An example (TOML; paths relative to the study file; every table and key, declared in
:mod:`microslip.config.schema`: ``microslip config-reference``)::

    base = "inclined_block.toml"        # an frf configuration (microslip frf's format)
    solve = "frf"                       # "frf" (default): forced responses; "modes": nonlinear modes ([modes])
    title = "Preload and excitation"    # optional

    [vary]                              # a grid: every combination of the lists
    "contact.sphere.preload" = ["25N", "37.5N", "50N"]   # a [[contact]] table named by its name (or number)
    "excitation.h1" = [["0.3N", "0N"], ["0.6N", "0N"]]   # a list value: a list of them

    [[case]]                            # and/or a list of cases, each table one case's values
    "damper.mass" = 0.012               # the only [[damper]]: its number may be left out
    "sweep.engine_order" = 2

    [random]                            # and/or random samples
    samples = 20
    seed = 1
    "contact.sphere.mu" = { uniform = [0.4, 0.6] }        # also normal = [mean, std], loguniform = [lo, hi],
                                                         # choice = [a, b, ...]; units as "20N" on both ends

    [mistuning]                         # blade stiffness scatter of a bladed disk ([cyclic] base)
    std = 0.02                          # standard deviation of each blade's relative stiffness deviation
    samples = 50                        # mistuned disks per combination of the other values
    seed = 1
    reduction = "exact"                 # how the assembled disk is condensed: "exact" (default) or "modal"
    # modes = 60                        # normal modes with "modal"

A key path is the table's name and the key joined by dots (see
:mod:`~microslip.study.key_paths`). The blocks combine as a product: every
grid point with every listed case, every random sample and every mistuned disk.
Every value is checked by building the base configuration with it before any
case is solved; a mistake is refused naming the study file, the block, the
path and the value.
"""

from __future__ import annotations

import copy
import hashlib
import itertools
import json
import re
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from ..common import _checks
from ..common._checks import close_spelling
from .. import config
from ..config import ConfigError, ConfigFiles, checked, config_from_data, read_toml
from ..config.schema import STUDY_KEYS, check_types
from .key_paths import set_key, set_key_in_place

# the study file's keys and those of its tables (STUDY_KEYS): declared once, in microslip.config.schema
SOLVES = ("frf", "modes")
DISTRIBUTIONS = ("uniform", "normal", "loguniform", "choice")
#: a number followed by a unit, as written in a configuration ("20N", "2.5um", "-3e-6 m")
_WITH_UNIT = re.compile(r"^\s*([-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?)\s*([^\d\s].*)?$")


@dataclass(frozen=True)
class Mistuning:
    """The ``[mistuning]`` block: random blade stiffness scatter of the assembled bladed disk."""

    std: float
    samples: int
    seed: int = 0
    reduction: str = "exact"
    modes: int | None = None


@dataclass(frozen=True)
class Case:
    """One case of a study: the values it sets, and for mistuning the disk's sample (None: the tuned sector)."""

    values: dict
    key: str
    mistuning_sample: int | None = None

    @property
    def label(self) -> str:
        """The values as ``path = value`` pairs (for messages and reports)."""
        parts = [f"{k} = {_show(v)}" for k, v in self.values.items()]
        if self.mistuning_sample is not None:
            parts.append(f"mistuned disk {self.mistuning_sample}")
        return ", ".join(parts) or "the base configuration"


@dataclass
class Study:
    """A design study read from a study file (:func:`load_study`): the base configuration and its cases.

    Attributes
    ----------
    path : Path
        The study file.
    base : Path
        The base configuration file.
    solve : {"frf", "modes"}
        Forced responses or nonlinear modes.
    title : str
        The study's title.
    grid : dict of str to list
        ``[vary]``: each key path's values (every combination is a case).
    listed : list of dict
        ``[[case]]`` tables: each a case's values.
    random_samples, random_seed : int
        ``[random]``: number of samples and the seed.
    distributions : dict of str to (str, list)
        ``[random]``: each key path's distribution and its arguments.
    mistuning : Mistuning or None
        ``[mistuning]``.
    data : dict
        The base configuration's tables, as read.
    files : ConfigFiles
        The files the base (and the values) name, read once.
    fingerprint : str
        A hash of the base file and every file it reads: cases keyed by it are
        solved again when one of them changes.
    """

    path: Path
    base: Path
    solve: str
    title: str
    grid: dict = field(default_factory=dict)
    listed: list = field(default_factory=list)
    random_samples: int = 0
    random_seed: int = 0
    distributions: dict = field(default_factory=dict)
    mistuning: Mistuning | None = None
    data: dict = field(default_factory=dict, repr=False)
    files: ConfigFiles = field(default_factory=ConfigFiles, repr=False)
    fingerprint: str = ""

    @property
    def parameters(self) -> list[str]:
        """The key paths the study varies, in the order of the file."""
        out = list(self.grid)
        for case in self.listed:
            out += [k for k in case if k not in out]
        return out + [k for k in self.distributions if k not in out]

    def cases(self) -> list[Case]:
        """Every case, in a fixed order: grid, then listed cases, then random samples, then mistuned disks."""
        grid = [dict(zip(self.grid, combo)) for combo in itertools.product(*self.grid.values())]
        listed = self.listed or [{}]
        rng = np.random.default_rng(self.random_seed)
        randoms = [{path: _draw(rng, *dist) for path, dist in self.distributions.items()}
                   for _ in range(self.random_samples)] or [{}]
        samples = [None] if self.mistuning is None else [None, *range(self.mistuning.samples)]
        out = []
        for g, c, r in itertools.product(grid, listed, randoms):
            values = {**g, **c, **r}
            out += [Case(values, self._key(values, s), s) for s in samples]
        return out

    def _key(self, values: dict, sample) -> str:
        mistuning = None if sample is None else {**self.mistuning.__dict__, "sample": sample}
        from ..common._version import __version__

        text = json.dumps({"base": self.fingerprint, "solve": self.solve, "values": values, "mistuning": mistuning,
                           "version": __version__}, sort_keys=True, default=str)
        return hashlib.sha256(text.encode()).hexdigest()[:16]

    def configuration(self, case: Case):
        """The case's configuration (:class:`~microslip.config.frf.FrfConfig`)."""
        if not isinstance(case, Case):
            raise TypeError(f"case must be a Case of this study (from Study.cases()), got {type(case).__name__}")
        data = copy.deepcopy(self.data)
        for path, value in case.values.items():
            set_key_in_place(data, path, value, where=str(self.path))
        return config_from_data(data, self.base, nonlinear=self.solve == "modes", files=self.files)


def load_study(path) -> Study:
    """Read a study file and check it: every key path and value against the base configuration.

    Parameters
    ----------
    path : str or Path
        The study file (TOML; format in this module's documentation).

    Returns
    -------
    Study

    Raises
    ------
    FileNotFoundError
        No such file, or no base configuration.
    ConfigError
        A key the study file does not know, a key path the base configuration
        has not, a value it refuses (wrong type or unit), a bad distribution;
        the message names the study file, the block, the path and the value.
    """
    path = _checks.file_path("path", path)
    raw = read_toml(path)
    _known(raw, "the study file", path)
    if "base" not in raw:
        raise ConfigError(f"{path}: a study needs base = \"<frf configuration>.toml\" (relative to the study file)")
    base = path.parent / _checked_text(raw["base"], "base", path)
    if not base.is_file():
        raise FileNotFoundError(f"{path}: base configuration {str(base)!r} does not exist")
    solve = raw.get("solve", "frf")
    if solve not in SOLVES:
        raise ConfigError(f"{path}: solve must be one of {', '.join(SOLVES)}, got {solve!r}")
    study = Study(path, base, solve, str(raw.get("title", path.stem)), data=read_toml(base))
    try:
        config_from_data(study.data, base, nonlinear=solve == "modes", files=study.files)
    except ConfigError as exc:
        raise ConfigError(f"{path}: the base configuration is refused: {exc}") from None
    study.grid = _grid(raw.get("vary", {}), path)
    study.listed = _listed(raw.get("case", []), path)
    if "random" in raw:
        study.random_samples, study.random_seed, study.distributions = _random(raw["random"], path)
    if "mistuning" in raw:
        study.mistuning = _mistuning(raw["mistuning"], study, path)
    if not (study.grid or study.listed or study.distributions or study.mistuning):
        raise ConfigError(f"{path}: the study varies nothing: give a [vary] table, [[case]] tables, a [random] "
                          f"table or a [mistuning] table")
    _check_values(study)
    study.fingerprint = _fingerprint(study)
    return study


def _known(table: dict, where: str, path) -> None:
    config.refuse_unknown(table, where, path, STUDY_KEYS)
    check_types(table, where, path)


def _checked_text(value, name: str, path) -> str:
    if not isinstance(value, str) or not value.strip():
        raise ConfigError(f"{path}: {name} must be a file name (a non-empty string), got {value!r}")
    return value


def _grid(table, path) -> dict:
    if not isinstance(table, dict):
        raise ConfigError(f"{path}: [vary] must be a table of key paths and lists of values, got {table!r}")
    out = {}
    for key, values in table.items():
        if not isinstance(values, list) or not values:
            raise ConfigError(f"{path}: [vary] {key!r} must be a non-empty list of values (one per case), "
                              f"got {values!r}")
        seen = {}
        for i, value in enumerate(values):  # as a case's key writes it: the same text is the same case
            text = json.dumps(value, sort_keys=True, default=str)
            if text in seen:
                raise ConfigError(f"{path}: [vary] {key!r} lists the value {_show(value)} twice (values "
                                  f"{seen[text] + 1} and {i + 1}): the cases would be one case solved twice, with "
                                  f"the same key; list each value once")
            seen[text] = i
        out[key] = values
    return out


def _listed(tables, path) -> list:
    if isinstance(tables, dict):
        raise ConfigError(f"{path}: case must be an array of tables, written [[case]] (one per case)")
    if not isinstance(tables, list) or not all(isinstance(t, dict) and t for t in tables):
        raise ConfigError(f"{path}: each [[case]] must be a table of key paths and values, got {tables!r}")
    return [dict(t) for t in tables]


def _random(table, path):
    if not isinstance(table, dict):
        raise ConfigError(f"{path}: [random] must be a table, got {table!r}")
    check_types(table, "[random]", path)
    if "samples" not in table:
        raise ConfigError(f"{path}: [random] needs samples (the number of random cases)")
    samples = checked(path, "", _checks.positive_int, "[random] samples", table["samples"])
    seed = checked(path, "", _checks.positive_int, "[random] seed", table.get("seed", 0), minimum=0)
    dists = {}
    for key, spec in table.items():
        if key in STUDY_KEYS["[random]"]:
            continue
        if "." not in key:
            _known({key: None}, "[random]", path)
        if not isinstance(spec, dict) or len(spec) != 1:
            raise ConfigError(f"{path}: [random] {key!r} must be one distribution, e.g. {{ uniform = [0.4, 0.6] }} "
                              f"({', '.join(DISTRIBUTIONS)}), got {spec!r}")
        (kind, args), = spec.items()
        if kind not in DISTRIBUTIONS:
            raise ConfigError(f"{path}: [random] {key!r}: unknown distribution "
                              f"{kind!r}{close_spelling(kind, DISTRIBUTIONS)} "
                              f"(one of {', '.join(DISTRIBUTIONS)})")
        dists[key] = (kind, _distribution_args(kind, args, f"[random] {key!r}", path))
    if not dists:
        raise ConfigError(f"{path}: [random] names no key path to draw (e.g. \"contact.sphere.mu\" = "
                          f"{{ uniform = [0.4, 0.6] }})")
    return samples, seed, dists


def _distribution_args(kind: str, args, what: str, path):
    if kind == "choice":
        if not isinstance(args, list) or not args:
            raise ConfigError(f"{path}: {what}: choice needs a non-empty list of values, got {args!r}")
        return list(args)
    if not isinstance(args, list) or len(args) != 2:
        raise ConfigError(f"{path}: {what}: {kind} needs two values [{'mean, std' if kind == 'normal' else 'lo, hi'}], "
                          f"got {args!r}")
    parsed = [_number_and_unit(a, f"{what} {kind}[{i}]", path) for i, a in enumerate(args)]
    (a, ua), (b, ub) = parsed
    if ua != ub:
        raise ConfigError(f"{path}: {what}: {kind}'s two values must have the same unit, got {args!r}")
    if kind == "normal" and b < 0 or kind != "normal" and not a < b:
        need = "std >= 0" if kind == "normal" else "lo < hi"
        raise ConfigError(f"{path}: {what}: {kind} needs {need}, got {args!r}")
    if kind == "loguniform" and a <= 0:
        raise ConfigError(f"{path}: {what}: loguniform needs positive bounds, got {args!r}")
    return [a, b, ua]


def _number_and_unit(value, what: str, path) -> tuple[float, str]:
    if isinstance(value, (int, float)) and not isinstance(value, bool):
        return float(value), ""
    m = _WITH_UNIT.match(value) if isinstance(value, str) else None
    if m is None:
        raise ConfigError(f"{path}: {what} must be a number or a number with a unit such as \"20N\", got {value!r}")
    return float(m.group(1)), (m.group(2) or "").strip()


def _draw(rng: np.random.Generator, kind: str, args):
    """One random value, written as the configuration takes it (with the unit of the bounds)."""
    if kind == "choice":
        return args[int(rng.integers(len(args)))]
    a, b, unit = args
    x = {"uniform": lambda: rng.uniform(a, b), "normal": lambda: rng.normal(a, b),
         "loguniform": lambda: float(np.exp(rng.uniform(np.log(a), np.log(b))))}[kind]()
    return f"{float(x)!r}{unit}" if unit else float(x)


def _mistuning(table, study: Study, path) -> Mistuning:
    if not isinstance(table, dict):
        raise ConfigError(f"{path}: [mistuning] must be a table, got {table!r}")
    _known(table, "[mistuning]", path)
    if study.solve != "frf":
        raise ConfigError(f"{path}: [mistuning] solves forced responses of the mistuned disk: it needs solve = \"frf\"")
    if "cyclic" not in study.data:
        raise ConfigError(f"{path}: [mistuning] needs a base configuration with a [cyclic] table (one sector of a "
                          f"bladed disk)")
    for key in ("std", "samples"):
        if key not in table:
            raise ConfigError(f"{path}: [mistuning] needs {key}")
    std = checked(path, "", _checks.positive_scalar, "[mistuning] std", table["std"], allow_zero=True)
    from ..frequency.structures.mistuning import MAX_STD

    if std > MAX_STD:
        raise ConfigError(f"{path}: [mistuning] std is a relative stiffness deviation and must be at most {MAX_STD} "
                          f"(a blade's stiffness scatters by a few percent), got {std!r}")
    samples = checked(path, "", _checks.positive_int, "[mistuning] samples", table["samples"])
    seed = checked(path, "", _checks.positive_int, "[mistuning] seed", table.get("seed", 0), minimum=0)
    reduction = table.get("reduction", "exact")
    if reduction not in ("exact", "modal"):
        raise ConfigError(f"{path}: [mistuning] reduction must be \"exact\" or \"modal\" (the assembled disk is "
                          f"condensed onto its contacts), got {reduction!r}")
    modes = table.get("modes")
    if modes is not None:
        modes = checked(path, "", _checks.positive_int, "[mistuning] modes", modes)
    return Mistuning(std, samples, seed, reduction, modes)


def _check_values(study: Study) -> None:
    """Build the base configuration with each value of each parameter (alone): refuse what it refuses."""
    blocks = [("[vary]", path, values) for path, values in study.grid.items()]
    blocks += [(f"[[case]] {i + 1}", path, [v]) for i, case in enumerate(study.listed) for path, v in case.items()]
    for path_, (kind, args) in study.distributions.items():
        probe = args if kind == "choice" else [_draw(np.random.default_rng(0), kind, args)]
        blocks.append(("[random]", path_, probe))
    for block, key, values in blocks:
        where = f"{study.path}: {block}"
        for value in values:
            data = set_key(study.data, key, value, where=where)
            try:
                config_from_data(data, study.base, nonlinear=study.solve == "modes", files=study.files)
            except (ConfigError, FileNotFoundError) as exc:
                raise ConfigError(f"{where} {key!r} = {_show(value)} is refused by the base configuration: "
                                  f"{exc}") from None


def _fingerprint(study: Study) -> str:
    """A hash of the base configuration's text and of every file it (and the study's values) read."""
    h = hashlib.sha256(study.base.read_bytes())
    for p in sorted(study.files.paths):
        h.update(str(p.name).encode())
        h.update(p.read_bytes() if p.is_file() else b"")
    return h.hexdigest()


def _show(value) -> str:
    return json.dumps(value) if isinstance(value, (list, str)) else repr(value)
