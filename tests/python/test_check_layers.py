"""scripts/check_layers.py on small trees: an include up the layers, a function declared in
cli/ but defined in commands/ (a call up the layers that no include shows), a call from cli/
of a function only commands/ declares, and the clean layout (main.cpp hands the table down)."""
import os
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
SCRIPT = os.path.join(ROOT, "scripts", "check_layers.py")


def tree(tmp_path, files):
    for rel, text in files.items():
        p = tmp_path / rel
        p.parent.mkdir(parents=True, exist_ok=True)
        p.write_text(text)
    return subprocess.run([sys.executable, SCRIPT, str(tmp_path)], capture_output=True, text=True)


CLEAN = {
    "experiments/cli/commands.hpp": "#pragma once\nstruct Subcommand {};\nusing CommandFactory = Subcommand (*)();\n",
    "experiments/cli/cli.hpp": '#pragma once\n#include "experiments/cli/commands.hpp"\n'
                               "int run_cli(const CommandFactory* table, int n);\n",
    "experiments/cli/cli.cpp": '#include "experiments/cli/cli.hpp"\n'
                               "int run_cli(const CommandFactory* table, int n) {\n  return n ? (table[0](), 0) : 1;\n}\n",
    "experiments/commands/all_commands.hpp": '#pragma once\n#include "experiments/cli/commands.hpp"\n'
                                             "Subcommand add_sweep_subcommand();\n",
    "experiments/commands/sweep_command.cpp": '#include "experiments/commands/all_commands.hpp"\n'
                                              "namespace {\nint join(int a) {\n  return a;\n}\n}  // namespace\n"
                                              "Subcommand add_sweep_subcommand() {\n  return {};\n}\n",
    "experiments/io/text.hpp": "#pragma once\nint join(int a);\n",
    "experiments/main.cpp": '#include "experiments/cli/cli.hpp"\n#include "experiments/commands/all_commands.hpp"\n'
                            "int main() {\n  CommandFactory t[] = {add_sweep_subcommand};\n  return run_cli(t, 1);\n}\n",
}


def test_clean_layout(tmp_path):
    r = tree(tmp_path, CLEAN)
    assert r.returncode == 0, r.stdout
    assert "layering clean" in r.stdout


def test_declared_below_defined_above(tmp_path):
    files = dict(CLEAN)
    files["experiments/cli/commands.hpp"] += "Subcommand add_sweep_subcommand();\n"
    files["experiments/commands/all_commands.hpp"] = '#pragma once\n#include "experiments/cli/commands.hpp"\n'
    r = tree(tmp_path, files)
    assert r.returncode == 1
    assert "add_sweep_subcommand() is declared in experiments/cli/commands.hpp (cli/) but defined in the higher " \
           "layer commands/" in r.stdout


def test_call_up_without_include(tmp_path):
    files = dict(CLEAN)
    files["experiments/cli/cli.cpp"] += "void f() {\n  add_sweep_subcommand();\n}\n"
    r = tree(tmp_path, files)
    assert r.returncode == 1
    assert "cli/ calls add_sweep_subcommand()" in r.stdout


def test_include_up(tmp_path):
    files = dict(CLEAN)
    files["experiments/cli/cli.cpp"] = '#include "experiments/commands/all_commands.hpp"\n' + files["experiments/cli/cli.cpp"]
    r = tree(tmp_path, files)
    assert r.returncode == 1
    assert "of the higher layer commands/" in r.stdout


def test_integrator_roles(tmp_path):
    files = dict(CLEAN)
    files["integrators/core/stepper_loop.hpp"] = '#pragma once\n#include "integrators/system/model.hpp"\n'
    files["integrators/system/model.hpp"] = "#pragma once\n"
    assert tree(tmp_path, files).returncode == 0
    files["integrators/core/stepper_loop.hpp"] += '#include "integrators/schemes/rkmk.hpp"\n'
    files["integrators/schemes/rkmk.hpp"] = "#pragma once\n"
    files["integrators/flat.hpp"] = "#pragma once\n"
    r = tree(tmp_path, files)
    assert r.returncode == 1
    assert 'integrators/core/stepper_loop.hpp:3: integrators/core/ includes "integrators/schemes/..." of the ' \
           "higher role schemes/" in r.stdout
    assert "integrators/flat.hpp:1: in no role folder of integrators/" in r.stdout
