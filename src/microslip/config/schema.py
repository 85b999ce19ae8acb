"""The configuration files' tables and keys, declared once: what the parsers accept and what the reference shows.

Each table of the ``frf`` configuration (read by ``microslip frf``, ``modes``, ``design`` and by design
studies) and of the study file (``microslip sweep``) is a :class:`Table` of :class:`Key` entries: the
key's name, its TOML type, its unit, its default, what it means and an example value. The parsers
(:mod:`microslip.config.frf`, :mod:`microslip.study.spec`) refuse every key a table does not declare and
check each value's type against it (:func:`check_types`); :func:`reference_markdown` renders the same
declarations as the configuration-file reference (``microslip config-reference``), so the two cannot
disagree.

To add a key, add a :class:`Key` to its table's list (in the order the messages list the accepted keys);
to add a table, add a :class:`Table` to :data:`FRF_TABLES` (and a ``Key`` of type ``"table"`` naming it
to the file's own table, :data:`FILE`), then read it in :func:`microslip.config.frf.config_from_data`.
"""

from __future__ import annotations

import re
from dataclasses import dataclass, fields

from ..common.errors import ConfigError
from ..frequency.numerics.continuation import StepControl

#: a key without a default that must be given (or one of its alternatives: the description says which)
REQUIRED = "required"

#: the TOML types a key may have: the Python types they are read as, and how the reference and messages name them
TYPES = {
    "number": ((int, float), "a real number"),
    "number or false": ((int, float, bool), "a real number or false"),
    "quantity": ((int, float, str), "a number or a string with a unit"),
    "integer": ((int,), "an integer"),
    "boolean": ((bool,), "True or False"),
    "string": ((str,), "a string"),
    "list": ((list,), "a list"),
    "table": ((dict,), "a table"),
    "tables": ((list,), "an array of tables"),
}


@dataclass(frozen=True)
class Key:
    """One key of a configuration table.

    Attributes
    ----------
    name : str
        The key as written; for keys named by a pattern (``h<harmonic>``), the pattern.
    type : str
        Its TOML types, names of :data:`TYPES` joined by ``" | "`` (``"string | list"``).
    unit : str
        The SI unit of a bare number (``"N"``, ``"m"``, ``"rad/s"``; ``""`` when it has none); a string
        may carry its own unit wherever the type is ``quantity``.
    default : object
        The value when the key is absent, :data:`REQUIRED`, or None (absent means "not used").
    description : str
        What it means (one or a few sentences, Markdown).
    example : str
        A value as written in TOML (``'"37.5N"'``, ``"[0, 1]"``).
    expects : str, optional
        How a message names the values it takes (default: from ``type``).
    applies_to : tuple of str, optional
        For the contact reference's keys: the kinds of reference the key applies to.
    pattern : str, optional
        A regular expression for keys named by a pattern (``h[1-9][0-9]*``).
    """

    name: str
    type: str
    unit: str
    default: object
    description: str
    example: str
    expects: str = ""
    applies_to: tuple = ()
    pattern: str = ""

    @property
    def python_types(self) -> tuple:
        """The Python types a value of this key may have (bool only where the type says boolean)."""
        return tuple(t for name in self.type.split(" | ") for t in TYPES[name.strip()][0])

    @property
    def accepts(self) -> str:
        """How a message and the reference name the values it takes."""
        return self.expects or " or ".join(TYPES[name.strip()][1] for name in self.type.split(" | "))

    @property
    def default_text(self) -> str:
        """The default as the reference shows it."""
        if self.default is None:
            return "none"
        if isinstance(self.default, str) and not self.default.startswith('"'):
            return self.default  # a sentence (REQUIRED, "16 H rounded up to 2^k", ...)
        return toml_value(self.default)

    def matches(self, key: str) -> bool:
        """Whether ``key`` is this key (its name, or its pattern)."""
        return re.fullmatch(self.pattern, key) is not None if self.pattern else key == self.name


@dataclass(frozen=True)
class Table:
    """One table of a configuration file.

    Attributes
    ----------
    name : str
        How messages name it: ``"[structure]"``, ``"[[contact]]"``, ``"the file"``.
    description : str
        What it holds (Markdown).
    keys : tuple of Key
        Its keys, in the order messages list them.
    header : str
        How it is written in TOML (``"[[damper.interface]]"``, ``'reference = {kind = "sphere", ...}'``; empty for
        the file's top level).
    """

    name: str
    description: str
    keys: tuple
    header: str = ""

    @property
    def names(self) -> tuple:
        """The names of the keys not named by a pattern (what messages list as accepted)."""
        return tuple(k.name for k in self.keys if not k.pattern)

    def key(self, name: str) -> Key | None:
        """The key ``name`` is, or None."""
        return next((k for k in self.keys if k.matches(name)), None)


