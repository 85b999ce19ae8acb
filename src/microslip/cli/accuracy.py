"""``microslip accuracy``: measure a saved model against the exact continuous contact on a family of load paths."""

from __future__ import annotations

from pathlib import Path

from ._args import add_output_folder, add_sphere_options, quantity


def add_parser(sub) -> None:
    p = sub.add_parser(
        "accuracy", help="measure a saved model against the exact contact on variable-normal-load paths",
        description="Run a model (JSON from 'microslip tune') and the exact continuous contact (method of "
                    "dimensionality reduction, a fine array of the same elements) on a family of periodic "
                    "load paths t = t_a sin(tau), N = N_m + N_a sin(tau + phi): N_a/N_m 0, 0.3, 0.6, 0.9; "
                    "phi 0, 90, 180 deg; peak load 0.1 to 1 times --load; t_a 0.1 to 3 times the gross-slip "
                    "displacement at the path's lowest load. Writes accuracy.csv (one row per path), "
                    "summary.txt (worst and median of each metric and where the worst occurs), "
                    "accuracy-maps.png (error maps) and accuracy-amplitude.png (error against amplitude).")
    p.add_argument("model", help="model JSON file")
    p.add_argument("--reference", choices=["sphere", "punch"], default=None,
                   help="the exact contact to compare with, through MDR: sphere (Hertz + Cattaneo-Mindlin + "
                        "Mindlin-Deresiewicz) or punch (flat punch with rounded edges, --flat-radius, "
                        "--edge-radius; the material options below apply to both). Default: the sphere the model "
                        "was tuned on, as its file records; a model tuned on anything else (measured loops, a "
                        "cylinder) is compared with a sphere or a punch only when asked here")
    add_sphere_options(p, defaults=False)
    p.add_argument("--flat-radius", type=quantity("length", sign="positive"), default=1e-3,
                   help="with --reference punch: radius of the flat face, e.g. 1mm (default 1mm)")
    p.add_argument("--edge-radius", type=quantity("length", sign="positive"), default=5e-3,
                   help="with --reference punch: radius of the rounded edge, e.g. 5mm (default 5mm)")
    p.add_argument("--load", type=quantity("force", sign="positive"), default=None,
                   help="the top of the family's loads, e.g. 37.5N (default: the load the model was tuned at, as "
                        "its file records; 37.5N for a model that records none). Another load is said in the "
                        "output")
    p.add_argument("--mdr-elements", type=int, default=2000,
                   help="elements of the exact reference (default 2000: errors below 1e-4 of the metrics)")
    p.add_argument("--steps-per-cycle", type=int, default=360,
                   help="samples per cycle of every path (default 360; the metrics change by < 1e-4 beyond 180)")
    p.add_argument("--min-load", type=quantity("force", sign="positive"), default=None,
                   help="also summarise the paths whose lowest load is at least this, e.g. 7.5N")
    p.add_argument("--min-amplitude", type=float, default=0.5,
                   help="with --min-load: and whose amplitude is at least this multiple of the gross-slip "
                        "displacement at their lowest load (default 0.5)")
    add_output_folder(p, "microslip-accuracy")
    p.set_defaults(func=run)


_PAPER = {"radius": 5e-3, "E": 200e9, "nu": 0.3}
_UNITS = {"radius": ("mm", 1e3), "E": ("GPa", 1e-9), "nu": ("", 1.0)}


def _show(name, value) -> str:
    unit, factor = _UNITS[name]
    return f"{value * factor:.6g}{' ' + unit if unit else ''}"


def choose_reference(args, model, say):
    """The reference kind, the sphere's material and the family's top load, from the options and the file.

    ``say(text)`` reports every choice the user should know of: a model that
    records no tuning, options that differ from it, a comparison with another
    kind of contact than the one tuned on. Returns ``(kind, material, load)``.
    """
    from ..reference import Sphere

    tuned = model.provenance
    mu = model.mu if args.mu is None else args.mu
    if abs(model.mu - mu) > 1e-12 * mu:
        raise ValueError(f"the model's friction coefficient ({model.mu:g}, from {args.model}) differs from the "
                         f"reference's (--mu {mu:g}): give the mu the model was tuned with")
    kind = args.reference
    if tuned is None:
        kind = kind or "sphere"
        say(f"{args.model} records no tuning (a model built by hand or written by an older version): compared with "
            "the sphere of the options (the paper's benchmark unless given) at the load of --load (default 37.5 N)")
    elif kind is None and tuned.kind != "Sphere":
        raise ValueError(f"{args.model} was {tuned.describe()}; the exact contacts here are a sphere or a punch, "
                         "not that: to compare it with one anyway, say which, --reference sphere (with --radius, "
                         "--E, --nu) or --reference punch")
    elif tuned.kind != "Sphere":
        say(f"{args.model} was tuned on a {tuned.kind}, not a sphere: it is compared with a {kind} as asked "
            f"(--reference {kind}), so its errors include the difference between the two contacts")
    kind = kind or "sphere"
    own = tuned.reference if tuned is not None and tuned.kind == "Sphere" else {}
    material = {}
    for name in ("radius", "E", "nu"):
        given = getattr(args, name)
        material[name] = given if given is not None else own.get(name, _PAPER[name])
        if given is not None and name in own and abs(given - own[name]) > 1e-12 * abs(own[name]):
            say(f"--{name} {_show(name, given)} differs from the sphere {args.model} was tuned on "
                f"({name} = {_show(name, own[name])})")
    material = Sphere(mu=mu, **material)
    load = args.load if args.load is not None else (tuned.normal_load if tuned is not None else 37.5)
    if tuned is not None and args.load is not None and abs(args.load - tuned.normal_load) > 1e-9 * tuned.normal_load:
        above = args.load > tuned.normal_load
        say(f"--load {args.load:.6g} N differs from the load {args.model} was tuned at ({tuned.normal_load:.6g} N): "
            f"the family's loads go up to {args.load:.6g} N"
            + (", beyond the tuning load, where every element is closed and the model only extrapolates" if above
               else f", not to the tuning load (drop --load to use {tuned.normal_load:.6g} N)"))
    return kind, material, load


