"""progress=: a tqdm bar (progress=True), a tqdm bar's update (the units since its last call),
or a callable progress(done, total); and the constructors' and continuation's words."""

from __future__ import annotations

import inspect
import io
import subprocess
import sys

import numpy as np
import pytest

import stickslip
from stickslip import Experiment

tqdm = pytest.importorskip("tqdm", reason="the progress tests need tqdm (a test extra)")

W = np.linspace(0.1, 2.5, 30)
BETA = np.linspace(0.5, 4.0, 20)


def test_a_tqdm_bars_update_fits_progress():
    plain = stickslip.phase_diagram(Experiment.paper(), w=W, beta=BETA)
    with tqdm.tqdm(total=600, file=io.StringIO()) as bar:
        m = stickslip.phase_diagram(Experiment.paper(), progress=bar.update, w=W, beta=BETA)
        # Given the points done since its last call: the bar ends at the map's size.
        assert bar.n == 600
    assert m.class_code.tobytes() == plain.class_code.tobytes()
    # A bar made without a total gets the call's.
    with tqdm.tqdm(file=io.StringIO()) as bar:
        stickslip.sweep(Experiment.paper(beta=3.61), "w", np.linspace(0.5, 1.5, 11),
                        progress=bar.update)
        assert (bar.n, bar.total) == (22, 22)


def test_a_callable_of_two_arguments_gets_done_and_total():
    calls = []
    stickslip.simulate(Experiment.paper(w=0.7, beta=1.2), periods=2000,
                       progress=lambda done, total: calls.append((done, total)))
    done, total = calls[-1]
    assert done == total >= 2000, calls
    assert all(t == total for _, t in calls)
    assert [d for d, _ in calls] == sorted(d for d, _ in calls)


def test_progress_true_draws_a_bar_and_closes_it(capfd):
    m = stickslip.phase_diagram(Experiment.paper(), progress=True, w=W, beta=BETA)
    err = capfd.readouterr().err
    assert "phase_diagram" in err and "600/600" in err, err
    assert m.shape == (30, 20)
    stickslip.lyapunov(Experiment(zeta=0, mu_s=3, w=0.33, beta=9), transient=100, periods=400,
                       progress=True)
    assert "lyapunov" in capfd.readouterr().err


def test_an_exception_of_the_callable_stops_the_computation():
    def stop(done, total):
        raise RuntimeError(f"stopped at {done} of {total}")

    with pytest.raises(RuntimeError, match="stopped at"):
        stickslip.phase_diagram(Experiment.paper(), progress=stop, w=np.linspace(0.1, 2.5, 200),
                                beta=np.linspace(0.5, 4, 200))


def test_bad_progress_is_named():
    for bad in (1, "yes", object()):
        with pytest.raises(TypeError, match="progress must be True"):
            stickslip.simulate(Experiment.paper(w=0.7, beta=1.2), periods=2, progress=bad)
    with pytest.raises(TypeError, match="takes no positional argument"):
        stickslip.simulate(Experiment.paper(w=0.7, beta=1.2), periods=2, progress=lambda: None)


def test_progress_true_without_tqdm_names_the_extra(tmp_path):
    script = ("import sys; sys.modules['tqdm'] = None\n"
              "import stickslip\n"
              "try:\n"
              "    stickslip.simulate(stickslip.Experiment.paper(w=0.7, beta=1.2), periods=2000,"
              " progress=True)\n"
              "except ModuleNotFoundError as e:\n"
              "    print(e)\n")
    done = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True,
                          cwd=tmp_path)
    assert "simulate(progress=True) needs tqdm, which is not installed: pip install " \
           "'stickslip[progress]'" in done.stdout, done.stdout + done.stderr


def test_help_shows_the_experiments_keywords():
    signature = inspect.signature(Experiment)
    assert list(signature.parameters) == ["zeta", "w", "beta", "phi", "mu_s", "y0", "v0", "vb"]
    assert "*args" not in str(signature)


def test_a_physical_keyword_of_the_dimensionless_constructor_says_where_it_goes():
    with pytest.raises(TypeError) as e:
        Experiment(omega=1)
    message = str(e.value)
    assert message.startswith("Experiment() takes the dimensionless model's keywords zeta, w, "
                              "beta, phi, mu_s, y0, v0, vb; omega (drive angular frequency"), message
    assert "Experiment.mechanics(...)" in message and "Experiment.paper(...)" in message
    with pytest.raises(TypeError, match="unknown experiment keyword 'gama'.*gamma"):
        Experiment(gama=1)
    assert Experiment(zeta=0.1, w=0.7, beta=1.2).w == 0.7


def test_continuation_from_rest_says_what_to_do(cli):
    exp = Experiment(zeta=0.05, w=0.5, beta=0.5)
    with pytest.raises(ValueError) as e:
        stickslip.continuation(exp, "beta", 0.5, 0.6)
    assert str(e.value) == ("from y0 = 0, v0 = 0 the motion comes to rest at beta = 0.5: "
                            "nothing to continue; start from a moving state "
                            "(experiment.replace(y0=..., v0=...)) or at another start")
    tool = cli.error("continue", "--zeta", "0.05", "--w", "0.5", "--over", "beta", "--from",
                     "0.5", "--to", "0.6")
    assert tool.startswith("from y0 = 0, v0 = 0 the motion comes to rest at beta = 0.5: "
                           "nothing to continue; start from a moving state"), tool