def toml_value(value) -> str:
    """``value`` written as TOML (strings quoted, booleans lower case, lists bracketed)."""
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, str):
        return value if value.startswith('"') else f'"{value}"'
    if isinstance(value, (list, tuple)):
        return "[" + ", ".join(toml_value(v) for v in value) + "]"
    return repr(value)


def _k(name, type_, unit, default, description, example, **kw) -> Key:
    return Key(name, type_, unit, default, description, example, **kw)


#: how a DOF is named (a number that is no index is refused by the parser, which lists the DOFs)
_A_DOF = "a DOF: an index or a name"

# --- the frf configuration ---------------------------------------------------------------------------------------

FILE = Table("the file", "The top level of the file: a title and the tables below.", (
    _k("title", "string", "", "the file's name", "The title of the plots and the report.",
       '"Block on an inclined plane"'),
    _k("structure", "table", "", REQUIRED, "The linear structure: `[structure]`.", "[structure]"),
    _k("cyclic", "table", "", None, "One sector of a bladed disk: `[cyclic]`.", "[cyclic]"),
    _k("contact", "tables", "", None, "The contacts, one `[[contact]]` table each.", "[[contact]]"),
    _k("damper", "tables", "", None, "Under-platform dampers, one `[[damper]]` table each.", "[[damper]]"),
    _k("excitation", "table", "", REQUIRED, "The harmonic forces: `[excitation]` (optional for `microslip modes`).",
       "[excitation]"),
    _k("sweep", "table", "", REQUIRED, "The frequency range and the harmonics: `[sweep]`.", "[sweep]"),
    _k("design", "table", "", None, "The damper's design curve of `microslip design`: `[design]`.", "[design]"),
    _k("continuation", "table", "", None, "The continuation's step control: `[continuation]`.", "[continuation]"),
    _k("output", "table", "", None, "What is plotted: `[output]`.", "[output]"),
    _k("modes", "table", "", None, "The nonlinear mode of `microslip modes`: `[modes]` (required there).", "[modes]"),
    _k("prestress", "table", "", None, "A static step before the dynamics (a bolted joint): `[prestress]`.",
       "[prestress]"),
    _k("speed", "table", "", None, "The stiffness over rotation speed (`SpeedModel`): `[speed]` (required by "
       "`microslip campbell`).", "[speed]"),
    _k("campbell", "table", "", None, "The Campbell diagram of `microslip campbell`: `[campbell]`.", "[campbell]"),
))

STRUCTURE = Table("[structure]", "The linear structure `M q'' + C q' + K q = f`: its matrices inline, from a "
                  "`.npz` file (`matrices`), from a finite-element file (`file`) or one file per matrix (`M`, `K`, "
                  "`C` as file names).", (
    _k("M", "list | string", "kg", REQUIRED, "Mass matrix, a list of rows; or the name of a file holding it "
       "(Matrix Market `.mtx`, `.mat`, `.npz`, `.op4`; then `K` too is a file).", "[[0.1, 0.0], [0.0, 0.1]]",
       expects="a matrix (a list of rows of numbers) or a file name"),
    _k("K", "list | string", "N/m", REQUIRED, "Stiffness matrix, as `M`.", "[[1e7, 0.0], [0.0, 1e7]]",
       expects="a matrix (a list of rows of numbers) or a file name"),
    _k("C", "list | string", "N s/m", None, "Damping matrix, as `M` (or `rayleigh`; no damping when both are "
       "absent).", "[[17.32, 0.0], [0.0, 17.32]]", expects="a matrix (a list of rows of numbers) or a file name"),
    _k("rayleigh", "list", "1/s, s", None, "`[alpha, beta]`: `C = alpha M + beta K` (instead of `C`).",
       "[1.0, 2e-6]", expects="a list [alpha, beta] (1/s, s) giving C = alpha M + beta K"),
    _k("dofs", "list", "", '"q0", "q1", ...', "A name for every DOF, used by contacts, forces and plots "
       "(default: the DOF map's names with `dof_map`).", '["x", "y"]',
       expects="a list of names (non-empty strings), one per DOF"),
    _k("matrices", "string", "", None, "A `.npz` file holding arrays `M`, `K` and optionally `C` (relative to "
       "the configuration file).", '"model.npz"'),
    _k("file", "string", "", None, "One finite-element file holding `M`, `K` and optionally `C` (`.mat` v5/v7.3, "
       "`.npz`, `.op4`).", '"blade.mat"'),
    _k("dof_map", "string", "", None, "With matrices read from files: a CSV file naming the node and component "
       "of every row, so contacts and forces may name DOFs `\"1204:x\"`.", '"dofs.csv"'),
    _k("names", "table", "", '{M = "M", K = "K", C = "C"}', "The variables of `file` holding each matrix, when "
       "they are named otherwise.", '{M = "MGG", K = "KGG"}'),
    _k("format", "string", "", "from the suffix", "The format of the matrix files when their suffix does not say "
       "it: `\"matrix-market\"`, `\"matlab\"`, `\"npz\"`, `\"op4\"`, `\"ansys-full\"`, `\"harwell-boeing\"`, "
       "`\"nastran-dmig\"` or `\"abaqus\"`.", '"abaqus"'),
), "[structure]")

