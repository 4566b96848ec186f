"""AIRR Studio in Blender: give objects their AIRR roles and see the aerial image without leaving.

The add-on (Edit > Preferences > Add-ons > Install..., this file) adds an "AIRR" tab to the 3D
view's sidebar. For the active object it shows the AIRR role and fields (display, half mirror,
retroreflector, observer or prop) and sets them; they are stored as the object's custom property
"airr" (a JSON string), which Blender's glTF exporter writes into the node's extras, where every
AIRR Studio program reads them (README, "Scenes"). "Render aerial image" exports the scene as it
stands to a GLB file, renders it with the `airr` Python module (installed with AIRR Studio, on
Debian's python3, which Blender uses) and shows the result as the image "AIRR aerial image".
Draw in metres (glTF's unit), as AIRR Studio reads glTF metres as millimetres x 1000.
"""
import json
import os
import tempfile

import bpy

bl_info = {
    "name": "AIRR Studio",
    "author": "AIRR Studio developers",
    "version": (0, 1, 0),
    "blender": (3, 4, 0),
    "location": "View3D > Sidebar > AIRR",
    "description": "AIRR roles for objects, and the aerial image of the scene rendered by AIRR Studio",
    "category": "Render",
}

ROLES = [
    ("none", "None", "Not part of the AIRR layout (a prop when it has a mesh)"),
    ("display", "Display", "The light source: its panel, image and intensity"),
    ("half_mirror", "Half mirror", "The beam splitter: reflectance and transmittance"),
    ("retroreflector", "Retroreflector", "A retroreflective sheet: its model preset"),
    ("observer", "Observer", "The camera the aerial image is seen from"),
    ("prop", "Prop", "A housing or other object that blocks and scatters light"),
]
IMAGE_NAME = "AIRR aerial image"


def role_fields(obj):
    """The object's AIRR fields (a dict; {} when it has none or they are not JSON)."""
    text = obj.get("airr")
    if not text:
        return {}
    try:
        fields = json.loads(text) if isinstance(text, str) else dict(text)
    except ValueError:
        return {}
    return fields if isinstance(fields, dict) else {}


def set_role(obj, role, image="", intensity=1.0, bezel_mm=0.0, reflectance=0.5, transmittance=0.5, preset="rf-ay"):
    """Sets (or with role "none" removes) the object's AIRR role and the role's fields."""
    if role == "none":
        if "airr" in obj:
            del obj["airr"]
        return
    fields = {"role": role}
    if role == "display":
        fields["intensity"] = intensity
        if image:
            fields["image"] = image
        if bezel_mm > 0:
            fields["bezel_mm"] = bezel_mm
    elif role == "half_mirror":
        fields["reflectance"] = reflectance
        fields["transmittance"] = transmittance
    elif role == "retroreflector":
        fields["model"] = {"type": "sinc_shift", "preset": preset}
    obj["airr"] = json.dumps(fields)


def render_aerial_image(context, spp=16, seed=1, width=0, height=0, glb_path=""):
    """Exports the scene to glb_path (a temporary file when empty), renders it with the airr module
    and puts the image into the Blender image IMAGE_NAME. Returns (image, glb_path)."""
    import airr  # the AIRR Studio Python module (Debian: /usr/lib/python3/dist-packages/airr)
    import numpy as np

    if not glb_path:
        glb_path = os.path.join(tempfile.mkdtemp(prefix="airr-blender-"), "layout.glb")
    bpy.ops.export_scene.gltf(filepath=glb_path, export_format="GLB", export_extras=True, export_cameras=True,
                              use_visible=True)
    scene = airr.Scene.load(glb_path)
    if width > 0:
        scene.set("observer.width", width)
    if height > 0:
        scene.set("observer.height", height)
    pixels = airr.render(scene, spp=spp, seed=seed)
    h, w, _ = pixels.shape
    image = bpy.data.images.get(IMAGE_NAME)
    if image is None or image.size[0] != w or image.size[1] != h:
        if image is not None:
            bpy.data.images.remove(image)
        image = bpy.data.images.new(IMAGE_NAME, width=w, height=h, alpha=True, float_buffer=True)
    image.colorspace_settings.name = "Linear"
    rgba = np.ones((h, w, 4), dtype=np.float32)
    rgba[:, :, :3] = pixels[::-1]  # Blender's rows run from the bottom
    image.pixels.foreach_set(rgba.ravel())
    image.update()
    image["airr_layout"] = glb_path
    for area in getattr(context.screen, "areas", []) if context.screen else []:
        if area.type == "IMAGE_EDITOR":
            area.spaces.active.image = image
    return image, glb_path


