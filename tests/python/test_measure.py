"""airr.psf against `airr psf`, and airr.mtf against the analytic MTF of a Gaussian-blurred edge."""
import math

import numpy as np
import pytest

import airr


def test_psf_equals_airr_psf(tmp_path, cli, small_scene):
    code, out, err = cli("psf", small_scene.path, "-o", tmp_path / "psf.csv", "--samples", 20000,
                         "--set", "observer.width=64", "--set", "observer.height=48")
    assert code == 0, err
    table = np.loadtxt(tmp_path / "psf.csv", delimiter=",", skiprows=1)
    p = airr.psf(small_scene, samples=20000)
    assert np.allclose(p["lp_per_mm"], table[:, 0], rtol=1e-9, atol=1e-12)
    assert np.allclose(p["mtf"], table[:, 1], rtol=1e-8, atol=1e-9)
    r50 = float(out.split("50%-energy radius: ")[1].split()[0])
    assert p["r50_mm"] == pytest.approx(r50, abs=5e-5)
    brightness = float(out.split("brightness: ")[1].split()[0])
    assert p["brightness"] == pytest.approx(brightness, rel=1e-5)
    # The 2D PSF: density per mm^2 holding (99.8% of) the brightness, peaked at the ideal point.
    image, mm = p["image"], p["image_mm_per_pixel"]
    assert image.shape == (129, 129)
    held = image.sum() * mm * mm
    assert 0.99 * p["brightness"] <= held <= p["brightness"] * (1 + 1e-9)
    peak = np.unravel_index(np.argmax(image), image.shape)
    assert abs(peak[0] - 64) <= 2 and abs(peak[1] - 64) <= 2


def blurred_edge(size, angle_deg, sigma):
    """A step edge through the centre, tilted by angle_deg from vertical, blurred by a Gaussian of
    sigma pixels: exactly 0.5 (1 + erf(d / (sigma sqrt 2))), d the distance from the edge."""
    a = math.radians(angle_deg)
    y, x = np.mgrid[0:size, 0:size].astype(float)
    d = (x - size / 2) * math.cos(a) - (y - size / 2) * math.sin(a)
    erf = np.vectorize(math.erf)
    return 0.1 + 0.8 * 0.5 * (1 + erf(d / (sigma * math.sqrt(2))))


def test_mtf_of_a_blurred_edge_is_the_gaussians():
    sigma = 1.5
    edge = blurred_edge(96, 5.0, sigma)
    m = airr.mtf(edge, mm_per_pixel=0.1)
    f = m["cycles_per_pixel"]
    expected = np.exp(-2 * math.pi**2 * sigma**2 * f**2)
    low = f <= 0.3
    assert np.max(np.abs(m["mtf"][low] - expected[low])) < 0.02
    assert m["edge"] == "vertical" and m["edge_angle_deg"] == pytest.approx(5.0, abs=0.3)
    assert m["lp_per_mm"] == pytest.approx(f / 0.1)
    # MTF50 of the Gaussian: f = sqrt(ln 2 / 2) / (pi sigma).
    assert m["mtf50_cycles_per_pixel"] == pytest.approx(math.sqrt(math.log(2) / 2) / (math.pi * sigma), rel=0.03)
    # The same edge as an RGB array and as a file give the same curve.
    rgb = np.repeat(edge[:, :, None], 3, axis=2)
    assert np.allclose(airr.mtf(rgb)["mtf"], m["mtf"], atol=1e-12)


def test_mtf_of_a_file_reads_its_pixel_size(tmp_path, cli, small_scene):
    code, _, err = cli("render", small_scene.path, "-o", tmp_path / "r.exr", "--spp", 2,
                       "--set", "observer.width=64", "--set", "observer.height=48")
    assert code == 0, err
    read = airr.read_image(str(tmp_path / "r.exr"))
    assert read["mm_per_pixel"] > 0 and read["pixels"].shape == (48, 64, 3)


def test_bad_images_are_value_errors(tmp_path):
    with pytest.raises(ValueError, match="missing.exr"):
        airr.mtf(str(tmp_path / "missing.exr"))
    with pytest.raises(ValueError, match="height x width"):
        airr.mtf(np.zeros((4, 4, 2)))
    with pytest.raises(ValueError):
        airr.mtf(np.full((64, 64), 0.5))  # flat: no edge


def test_an_image_that_cannot_be_written_says_why(tmp_path):
    pixels = np.zeros((4, 4, 3), dtype=np.float32)
    with pytest.raises(ValueError, match="Not a directory"):
        airr.write_image("/dev/full/x.png", pixels)
    with pytest.raises(ValueError, match="No such file or directory"):
        airr.write_image(str(tmp_path / "no" / "x.exr"), pixels)