CONTACT = Table("[[contact]]", "A contact attached to the structure: its law (a model file, or a reference "
                "tuned when the file is read) and the directions its displacements are read along.", (
    _k("model", "string", "", REQUIRED, "The contact model's file, from `microslip tune` (or `reference`).",
       '"sphere_4_elements.json"'),
    _k("reference", "table", "", None, "A reference contact tuned when the configuration is read, as `microslip "
       "tune --reference` tunes it (instead of `model`): the table `reference = {...}` below.",
       '{kind = "sphere", radius = "5mm"}'),
    _k("load", "quantity", "N", None, "With `reference`: the normal load the contact is tuned at (required "
       "there).", '"37.5N"'),
    _k("elements", "integer", "", 4, "With `reference`: the number of elements of the tuned array.", "4"),
    _k("tangential", "integer | string | list | table", "", REQUIRED, "The tangential displacement `t = b_t . q`: "
       "a DOF (index or name), a coefficient per DOF, or a table `{\"0\" = 1, \"1\" = -1}` of DOFs; two directions "
       "for a contact moving on its plane, `[dir1, dir2]`. With `[cyclic]`, `\"next:j\"` names DOF j of the next "
       "sector.", "[0.866, 0.5]", expects="a DOF, a list of coefficients or a table of DOFs"),
    _k("normal", "integer | string | list | table", "", None, "The normal approach `n = b_n . q + approach`, as "
       "`tangential`; omitted, the approach is imposed (`approach`).", "[-0.5, 0.866]",
       expects="a DOF, a list of coefficients or a table of DOFs"),
    _k("preload", "quantity", "N", None, "A static force on the structure along `normal`, shared between the contact "
       "and the structure's springs.", '"37.5N"'),
    _k("approach", "quantity", "m", None, "An imposed approach at `q = 0` (an interference fit); required with "
       "`normal` omitted, the approach is then fixed.",
       '"2um"'),
    _k("name", "string", "", '"contact0", "contact1", ...', "The contact's name in messages, reports and study key paths.",
       '"sphere"'),
), "[[contact]]")

REFERENCE = Table("reference", "The reference contact of `[[contact]]` and `[[damper.interface]]` "
                  "tuned when the configuration is read: a sphere on a plane (`kind = \"sphere\"`) or a flat punch "
                  "with rounded edges (`kind = \"punch\"`, through the method of dimensionality reduction).", (
    _k("kind", "string", "", REQUIRED, "`\"sphere\"` or `\"punch\"`.", '"punch"', applies_to=("sphere", "punch")),
    _k("radius", "quantity", "m", 5e-3, "The sphere's radius.", '"5mm"', applies_to=("sphere",)),
    _k("flat_radius", "quantity", "m", REQUIRED, "The radius of the punch's flat face.", '"1mm"',
       applies_to=("punch",)),
    _k("edge_radius", "quantity", "m", REQUIRED, "The radius of the punch's rounded edge.", '"5mm"',
       applies_to=("punch",)),
    _k("mdr_elements", "integer", "", 2000, "The punch's springs in the method of dimensionality reduction.",
       "2000", applies_to=("punch",)),
    _k("E", "quantity", "Pa", 200e9, "Young's modulus of the body (and of the second, unless `E2`).",
       '"200GPa"', applies_to=("sphere", "punch")),
    _k("nu", "quantity", "", 0.3, "Poisson's ratio of the body.", "0.3", applies_to=("sphere", "punch")),
    _k("mu", "quantity", "", 0.4, "The friction coefficient.", "0.4", applies_to=("sphere", "punch")),
    _k("E2", "quantity", "Pa", None, "Young's modulus of the second body (with `nu2`).", '"210GPa"',
       applies_to=("sphere", "punch")),
    _k("nu2", "quantity", "", None, "Poisson's ratio of the second body (with `E2`).", "0.3",
       applies_to=("sphere", "punch")),
), 'reference = {kind = "...", ...}')

