"""The command line's grammar: every command, its arguments, their units and bounds."""

from __future__ import annotations

import argparse
import math
import sys

from shaftfem.cli import commands as cmd
from shaftfem.errors import EXIT_BAD_INPUT
from shaftfem.scene.schema import (
    DEFAULT_MAX_DOFS,
    ELEMENT_ORDERS,
    GEOMETRY_ORDERS,
    MAX_DOFS_LIMIT,
    MAX_MODE_COUNT,
)

# fem.factor.FACTORISERS plus "auto"; spelled out here because the CLI must not import
# SciPy before a command needs it (`shaftfem size` loads no solver).
SOLVERS = ("auto", "pardiso", "cholmod", "superlu")
SCENE_HELP = "scene file or name of a shipped scene (default: paper2018)"


def _number(kind, high: float, exclusive: bool = False):
    """An argparse type: a finite number in (0, high] ((0, high) if exclusive)."""
    def parse(text: str):
        try:
            v = kind(text)
        except ValueError:
            raise argparse.ArgumentTypeError(f"{text!r} is not {kind.__name__}") from None
        if not (0 < v < high if exclusive else 0 < v <= high):  # also refuses nan and inf
            raise argparse.ArgumentTypeError(
                f"{text!r} must be in (0, {high:g}{')' if exclusive else ']'}")
        return v
    return parse


_size_mm = _number(float, 20_000)
_percent = _number(float, 100, exclusive=True)
_hz = _number(float, 1e7)
_count = _number(int, MAX_MODE_COUNT)
_workers = _number(int, 1024)
_accuracy = _number(float, 50)
_max_dofs = _number(int, MAX_DOFS_LIMIT)


def _sizes(text: str) -> list[float]:
    try:
        v = [float(x) for x in text.split(",") if x.strip()]
    except ValueError:
        raise argparse.ArgumentTypeError(f"{text!r}: expected sizes in mm, e.g. 12,9,6.75") from None
    if not v or not all(0 < x <= 20_000 for x in v):
        raise argparse.ArgumentTypeError(f"{text!r}: sizes must be in (0, 20000] mm")
    return v


def _grid(first: str, last: str, example: str, unit: str, what: str, high: float,
          most: int, positive: bool = False):
    """A parser of FIRST:LAST:N: N values from FIRST to LAST in `unit`, 0 <= FIRST (or
    0 < FIRST where `positive`) < LAST <= high, N in [2, most]."""
    form = f"{first}:{last}:N"
    below = "<" if positive else "<="
    top = f"1e{round(math.log10(high))}"

    def parse(text: str) -> tuple[float, float, int]:
        try:
            a, b, n = text.split(":")
            start, stop, count = float(a), float(b), int(n)
        except ValueError:
            raise argparse.ArgumentTypeError(f"{text!r}: expected {form}, e.g. {example} "
                                             f"({unit}, and how many {what})") from None
        if not ((start > 0 if positive else start >= 0) and start < stop <= high
                and 2 <= count <= most):
            raise argparse.ArgumentTypeError(f"{text!r}: need 0 {below} {first} < {last} <= "
                                             f"{top} {unit} and N in [2, {most}]")
        return start, stop, count
    return parse


# N speeds (r/min), frequencies (Hz), stiffnesses (N/mm, evenly in log) and values of Q
_speed_range = _grid("START", "STOP", "0:12000:31", "r/min", "speeds", 1e6, 1001)
_frequency_range = _grid("START", "STOP", "5:150:300", "Hz", "frequencies", 1e6, 100_001)
_stiffness_range = _grid("A", "B", "100:1e6:40", "N/mm", "stiffnesses", 1e12, 400,
                         positive=True)
_q_range = _grid("A", "B", "0:5000:20", "N/mm", "values", 1e10, 400)


def _span(text: str) -> tuple[float, float]:
    """START:STOP, r/min."""
    try:
        a, b = text.split(":")
        start, stop = float(a), float(b)
    except ValueError:
        raise argparse.ArgumentTypeError(f"{text!r}: expected START:STOP, e.g. 500:3000 "
                                         "(r/min)") from None
    if not (0 <= start <= 1e6 and 0 <= stop <= 1e6 and start != stop):
        raise argparse.ArgumentTypeError(f"{text!r}: need two different speeds in [0, 1e6] "
                                         "r/min")
    return start, stop


