"""The command module of each kind of study, for the commands that run a case file."""

from __future__ import annotations

from types import ModuleType

from . import cmd_force, cmd_info, cmd_sections, cmd_simulate

__all__ = ["STUDY_COMMANDS", "command_module"]

#: The command module of each kind of study: ``outcome(result)`` and ``run_study(study)``.
STUDY_COMMANDS: dict[str, ModuleType] = {
    "info": cmd_info,
    "sections": cmd_sections,
    "force": cmd_force,
    "simulate": cmd_simulate,
}


def command_module(command: str) -> ModuleType:
    """The module of the command that runs a study of this kind."""
    return STUDY_COMMANDS[command]