CYCLIC = Table("[cyclic]", "The structure is one sector of a bladed disk (`CyclicStructure`), solved for a "
               "travelling-wave excitation of an engine order.", (
    _k("sectors", "integer", "", REQUIRED, "The number of sectors (at least 3).", "24"),
    _k("left", "integer | string | list", "", REQUIRED, "The left boundary's DOFs (indices or names); a list of a "
       "node's DOFs for one node: `[[0, 1, 2]]`.", "[0]"),
    _k("right", "integer | string | list", "", REQUIRED, "The right boundary's DOFs: `right[j]` of a sector is "
       "`left[j]` of the next.", "[1]"),
    _k("engine_order", "integer", "", REQUIRED, "The excitation's engine order (here or in `[sweep]`).", "3"),
    _k("frame", "string", "", '"cylindrical"', "`\"cylindrical\"`: every DOF in a frame turning with the sector "
       "(as ANSYS CECYC/CPCYC and Nastran CYAX give them); `\"cartesian\"`: the global frame, the right boundary "
       "the left one turned by `2 pi / sectors` about the axis.", '"cartesian"'),
    _k("axis", "list", "", [0, 0, 1], "The disk's axis.", "[0, 0, 1]"),
    _k("point", "list", "m", [0, 0, 0], "A point of the axis.", "[0, 0, 0]"),
    _k("coordinates", "string | table | list", "m", None, "The boundary nodes' positions (required with "
       "`\"cartesian\"`): a CSV file with columns node, x, y(, z), a table `{\"1014\" = [0.1, 0, 0]}`, or the left "
       "and right nodes' positions `[[[x, y, z], ...], [[x, y, z], ...]]`.", '"nodes.csv"'),
    _k("nodes", "list", "", "the DOF map's", "`\"cartesian\"`: the other nodes' DOF tuples a `\"next:j\"` DOF may "
       "be in.", "[[4, 5, 6]]"),
), "[cyclic]")

DAMPER = Table("[[damper]]", "An under-platform damper (`UnderPlatformDamper`): a rigid body between two "
               "platforms, pressed by its centrifugal load, touching them through its interfaces.", (
    _k("mass", "quantity", "kg", REQUIRED, "The damper's mass.", "0.01"),
    _k("inertia", "quantity", "kg m^2", REQUIRED, "Its moment of inertia about its centre of mass.", "5e-7"),
    _k("centrifugal_load", "quantity", "N", REQUIRED, "The load pressing it against the platforms (or `speed` "
       "and `radius`).", '"300N"'),
    _k("speed", "quantity", "rad/s", None, "The rotation speed (`\"3000rpm\"`), with `radius`: the load is "
       "`mass radius speed^2`.", '"1000rad/s"'),
    _k("radius", "quantity", "m", None, "The radius of its centre of mass, with `speed`.", '"0.25m"'),
    _k("damping", "quantity", "1/s", 0.0, "Mass-proportional damping of the damper's motion.", "50.0"),
    _k("retention", "quantity", "N/m", 0.0, "The features keeping the damper in its pocket: a spring from each of "
       "its X, Y and arc R DOFs to the disk.", '"1e3N/m"'),
    _k("interface", "tables", "", REQUIRED, "Its interfaces, one `[[damper.interface]]` table each.",
       "[[damper.interface]]"),
), "[[damper]]")

INTERFACE = Table("[[damper.interface]]", "One interface of the damper with a platform: its contact points and "
                  "their law.", (
    _k("model", "string | list", "", REQUIRED, "The contacts' law: a model file, or a list of them, one per point "
       "(or `reference`).", '"flat.json"'),
    _k("reference", "table", "", None, "As in `[[contact]]`.", '{kind = "sphere"}'),
    _k("load", "quantity", "N", None, "As in `[[contact]]`.", '"37.5N"'),
    _k("elements", "integer", "", 4, "As in `[[contact]]`.", "4"),
    _k("points", "list", "m", REQUIRED, "The contact points on the damper, from its centre of mass.",
       "[[-2e-3, 1.5e-3], [-1e-3, 2.5e-3]]"),
    _k("angle", "quantity", "deg", REQUIRED, "The interface's normal, from the damper into the platform: degrees, "
       "or a string with its unit (`\"2.1rad\"`); a bare number of magnitude up to 2 pi that is not whole is "
       "refused (its unit is asked for).", "120"),
    _k("platform", "table | list", "", REQUIRED, "The platform's DOFs at the points, `{x = 0, y = 1}` (a list: one "
       "per point; `\"next:j\"` for the next sector's).", "{x = 0, y = 1}"),
    _k("name", "string", "", '"interface0", "interface1", ...', "The interface's name in messages and reports.", '"flat"'),
), "[[damper.interface]]")