class _Parser(argparse.ArgumentParser):
    """argparse, with its errors on one line like every other error (exit 2)."""

    def error(self, message: str):
        print(f"{self.prog}: error: {message} (see {self.prog} --help)", file=sys.stderr)
        raise SystemExit(EXIT_BAD_INPUT)

    def parse_args(self, args=None, namespace=None):
        """As argparse's, but an unknown flag is reported by its command, whose help
        lists the flags it takes."""
        parsed, extras = self.parse_known_args(args, namespace)
        if extras:
            command = self._subcommands().get(getattr(parsed, "command", None) or "", self)
            command.error(f"unrecognized arguments: {' '.join(extras)}")
        return parsed

    def _subcommands(self) -> dict[str, argparse.ArgumentParser]:
        for action in self._actions:
            if isinstance(action, argparse._SubParsersAction):
                return dict(action.choices)
        return {}


def _version() -> str:
    from shaftfem import __version__

    return __version__


def build_parser() -> argparse.ArgumentParser:
    p = _Parser(
        prog="shaftfem",
        description="Finite-element modal analysis of machine shafts: free-free, or installed "
        "in the bearings of the scene's [[support]] tables.",
    )
    p.add_argument("--version", action="version", version=f"shaftfem {_version()}")
    sub = p.add_subparsers(dest="command", required=True)
    m = _modal_command(sub, "modes", "natural frequencies with their error bounds (in the "
                       "scene's supports if it has any, else free-free)", cmd.cmd_modes,
                       estimate=True)
    m.add_argument("--speed-rpm", type=_number(float, 1e6), metavar="N",
                   help="also the whirl table of the shaft turning at N r/min (needs [rotor] "
                   "for the frame, or takes the default one)")
    m.add_argument("--sensitivity", action="store_true",
                   help="also solve the same mesh with each modelling choice the scene makes "
                   "flipped (each part's joint, each held seat's coupling) and show how far "
                   "each frequency moves, beside its bound")
    _modal_command(sub, "check", "resonance check against the scene's excitations (exit 1 if "
                   "a margin is violated, 4 if it holds on a free-free shaft)", cmd.cmd_check,
                   margin=True)
    e = _modal_command(sub, "export", "mode shapes (VTU/PVD), tables (CSV/JSON), mesh (MSH), "
                       "solid (STEP/BREP); or a CalculiX deck", cmd.cmd_export, json=False,
                       out="required")
    e.add_argument("--format", choices=("vtk", "calculix"), default="vtk",
                   help="vtk: mode shapes and tables (default); calculix: shaft.inp, a C3D10 "
                   "*FREQUENCY deck of the same mesh and material")
    _modal_command(sub, "render", "pictures: the shaft, every mode (PNG) and each mode moving "
                   "(GIF)", cmd.cmd_render, json=False, out="required")
    d = _modal_command(sub, "design", "sizing, modes, resonance check, files, pictures and a "
                       "report (report.md, and report.html with a 3D view of every mode)",
                       cmd.cmd_design, json=False, out="optional", estimate=True, margin=True)
    d.add_argument("--no-html", action="store_true",
                   help="leave out report.html (a self-contained page of about 3 MB with an "
                   "interactive 3D view of every mode)")
    cb = _modal_command(sub, "campbell", "the shaft turning ([rotor]): whirl frequencies "
                        "against speed, forward and backward, critical speeds, log decrements; "
                        "campbell.png in --out", cmd.cmd_campbell, out="optional")
    cb.add_argument("--speeds-rpm", type=_speed_range, metavar="START:STOP:N",
                    help="the diagram's speeds, r/min (default: 0 to [rotor] max_speed_rpm at "
                    "[rotor] campbell_points)")
    u = _modal_command(sub, "ucs", "the undamped critical speed map: the lateral critical "
                       "speeds against the bearings' stiffness, every bearing alike, with the "
                       "scene's bearings drawn over it; ucs.png, ucs.csv and ucs.json in --out",
                       cmd.cmd_ucs, out="optional")
    which = u.add_mutually_exclusive_group()
    which.add_argument("--backward", action="store_true",
                       help="the synchronous backward critical speeds (default: forward)")
    which.add_argument("--standstill", action="store_true",
                       help="the natural frequencies at standstill instead (ross's run_ucs "
                       "default; a rotor with gyroscopic moments has its critical speeds "
                       "elsewhere)")
    u.add_argument("--stiffness-n-per-mm", type=_stiffness_range, metavar="A:B:N",
                   help="N stiffnesses from A to B, N/mm, evenly in log (default: four decades "
                   "about the scene's bearings, 40 of them)")
    lv = _modal_command(sub, "level1", "API 684 Level I stability screening: the first "
                        "forward mode's log decrement against an applied cross-coupling Q at "
                        "the highest operating speed, Q_0 and the API 617 criteria; level1.png "
                        "in --out", cmd.cmd_level1, out="optional")
    lv.add_argument("--q-n-per-mm", type=_q_range, metavar="A:B:N",
                    help="N values of Q from A to B, N/mm (default: 20 from 0 to 1.5 Q_0, or to "
                    "2 Q_A if more)")
    lv.add_argument("--at-mm", type=float, metavar="Z",
                    help="where Q acts, mm from the shaft's left end (default: the stage with "
                    "the largest Wachel estimate, else mid-span between the bearings)")
    lv.add_argument("--qa-n-per-mm", type=float, metavar="Q",
                    help="the anticipated cross-coupling Q_A, N/mm (default: the stages' "
                    "Wachel estimates)")
    ru = _modal_command(sub, "runup", "a run-up (or coast-down) through the critical speeds: "
                        "the unbalance response integrated in time at a constant acceleration, "
                        "its envelope beside the steady one; runup.png in --out", cmd.cmd_runup,
                        out="optional")
    ru.add_argument("--accel-rpm-per-s", type=float, required=True, metavar="A",
                    help="the angular acceleration, r/min per s (negative: a coast-down)")
    ru.add_argument("--speeds-rpm", type=_span, metavar="START:STOP",
                    help="from and to, r/min (default: 0 to [rotor] max_speed_rpm, or back)")
    fr = _modal_command(sub, "frf", "the running machine's frequency response (a hammer "
                        "test while it turns): the receptance of a section to a force on "
                        "another, against frequency, at each speed; frf.png in --out",
                        cmd.cmd_frf, out="optional")
    fr.add_argument("--at-mm", type=float, required=True, metavar="Z",
                    help="where the force acts, mm from the shaft's left end")
    fr.add_argument("--probe-mm", type=float, metavar="Z",
                    help="where the response is read, mm (default: where the force acts)")
    fr.add_argument("--frequencies-hz", type=_frequency_range, metavar="START:STOP:N",
                    required=True, help="the force's frequencies, Hz")
    fr.add_argument("--speeds-rpm", type=float, nargs="+", metavar="N",
                    help="the speeds, r/min (default: standstill and the operating speeds)")
    _modal_command(sub, "static", "the installed shaft under its static loads (its weight, "
                   "[[force]]): each support's reaction and the deflection line; static.png "
                   "in --out", cmd.cmd_static, out="optional")
    _modal_command(sub, "strength", "will the shaft hold: its duty ([[force]], [[torque]], "
                   "gravity) on the solid, the hot spots with their bounds, fatigue and yield "
                   "by the FKM guideline, slopes and deflections at the seats ([strength]); "
                   "exit 1 when a check fails; strength.vtp (the stresses and FKM's "
                   "utilisation on the surface, for ParaView), hot_spots.png and "
                   "strength.json in --out", cmd.cmd_strength, out="optional")
    _modal_command(sub, "paper", "the paper's Table 2 and stated sizing beside ours",
                   cmd.cmd_paper, json=False)
    sw = _dask_command(sub, "sweep", "run many variants of a scene on Dask (resumable)",
                       "sweep file (TOML): base scene and parameter axes or points", cmd.cmd_sweep)
    sw.add_argument("--estimate", action="store_true",
                    help="also bound each frequency's error (one more solve per variant: "
                    "on a coarser mesh, or of the lower orders at orders 3 to 5)")
    _dask_command(sub, "calibrate", "find unknown scene values that reproduce target "
                  "frequencies (grid on Dask, then least squares)",
                  "calibration file (TOML): base, unknowns, targets", cmd.cmd_calibrate)
    _study_command(sub)
    s = sub.add_parser("size", help="size the screw shaft from its duty (paper eqs. 1-9)")
    s.add_argument("scene", nargs="?", default=None, help=SCENE_HELP)
    s.add_argument("--json", metavar="FILE", help="also write the results as JSON")
    s.set_defaults(func=cmd.cmd_size)
    return p


