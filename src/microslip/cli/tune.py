"""``microslip tune``: tune the paper's array on a reference contact and save it as JSON.

Without loop files the reference is a sphere (Hertz + Cattaneo--Mindlin), or
with ``--reference punch`` a flat punch with rounded edges (the flat face of a
damper; ``--flat-radius``, ``--edge-radius``), exact through the method of
dimensionality reduction, the same path as ``tune(mdr(...).as_reference())``.
``--E2``/``--nu2`` give the second body another material.
With loop files (``microslip tune LOOPS... --normal-law palmgren --length 10mm
--radius 5mm --elements 6 -o model.json``) the reference is built from the
measured loops and a cylinder's normal law, and a report (HTML + Markdown)
with the loops, the fitted branch, the per-element loops, the normal curve
and the validation at every measured load is written next to the model.
"""

from __future__ import annotations

import json
from dataclasses import replace
from pathlib import Path

from ._args import (add_second_body_options, add_sphere_options, load_range, output_file, output_folder, percent,
                    positive_int, quantity, quantity_list, second_body_from)

#: the references of the command line: what each is, and the geometry options it takes (dest -> option)
_KINDS = {"sphere": "sphere on a plane", "cylinder": "cylinder on a flat (measured LOOPS)",
          "punch": "flat punch with rounded edges"}
_GEOMETRY = {"radius": "--radius", "length": "--length", "normal_law": "--normal-law",
             "flat_radius": "--flat-radius", "edge_radius": "--edge-radius", "mdr_elements": "--mdr-elements"}
_USES = {"sphere": ("radius",), "cylinder": ("radius", "length", "normal_law"),
         "punch": ("flat_radius", "edge_radius", "mdr_elements")}
_NEEDS = {"sphere": (), "cylinder": (), "punch": ("flat_radius", "edge_radius")}
_DEFAULTS = {"radius": 5e-3, "length": 10e-3, "normal_law": "palmgren", "mdr_elements": 2000}
_EXAMPLES = {"flat_radius": "1mm", "edge_radius": "5mm"}