EXCITATION = Table("[excitation]", "The harmonic forces `F cos(h omega t + phase)` on the DOFs (N): one value per "
                   "DOF, or a table of DOFs by name or index (the others 0 N).", (
    _k("static", "list | table", "N", None, "The static force.", '[0.0, "-1N"]', pattern="static"),
    _k("h<harmonic>", "list | table", "N", None, "The amplitudes of harmonic h (`h1` at the excitation frequency), "
       "h at most `[sweep] harmonics`.", '["0.6N", "0N"]', pattern=r"h[1-9][0-9]*"),
    _k("phase_h<harmonic>", "list | table", "deg", 0.0, "The phases of harmonic h: `F = amplitude exp(i phase)`.",
       "[0.0, 90.0]", pattern=r"phase_h[1-9][0-9]*"),
    _k("scale", "quantity", "", 1.0, "Multiplies every harmonic's amplitude (not the static force).", "2.0",
       pattern="scale"),
), "[excitation]")

SWEEP = Table("[sweep]", "The frequency range followed and the harmonic balance's settings.", (
    _k("omega", "list", "rad/s", REQUIRED, "The range `[start, end]` (or `frequency`; optional for `microslip "
       "modes`); strings with units: `\"60Hz\"` is 2 pi 60 rad/s.", "[12000, 16500]",
       expects="a list [start, end]"),
    _k("frequency", "list", "Hz", None, "The range in Hz (instead of `omega`).", "[1900, 2600]",
       expects="a list [start, end]"),
    _k("harmonics", "integer", "", 5, "The harmonics kept.", "7"),
    _k("samples", "integer", "", "16 H rounded up to a power of 2 (at least 32)", "AFT samples per period.", "256"),
    _k("reduction", "string", "", '"auto"', "`\"auto\"`, `\"exact\"`, `\"modal\"` or `\"none\"`: harmonic balance on "
       "the contact DOFs, the rest condensed exactly or modally (see `frequency_response`).", '"exact"'),
    _k("modes", "integer", "", None, "The normal modes kept with `\"modal\"`.", "60"),
    _k("engine_order", "integer", "", None, "With `[cyclic]`: the excitation's engine order (here or there).",
       "3"),
), "[sweep]")

_STEP_CONTROL = {f.name: f.default for f in fields(StepControl)}
CONTINUATION = Table("[continuation]", "The pseudo-arclength continuation's step control (`StepControl`; "
                     "steps in scaled arclength units).", (
    _k("ds_initial", "number", "", _STEP_CONTROL["ds_initial"], "The first step (clipped into `[ds_min, "
       "ds_max]`).", "0.02"),
    _k("chord_error", "number or false", "", _STEP_CONTROL["chord_error"], "The distance between the curve and the straight "
       "line joining two consecutive points that the steps aim at (scaled units, positive): longer steps where the "
       "curve is straight, shorter where it bends. For `microslip modes`: the frequency's and damping's difference "
       "from those lines against the log amplitude, over the stuck frequency (the mode's default 1.5e-5 with steps "
       "of up to a decade and turns of up to 0.3 rad; see the nonlinear-modes guide). Unset (a forced response) "
       "or false (a mode: its former steps of at most 1/20 decade and 0.1 rad): steps set by `max_angle`, the "
       "corrector's iterations and `ds_max` alone.", "1e-4"),
    _k("ds_max", "number", "", _STEP_CONTROL["ds_max"], "The largest step.", "0.05"),
    _k("ds_min", "number", "", _STEP_CONTROL["ds_min"], "The smallest step.", "1e-7"),
    _k("max_angle", "number", "rad", _STEP_CONTROL["max_angle"], "The largest turn of the tangent per step, in "
       "(0, pi).", "0.1"),
    _k("max_iterations", "integer", "", _STEP_CONTROL["max_iterations"], "Corrector iterations before a step is "
       "refused.", "12"),
    _k("max_points", "integer", "", _STEP_CONTROL["max_points"], "Points after which the continuation stops (the "
       "curve is then incomplete).", "5000"),
    _k("target_iterations", "integer", "", _STEP_CONTROL["target_iterations"], "Corrector iterations the step "
       "size aims at.", "3"),
    _k("tolerance", "number", "", _STEP_CONTROL["tolerance"], "Convergence: scaled Newton step and relative "
       "residual below this, in (0, 1).", "1e-9"),
), "[continuation]")