def _modal_command(sub, name: str, help: str, func, json: bool = True, out: str | None = None,
                   estimate: bool = False, margin: bool = False) -> argparse.ArgumentParser:
    """A command that solves a scene's modes: the scene, its mesh and modes, the outputs."""
    c = sub.add_parser(name, help=help)
    c.add_argument("scene", nargs="?", default=None, help=SCENE_HELP)
    c.add_argument("--mesh-size", type=_size_mm, metavar="MM",
                   help="element size away from the grooves, mm (groove sizes scale with it)")
    c.add_argument("--order", type=int, choices=ELEMENT_ORDERS,
                   help="element order: 1 to 5 (3 to 5: hierarchical; free shafts) "
                   "(default: scene)")
    c.add_argument("--geometry-order", type=int, choices=GEOMETRY_ORDERS,
                   help="how the elements follow the CAD surfaces: 2 (quadratic) or 3 "
                   "(cubic; orders 3 to 5) (default: scene, else 2)")
    c.add_argument("--modes", type=_count, metavar="N",
                   help="number of elastic modes (default: the scene's [modes] count, else 10)")
    c.add_argument("--max-frequency", type=_hz, metavar="HZ",
                   help="every elastic mode below this frequency, Hz, instead of a count")
    if json:
        c.add_argument("--json", metavar="FILE", help="also write the results as JSON")
    if out is not None:
        c.add_argument("--out", metavar="DIR", required=out == "required",
                       help="output folder" + ("" if out == "required"
                                               else " (default: out/SCENE)"))
    c.add_argument("--solver", choices=SOLVERS,
                   default="auto", help="sparse factorisation behind shift-invert "
                   "(default: the fastest installed; superlu is pure SciPy)")
    # every modal command takes the same modal flags; those a command does not use say so
    c.add_argument("--margin", type=_percent, metavar="PERCENT",
                   help="required separation margin, %% (default: scene, else 15)"
                   + ("" if margin else "; used by check and design"))
    c.add_argument("--no-estimate", action="store_true",
                   help="skip the error bound (one more solve: on a coarser mesh, or of the "
                   "lower orders at orders 3 to 5)" + ("" if estimate else
                                                      "; this command computes none"))
    _accuracy_arguments(c)
    c.add_argument("--free", action="store_true",
                   help="free-free: leave the scene's [[support]] bearings off (the shaft "
                   "hanging free, as in a hammer test; attached parts stay on)")
    c.add_argument("--no-cache", action="store_true",
                   help="neither read nor write the cache: build the CAD solid and every "
                   "mesh afresh and keep none of them")
    c.add_argument("-q", "--quiet", action="store_true", help="no progress lines")
    c.set_defaults(func=func)
    return c