class AIRR_OT_set_role(bpy.types.Operator):
    """Set the active object's AIRR role and fields"""

    bl_idname = "airr.set_role"
    bl_label = "Set AIRR role"
    bl_options = {"REGISTER", "UNDO"}

    role: bpy.props.EnumProperty(name="Role", items=ROLES, default="none")
    image: bpy.props.StringProperty(name="Image", description="Display: the image file it shows", subtype="FILE_PATH")
    intensity: bpy.props.FloatProperty(name="Intensity", default=1.0, min=0.0)
    bezel_mm: bpy.props.FloatProperty(name="Bezel (mm)", default=0.0, min=0.0)
    reflectance: bpy.props.FloatProperty(name="Reflectance", default=0.5, min=0.0, max=1.0)
    transmittance: bpy.props.FloatProperty(name="Transmittance", default=0.5, min=0.0, max=1.0)
    preset: bpy.props.StringProperty(name="Preset", description="Retroreflector: a preset's name or file",
                                     default="rf-ay")

    @classmethod
    def poll(cls, context):
        return context.active_object is not None

    def invoke(self, context, event):
        fields = role_fields(context.active_object)
        self.role = fields.get("role", "none") if fields.get("role") in {r[0] for r in ROLES} else "none"
        for key in ("image", "intensity", "bezel_mm", "reflectance", "transmittance"):
            if key in fields:
                setattr(self, key, fields[key])
        if isinstance(fields.get("model"), dict) and "preset" in fields["model"]:
            self.preset = fields["model"]["preset"]
        return context.window_manager.invoke_props_dialog(self)

    def draw(self, context):
        layout = self.layout
        layout.prop(self, "role")
        shown = {"display": ("image", "intensity", "bezel_mm"), "half_mirror": ("reflectance", "transmittance"),
                 "retroreflector": ("preset",)}.get(self.role, ())
        for key in shown:
            layout.prop(self, key)

    def execute(self, context):
        set_role(context.active_object, self.role, self.image, self.intensity, self.bezel_mm, self.reflectance,
                 self.transmittance, self.preset)
        return {"FINISHED"}


class AIRR_OT_render(bpy.types.Operator):
    """Render the aerial image of the scene as it stands, with AIRR Studio"""

    bl_idname = "airr.render_aerial_image"
    bl_label = "Render aerial image"

    spp: bpy.props.IntProperty(name="Samples per pixel", default=16, min=1, max=65536)
    seed: bpy.props.IntProperty(name="Seed", default=1, min=0)
    width: bpy.props.IntProperty(name="Width", description="Pixels (0: the layout's observer's)", default=0, min=0)
    height: bpy.props.IntProperty(name="Height", description="Pixels (0: the layout's observer's)", default=0, min=0)
    glb_path: bpy.props.StringProperty(name="Layout file", description="Where the GLB goes (empty: a temporary file)",
                                       subtype="FILE_PATH")

    def execute(self, context):
        try:
            image, path = render_aerial_image(context, self.spp, self.seed, self.width, self.height, self.glb_path)
        except ImportError as e:
            self.report({"ERROR"}, f"the airr Python module is not installed for Blender's Python: {e}")
            return {"CANCELLED"}
        except ValueError as e:  # the layout's problem, as AIRR Studio words it
            self.report({"ERROR"}, str(e))
            return {"CANCELLED"}
        self.report({"INFO"}, f"{image.size[0]} x {image.size[1]} aerial image from {path}")
        return {"FINISHED"}


class AIRR_PT_panel(bpy.types.Panel):
    bl_label = "AIRR"
    bl_space_type = "VIEW_3D"
    bl_region_type = "UI"
    bl_category = "AIRR"

    def draw(self, context):
        layout = self.layout
        obj = context.active_object
        if obj is not None:
            fields = role_fields(obj)
            layout.label(text=f"{obj.name}: {fields.get('role', 'no role')}")
            for key, value in fields.items():
                if key != "role":
                    layout.label(text=f"{key}: {json.dumps(value)}")
            layout.operator(AIRR_OT_set_role.bl_idname)
        layout.separator()
        layout.operator(AIRR_OT_render.bl_idname)


CLASSES = (AIRR_OT_set_role, AIRR_OT_render, AIRR_PT_panel)


def register():
    for c in CLASSES:
        bpy.utils.register_class(c)


def unregister():
    for c in reversed(CLASSES):
        bpy.utils.unregister_class(c)
