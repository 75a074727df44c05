"""dembridge from Python: run cases, read their results, step and solve DEM models.

    import dembridge
    run = dembridge.run("examples/cantilever.prm", output_dir="out/c",
                        set={"Bonds/model": "timoshenko"})
    run.summary["tip_deflection"]        # summary.json as a dict
    run.history["time"]                  # history.csv as NumPy arrays, one per column

    model = dembridge.Model("examples/cantilever.prm")
    model.step(100)
    model.positions                      # (N, 3) view of the model's own arrays

    model = dembridge.Model("examples/compression_hcp.prm", set={"Bonds/stiffness ratio": 3})
    model.solve_static()                 # the command line's static solver
    model.figures()["youngs_modulus"]    # summary.json's figures of the model's state

A case is a .prm or .json file, or a dict in the form of summary.json's `parameters`
({"Mode": "dem", "Particles": {"radius": 0.01, ...}}). `set` overrides keys as the command
line's --set does. Errors are the command line's one-line messages, raised as
dembridge.CaseError (a ValueError) naming the file and the key.
"""
import csv
import io
import json
import os
import tempfile

import numpy as np

from ._dembridge import CaseError
from ._dembridge import calibrate  # noqa: F401 (docs/calibration.md)
from ._dembridge import Model as _Model
from ._dembridge import check_case_file as _check_case_file
from ._dembridge import run_case_file as _run_case_file

__all__ = ["run", "Run", "Model", "CaseError", "check", "read_history", "overrides", "calibrate"]


def _value_text(value):
    """A parameter value as a case file writes it."""
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, (list, tuple, np.ndarray)):
        return ", ".join(_value_text(v) for v in value)
    if isinstance(value, float):
        return repr(value)
    return str(value)


def overrides(settings):
    """{"Section/Key": value} (or an iterable of "Section/Key=value") as --set strings."""
    if settings is None:
        return []
    if isinstance(settings, dict):
        return [f"{key}={_value_text(value)}" for key, value in settings.items()]
    return [str(s) for s in settings]


class _CaseFile:
    """A case given as a path or a dict, as a file the library reads (a dict: a temporary
    .json file, removed on exit)."""

    def __init__(self, case):
        self._temporary = None
        if isinstance(case, dict):
            handle, self.path = tempfile.mkstemp(prefix="dembridge-case-", suffix=".json")
            with os.fdopen(handle, "w") as out:
                json.dump({k: _json_value(v) for k, v in case.items()}, out)
            self._temporary = self.path
        else:
            self.path = os.fspath(case)

    def __enter__(self):
        return self.path

    def __exit__(self, *exc):
        if self._temporary:
            os.remove(self._temporary)


def _json_value(value):
    if isinstance(value, dict):
        return {k: _json_value(v) for k, v in value.items()}
    if isinstance(value, (bool, int, float, str)):
        return value
    return _value_text(value)


def read_history(path):
    """history.csv (or any of our CSV files) as {column: NumPy array}."""
    with open(path, newline="") as f:
        return _columns(f)


def _columns(lines):
    """CSV lines as {column: NumPy array} (numbers where every value is one)."""
    rows = list(csv.reader(lines))
    if not rows:
        return {}
    header, data = rows[0], rows[1:]
    columns = {}
    for k, name in enumerate(header):
        values = [r[k] for r in data]
        try:
            columns[name] = np.array([float(v) for v in values])
        except ValueError:
            columns[name] = np.array(values)
    return columns


class Run:
    """A finished run: its folder, summary.json as a dict, history.csv as arrays."""

    def __init__(self, output_dir):
        self.output_dir = os.fspath(output_dir)
        with open(os.path.join(self.output_dir, "summary.json")) as f:
            self.summary = json.load(f)
        self._history = None

    @property
    def history(self):
        """history.csv as {column: array} (empty for runs without one, e.g. static ones)."""
        if self._history is None:
            path = os.path.join(self.output_dir, "history.csv")
            self._history = read_history(path) if os.path.exists(path) else {}
        return self._history

    def files(self, pattern=""):
        """The run's output files whose names contain `pattern`, sorted."""
        return sorted(os.path.join(self.output_dir, f)
                      for f in self.summary.get("output_files", []) if pattern in f)

    def __repr__(self):
        return f"dembridge.Run({self.output_dir!r})"


def run(case, output_dir=None, set=None):  # noqa: A002 (the command line's name for it)
    """Runs a case as `dembridge run CASE --set ... --output-dir DIR` does; returns its Run.

    output_dir None: output/<case name> in the working directory, as the command line."""
    with _CaseFile(case) as path:
        if output_dir is None:
            stem = "case" if isinstance(case, dict) else os.path.splitext(os.path.basename(path))[0]
            output_dir = os.path.join("output", stem)
        _run_case_file(path, overrides(set), os.fspath(output_dir))
    return Run(output_dir)


def check(case, set=None):  # noqa: A002
    """Reads and checks a case without running it; returns its parameters as a dict."""
    with _CaseFile(case) as path:
        return json.loads(_check_case_file(path, overrides(set)))


class Model(_Model):
    """A DEM case built as `dembridge run` builds it, to step or solve from Python.

    Model(case, set=None); step(n): explicit time steps; solve_static(time=None): one solve of
    the command line's static solver (the loads at `time`, None: the final state), its solver
    figures as a dict; run(): the case to its end as `dembridge run` runs it, static or
    explicit, without files; figures(): summary.json's figures of the current state (after
    run(), the command line's to the bit, an explicit run's fits to its load history aside).
    A model is stepped, or solved, or run; history: run()'s history.csv as arrays. Arrays: positions, reference_positions,
    displacements, velocities, angular_velocities, forces, torques, radii, masses, ids,
    bond_ends, bond_states, bond_damage, bond_forces; stresses() (N, 3, 3) in Pa. The arrays
    other than displacements, bond_ends and stresses() are read-only views of the model's
    storage: they follow the model as it steps."""

    def __init__(self, case, set=None):  # noqa: A002
        with _CaseFile(case) as path:
            super().__init__(path, overrides(set))

    @property
    def history(self):
        """history.csv's columns of run() as {column: array} (one row per record of an explicit
        run, per load step of a static one); empty before run()."""
        return _columns(io.StringIO(self.history_text)) if self.history_text else {}