def add_parser(sub) -> None:
    p = sub.add_parser(
        "tune", help="tune a microslip model and write it as JSON",
        description="Tune the paper's microslip array on a reference contact (eqs. 1-9) and write the "
                    "model as JSON, readable by MicroslipModel.load and by 'microslip simulate'. Without LOOPS "
                    "the reference is a sphere on a plane. With LOOPS (measured hysteresis loops at one or more "
                    "normal loads) the branch of the steady loop at the highest load is fitted with a smooth "
                    "concave curve and the array is tuned on it and on a cylinder's normal law (paper Sect. 3); "
                    "--mu then defaults to a fit of the slip forces and --load to the highest load, and a report "
                    "is written. Units go with their values: 10mm, 2.5um, 30N, 200GPa.")
    p.add_argument("loops", nargs="*", metavar="LOOPS",
                   help="loop files: CSV/text whose header names columns with units (e.g. 'time [s], t [um], "
                        "T [N], N [N]'), or the ARTS-Lab damper JSON; append @LOAD to give a file's normal load, "
                        "e.g. run1.csv@36.6N (else a '# normal load = ...' comment or the mean of its N column)")
    p.add_argument("--reference", choices=list(_KINDS), default=None,
                   help="the reference contact: sphere (on a plane, Hertz + Cattaneo-Mindlin; --radius), punch "
                        "(a flat punch with rounded edges, the flat face of a damper, exact through the method of "
                        "dimensionality reduction; --flat-radius, --edge-radius, --mdr-elements) or cylinder (on "
                        "a flat: needs LOOPS, which give its tangential law; --radius, --length, --normal-law). "
                        "--E, --nu, --mu, --E2, --nu2 apply to all. An option a reference does not use is refused. "
                        "Default: sphere without LOOPS, cylinder with LOOPS")
    add_sphere_options(p)
    p.set_defaults(mu=None, radius=None)  # None: not given (refused for the punch); 5mm for a sphere, a cylinder
    add_second_body_options(p)
    k = p.add_argument_group("flat punch with rounded edges (--reference punch)")
    k.add_argument("--flat-radius", type=quantity("length", sign="positive"), default=None,
                   help="with --reference punch (required): radius of the flat face, e.g. 1mm")
    k.add_argument("--edge-radius", type=quantity("length", sign="positive"), default=None,
                   help="with --reference punch (required): radius of the rounded edge, e.g. 5mm")
    k.add_argument("--mdr-elements", type=positive_int, default=None,
                   help="with --reference punch: elements of the exact MDR array the model is tuned on, built up "
                        "to --load (default 2000)")
    p.add_argument("--load", type=quantity("force", sign="positive"), default=None,
                   help="normal load N_tot to tune at, e.g. 37.5N (default: 37.5N for the sphere and the punch, "
                        "the highest "
                        "measured load with LOOPS)")
    pts = p.add_mutually_exclusive_group()
    pts.add_argument("--elements", type=int, default=None,
                     help="number of elements J; points evenly spaced in force (default 4)")
    pts.add_argument("--forces", type=quantity_list("force", sign="positive"), default=None,
                     help="tuning forces, comma-separated, increasing, last = mu*N_tot (e.g. 3.75N,7.5N,11.25N,15N)")
    pts.add_argument("--displacements", type=quantity_list("length", sign="positive"), default=None,
                     help="tuning displacements, comma-separated, increasing, last at gross slip")
    p.add_argument("--load-range", type=load_range, default=None,
                   help="sphere only: loads N_lo,N_hi the contact meets, e.g. 7.5N,37.5N; the points of --elements "
                        "are then optimised for the worst error over that range (see 'microslip target'); --load "
                        "defaults to N_hi. The paper's sphere over 7.5N,37.5N reuses stored points (instant); "
                        "other problems are searched afresh (minutes)")
    g = p.add_argument_group("measured loops (with LOOPS): cylinder on a plane; --radius, --E, --nu above apply")
    g.add_argument("--normal-law", default=None,
                   help="normal force-approach law: 'palmgren' (Harris), 'lundberg' (Lundberg-Sjovall), or a "
                        "table file with columns 'n [unit]' and 'N [unit]' (monotone) (default palmgren)")
    g.add_argument("--length", type=quantity("length", sign="positive"), default=None,
                   help="length of the line of contact, e.g. 10mm (default 10mm)")
    g.add_argument("--t-column", metavar="DISP_COLUMN", default=None,
                   help="name of the tangential displacement column (default: t, x, u or displacement)")
    g.add_argument("--T-column", dest="T_column", metavar="FORCE_COLUMN", default=None,
                   help="name of the tangential force column (default: T, F or force)")
    g.add_argument("--N-column", dest="N_column", metavar="LOAD_COLUMN", default=None,
                   help="name of the normal load column (default N)")
    g.add_argument("--t-unit", metavar="DISP_UNIT", default=None,
                   help="unit of the displacement column when the header has none, e.g. um (a unit that differs "
                        "from the header's is an error)")
    g.add_argument("--T-unit", dest="T_unit", metavar="FORCE_UNIT", default=None,
                   help="unit of the force column when the header has none, e.g. N (a unit that differs from the "
                        "header's is an error)")
    g.add_argument("--out", "--report", dest="report", default=None, type=output_folder, metavar="DIR",
                   help="folder for the report, created if needed (default: the folder of -o); files "
                        "<model stem>-report.*")
    g.add_argument("--quiet", action="store_true", help="do not show progress on standard error")
    p.add_argument("-o", "--output", default="model.json", type=output_file("model.json"),
                   help="model file to write (default model.json)")
    p.set_defaults(func=run)


