"""The hand-written stubs match the compiled core (mypy's stubtest), and the package
type-checks against them (mypy), so that the stubs cannot drift from the code."""

from __future__ import annotations

import json
import pathlib
import re
import subprocess
import sys
from typing import List

import pytest

from conftest import ROOT, TARGET

pytest.importorskip("mypy", reason="the typing tests need mypy (a test extra)")


def run(*args: str, cwd: object = None) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", *args], capture_output=True, text=True,
                          cwd=cwd)


def test_stubs_match_the_compiled_core():
    done = run("mypy.stubtest", "stickslip._core")
    assert done.returncode == 0, done.stdout + done.stderr


def test_the_package_type_checks():
    # xarray and distributed are optional; their own types are not checked here.
    done = run("mypy", "-p", "stickslip", "--ignore-missing-imports",
               "--cache-dir", str(TARGET / "mypy-cache"))
    assert done.returncode == 0, done.stdout + done.stderr


# Code that uses every kind of result and attribute as a researcher would, type-checked with
# --strict against the package's annotations and stubs (a misspelt or missing attribute, or an
# untyped to_xarray, fails here).
USES_EVERY_ATTRIBUTE = '''
from typing import Any, Dict, List, Optional, Tuple

import numpy as np
import numpy.typing as npt
import xarray

import stickslip
import stickslip.dask

exp = stickslip.Experiment.paper(w=0.7, beta=1.2)
run = stickslip.simulate(exp, periods=3)
columns: List[npt.NDArray[Any]] = [run.tau, run.y, run.v, run.drive, run.phase, run.t_s,
                                   run.uc_V, run.i_A, run.u_V, run.r_m, run.rdot_m_s, run.F_N]
trajectory: xarray.Dataset = run.to_xarray()
frame = run.to_pandas()
events: npt.NDArray[Any] = run.events
s = stickslip.steady(exp)
motion: str = s.motion_class
stops: float = s.stops_per_period
period: Optional[int] = s.period
m = stickslip.phase_diagram(exp, w=[0.7], beta=[1.2])
stops_map: npt.NDArray[Any] = m.stops_per_period
dataset: xarray.Dataset = m.to_xarray()
sweep_set: xarray.Dataset = stickslip.sweep(exp, "w", [0.7]).to_xarray()
scales: Optional[Dict[str, Any]] = exp.scales()
b = stickslip.continuation(exp, "beta", 1.2, 1.3)
branch: List[npt.NDArray[Any]] = [b.value, b.y, b.v, b.amplitude, b.period, b.stops_per_period,
                                  b.turns, b.mu1_re, b.mu1_im, b.mu2_re, b.mu2_im, b.stable,
                                  b.arclength]
start: Tuple[float, float, int, int] = b.start
basin_set: xarray.Dataset = stickslip.basins(exp, (-1, 1), (-1, 1), 2).to_xarray()
bif_set: xarray.Dataset = stickslip.bifurcation(exp, "w", [0.7]).to_xarray()
dask_map: stickslip.PhaseDiagram = stickslip.dask.phase_diagram(exp, w=[0.7], beta=[1.2])
rec: stickslip.ScopeRecord = stickslip.read_scope("run.csv", drive="CH1", response="CH2")
rec_columns: List[npt.NDArray[Any]] = [rec.t_s, rec.drive, rec.response, *rec.channels.values()]
rec_meta: Tuple[str, float, float, float, int, Optional[float], int, str] = (
    rec.format, rec.freq_Hz, rec.amplitude_V, rec.sample_interval_s, rec.periods,
    rec.resolution_V["CH1"], rec.clipped["CH1"], rec.units["CH1"])
table: stickslip.AmplitudeTable = stickslip.read_amplitudes("gain.csv")
table_columns: List[npt.NDArray[Any]] = [table.freq_Hz, table.U_V, table.response_V,
                                         table.A1_V, table.A3_V, table.line]
fitted: stickslip.FitResult = stickslip.fit(exp, data=[rec], free=("resistance", "ut"))
values: Dict[str, float] = fitted.parameters
errors: Dict[str, float] = fitted.stderr
ci: Tuple[float, float] = fitted.ci95["resistance"]
matrices: List[npt.NDArray[Any]] = [fitted.covariance, fitted.correlation]
residuals: List[npt.NDArray[Any]] = [r.residual_V for r in fitted.records]
fitted_exp: stickslip.Experiment = fitted.exp
fit_dict: Dict[str, Any] = fitted.to_dict()
fit_set: xarray.Dataset = fitted.to_xarray()
chi2: Optional[float] = fitted.chi2_dof
drift: List[stickslip.FitResult] = stickslip.fit(exp, data=[rec, "b.csv"], per_record=True)
from_table: stickslip.FitResult = stickslip.fit(exp, data=[table], model="pwl")
'''

