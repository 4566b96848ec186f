"""The ray file: airr.record_rays and `airr render --rays` write the same bytes, airr.read_rays reads
them back, and the paths a layer's expression selects add up to that layer's image."""
import numpy as np
import pytest

import airr

# Every path but the first sheet's aerial image: the second sheet's, the housing's, the display
# seen. Its layer carries no control variate (that goes to the paths of both sheets' aerial
# images, which no layer selects alone), so the render's layer is the plain mean of the same paths.
OTHERS = "D [^S0:retro]* E"


@pytest.fixture
def kiosk():
    """The shipped two-sheet kiosk at 64 x 48 pixels."""
    scene = airr.Scene.load(airr.asset_dir() + "/scenes/two_sheet_kiosk.json")
    scene.set("observer.width", 64)
    scene.set("observer.height", 48)
    return scene


def test_the_ray_file_round_trips_and_adds_up_to_its_layer(tmp_path, cli, kiosk):
    out = tmp_path / "py.rays"
    summary = airr.record_rays(kiosk, out, spp=2, seed=3, select=OTHERS)
    rays = airr.read_rays(out)
    paths, segments = rays["paths"], rays["segments"]
    assert rays["complete"] and summary["complete"]
    assert len(paths) == summary["paths"] == rays["selected"] == summary["selected"] > 0
    assert len(segments) == summary["segments"]
    assert (rays["width"], rays["height"], rays["spp"], rays["expression"]) == (64, 48, 2, OTHERS)

    _, parts = airr.render(kiosk, spp=2, seed=3, layers={"others": OTHERS})
    image = np.zeros((48, 64, 3))
    np.add.at(image, (paths["y"], paths["x"]), paths["contribution"])
    assert parts["others"].max() > 0
    assert np.allclose(image / 2, parts["others"], rtol=1e-5, atol=1e-7)

    # A path leaves the display (event 0) and its last segment carries what it brings the eye.
    assert np.all(segments["kind"][paths["first_segment"]] == 0)
    last = paths["first_segment"] + paths["segment_count"] - 1
    assert np.array_equal(segments["radiance"][last], paths["contribution"])
    assert np.allclose(np.linalg.norm(segments["direction"], axis=1), 1, atol=1e-5)

    # The command writes the same file for the same scene and seed.
    scene_file = tmp_path / "scene.json"
    kiosk.save(scene_file)
    code, _, err = cli("render", scene_file, "-o", tmp_path / "a.exr", "--spp", 2, "--seed", 3, "--rays",
                       tmp_path / "cli.rays", "--rays-select", OTHERS)
    assert code == 0, err
    assert (tmp_path / "cli.rays").read_bytes() == out.read_bytes()


def test_bad_arguments_and_torn_files_raise_value_error(tmp_path, small_scene):
    with pytest.raises(ValueError, match="at character 5"):
        airr.record_rays(small_scene, tmp_path / "x.rays", select="D H:q E")
    with pytest.raises(ValueError, match="Not a directory"):
        airr.record_rays(small_scene, "/dev/full/x.rays")
    with pytest.raises(ValueError, match="the ray limit must be in"):
        airr.record_rays(small_scene, tmp_path / "x.rays", limit=0)
    assert not (tmp_path / "x.rays").exists()

    whole = tmp_path / "whole.rays"
    airr.record_rays(small_scene, whole, spp=1, limit=40)
    assert not airr.read_rays(whole)["complete"]
    torn = tmp_path / "torn.rays"
    torn.write_bytes(whole.read_bytes()[:-5])
    with pytest.raises(ValueError, match="torn.rays: .* bytes where the header announces"):
        airr.read_rays(torn)
    (tmp_path / "other.rays").write_bytes(b"not a ray file at all, but long enough to hold a header" * 2)
    with pytest.raises(ValueError, match="not a ray file"):
        airr.read_rays(tmp_path / "other.rays")
