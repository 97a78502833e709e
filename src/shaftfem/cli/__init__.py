"""`shaftfem` on the command line: parse, call one library function, print, exit code.

Exit codes: 0 success, 1 a check failed (resonance), 2 bad input, 3 a failure inside
the computation (mesher, solver, cache, disk, cluster). Every error is one line on
stderr naming what was wrong; no traceback (SHAFTFEM_DEBUG=1 shows one, with the
library's error behind it).
"""

from __future__ import annotations

import os
import sys
import traceback
import warnings
from pathlib import Path

from shaftfem.cli import commands
from shaftfem.cli.parser import build_parser
from shaftfem.errors import EXIT_COMPUTATION, ShaftfemError


def main(argv: list[str] | None = None) -> int:
    from shaftfem.runtime import configure_threads

    configure_threads()  # before NumPy loads (shaftfem.runtime says why)
    try:
        args = build_parser().parse_args(argv)
    except SystemExit as exc:  # --help (0) or a bad command line (2, already said)
        return int(exc.code or 0)
    try:
        with warnings.catch_warnings():
            warnings.showwarning = _show_warning
            commands.check_outputs(args)
            return args.func(args)
    except ShaftfemError as exc:
        _debug_traceback(exc)
        print(f"shaftfem: error: {_one_line(exc)}", file=sys.stderr)
        return exc.exit_code
    except KeyboardInterrupt:
        print("shaftfem: interrupted", file=sys.stderr)
        return 130
    except OSError as exc:  # the disk: a folder that is a file, no space, no permission
        _debug_traceback(exc)
        print(f"shaftfem: error: {_one_line(exc)}", file=sys.stderr)
        return EXIT_COMPUTATION
    except Exception as exc:  # not translated where it happened: still one line, exit 3
        if os.environ.get("SHAFTFEM_DEBUG"):
            raise
        print(f"shaftfem: error: the computation failed unexpectedly: {type(exc).__name__}: "
              f"{_one_line(exc)} (set SHAFTFEM_DEBUG=1 for the traceback)", file=sys.stderr)
        return EXIT_COMPUTATION


def entry() -> None:
    """The `shaftfem` command: main() in a child process that Ctrl-C always stops
    (shaftfem.supervise)."""
    from shaftfem.supervise import supervised

    argv = sys.argv[1:]
    folders = _output_folders(argv)
    if folders is None:  # --help, or a bad command line: nothing to supervise
        sys.exit(main(argv))
    sys.exit(supervised(lambda: main(argv), folders))


def _output_folders(argv: list[str]) -> list[Path] | None:
    """The folders a command line may write into, for the clean-up after a stop; None
    where it does not parse (or asks for help), said by main() itself."""
    import contextlib
    import io

    try:
        with contextlib.redirect_stdout(io.StringIO()), contextlib.redirect_stderr(io.StringIO()):
            args = build_parser().parse_args(argv)
    except SystemExit:
        return None
    if args.func is commands.cmd_design and not args.out:
        try:
            from shaftfem.scene.load import load_scene

            return [commands.design_out(args, load_scene(args.scene).name)]
        except Exception:  # the child says what is wrong with the scene
            return []
    if args.func in (commands.cmd_sweep, commands.cmd_calibrate):
        return [commands.dask_out(args)]
    out = getattr(args, "out", None)
    return [Path(out)] if out else []


def _show_warning(message, category, *_args, **_kwargs) -> None:
    print(f"shaftfem: warning: {_one_line(message)}", file=sys.stderr)


def _debug_traceback(exc: BaseException) -> None:
    """With SHAFTFEM_DEBUG=1: the traceback, with the library error behind ours as its
    cause (gmsh's, PARDISO's, ARPACK's)."""
    if os.environ.get("SHAFTFEM_DEBUG"):
        traceback.print_exception(exc, file=sys.stderr)


def _one_line(exc: BaseException) -> str:
    return " ".join(str(exc).split()) or type(exc).__name__


if __name__ == "__main__":
    sys.exit(main())
