"""Every command's ``--help`` is its documentation: it must print, for every subcommand and
every action of one (argparse formats the help only when asked, so a ``%`` written in a help
text breaks ``--help`` alone, as ``continuum --help`` was: "TypeError: %o format: an integer
is required, not dict")."""

from __future__ import annotations

import argparse

from upliftlab.cli import parser


def _commands(p: argparse.ArgumentParser, prefix: tuple[str, ...] = ()):
    """(words, parser) of ``p`` and of every subcommand below it."""
    yield prefix, p
    for action in p._actions:
        if isinstance(action, argparse._SubParsersAction):
            for name, sub in action.choices.items():
                yield from _commands(sub, prefix + (name,))


def test_every_command_formats_its_help():
    commands = dict(_commands(parser()))
    # the reference: the subcommands `upliftlab --help` lists (README, docs/getting-started)
    for name in ("run", "paper", "scenes", "advise", "report", "continuum", "opensees",
                 "calibrate", "study", "store"):
        assert (name,) in commands
    for words, p in commands.items():
        text = p.format_help()
        assert text.startswith("usage: upliftlab"), words
    text = commands[("continuum",)].format_help()
    assert "at most 10% of the solve's CPU time" in " ".join(text.split())
