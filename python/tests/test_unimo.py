"""Tests of the Python package: compile, simulate, errors, sweeps on local threads and
on a Dask LocalCluster of two worker processes."""

from pathlib import Path

import numpy as np
import pytest

import unimo

ROOT = Path(__file__).resolve().parents[2]
BALL = ROOT / "models" / "BouncingBall.mo"


def first_rebound(result):
    """The highest point between the first and the second bounce."""
    return float(np.max(result["h"][result["bounces"] == 1]))


@pytest.fixture(scope="module")
def ball():
    return unimo.compile(BALL)


def test_simulate_returns_numpy_columns_units_and_stats(ball):
    r = ball.simulate(stop_time=1.0)
    assert isinstance(r.time, np.ndarray) and r.time[-1] == pytest.approx(1.0)
    assert r.names == ball.names and "h" in r.names
    assert r["h"][-1] == pytest.approx(10 - 9.81 / 2, abs=1e-6)
    assert r.stats["steps"] > 0 and r.stats["events"] == 0
    frame = r.to_pandas()
    assert list(frame.columns) == ["time"] + r.names
    assert len(frame) == len(r)


def test_outputs_select_columns(ball):
    r = ball.simulate(stop_time=1.0, outputs=["h"])
    assert r.names == ["h"]


def test_units_come_from_the_model():
    r = unimo.simulate(ROOT / "models" / "FlySlideRoll.mo", stop_time=0.5)
    assert r.units, "FlySlideRoll declares units"
    assert all(isinstance(u, str) and u for u in r.units.values())


def test_params_recompile_and_the_first_rebound_is_e2_h0(ball):
    for e in (0.5, 0.8):
        r = ball.simulate(stop_time=3.5, params={"e": e}, points=3500)
        assert first_rebound(r) == pytest.approx(e * e * 10, abs=1e-3)
    model = unimo.compile(BALL, params={"h0": 2.0})
    assert model.simulate(stop_time=0.1)["h"][0] == pytest.approx(2.0)


def test_model_errors_carry_code_message_and_location(tmp_path):
    bad = tmp_path / "Bad.mo"
    bad.write_text("model Bad\n  Real x;\nequation\n  der(x) = y;\nend Bad;\n")
    with pytest.raises(unimo.ModelError) as info:
        unimo.compile(bad)
    e = info.value
    assert e.code.startswith("E2")
    assert "y" in e.message
    assert e.location == f"{bad}:4:12"


def test_unknown_parameter_is_a_usage_error(ball):
    with pytest.raises(unimo.UsageError) as info:
        ball.simulate(params={"ee": 0.5})
    assert info.value.code == "E0003"
    assert "did you mean" in info.value.rendered


def test_a_failed_run_raises_and_keeps_its_rows():
    # A deterministic failure: the model's assertion fails once time passes 3.5.
    model = unimo.compile(Path(__file__).resolve().parent / "AssertAfterThree.mo")
    with pytest.raises(unimo.SimulationError) as info:
        model.simulate()
    e = info.value
    assert e.code == "E4004"
    assert e.result is not None and e.result.time[-1] > 3.0


def sweep_checks(table):
    ok = table[table.status == "ok"]
    failed = table[table.status == "failed"]
    assert len(ok) == 4 and len(failed) == 1
    for _, row in ok.iterrows():
        assert row["rebound"] == pytest.approx(row["e"] ** 2 * 10, abs=1e-3)
    assert failed.iloc[0]["error_code"] == "E0004"
    assert "finite number" in failed.iloc[0]["error_message"]


SAMPLES = [{"e": e} for e in (0.5, 0.6, 0.7, 0.8)] + [{"e": "oops"}]


def summary(result):
    return {"rebound": first_rebound(result)}


def test_sweep_on_local_threads(ball):
    table = ball.sweep(SAMPLES, jobs=2, summary=summary, stop_time=3.5, points=3500)
    assert list(table["e"][:4]) == [0.5, 0.6, 0.7, 0.8]
    sweep_checks(table)


def test_sweep_grid_final_values(ball):
    table = ball.sweep({"e": [0.5, 0.9], "h0": [10, 20]}, outputs=["h"], stop_time=1.0)
    assert len(table) == 4 and (table.status == "ok").all()
    assert list(table.h0) == [10, 20, 10, 20]
    assert np.allclose(table["h"], table["h0"] - 9.81 / 2, atol=1e-6)


def test_sweep_on_a_dask_local_cluster(ball):
    distributed = pytest.importorskip("dask.distributed")
    with distributed.LocalCluster(
        n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None
    ) as cluster, distributed.Client(cluster) as client:
        table = ball.sweep(
            SAMPLES, client=client, summary=summary, stop_time=3.5, points=3500
        )
    sweep_checks(table)
    assert list(table["e"]) == [s["e"] for s in SAMPLES]