def run(args) -> int:
    import sys
    import warnings

    import matplotlib.pyplot as plt
    import numpy as np

    from ..common._checks import positive_int, positive_scalar
    from ..common._io import atomic_write, save_figure
    from ..common._progress import Progress
    from ..accuracy.compare import accuracy, restriction_mask
    from ..model import BeyondTuningWarning, MicroslipModel
    from ..accuracy.paths import default_family
    from ..reference.mdr import mdr
    from ..reference.profiles import RoundedPunch

    model = MicroslipModel.load(args.model)
    positive_int("--mdr-elements", args.mdr_elements)
    positive_int("--steps-per-cycle", args.steps_per_cycle, minimum=8)
    positive_scalar("--min-amplitude", args.min_amplitude, allow_zero=True)
    said = []

    def say(text):
        said.append(text)
        print(f"microslip accuracy: warning: {text}", file=sys.stderr)

    kind, material, load = choose_reference(args, model, say)
    out = Path(args.out)
    bar = Progress(4, enabled=not args.quiet)
    bar.step("load paths and exact reference")
    if kind == "punch":
        profile = RoundedPunch(args.flat_radius, args.edge_radius)
        exact = mdr(material, max_load=load, elements=args.mdr_elements, profile=profile)
        reference = exact.as_reference()
        what = (f"a flat punch with rounded edges (flat radius {args.flat_radius * 1e3:.6g} mm, edge radius "
                f"{args.edge_radius * 1e3:.6g} mm)")
    else:
        reference = material
        exact = mdr(material, max_load=load, elements=args.mdr_elements)
        what = "a sphere"
    what += (f", radius {material.radius * 1e3:.6g} mm, E = {material.E * 1e-9:.6g} GPa, nu = {material.nu:g}, "
             f"mu = {material.mu:g}")
    family = default_family(reference, load, steps_per_cycle=args.steps_per_cycle)
    if args.min_load is not None:
        mask = restriction_mask(family, args.min_load, args.min_amplitude)
        if not mask.any():  # before the runs
            Nmin = np.array([p.params["N_m"] - p.params["N_a"] for p in family])
            raise ValueError(f"no path of the family has its lowest load >= --min-load {args.min_load:g} N and "
                             f"an amplitude >= --min-amplitude {args.min_amplitude:g} t_gs(N_min); the lowest "
                             f"loads run from {Nmin.min():.4g} to {Nmin.max():.4g} N, the amplitudes up to "
                             f"{max(p.params['amplitude'] for p in family):g}")
    bar.step(f"running both models on {len(family)} paths")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", BeyondTuningWarning)  # a --load above the tuning load is said above
        report = accuracy(model, exact, family, progress=not args.quiet)
    bar.step("writing")
    report.to_csv(out / "accuracy.csv")
    from ..common.report import run_lines

    punch = kind == "punch"
    text = run_lines({"model": args.model, "reference": kind, "radius": f"{material.radius * 1e3:g} mm",
                      "E": f"{material.E / 1e9:g} GPa", "nu": f"{material.nu:g}", "mu": f"{material.mu:g}",
                      **({"flat radius": f"{args.flat_radius * 1e3:g} mm",
                          "edge radius": f"{args.edge_radius * 1e3:g} mm"} if punch else {}),
                      "loads up to": f"{load:g} N", "MDR elements": f"{args.mdr_elements}",
                      "samples per cycle": f"{args.steps_per_cycle}",
                      "min load": "none" if args.min_load is None else f"{args.min_load:g} N",
                      "min amplitude": f"{args.min_amplitude:g} t_gs(N_min)"}) + [""]
    tuned = model.provenance
    text += [f"model {args.model} (J = {model.elements})"
            + (f", {tuned.describe()}" if tuned is not None else ", no record of its tuning"),
            f"against the exact contact of {what} (MDR, {args.mdr_elements} elements), loads up to {load:g} N"]
    text += [f"note: {line}" for line in said]
    text += ["", "all paths:", report.summary_text()]
    if args.min_load is not None:
        text += ["", f"paths with N >= {args.min_load:g} N and t_a >= {args.min_amplitude:g} t_gs(N_min):",
                 report.where(mask).summary_text()]
    threshold = report.threshold_amplitude(0.10)
    text += ["", f"|energy error| <= 10 % on every path with t_a >= {threshold:g} t_gs(N_min)" if threshold == threshold
             else "|energy error| exceeds 10 % on some path at every amplitude of the family"]
    atomic_write(out / "summary.txt", "\n".join(text) + "\n")
    fig = report.plot()
    save_figure(fig, out / "accuracy-maps.png", dpi=130, bbox_inches="tight")
    plt.close(fig)
    ax = report.plot_amplitude(label=f"J = {model.elements}")
    save_figure(ax.figure, out / "accuracy-amplitude.png", dpi=130, bbox_inches="tight")
    plt.close(ax.figure)
    bar.done(f"wrote {out}")
    print("\n".join(text))
    return 0
