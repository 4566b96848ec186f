"""airr.Scene and airr.render against `airr render` and `airr --set`."""
import math
import os
import threading

import numpy as np
import pytest

import airr
from conftest import cpu_seconds_while_idle, ctrl_c_latency

SMALL = ["--set", "observer.width=64", "--set", "observer.height=48"]


def test_a_render_equals_airr_render_pixel_for_pixel(tmp_path, cli, small_scene):
    code, _, err = cli("render", small_scene.path, "-o", tmp_path / "cli.exr", "--spp", 4, "--seed", 3, *SMALL)
    assert code == 0, err
    expected = airr.read_image(str(tmp_path / "cli.exr"))["pixels"]
    image = airr.render(small_scene, spp=4, seed=3)
    assert image.dtype == np.float32 and image.shape == (48, 64, 3)
    assert np.array_equal(image, expected)
    assert image.max() > 0  # the aerial image is there
    # Another seed is another image: the comparison can fail.
    assert not np.array_equal(airr.render(small_scene, spp=4, seed=4), expected)


def test_components_add_up_to_the_image(small_scene):
    image, parts = airr.render(small_scene, spp=2, seed=1, components=True)
    assert sorted(parts) == ["aerial", "direct", "luminaires", "reflection", "rest", "room", "sun"]
    total = sum(parts.values())
    assert np.allclose(total, image, rtol=1e-5, atol=1e-6)
    assert parts["aerial"].max() > 0


def test_path_expression_layers_partition_the_image(small_scene):
    image, parts = airr.render(small_scene, spp=2, seed=1,
                               layers={"aerial0": "D .* S0:retro .* E", "others": "D [^S0:retro]* E"})
    assert list(parts) == ["aerial0", "others", "unmatched"]
    assert np.allclose(parts["aerial0"] + parts["others"], image, rtol=1e-5, atol=1e-6)
    assert parts["aerial0"].max() > 0 and parts["unmatched"].max() == 0
    with pytest.raises(ValueError, match="at character 5"):
        airr.render(small_scene, spp=1, layers={"x": "D H:q E"})
    with pytest.raises(ValueError, match="aerial names another of the render's outputs"):
        airr.render(small_scene, spp=1, components=True, layers={"aerial": "D .* E"})


def test_a_display_luminance_puts_the_images_in_cd_per_m2(small_scene):
    assert small_scene.units == "relative"
    assert airr.psf(small_scene, samples=2000)["luminance_cd_m2"] is None
    small_scene.set("source.luminance_cd_m2", 500)
    assert small_scene.units == "cd/m2"
    p = airr.psf(small_scene, samples=2000)
    assert p["luminance_cd_m2"] == pytest.approx(500 * p["brightness"], rel=1e-12)
    with pytest.raises(ValueError, match="source.luminance_cd_m2"):
        small_scene.set("source.luminance_cd_m2", -1)


def test_the_room_is_its_own_component_in_cd_per_m2(small_scene):
    small_scene.set("source.luminance_cd_m2", 500)
    _, dark = airr.render(small_scene, spp=2, seed=1, components=True)
    small_scene.set("environment.room.illuminance_lux", 500)
    image, lit = airr.render(small_scene, spp=2, seed=1, components=True)
    assert np.allclose(sum(lit.values()), image, rtol=1e-5, atol=1e-4)
    assert dark["room"].max() == 0 and lit["room"].max() > 0
    # Passive parts: nothing shows the room brighter than its surround, 500 / pi cd/m2.
    assert lit["room"].max() <= 500 / math.pi * (1 + 1e-5)
    assert np.array_equal(lit["aerial"], dark["aerial"])
    zone = airr.viewzone(small_scene, grid=3, full=True, spp=2)
    assert zone["contrast"].shape == (3, 3) and sorted(zone["legible_share"]) == [1.5, 3.0, 25.0]
    assert np.all(zone["contrast"] >= 1) and zone["luminance"].max() > 0
    assert zone["char_height_arcmin"].shape == (3, 3) and np.nanmin(zone["char_height_arcmin"]) >= 16 - 1e-9
    with pytest.raises(ValueError, match="environment.room.illuminance_lux"):
        small_scene.set("environment.room.illuminance_lux", -1)
    with pytest.raises(ValueError, match="source.luminance_cd_m2"):
        small_scene.set("source.luminance_cd_m2", 0)