def _accuracy_arguments(c: argparse.ArgumentParser) -> None:
    c.add_argument("--accuracy", type=_accuracy, metavar="PERCENT",
                   help="bound every frequency's error below PERCENT. Alone, the "
                   "discretisation is chosen from costs measured on grooved shafts (the "
                   "default mesh, order 5 on cubic elements, or meshes adapted at order 2), "
                   "and a PERCENT beyond the budget stops at once (exit 2); with "
                   "--mesh-size, --order or --geometry-order, the mesh (order 2) or the "
                   "element orders (3 to 5) are adapted from there (default: the scene's "
                   "[mesh] target_error_percent, else the fixed mesh)")
    c.add_argument("--max-dofs", type=_max_dofs, metavar="N",
                   help="DOF budget of the adapted space (default: the scene's, else "
                   f"{DEFAULT_MAX_DOFS})")
    c.add_argument("--strict-accuracy", action="store_true",
                   help="exit 1 when the accuracy asked for is not reached in the budget")


def _dask_command(sub, name: str, help: str, file_help: str, func) -> argparse.ArgumentParser:
    """A command that runs many scenes on Dask workers."""
    c = sub.add_parser(name, help=help)
    c.add_argument(name if name == "sweep" else "calibration", help=file_help)
    c.add_argument("--out", help=f"output folder (default out/ and the {name} file's name)")
    c.add_argument("--workers", type=_workers, default=2,
                   help="local worker processes (default 2)")
    c.add_argument("--scheduler", metavar="ADDRESS",
                   help="an existing Dask scheduler, e.g. tcp://host:8786, instead of local "
                   "workers")
    c.add_argument("-q", "--quiet", action="store_true", help="no progress lines")
    c.set_defaults(func=func)
    return c


def _study_command(sub) -> None:
    st = sub.add_parser("study", help="work-precision study: a ladder of P1 and P2 meshes")
    st.add_argument("scene", nargs="?", default=None, help=SCENE_HELP)
    st.add_argument("--p2", type=_sizes, default=[12.0, 9.0, 6.75, 5.0625],
                    help="P2 element sizes, mm (geometric; the three finest make the reference)")
    st.add_argument("--p1", type=_sizes, default=[8.0, 6.0, 4.5], help="P1 element sizes, mm")
    st.add_argument("--out", default="out/study", help="output folder (default: out/study)")
    st.add_argument("--solver", choices=SOLVERS, default="auto",
                    help="sparse factorisation behind shift-invert (default: auto)")
    st.add_argument("-q", "--quiet", action="store_true", help="no progress lines")
    st.set_defaults(func=cmd.cmd_study)