# A plain script on a map of exponents: with lyapunov=True its arrays are arrays, not
# Optional (the overloads of phase_diagram); without, they are None.
EXPONENT_MAP = '''
import numpy as np
import numpy.typing as npt

import stickslip
import stickslip.dask

exp = stickslip.Experiment(zeta=0, mu_s=3)
m = stickslip.phase_diagram(exp, lyapunov=True, w=np.linspace(0.2, 0.6, 3), beta=[9.0])
largest: float = float(np.nanmax(m.lambda1))
first = m.lambda1[0, 0] - m.lambda1_error[0, 0]
errors: npt.NDArray[np.float64] = m.lambda_error
chaotic = m.lambda1[m.class_code == 4]
mean: float = float(m.lambda1.mean()) + float(np.sum(m.lambda1_error > 0))
d = stickslip.dask.phase_diagram(exp, lyapunov=True, w=[0.33], beta=[9.0])
on_dask: float = float(d.lambda1.max())
plain = stickslip.phase_diagram(exp, w=[0.33], beta=[9.0])
nothing: None = plain.lambda1
flag = bool(len(m.dims))
either = stickslip.phase_diagram(exp, lyapunov=flag, w=[0.33], beta=[9.0])
if either.lambda1 is not None:
    maybe: float = float(either.lambda1.max())
back = stickslip.PhaseDiagram.from_xarray(m.to_xarray())
bar = stickslip.phase_diagram(exp, progress=True, w=[0.33], beta=[9.0])
'''


def test_a_map_of_exponents_type_checks_strictly(tmp_path):
    """mypy --strict finds nothing in a plain script that reads a map's exponents (before the
    overloads it found 8 errors: the arrays were typed Optional with lyapunov=True too)."""
    (tmp_path / "exponents.py").write_text(EXPONENT_MAP)
    done = run("mypy", "--strict", "--cache-dir", str(TARGET / "mypy-cache"),
               "--no-error-summary", "--show-error-codes", "exponents.py", cwd=tmp_path)
    assert done.returncode == 0 and not done.stdout.strip(), done.stdout + done.stderr


def code_blocks(markdown: pathlib.Path) -> List[str]:
    """The ```python blocks of a Markdown file."""
    return re.findall(r"```python\n(.*?)```", markdown.read_text(), flags=re.S)


def notebook_code(path: pathlib.Path) -> str:
    """The code cells of a notebook as one module (IPython's % and ! lines left out)."""
    cells = json.loads(path.read_text())["cells"]
    code = ["".join(c["source"]) for c in cells if c["cell_type"] == "code"]
    lines = [line for cell in code for line in cell.splitlines() + [""]
             if not line.lstrip().startswith(("%", "!"))]
    return "\n".join(lines) + "\n"


def test_examples_docs_and_notebook_type_check_strictly(tmp_path):
    """mypy --strict over examples/python/*.py, the Python examples of the README and
    docs/python.md, the notebook's code cells and code that uses every attribute."""
    files = {}
    for path in sorted((ROOT / "examples" / "python").glob("*.py")):
        files[f"example_{path.stem}.py"] = path.read_text()
    for doc in (ROOT / "README.md", ROOT / "docs" / "python.md"):
        for k, block in enumerate(code_blocks(doc)):
            files[f"{doc.stem.lower()}_{k}.py"] = block
    assert any(name.startswith("readme_") for name in files), "the README lost its example"
    files["notebook.py"] = notebook_code(ROOT / "examples" / "python" / "paper.ipynb")
    files["attributes.py"] = USES_EVERY_ATTRIBUTE
    for name, text in files.items():
        (tmp_path / name).write_text(text)
    # distributed has no type information of its own (and the package adds no stub
    # packages): calls into it are not checked; dask-jobqueue (the Slurm example) is not a
    # test extra. Everything else is checked.
    (tmp_path / "mypy.ini").write_text("[mypy]\nstrict = True\n"
                                       "untyped_calls_exclude = distributed\n"
                                       "[mypy-dask_jobqueue.*]\nignore_missing_imports = True\n")
    done = run("mypy", "--config-file", "mypy.ini",
               "--cache-dir", str(TARGET / "mypy-cache"), "--no-error-summary",
               "--hide-error-context", "--show-error-codes", *sorted(files), cwd=tmp_path)
    errors = []
    for error in (line for line in done.stdout.splitlines() if ": error: " in line):
        name, line, _ = error.split(":", 2)
        errors.append(f"{error}\n    {files[name].splitlines()[int(line) - 1].strip()}")
    assert not errors, "\n".join(errors) + "\n" + done.stderr
    assert done.returncode == 0 and not done.stderr, done.stdout + done.stderr
