"""Run command lines as on a machine without some libraries (for tests/test_extras.py).

    python tests/without_extras.py MODULE[,MODULE...] '[["info", "m.stl", "--plot", "x.png"]]'

An import hook refuses the named modules and their submodules (``import matplotlib.pyplot``
raises ``ModuleNotFoundError`` as when matplotlib is not installed), and the computations a
command does are replaced by a function that fails loudly: a command that reaches its work
before checking its libraries says ``work started``. Each command line runs in this process
in turn; their exit statuses, standard output and standard error are printed as JSON.
"""

from __future__ import annotations

import contextlib
import importlib.abc
import io
import json
import sys


class Refuse(importlib.abc.MetaPathFinder):
    """Refuses to import the given top-level modules and everything below them."""

    def __init__(self, names: set[str]) -> None:
        self.names = names

    def find_spec(self, fullname, path, target=None):
        if fullname.split(".")[0] in self.names:
            raise ModuleNotFoundError(f"No module named {fullname!r}", name=fullname)
        return None


def _work_started(*args, **kwargs):
    raise RuntimeError("work started")


def main() -> None:
    blocked = set(sys.argv[1].split(","))
    for name in list(sys.modules):
        if name.split(".")[0] in blocked:
            raise SystemExit(f"{name} is already imported")
    sys.meta_path.insert(0, Refuse(blocked))

    from hullslice import cli, sweeps
    from hullslice.cli import cmd_report, outputs

    outputs.execute = _work_started
    cmd_report.execute = _work_started
    sweeps.sweep = _work_started

    results = []
    for argv in json.loads(sys.argv[2]):
        out, err = io.StringIO(), io.StringIO()
        with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
            code = cli.main(argv)
        results.append({"code": code, "out": out.getvalue(), "err": err.getvalue()})
    print(json.dumps(results))


if __name__ == "__main__":
    main()
