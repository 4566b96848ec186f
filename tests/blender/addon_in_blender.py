"""Run by Debian's blender in background mode (tests/check_blender.sh): builds a scene from a
layout with its AIRR roles stripped, gives the parts their roles again through the add-on's
operator, and renders the aerial image through the add-on. Writes the image's pixels (as Blender
holds them, read back) for the caller to compare with `airr render` of the GLB Blender exported.

Arguments after "--": the add-on file, the folder holding the airr package, the layout (GLB),
the output folder."""
import importlib.util
import json
import os
import sys

import bpy

addon_path, package_dir, layout, out = sys.argv[sys.argv.index("--") + 1:]
sys.path.insert(0, package_dir)
spec = importlib.util.spec_from_file_location("airr_studio_addon", addon_path)
addon = importlib.util.module_from_spec(spec)
spec.loader.exec_module(addon)
addon.register()

# An empty scene, then the layout with the roles stripped and the names made plain, so that only
# the add-on gives the parts their roles.
for obj in list(bpy.data.objects):
    bpy.data.objects.remove(obj)
bpy.ops.import_scene.gltf(filepath=layout, import_shading="FLAT")
roles = {}
for i, obj in enumerate(sorted(bpy.data.objects, key=lambda o: o.name)):
    for holder in (obj, obj.data):
        if holder is not None and "airr" in holder:
            roles[obj] = addon.role_fields(holder) or roles.get(obj, {})
            del holder["airr"]
    obj.name = f"part {i}"
assert roles, "the layout's parts had no roles to strip"

for obj, fields in roles.items():
    bpy.context.view_layer.objects.active = obj
    kwargs = {"role": fields["role"]}
    for key in ("intensity", "bezel_mm", "reflectance", "transmittance"):
        if key in fields:
            kwargs[key] = fields[key]
    if isinstance(fields.get("model"), dict) and "preset" in fields["model"]:
        kwargs["preset"] = fields["model"]["preset"]
    assert bpy.ops.airr.set_role(**kwargs) == {"FINISHED"}
    assert addon.role_fields(obj)["role"] == fields["role"], addon.role_fields(obj)
print("roles set:", sorted(f["role"] for f in roles.values()))

result = bpy.ops.airr.render_aerial_image(spp=4, seed=3, width=64, height=48,
                                          glb_path=os.path.join(out, "blender.glb"))
assert result == {"FINISHED"}, result
image = bpy.data.images[addon.IMAGE_NAME]
import numpy as np

w, h = image.size
pixels = np.empty(w * h * 4, dtype=np.float32)
image.pixels.foreach_get(pixels)
np.save(os.path.join(out, "addon.npy"), pixels.reshape(h, w, 4)[::-1, :, :3])
print("aerial image:", w, "x", h, "from", image["airr_layout"])