def test_the_sun_and_a_luminaire_are_components_and_the_psf_gives_the_smallest_character(small_scene):
    small_scene.set("source.luminance_cd_m2", 500)
    small_scene.set("environment.sun.illuminance_lux", 50000)
    small_scene.set("environment.sun.elevation_deg", 60)
    small_scene.set("environment.luminaires", [{"luminance_cd_m2": 2000, "pose": {"center_mm": [0, 800, 200], "pitch_deg": -90}}])
    image, parts = airr.render(small_scene, spp=2, seed=1, components=True)
    assert {"sun", "luminaires", "luminaire0"} <= set(parts)
    seven = ("aerial", "direct", "reflection", "rest", "room", "sun", "luminaires")
    assert np.allclose(sum(parts[k] for k in seven), image, rtol=1e-5, atol=1e-3)
    assert parts["luminaires"].max() > 0 and np.array_equal(parts["luminaire0"], parts["luminaires"])
    with pytest.raises(ValueError, match="below the horizon"):
        small_scene.set("environment.sun.elevation_deg", -10)
    p = airr.psf(small_scene, samples=20000)
    assert math.isfinite(p["char_height_mm"]) and p["char_height_arcmin"] >= 16 - 1e-9


BAD_SETS = [
    ("bogus.key", "1"),
    ("retroreflectors.0.pose.pitch_deg", "abc"),
    ("retroreflectors.0.pose.pitch_deg", float("nan")),
    ("retroreflectors.5.pose.pitch_deg", 1),
    ("floating_distance_mm", -5),
    ("observer.width", 0),
    ("observer.width", 10**12),
    ("observer.height", -(2**40)),
    ("tilt_deg", 100),
]


@pytest.mark.parametrize("key,value", BAD_SETS)
def test_a_bad_set_raises_the_clis_message(tmp_path, cli, key, value):
    scene = airr.Scene.load(airr.default_scene_path())
    text = "nan" if isinstance(value, float) and math.isnan(value) else str(value)
    code, _, err = cli("render", scene.path, "-o", tmp_path / "x.png", "--spp", 1, "--set", f"{key}={text}")
    assert code != 0
    message = [line for line in err.splitlines() if line.startswith("error: ")][0][len("error: "):]
    tilt = scene.get("tilt_deg")
    with pytest.raises(ValueError) as raised:
        scene.set(key, value)
    assert str(raised.value) == message
    assert scene.get("tilt_deg") == tilt and scene.overrides == []  # unchanged


def test_a_value_beyond_the_fields_type_is_reported_as_given():
    scene = airr.Scene.load(airr.default_scene_path())
    with pytest.raises(ValueError, match=r"observer.width: .*\(is 1000000000000\)"):
        scene.set("observer.width", 10**12)
    with pytest.raises(ValueError, match=r"\(is 1000000000000\)"):
        scene.set("observer.width", np.int64(10**12))


def test_set_get_and_save_round_trip(tmp_path):
    scene = airr.Scene.load(airr.default_scene_path())
    scene.set("tilt_deg", 20)
    scene.set("floating_distance_mm", 200.5)
    assert scene.get("retroreflectors.0.pose.pitch_deg") == 20
    assert scene.get("floating_distance_mm") == pytest.approx(200.5, abs=1e-9)
    scene.save(tmp_path / "mine.json")
    again = airr.Scene.load(tmp_path / "mine.json")
    assert again.to_json() == scene.to_json()
    assert again.get("floating_distance_mm") == pytest.approx(200.5, abs=1e-9)
    with pytest.raises(ValueError, match="nope.json"):
        airr.Scene.load(tmp_path / "nope.json")


def test_progress_rises_to_one_and_an_exception_in_it_stops_the_render(small_scene):
    fractions = []
    airr.render(small_scene, spp=16, seed=1, progress=fractions.append)
    assert fractions[-1] == 1.0 and len(fractions) >= 3
    assert all(a < b for a, b in zip(fractions, fractions[1:]))

    class Enough(Exception):
        pass

    calls = []

    def stop_at_the_third_call(f):
        calls.append(f)
        if len(calls) == 3:
            raise Enough(f)

    busy = airr.Scene.load(airr.default_scene_path())
    busy.set("observer.width", 256)
    busy.set("observer.height", 256)
    with pytest.raises(Enough):
        airr.render(busy, spp=100000, progress=stop_at_the_third_call)
    assert len(calls) == 3
    # Nothing of it runs on: the process's CPU time stays put.
    assert cpu_seconds_while_idle() < 0.1