OUTPUT = Table("[output]", "What the plots and the report show.", (
    _k("plot", "list", "", "the first 6 DOFs", "The DOFs plotted, indices or names.", '["x", "y"]',
       expects="a list of DOFs (indices or names)"),
    _k("harmonic", "integer", "", "max |q - q0|", "The plotted amplitude: a harmonic, or omitted for the largest "
       "deviation from the static value over a period.", "1"),
    _k("frequency_unit", "string", "", '"Hz"', "The frequency axis of the plots and the report: `\"Hz\"` or "
       "`\"rad/s\"`.", '"rad/s"'),
), "[output]")

MODES = Table("[modes]", "The nonlinear mode of `microslip modes` (extended periodic motion concept); there "
              "`[excitation]` and the range of `[sweep]` are optional.", (
    _k("mode", "integer", "", 1, "The linear mode, contacts stuck, it starts from (1: the lowest).", "1"),
    _k("amplitude", "list", "kg^1/2 m", [1e-8, 1e-4], "The modal amplitude range `[start, end]` (`a = sqrt(m) x` "
       "for a rigid mass m).", "[1e-9, 1e-5]", expects="a list [start, end] of modal amplitudes (kg^1/2 m)"),
    _k("dof", "integer | string | number", "", "the first DOF plotted", "The DOF whose amplitude the plots also "
       "show.", '"x"', expects=_A_DOF),
    _k("compare", "boolean", "", True, "Also solve `[excitation]`'s forced response over `[sweep]` by harmonic "
       "balance and compare it with the one synthesised from the mode.", "true"),
    _k("nodal_diameter", "integer", "", "the engine order", "With `[cyclic]`: the mode's nodal diameter.", "3"),
    _k("folds", "string", "", '"stop"', "Where the mode turns back in amplitude: `\"stop\"` ends it there (with a "
       "warning), `\"follow\"` follows the curve beyond the fold.", '"follow"'),
), "[modes]")

DESIGN = Table("[design]", "The damper's design curve of `microslip design`: the peak response against the "
               "(one) damper's centrifugal load.", (
    _k("loads", "list", "N", REQUIRED, "The centrifugal loads, from sliding to stuck.", '["3N", "20N", "300N"]'),
    _k("dof", "integer | string | number", "", REQUIRED, "The DOF whose peak is read.", "2", expects=_A_DOF),
), "[design]")

PRESTRESS = Table("[prestress]", "A static step first (a bolted joint): the static loads (the contacts' preloads, "
                  "`[excitation] static`, the dampers' centrifugal loads) with the friction released or stuck; the "
                  "dynamics then start from that state with every contact's sliders reset there.", (
    _k("friction", "string", "", "released", "`\"released\"` (a frictionless static solve, then the sliders reset "
       "there: the dynamics start stuck at that state) or `\"stuck\"` (loaded from the unloaded state).",
       '"released"', expects='"released" or "stuck"'),
    _k("modes", "integer", "", None, "Linear modes of the prestressed structure (contacts stuck there) to report.",
       "6"),
    _k("modal_damping", "list", "", None, "Damping ratios on the prestressed modes, one per mode: `C` from them "
       "(replaces `C`; not for a sector).", "[0.01, 0.02]"),
    _k("rayleigh_damping", "list", "", None, "Two damping ratios: `C = alpha M + beta K_p` with these ratios on two "
       "prestressed modes (not for a sector).", "[0.01, 0.02]"),
    _k("rayleigh_modes", "list", "", [1, 2], "The two prestressed modes `rayleigh_damping` is fitted on.", "[1, 2]"),
), "[prestress]")

SPEED = Table("[speed]", "The stiffness over rotation speed (`SpeedModel`): `K(Omega) = K0 + Omega^2 K1 "
              "(+ Omega^4 K2)` through 2 or 3 speeds, `[structure] K` at the first.", (
    _k("at", "list", "rad/s", REQUIRED, "The 2 or 3 rotation speeds: `[structure] K`'s first, then one per matrix "
       "of `K` (numbers in rad/s, or strings with units).", '["0rpm", "6000rpm"]'),
    _k("K", "list", "N/m", REQUIRED, "The stiffness at the other speeds: files (`.mtx`, `.npz`, `.mat`, `.op4`: "
       "the variable `K`, or `[structure] names.K`) or inline matrices.", '["K6000.mtx"]'),
), "[speed]")

