"""``microslip accuracy``: measure a saved model against the exact continuous contact on a family of load paths."""

from __future__ import annotations

from pathlib import Path

from ._args import add_output_folder, add_sphere_options, quantity, sphere_from


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
    p.add_argument("--reference", choices=["sphere", "punch"], default="sphere",
                   help="the exact contact to compare with, through MDR: sphere (Hertz + Cattaneo-Mindlin + "
                        "Mindlin-Deresiewicz, the default) or punch (flat punch with rounded edges, "
                        "--flat-radius, --edge-radius; the material options below apply to both)")
    add_sphere_options(p)
    p.add_argument("--flat-radius", type=quantity("length"), default=1e-3,
                   help="with --reference punch: radius of the flat face, e.g. 1mm (default 1mm)")
    p.add_argument("--edge-radius", type=quantity("length"), default=5e-3,
                   help="with --reference punch: radius of the rounded edge, e.g. 5mm (default 5mm)")
    p.add_argument("--load", type=quantity("force"), default=37.5,
                   help="tuning load N_tot of the model, the top of the family's loads, e.g. 37.5N "
                        "(default 37.5N)")
    p.add_argument("--mdr-elements", type=int, default=2000,
                   help="elements of the exact reference (default 2000: errors below 1e-4 of the metrics)")
    p.add_argument("--steps-per-cycle", type=int, default=360,
                   help="samples per cycle of every path (default 360; the metrics change by < 1e-4 beyond 180)")
    p.add_argument("--min-load", type=quantity("force"), default=None,
                   help="also summarise the paths whose lowest load is at least this, e.g. 7.5N")
    p.add_argument("--min-amplitude", type=float, default=0.5,
                   help="with --min-load: and whose amplitude is at least this multiple of the gross-slip "
                        "displacement at their lowest load (default 0.5)")
    add_output_folder(p, "microslip-accuracy")
    p.set_defaults(func=run)


def run(args) -> int:
    import matplotlib.pyplot as plt

    from ..common._checks import positive_int, positive_scalar
    from ..common._io import atomic_write, save_figure
    from ..common._progress import Progress
    from ..accuracy.compare import accuracy, restriction_mask
    from ..model import MicroslipModel
    from ..accuracy.paths import default_family
    from ..reference.mdr import mdr
    from ..reference.profiles import RoundedPunch

    model = MicroslipModel.load(args.model)
    positive_int("--mdr-elements", args.mdr_elements)
    positive_int("--steps-per-cycle", args.steps_per_cycle, minimum=8)
    positive_scalar("--load", args.load)
    if args.min_load is not None:
        positive_scalar("--min-load", args.min_load)
    positive_scalar("--min-amplitude", args.min_amplitude, allow_zero=True)
    material = sphere_from(args)
    if abs(model.mu - material.mu) > 1e-12 * material.mu:
        raise ValueError(f"the model's friction coefficient ({model.mu:g}, from {args.model}) differs from the "
                         f"reference's (--mu {material.mu:g}): give the mu the model was tuned with")
    out = Path(args.out)
    bar = Progress(4, enabled=not args.quiet)
    bar.step("load paths and exact reference")
    if args.reference == "punch":
        profile = RoundedPunch(args.flat_radius, args.edge_radius)
        exact = mdr(material, max_load=args.load, elements=args.mdr_elements, profile=profile)
        reference = exact.as_reference()
    else:
        reference = material
        exact = mdr(material, max_load=args.load, elements=args.mdr_elements)
    family = default_family(reference, args.load, steps_per_cycle=args.steps_per_cycle)
    bar.step(f"running both models on {len(family)} paths")
    report = accuracy(model, exact, family, progress=not args.quiet)
    bar.step("writing")
    report.to_csv(out / "accuracy.csv")
    from ..common.report import run_lines

    punch = args.reference == "punch"
    text = run_lines({"model": args.model, "reference": args.reference, "sphere radius": f"{args.radius * 1e3:g} mm",
                      "E": f"{args.E / 1e9:g} GPa", "nu": f"{args.nu:g}", "mu": f"{args.mu:g}",
                      **({"flat radius": f"{args.flat_radius * 1e3:g} mm",
                          "edge radius": f"{args.edge_radius * 1e3:g} mm"} if punch else {}),
                      "tuning load": f"{args.load:g} N", "MDR elements": f"{args.mdr_elements}",
                      "samples per cycle": f"{args.steps_per_cycle}",
                      "min load": "none" if args.min_load is None else f"{args.min_load:g} N",
                      "min amplitude": f"{args.min_amplitude:g} t_gs(N_min)"}) + [""]
    text += [f"model {args.model} (J = {model.elements}) against the exact contact (MDR, "
            f"{args.mdr_elements} elements), tuning load {args.load:g} N", "", "all paths:", report.summary_text()]
    if args.min_load is not None:
        mask = restriction_mask(report.paths, args.min_load, args.min_amplitude)
        if not mask.any():
            Nmin = report.param("N_m") - report.param("N_a")
            raise ValueError(f"no path of the family has its lowest load >= --min-load {args.min_load:g} N and "
                             f"an amplitude >= --min-amplitude {args.min_amplitude:g} t_gs(N_min); the lowest "
                             f"loads run from {Nmin.min():.4g} to {Nmin.max():.4g} N, the amplitudes up to "
                             f"{report.param('amplitude').max():g}")
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
