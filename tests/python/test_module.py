#!/usr/bin/python3
"""The Python module against the command line (tests/python/CMakeLists.txt says what and why)."""
import argparse
import os
import shutil
import subprocess
import sys
import unittest

import numpy as np

# the dembridge .vtu reader of the app tests (meshio does not read VTK's String field arrays)
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "app"))
from static_output import vtu_array  # noqa: E402

ARGS = None


def cli_run(case, out, *sets):
    command = [ARGS.dembridge, "run", case, "--output-dir", out]
    for s in sets:
        command += ["--set", s]
    return subprocess.run(command, capture_output=True, text=True)


def fresh(name):
    path = os.path.join(ARGS.out, name)
    shutil.rmtree(path, ignore_errors=True)
    return path


class RunLikeTheCommandLine(unittest.TestCase):
    """dembridge.run() writes what `dembridge run` writes, figure for figure, file for file."""

    def same_outputs(self, case, sets):
        import dembridge
        cli, py = fresh(case + "_cli"), fresh(case + "_python")
        overrides = dict(s.split("=", 1) for s in sets)
        done = cli_run(os.path.join(ARGS.examples, case + ".prm"), cli, *sets)
        self.assertEqual(done.returncode, 0, done.stderr)
        run = dembridge.run(os.path.join(ARGS.examples, case + ".prm"), output_dir=py, set=overrides)
        compared = subprocess.run([sys.executable, ARGS.compare, cli, py],
                                  capture_output=True, text=True)
        self.assertEqual(compared.returncode, 0, compared.stdout + compared.stderr)
        return run

    def test_cantilever(self):
        run = self.same_outputs("cantilever", [])
        self.assertEqual(run.summary["mode"], "dem")
        # the tip deflection of the thesis' cantilever (tests/app: 8.534242e-3 m)
        self.assertAlmostEqual(run.summary["tip_deflection"], 8.534242e-3, delta=5e-5)
        history = run.history
        self.assertEqual(len(history["time"]), len(history["step"]))
        self.assertGreater(len(history["time"]), 2)
        self.assertTrue(np.all(np.diff(history["time"]) > 0))

    def test_hcp_compression(self):
        run = self.same_outputs("compression_hcp", [])
        self.assertEqual(run.summary["solver"]["type"], "static")

    def test_overrides(self):
        run = self.same_outputs("cantilever", ["Bonds/model=euler_bernoulli"])
        # tests/app: the Euler-Bernoulli beam's tip deflection 8.488264e-3 m
        self.assertAlmostEqual(run.summary["tip_deflection"], 8.488264e-3, delta=5e-5)


class Arrays(unittest.TestCase):
    """The model's arrays are its state: the last ParaView file's displacements, to the bit."""

    def test_displacements_match_the_paraview_file(self):
        import dembridge
        case = os.path.join(ARGS.examples, "cantilever.prm")
        out = fresh("cantilever_arrays")
        done = cli_run(case, out)
        self.assertEqual(done.returncode, 0, done.stderr)
        last = sorted(f for f in os.listdir(out) if f.startswith("particles_") and f.endswith(".vtu"))[-1]
        kind, u_values = vtu_array(os.path.join(out, last), "displacement")
        self.assertEqual(kind, "Float64")  # every bit of the model's doubles
        _, ids_file = vtu_array(os.path.join(out, last), "id")
        model = dembridge.Model(case)
        figures = model.run()
        self.assertEqual(figures["stop_reason"], _summary(out)["stop_reason"])
        self.assertEqual(figures["steps"], _summary(out)["steps"])
        u_file = np.array(u_values).reshape(-1, 3)
        row_of_id = np.argsort(model.ids)
        u_model = model.displacements[row_of_id[np.array(ids_file, dtype=int)]]
        self.assertEqual(u_model.shape, u_file.shape)
        self.assertGreater(np.abs(u_file).max(), 1e-3)  # the tip moved (8.5 mm)
        np.testing.assert_array_equal(u_model, u_file)

    def test_views_follow_the_model(self):
        import dembridge
        model = dembridge.Model(os.path.join(ARGS.examples, "cantilever.prm"))
        positions = model.positions
        self.assertEqual(positions.shape, (model.n_particles, 3))
        self.assertFalse(positions.flags.writeable)
        before = positions.copy()
        model.step(200)
        self.assertEqual(model.steps, 200)
        self.assertGreater(np.abs(positions - before).max(), 0.0)  # the same memory, moved
        np.testing.assert_array_equal(positions - model.reference_positions, model.displacements)
        self.assertEqual(model.bond_ends.shape, (model.n_bonds, 2))
        self.assertTrue(np.all(model.bond_states == 0))
        self.assertEqual(model.stresses().shape, (model.n_particles, 3, 3))


class Errors(unittest.TestCase):
    """A bad key raises CaseError with the command line's one line, naming the key."""

    def test_unknown_key(self):
        import dembridge
        case = os.path.join(ARGS.examples, "cantilever.prm")
        key = "Bonds/stiffnes ratio"
        done = cli_run(case, fresh("bad_key_cli"), key + "=2")
        self.assertEqual(done.returncode, 1)
        cli_line = done.stderr.strip().splitlines()[-1].removeprefix("dembridge: error: ")
        with self.assertRaises(dembridge.CaseError) as raised:
            dembridge.run(case, output_dir=fresh("bad_key_python"), set={key: 2})
        self.assertIn("stiffnes ratio", str(raised.exception))
        self.assertEqual(str(raised.exception), cli_line)
        self.assertIsInstance(raised.exception, ValueError)
        with self.assertRaises(dembridge.CaseError) as raised:
            dembridge.Model(case, set={key: 2})
        self.assertEqual(str(raised.exception), cli_line)

    def test_bad_value_names_the_key(self):
        import dembridge
        case = os.path.join(ARGS.examples, "cantilever.prm")
        done = cli_run(case, fresh("bad_value_cli"), "Bonds/model=spaghetti")
        self.assertEqual(done.returncode, 1)
        cli_line = done.stderr.strip().splitlines()[-1].removeprefix("dembridge: error: ")
        with self.assertRaises(dembridge.CaseError) as raised:
            dembridge.Model(case, set={"Bonds/model": "spaghetti"})
        self.assertIn("Bonds/model", str(raised.exception))
        self.assertEqual(str(raised.exception), cli_line)

    def test_dict_case(self):
        import dembridge
        parameters = dembridge.check(os.path.join(ARGS.examples, "cantilever.prm"))
        self.assertEqual(parameters["Mode"], "dem")
        run = dembridge.run(parameters, output_dir=fresh("dict_case"))
        self.assertAlmostEqual(run.summary["tip_deflection"], 8.534242e-3, delta=5e-5)


def _summary(folder):
    import json
    with open(os.path.join(folder, "summary.json")) as f:
        return json.load(f)


if __name__ == "__main__":
    parser = argparse.ArgumentParser()
    parser.add_argument("--dembridge", required=True)
    parser.add_argument("--examples", required=True)
    parser.add_argument("--compare", required=True)
    parser.add_argument("--out", required=True)
    ARGS, rest = parser.parse_known_args()
    os.makedirs(ARGS.out, exist_ok=True)
    unittest.main(argv=[sys.argv[0]] + rest, verbosity=2)