def reference_kind(args) -> str:
    """The reference of the command line, its options checked: a missing one named, one it does not use refused
    naming the reference; the options it uses and were not given get their defaults (in ``args``)."""
    kind = args.reference or ("cylinder" if args.loops else "sphere")
    if args.loops and kind != "cylinder":
        raise ValueError(f"measured LOOPS are tuned on a cylinder on a flat (--reference cylinder), not on a "
                         f"{_KINDS[kind]} (--reference {kind}): drop --reference {kind} or the loop files")
    if kind == "cylinder" and not args.loops:
        raise ValueError("--reference cylinder needs measured LOOPS: a cylinder on a flat has a normal law "
                         "(--normal-law) but no closed-form tangential law, so its tangential branch is fitted to "
                         "loop files (microslip tune LOOPS... --reference cylinder --length 10mm)")
    for name, option in _GEOMETRY.items():
        if getattr(args, name) is not None and name not in _USES[kind]:
            users = [k for k in _KINDS if name in _USES[k]]
            raise ValueError(f"{option} does not apply to the {_KINDS[kind]} (--reference {kind}); it is an option "
                             f"of --reference {' or '.join(users)}")
    for name in _NEEDS[kind]:
        if getattr(args, name) is None:
            raise ValueError(f"--reference {kind} needs {_GEOMETRY[name]} (e.g. {_GEOMETRY[name]} "
                             f"{_EXAMPLES[name]}): the {_KINDS[kind]} has no default")
    for name in _USES[kind]:
        if getattr(args, name) is None and name in _DEFAULTS:
            setattr(args, name, _DEFAULTS[name])
    return kind


def reference_from(args, kind: str, load: float):
    """The reference contact of the command line, exactly as the Python API builds it (``kind`` checked)."""
    from ..reference import RoundedPunch, Sphere, mdr

    second = second_body_from(args)
    if kind == "sphere":
        return Sphere(radius=args.radius, E=args.E, nu=args.nu, mu=args.mu, **second)
    # the punch: its material carried by a sphere whose radius the profile replaces (microslip.mdr's reference)
    material = Sphere(radius=args.edge_radius, E=args.E, nu=args.nu, mu=args.mu, **second)
    return mdr(material, max_load=load, elements=args.mdr_elements,
               profile=RoundedPunch(args.flat_radius, args.edge_radius)).as_reference()


def run(args) -> int:
    if args.loops and args.load_range is not None:
        raise ValueError("--load-range applies to the sphere and the punch, not to measured LOOPS")
    kind = reference_kind(args)
    if args.loops:
        return _run_loops(args)
    if args.report is not None:
        raise ValueError(f"--out is the folder of the report on measured LOOPS; the {kind}'s model goes to -o FILE")
    from ..tuning import tune

    mu_source = "given (--mu)" if args.mu is not None else "the default --mu 0.4 (the paper's)"
    if args.mu is None:
        args.mu = 0.4
    second_body_from(args)  # before the load's default: both or neither
    points_given = args.forces is not None or args.displacements is not None
    load = 37.5 if args.load is None else args.load
    extra = {}
    if args.load_range is not None:
        if points_given:
            raise ValueError("--load-range chooses the tuning points itself: give --elements, not --forces or "
                             "--displacements")
        load = args.load_range[1] if args.load is None else args.load
        extra = {"load_range": args.load_range, "progress": not args.quiet}
    reference = reference_from(args, kind, load)
    model = tune(reference, load, forces=args.forces, displacements=args.displacements,
                 elements=None if points_given else (4 if args.elements is None else args.elements), **extra)
    tuned = model.provenance
    notes = {}
    if kind == "punch":  # the MDR array records its profile and mu; the material is kept here
        notes = {"reference": "punch", "E": args.E, "nu": args.nu, "mdr_elements": args.mdr_elements,
                 **second_body_from(args)}
    model = model.with_provenance(replace(tuned, mu_source=mu_source, notes={**tuned.notes, **notes}))
    model.save(args.output)
    print(json.dumps({"written": args.output, "elements": model.elements, "mu": model.mu}))
    return 0


