"""`shaftfem` on the command line: it reads arguments, calls the steps, prints.

Exit codes: 0 success, 1 a check failed (resonance), 2 bad input or a failed step.
Every error is one line on stderr naming what was wrong; no traceback.
"""

from __future__ import annotations

import argparse
import sys
import time

from .errors import ShaftfemError


class _Progress:
    """Progress lines with elapsed time on stderr, for the long steps."""

    def __init__(self, quiet: bool = False):
        self.t0 = time.perf_counter()
        self.quiet = quiet

    def __call__(self, msg: str) -> None:
        if not self.quiet:
            print(f"[{time.perf_counter() - self.t0:7.1f} s] {msg}", file=sys.stderr, flush=True)


def _positive_float(text: str) -> float:
    try:
        v = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"{text!r} is not a number") from None
    if not v > 0:
        raise argparse.ArgumentTypeError(f"{text!r} must be > 0")
    return v


def _cmd_modes(args) -> int:
    from .export import modes_record, write_json
    from .pipeline import run_modes, with_mesh
    from .scene import load_scene

    scene = with_mesh(load_scene(args.scene), args.mesh_size, args.order)
    result = run_modes(scene, use_cache=not args.no_cache, progress=_Progress(args.quiet))
    print(format_modes(result))
    if args.json:
        write_json(args.json, modes_record(result))
        print(f"wrote {args.json}")
    return 0


def format_modes(result) -> str:
    """The modes table as a designer reads it (every number with its unit)."""
    m, scene = result.modes, result.scene
    exc = scene.excitations[0] if scene.excitations else None
    lines = [
        f"scene {scene.name}: P{scene.mesh.order}, {m.n_dofs} DOFs, "
        f"{result.mesh.n_elements} elements, element size {scene.mesh.size * 1e3:g} mm "
        f"(grooves {scene.mesh.groove_size * 1e3:g} mm)",
        f"rigid-body modes: {m.n_rigid} (all below {max(m.rigid_frequencies):.1e} Hz)",
        "",
    ]
    head = f"{'mode':>4}  {'frequency':>12}  {'kind':<8}  {'residual':>9}"
    if exc:
        head += f"  {'f / ' + exc.name + ' ' + format(exc.frequency, 'g') + ' Hz':>20}"
    lines.append(head)
    for i, (f, kind, r) in enumerate(zip(m.frequencies, m.kinds, m.residuals)):
        row = f"{i + 1:>4}  {f:>9.2f} Hz  {kind:<8}  {r:>9.1e}"
        if exc:
            row += f"  {f / exc.frequency:>20.2f}"
        lines.append(row)
    t = result.seconds
    lines.append("")
    lines.append("time: " + ", ".join(f"{k} {v:.1f} s" for k, v in t.items()))
    return "\n".join(lines)


def _cmd_size(args) -> int:
    from .sizing import format_sizing, size_from_scene
    from .export import write_json
    from .scene import load_scene

    scene = load_scene(args.scene)
    result = size_from_scene(scene)
    print(format_sizing(result))
    if args.json:
        write_json(args.json, result.as_dict())
        print(f"wrote {args.json}")
    return 0 if result.ok else 1


def build_parser() -> argparse.ArgumentParser:
    p = argparse.ArgumentParser(
        prog="shaftfem",
        description="Finite-element modal analysis of machine shafts (free-free).",
    )
    sub = p.add_subparsers(dest="command", required=True)

    m = sub.add_parser("modes", help="first ten free-free natural frequencies")
    m.add_argument("scene", nargs="?", default=None,
                   help="scene file or name in geometry/ (default: paper2018)")
    m.add_argument("--mesh-size", type=_positive_float, metavar="MM",
                   help="element size away from the grooves, mm (groove sizes scale with it)")
    m.add_argument("--order", type=int, choices=(1, 2), help="element order (default: scene)")
    m.add_argument("--json", metavar="FILE", help="also write the results as JSON")
    m.add_argument("--no-cache", action="store_true", help="rebuild the CAD solid")
    m.add_argument("-q", "--quiet", action="store_true", help="no progress lines")
    m.set_defaults(func=_cmd_modes)

    s = sub.add_parser("size", help="size the screw shaft from its duty (paper eqs. 1-9)")
    s.add_argument("scene", nargs="?", default=None,
                   help="scene file or name in geometry/ (default: paper2018)")
    s.add_argument("--json", metavar="FILE", help="also write the results as JSON")
    s.set_defaults(func=_cmd_size)
    return p


def main(argv: list[str] | None = None) -> int:
    parser = build_parser()
    args = parser.parse_args(argv)
    try:
        return args.func(args)
    except ShaftfemError as exc:
        print(f"shaftfem: error: {exc}", file=sys.stderr)
        return 2
    except KeyboardInterrupt:
        print("shaftfem: interrupted", file=sys.stderr)
        return 130


if __name__ == "__main__":
    sys.exit(main())
