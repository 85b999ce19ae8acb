"""``microslip config-reference``: the configuration files' reference, every table and key, in Markdown."""

from __future__ import annotations

from ._args import output_file


def add_parser(sub) -> None:
    p = sub.add_parser(
        "config-reference", help="print the reference of the configuration files (frf, modes, design, study)",
        description="Print the reference of the configuration files read by 'microslip frf', 'modes', 'design' "
                    "and 'sweep': every table and key with its type, unit, default, an example and what it means, "
                    "in Markdown. It is rendered from the declarations the commands check a file against, so it "
                    "lists exactly the keys they accept.")
    p.add_argument("-o", "--output", type=output_file("configuration.md"), default=None, metavar="FILE",
                   help="write the reference to FILE (Markdown) instead of printing it")
    p.set_defaults(func=run)


def run(args) -> int:
    from ..common._io import atomic_write
    from ..config import reference_markdown

    text = reference_markdown()
    if args.output is None:
        print(text, end="")
    else:
        atomic_write(args.output, text)
        print(f"reference: {args.output}")
    return 0