def _check_normal_law(law: str) -> None:
    """Refuse a --normal-law that is neither a law's name nor a file (before any file is read)."""
    if law not in ("palmgren", "lundberg") and not Path(law).is_file():
        raise ValueError(f"--normal-law must be 'palmgren', 'lundberg' or an existing table file, got {law!r}")


def normal_law(args):
    """The cylinder of the command line, its law a name or a table file."""
    from ..reference import Cylinder

    law = args.normal_law
    _check_normal_law(law)
    second = second_body_from(args)
    if law in ("palmgren", "lundberg"):
        return Cylinder(length=args.length, radius=args.radius, E=args.E, nu=args.nu, mu=args.mu, law=law, **second)
    return Cylinder.from_file(law, args.length, args.radius, args.E, args.nu, args.mu, **second)


def _split_load(item: str):
    from ..common.units import parse_quantity

    path, sep, load = item.rpartition("@")
    if not sep or not path:
        return item, None
    value = parse_quantity(load, "force", name=f"load of {path}")
    if not value > 0:
        raise ValueError(f"the load of {path} ({item!r}) must be positive, got {load!r}")
    return path, value


def _loops_option(kind: str, role: str):
    """The option giving the column (``kind="column"``) or the unit (``"unit"``) of ``role``, for messages."""
    metavar = {"column": "NAME", "unit": "UNIT"}[kind]
    if role in ("t", "T", "N") if kind == "column" else role in ("t", "T"):
        return f"--{role}-{kind}", f"--{role}-{kind} {metavar}"
    return None


def _run_loops(args) -> int:
    from ..measured import loops
    from ..measured.loops import read_with_options
    from ..common._progress import Progress
    from ..measured.loop_tuning import tune_on_loops

    _check_normal_law(args.normal_law)
    second_body_from(args)  # both or neither, before any file is read
    for item in args.loops:  # every file named exists before the first is read
        path, _ = _split_load(item)
        if not Path(path).is_file():
            raise ValueError(f"loop file {path!r} does not exist" if not Path(path).exists()
                             else f"loop file {path!r} is not a file")
    bar = Progress(len(args.loops) + 2, enabled=not args.quiet)
    columns = {k: v for k, v in (("t", args.t_column), ("T", args.T_column), ("N", args.N_column)) if v}
    units = {k: v for k, v in (("t", args.t_unit), ("T", args.T_unit)) if v}
    analysed = []
    for item in args.loops:
        path, load = _split_load(item)
        bar.step(f"reading and analysing {path}")
        record = read_with_options(path, _loops_option, columns=columns, units=units, normal_load=load)
        analysed.append(loops.analyse(record))
    bar.step("fitting the branch, tuning, validating")
    points_given = args.forces is not None or args.displacements is not None
    result = tune_on_loops(analysed, normal_law(args),
                           elements=None if points_given else (4 if args.elements is None else args.elements),
                           forces=args.forces, displacements=args.displacements, normal_load=args.load)
    tuned = result.model.provenance
    notes = {"normal_law_table": args.normal_law} if args.normal_law not in ("palmgren", "lundberg") else {}
    model = result.model.with_provenance(replace(tuned, loops=tuple(_split_load(i)[0] for i in args.loops),
                                                 notes={**tuned.notes, **notes}))
    model.save(args.output)
    out = Path(args.output)
    bar.step("writing the report")
    html, md = result.report(Path(args.report) if args.report else out.parent, stem=f"{out.stem}-report")
    bar.done(f"wrote {args.output}")
    worst = result.validation.worst()
    print(json.dumps({"written": args.output, "report": [str(html), str(md)], "elements": result.model.elements,
                      "mu": round(result.reference.mu, 4), "normal_load_N": result.reference.normal_load,
                      "fit_relative_residual_percent": percent(result.reference.fit.relative_residual),
                      "worst_validation_difference_percent": {k: percent(v) for k, v in worst.items()}}))
    return 0