CAMPBELL = Table("[campbell]", "The Campbell diagram of `microslip campbell` (every key optional).", (
    _k("speeds", "list", "rad/s", "0 to the last of `[speed] at`", "The range `[start, end]` of rotation speeds.",
       '["0rpm", "8000rpm"]'),
    _k("points", "integer", "", 41, "Evenly spaced speeds over the range.", "41"),
    _k("engine_orders", "list", "", [1, 2, 3, 4, 5, 6], "The engine-order lines drawn and crossed.", "[1, 2, 3, 4]"),
    _k("modes", "integer", "", "6 or the DOFs", "Modes per system (per nodal diameter with `[cyclic]`).", "6"),
    _k("contacts", "string", "", "both", "`\"stuck\"` (at the static state), `\"free\"` (no contacts) or "
       "`\"both\"`.", '"both"', expects='"stuck", "free" or "both"'),
    _k("nodal_diameters", "list", "", "all, 0 to sectors // 2", "With `[cyclic]`: the nodal diameters solved.",
       "[0, 1, 2]"),
), "[campbell]")

#: the tables of the frf configuration, in the order the reference shows them
FRF_TABLES = (FILE, STRUCTURE, CONTACT, REFERENCE, CYCLIC, DAMPER, INTERFACE, EXCITATION, SWEEP, CONTINUATION,
              OUTPUT, MODES, PRESTRESS, DESIGN, SPEED, CAMPBELL)

# --- the study file ----------------------------------------------------------------------------------------------

_KEY_PATH = r"[^.\s]+(\.[^.\s]+)+"
STUDY_FILE = Table("the study file", "A study names a base `frf` configuration and the values to vary by their "
                   "key paths: a table's name and the key joined by dots (`\"sweep.harmonics\"`); a `[[contact]]` or "
                   "`[[damper]]` is named by its `name` or its number from 1 (`\"contact.sphere.preload\"`), the "
                   "number left out when there is one (`\"damper.mass\"`). The blocks combine as a product: every "
                   "grid point with every listed case, every random sample and every mistuned disk.", (
    _k("base", "string", "", REQUIRED, "The base configuration (relative to the study file).",
       '"inclined_block.toml"', expects="a file name (a non-empty string)"),
    _k("solve", "string", "", '"frf"', "`\"frf\"`: forced responses; `\"modes\"`: nonlinear modes (its `[modes]`).",
       '"frf"'),
    _k("title", "string", "", "the file's name", "The study's title.", '"Preload and excitation"'),
    _k("vary", "table", "", None, "A grid: every combination of the lists of `[vary]`.", "[vary]"),
    _k("case", "tables", "", None, "Listed cases, one `[[case]]` table each.", "[[case]]"),
    _k("random", "table", "", None, "Random samples: `[random]`.", "[random]"),
    _k("mistuning", "table", "", None, "Blade stiffness scatter of a bladed disk (a `[cyclic]` base): "
       "`[mistuning]`.", "[mistuning]"),
))

VARY = Table("[vary]", "A grid of values: each key path with the list of its values (a list value: a list of "
             "them).", (
    _k("<key path>", "list", "", None, "The values of the key at this path, each written as in the base "
       "configuration (numbers, strings with units, lists).", '["25N", "37.5N", "50N"]', pattern=_KEY_PATH),
), "[vary]")

CASE = Table("[[case]]", "One case: the values it sets, by key path.", (
    _k("<key path>", "quantity | boolean | list | table", "", None, "The key's value in this case.", "0.012",
       pattern=_KEY_PATH),
), "[[case]]")

RANDOM = Table("[random]", "Random samples: each key path with its distribution, `{ uniform = [lo, hi] }`, "
               "`{ normal = [mean, std] }`, `{ loguniform = [lo, hi] }` or `{ choice = [a, b, ...] }` (units as "
               "`\"20N\"` on both ends).", (
    _k("samples", "integer", "", REQUIRED, "The number of random cases.", "20"),
    _k("seed", "integer", "", 0, "The random generator's seed.", "1"),
    _k("<key path>", "table", "", None, "The distribution of the key at this path.", "{ uniform = [0.4, 0.6] }",
       pattern=_KEY_PATH),
), "[random]")

