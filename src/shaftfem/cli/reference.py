"""The command reference (docs/commands.md) as Markdown, made from the parser.

One section per command: its usage line and every argument with its default and help,
so the page lists exactly what `shaftfem COMMAND --help` accepts. An argument without
help text is an error here, and so fails the docs test.
"""

from __future__ import annotations

import argparse

from shaftfem.cli.parser import build_parser

HEAD = """\
# Command reference

Every command and argument of `shaftfem`, as `shaftfem COMMAND --help` gives them. The
options shared by the modal commands, the exit status and the environment are in
[the command line](cli.md).

This page is generated from the parser in `shaftfem.cli.parser` by
`python scripts/write_docs.py`; a test fails when the two disagree.
"""


def _subcommands(parser: argparse.ArgumentParser) -> dict[str, tuple[str, argparse.ArgumentParser]]:
    """name -> (help, parser) of every command, in the parser's order."""
    for action in parser._actions:
        if isinstance(action, argparse._SubParsersAction):
            helps = {a.dest: a.help or "" for a in action._choices_actions}
            return {name: (helps.get(name, ""), p) for name, p in action.choices.items()}
    return {}


def _name(a: argparse.Action) -> str:
    if not a.option_strings:
        return str(a.metavar or a.dest).upper()
    flags = ", ".join(a.option_strings)
    if a.nargs == 0:
        return flags
    meta = a.metavar or ("|".join(map(str, a.choices)) if a.choices else a.dest.upper())
    return f"{flags} {meta}"


def _default(a: argparse.Action) -> str:
    if a.nargs == 0 or a.default in (None, argparse.SUPPRESS):
        return ""
    if isinstance(a.default, list):
        return ",".join(f"{v:g}" for v in a.default)
    return str(a.default)


def _cell(text: str) -> str:
    return " ".join(text.replace("|", "\\|").replace("%%", "%").split())


def command_reference() -> str:
    """The command reference page."""
    out = [HEAD]
    for name, (help_, p) in _subcommands(build_parser()).items():
        if not help_:
            raise ValueError(f"command {name} has no help text")
        usage = " ".join(p.format_usage().split()).removeprefix("usage: ")
        out += [f"## `{name}`", "", help_[:1].upper() + help_[1:] + ".", "",
                "```text", usage, "```", "",
                "| argument | default | what it does |", "|---|---|---|"]
        for a in p._actions:
            if isinstance(a, argparse._HelpAction):
                continue
            if not a.help:
                raise ValueError(f"{name} {_name(a)} has no help text")
            required = " (required)" if a.required and a.option_strings else ""
            out.append(f"| `{_cell(_name(a))}`{required} | {_cell(_default(a))} | {_cell(a.help)} |")
        out.append("")
    return "\n".join(out)
