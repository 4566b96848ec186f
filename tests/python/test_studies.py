"""airr.sweep, airr.viewzone, airr.optimise and airr.tolerance against the commands' files."""
import csv
import io
import json

import numpy as np
import pytest

import airr
from conftest import cpu_seconds_while_idle, ctrl_c_latency


def test_sweep_equals_airr_sweep(tmp_path, cli, small_scene):
    vary = ["floating_distance=150:250:50", "tilt=0:10:10"]
    code, _, err = cli("sweep", small_scene.path, "--vary", vary[0], "--vary", vary[1], "--psf",
                       "--samples", 20000, "-o", tmp_path / "s.csv",
                       "--set", "observer.width=64", "--set", "observer.height=48")
    assert code == 0, err
    fractions = []
    s = airr.sweep(small_scene, vary=vary, psf=True, psf_samples=20000, progress=fractions.append)
    assert s["csv"] == (tmp_path / "s.csv").read_text()
    assert len(s["mean_mtf"]) == 6 and fractions[-1] == 1.0
    rows = list(csv.DictReader(io.StringIO(s["csv"])))
    assert np.allclose(s["mean_mtf"], [float(r["mean_mtf_0_1"]) for r in rows], rtol=1e-6)
    with pytest.raises(ValueError, match="tilt"):
        airr.sweep(small_scene, vary=["tilt=10:0:5"])


def test_sweep_keeps_points_that_are_no_layout(tmp_path, cli):
    kiosk = airr.Scene.load(airr.asset_dir() + "/scenes/two_sheet_kiosk.json")
    vary = ["floating_distance=240:300:30"]
    code, _, err = cli("sweep", kiosk.path, "--vary", vary[0], "--psf", "--samples", 5000, "-o", tmp_path / "k.csv")
    assert code == 0, err
    s = airr.sweep(kiosk, vary=vary, psf=True, psf_samples=5000)
    assert s["csv"] == (tmp_path / "k.csv").read_text()
    assert list(s["floating_distance_mm"]) == [240, 270, 300]
    assert s["reason"][0] == "" and s["mean_mtf"][0] > 0
    assert all("misses the half mirror" in r for r in s["reason"][1:]) and np.all(np.isnan(s["mean_mtf"][1:]))
    with pytest.raises(ValueError, match="no other point of the sweep is a layout"):
        airr.sweep(kiosk, vary=["floating_distance=270:300:30"])


def test_viewzone_equals_airr_viewzone(tmp_path, cli, small_scene):
    code, _, err = cli("viewzone", small_scene.path, "--grid", 5, "-o", tmp_path / "z.csv")
    assert code == 0, err
    rows = list(csv.DictReader(open(tmp_path / "z.csv")))
    z = airr.viewzone(small_scene, grid=5)
    visible = z["visible"]
    assert visible.shape == (5, 5)
    by_eye = {(float(r["x_mm"]), float(r["y_mm"])): float(r["visible_fraction"]) for r in rows}
    for j, y in enumerate(z["y_mm"]):
        for i, x in enumerate(z["x_mm"]):
            assert visible[j, i] == pytest.approx(by_eye[(x, y)], abs=1e-6)
    assert visible.max() > 0.5 and visible.min() < visible.max()


def write_spec(tmp_path, extra):
    spec = {"format": "airr-design", "version": 1, "scene": airr.default_scene_path(), **extra}
    path = tmp_path / "spec.json"
    path.write_text(json.dumps(spec))
    return path


def test_optimise_equals_airr_optimise(tmp_path, cli):
    spec = write_spec(tmp_path, {
        "variables": [{"key": "tilt_deg", "min": 0, "max": 40}],
        "objectives": [{"metric": "size_z_mm", "goal": "minimise"}],
        "search": {"global_evaluations": 20, "local_evaluations": 10}})
    code, _, err = cli("optimise", spec, "-o", tmp_path / "best_cli.json")
    assert code == 0, err
    r = airr.optimise(str(spec), output=str(tmp_path / "best.json"))
    assert (tmp_path / "best.json").read_text() == (tmp_path / "best_cli.json").read_text()
    trials = list(csv.DictReader(open(tmp_path / "best_cli_evaluations.csv")))
    assert len(trials) == len(r["score"])
    assert np.allclose(r["x"][:, 0], [float(t["tilt_deg"]) for t in trials])
    assert r["best_feasible"] and r["variables"] == ["tilt_deg"]


def test_tolerance_equals_airr_tolerance(tmp_path, cli):
    spec = write_spec(tmp_path, {
        "objectives": [{"metric": "r50_mm", "goal": "minimise"}],
        "search": {"psf_samples": 5000},
        "tolerances": [{"key": "retroreflectors.0.pose.pitch_deg", "sd": 0.5}, {"key": "floating_distance_mm", "sd": 5}],
        "tolerance": {"samples": 30, "seed": 3}})
    code, _, err = cli("tolerance", spec, "-o", tmp_path / "t.csv")
    assert code == 0, err
    rows = list(csv.DictReader(open(tmp_path / "t.csv")))
    t = airr.tolerance(str(spec))
    assert t["samples"] == 30 and t["tolerances"] == ["retroreflectors.0.pose.pitch_deg", "floating_distance_mm"]
    (name, m), = t["metrics"].items()
    column = next(k for k in rows[0] if k.startswith("r50_mm"))
    assert np.allclose(m["values"], [float(r[column]) for r in rows], rtol=1e-9)
    assert t["sensitivity"].shape == (2, 1)
    # Each layout's drawn values, in the CSV and the dict alike, spread about the nominal as asked.
    assert t["drawn"].shape == (30, 2)
    assert np.allclose(t["drawn"][:, 0], [float(r["retroreflectors.0.pose.pitch_deg"]) for r in rows], rtol=1e-9)
    nominal = airr.Scene.load(airr.default_scene_path()).get("floating_distance_mm")
    assert abs(t["drawn"][:, 1].mean() - nominal) < 3 and 2 < t["drawn"][:, 1].std() < 8  # sd 5
    assert len(t["worst"]) == 5 and all(0 <= i < 30 for i in t["worst"])


def test_a_study_stops_at_an_exception_in_its_progress(small_scene):
    class Enough(Exception):
        pass

    def stop(f):
        if f > 0:
            raise Enough()

    with pytest.raises(Enough):
        airr.viewzone(small_scene, grid=15, progress=stop)
    with pytest.raises(Enough):
        airr.sweep(small_scene, vary=["floating_distance=100:300:10"], psf_samples=20000, progress=stop)


def test_ctrl_c_stops_a_fit_and_nothing_runs_on():
    latency = ctrl_c_latency(0.5, lambda: airr.fit(airr.asset_dir() + "/fit_example", samples=200000))
    print(f"Ctrl+C to KeyboardInterrupt in a fit: {latency * 1000:.0f} ms")
    assert latency < 1.0
    assert cpu_seconds_while_idle() < 0.1