MISTUNING = Table("[mistuning]", "Random blade stiffness scatter of the assembled bladed disk (a base with "
                  "`[cyclic]`, `solve = \"frf\"`): every other case solved on mistuned disks too.", (
    _k("std", "number", "", REQUIRED, "The standard deviation of each blade's relative stiffness deviation.",
       "0.02"),
    _k("samples", "integer", "", REQUIRED, "Mistuned disks per combination of the other values.", "50"),
    _k("seed", "integer", "", 0, "The random generator's seed.", "1"),
    _k("reduction", "string", "", '"exact"', "How the assembled disk is condensed: `\"exact\"` or `\"modal\"`.",
       '"exact"'),
    _k("modes", "integer", "", None, "The normal modes kept with `\"modal\"`.", "60"),
), "[mistuning]")

#: the tables of the study file, in the order the reference shows them
STUDY_TABLES = (STUDY_FILE, VARY, CASE, RANDOM, MISTUNING)

#: the keys each table of the frf configuration accepts (the keys named by a pattern left out)
KEYS = {t.name: t.names for t in FRF_TABLES if t is not REFERENCE and t is not EXCITATION}
#: the same for the study file's tables
STUDY_KEYS = {t.name: t.names for t in STUDY_TABLES if t.name in ("the study file", "[random]", "[mistuning]")}
#: every table by its name
TABLES = {t.name: t for t in FRF_TABLES + STUDY_TABLES}


def check_types(table: dict, where: str, path, label: str | None = None) -> None:
    """Refuse a value whose TOML type the key of ``where`` does not take, naming the file, the table and the key.

    Keys whose type is a table or an array of tables are left to the code that reads them (its message says how
    to write them); so are keys the table does not declare (:func:`microslip.config.frf.refuse_unknown`).
    """
    spec = TABLES[where]
    for name, value in table.items():
        key = spec.key(name)
        if key is None or key.type in ("table", "tables"):
            continue
        if isinstance(value, bool) and bool not in key.python_types or not isinstance(value, key.python_types):
            what = f"{label or where} {name}" if spec.header else name  # a top-level key is named alone
            raise ConfigError(f"{path}: {what} must be {key.accepts}, got {value!r} (e.g. {name} = {key.example})")


# --- the reference -----------------------------------------------------------------------------------------------

_INTRO = """Every number is SI unless it is a string with a unit (`"37.5N"`, `"2um"`, `"2kHz"`, `"3000rpm"`);
file names are relative to the configuration file. Every table refuses a key it does not know, naming the
table and the keys it accepts (the closest one first when a key looks misspelled), and a value of the wrong
type, naming the key and what it takes."""


def _cell(text: str) -> str:
    return str(text).replace("|", "\\|").replace("\n", " ")


def _table_markdown(table: Table, level: str) -> list[str]:
    title = "The file's top level" if table.name in ("the file", "the study file") else f"`{table.header}`"
    lines = [f"{level} {title}", "", table.description, ""]
    lines += ["| key | type | unit | default | example | description |", "|---|---|---|---|---|---|"]
    for key in table.keys:
        described = key.description
        if key.applies_to and len(key.applies_to) == 1:
            described = f"(kind = \"{key.applies_to[0]}\") {described}"
        lines.append(f"| `{_cell(key.name)}` | {_cell(key.accepts)} | {_cell(key.unit) or '-'} | "
                     f"{_cell(key.default_text)} | `{_cell(key.example)}` | {_cell(described)} |")
    return lines + [""]


def reference_markdown() -> str:
    """The configuration-file reference, in Markdown: every table and key with its type, unit, default and example.

    Rendered from the declarations the parsers check files against (:data:`FRF_TABLES`,
    :data:`STUDY_TABLES`); ``microslip config-reference`` prints it.

    Returns
    -------
    str
        A Markdown (MyST) page whose first line is its title (a level-1 heading).
    """
    lines = ["# Configuration files", "", _INTRO, "",
             "## The `frf` configuration", "",
             "Read by `microslip frf`, `microslip modes` (with `[modes]`) and `microslip design` (with `[design]` "
             "and one `[[damper]]`), by `microslip.config.load_config` and as the base of a design study.", ""]
    for table in FRF_TABLES:
        lines += _table_markdown(table, "###")
    lines += ["## The study file", "",
              "Read by `microslip sweep` and `microslip.sweep`. Every value is checked by building the base "
              "configuration with it before any case is solved.", ""]
    for table in STUDY_TABLES:
        lines += _table_markdown(table, "###")
    return "\n".join(lines).rstrip("\n") + "\n"
