"""AIRR Studio from Python: load a scene, change it, render it, measure it.

The same libraries as the `airr` command and the designer, with numpy arrays in and out:

    import airr
    scene = airr.Scene.load(airr.default_scene_path())
    scene.set("retroreflectors.0.pose.pitch_deg", 20)
    image = airr.render(scene, spp=64, seed=1)        # float32, height x width x 3, linear
    blur = airr.psf(scene)                             # MTF curve, r50, brightness, 2D PSF
    edge = airr.mtf(image)                             # slanted-edge MTF of an image

Long calls run without the GIL, take a `progress` callable (the fraction done) and stop at
Ctrl+C (KeyboardInterrupt). Bad input raises ValueError with the message the command gives.
See docs/python.md.
"""
import os as _os

from . import _airr
from ._airr import (Scene, __version__, asset_dir, compare, fit, mtf, optimise, psf, read_image, record_rays, render,
                    sweep, tolerance, viewzone, write_image)
from ._rays import read_rays

__all__ = ["Scene", "asset_dir", "compare", "default_scene_path", "fit", "mtf", "optimise", "psf", "read_image",
           "read_rays", "record_rays", "render", "sweep", "tolerance", "viewzone", "write_image", "__version__"]


def _use_assets_beside_the_package():
    """The shipped assets: $AIRR_ASSETS, else where this package's build or install put them."""
    if _os.environ.get("AIRR_ASSETS"):
        return
    from . import _locations

    _airr._set_asset_dir(_os.path.normpath(_os.path.join(_os.path.dirname(__file__), _locations.ASSETS)))


_use_assets_beside_the_package()


def default_scene_path():
    """The scene the designer opens by default (the reference layout with an RF-Ay sheet)."""
    return _os.path.join(asset_dir(), "scenes", "default.json")