def test_ctrl_c_stops_a_render_within_a_second():
    busy = airr.Scene.load(airr.default_scene_path())
    busy.set("observer.width", 256)
    busy.set("observer.height", 256)
    latency = ctrl_c_latency(1.0, lambda: airr.render(busy, spp=100000))
    print(f"Ctrl+C to KeyboardInterrupt: {latency * 1000:.0f} ms")
    assert latency < 1.0
    assert cpu_seconds_while_idle() < 0.1


def test_two_threads_render_what_one_after_the_other_renders(small_scene):
    other = airr.Scene.load(airr.default_scene_path())
    other.set("observer.width", 64)
    other.set("observer.height", 48)
    other.set("tilt_deg", 25)
    alone = [airr.render(small_scene, spp=8, seed=2), airr.render(other, spp=8, seed=2)]
    assert not np.array_equal(alone[0], alone[1])
    together = [None, None]

    def run(i, scene):
        together[i] = airr.render(scene, spp=8, seed=2)

    threads = [threading.Thread(target=run, args=(0, small_scene)), threading.Thread(target=run, args=(1, other))]
    for t in threads:
        t.start()
    # The renders leave the GIL free: this thread counts on meanwhile.
    counted = 0
    while any(t.is_alive() for t in threads):
        counted += 1
    for t in threads:
        t.join()
    assert np.array_equal(together[0], alone[0]) and np.array_equal(together[1], alone[1])
    assert counted > 1000


# Every kind of Python value Scene.set may be given, at keys of each type: a sound value sets, any
# other raises ValueError naming the key, and leaves the scene as it was.
PYTHON_VALUES = [
    640, 10**12, 10**400, -(2**63), 2**64, 200.5, 1e308, -0.0, float("nan"), float("inf"), True, None,
    "12.5", "abc", "", [0, 1, 2], (0, 1, 2), [[0], [1]], [float("nan"), 1, 2], {"a": 1},
    np.int8(5), np.uint64(2**64 - 1), np.int64(-5), np.float32(1.5), np.float64(1e-300), np.bool_(True),
    np.array(3.0), np.array([1.0, 2.0, 3.0]), np.zeros((2, 2)), b"bytes", 1 + 2j, object(),
]
SET_KEYS = ["observer.width", "floating_distance_mm", "retroreflectors.0.pose.center_mm", "display.image"]


@pytest.mark.parametrize("key", SET_KEYS)
def test_every_python_value_sets_or_raises_value_error(key):
    scene = airr.Scene.load(airr.default_scene_path())
    for value in PYTHON_VALUES:
        before = scene.to_json()
        try:
            scene.set(key, value)
        except ValueError as e:
            assert key in str(e) or "(with --set)" in str(e), (key, value, str(e))
            assert "\n" not in str(e)
            assert scene.to_json() == before, (key, value)


def test_polarization_fields_set_get_and_render(tmp_path):
    """The p-AIRR scene's parts through the module: the plate half mirror, the sheet's film and the
    observer's analyzer are keys like any other, and crossing the analyzer with the LCD's light
    through the plain mirror darkens the image as Malus's law says."""
    scene = airr.Scene.load(os.path.join(airr.asset_dir(), "scenes", "p_airr.json"))
    scene.set("observer.width", 48)
    scene.set("observer.height", 48)
    assert scene.get("half_mirror.kind") == "reflective_polarizer"
    assert scene.get("retroreflectors.0.films.0.retardance_waves") == pytest.approx(0.25)
    scene.set("half_mirror.kind", "plate")
    scene.set("half_mirror.plate.thickness_mm", 2.0)
    assert scene.get("half_mirror.plate.thickness_mm") == 2.0
    scene.save(tmp_path / "plate.json")
    assert airr.Scene.load(tmp_path / "plate.json").to_json() == scene.to_json()
    with pytest.raises(ValueError, match="thickness_mm"):
        scene.set("half_mirror.plate.thickness_mm", float("nan"))

    scene.set("half_mirror.kind", "half_mirror")
    scene.set("retroreflectors.0.films", [])
    brightness = {}
    for angle in (0, 90):
        scene.set("observer.analyzer_deg", angle)
        brightness[angle] = float(np.mean(airr.render(scene, spp=4, seed=3)))
    assert brightness[0] > 0
    assert min(brightness.values()) < 0.05 * max(brightness.values())
