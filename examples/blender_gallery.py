"""Renders docs/gallery/blender_default.png: the add-on's limit surface of assets/default.obj coloured
by K, beside its control mesh, with Cycles on the CPU (headless).

    BLENDER_USER_SCRIPTS=$(mktemp -d) blender -b --factory-startup -noaudio --python-exit-code 1 \\
        -P examples/blender_gallery.py -- build/blender/polarview_blender.zip docs/gallery/blender_default.png

The add-on is installed into BLENDER_USER_SCRIPTS (a throw-away folder), as the test does."""
import math
import os
import sys

import bpy
from mathutils import Vector

zip_path, out = sys.argv[sys.argv.index("--") + 1:][:2]
here = os.path.dirname(os.path.abspath(__file__))
bpy.ops.preferences.addon_install(filepath=os.path.abspath(zip_path), overwrite=True)
bpy.ops.preferences.addon_enable(module="polarview_blender")
for obj in list(bpy.data.objects):
    bpy.data.objects.remove(obj)

# The model, subdivided by the add-on: C2PS level 4, 8 samples a patch edge.
bpy.ops.wm.obj_import(filepath=os.path.join(here, "..", "assets", "default.obj"), forward_axis='Y', up_axis='Z')
model = bpy.context.selected_objects[0]
bpy.context.view_layer.objects.active = model
bpy.ops.polarview.subdivide(scheme="c2ps", level=4, samples=8)
surface = model.polarview.result

# The control mesh as a dark wire cage.
cage = bpy.data.materials.new("cage")
cage.use_nodes = True
cage.node_tree.nodes["Principled BSDF"].inputs["Base Color"].default_value = (0.02, 0.02, 0.02, 1.0)
model.data.materials.append(cage)
wire = model.modifiers.new("cage", 'WIREFRAME')
wire.thickness = 0.025

# Camera and light: both objects in view, from a little above.
centre = (Vector(model.location) + Vector(surface.location)) / 2 + Vector((0.0, 0.0, 0.1))
camera = bpy.data.objects.new("camera", bpy.data.cameras.new("camera"))
camera.location = centre + Vector((0.0, -9.4, 2.4))
camera.rotation_euler = (centre - camera.location).to_track_quat('-Z', 'Y').to_euler()
camera.data.lens = 50
bpy.context.scene.collection.objects.link(camera)
bpy.context.scene.camera = camera
sun = bpy.data.objects.new("sun", bpy.data.lights.new("sun", 'SUN'))
sun.data.energy = 3.0
sun.rotation_euler = (math.radians(40), math.radians(10), math.radians(-30))
bpy.context.scene.collection.objects.link(sun)
world = bpy.data.worlds.new("world")
world.use_nodes = True
world.node_tree.nodes["Background"].inputs["Color"].default_value = (0.9, 0.9, 0.9, 1.0)
world.node_tree.nodes["Background"].inputs["Strength"].default_value = 0.8
bpy.context.scene.world = world

# Cycles on the CPU, few samples, the colours as the map gives them (Standard, not Filmic).
scene = bpy.context.scene
scene.render.engine = 'CYCLES'
scene.cycles.device = 'CPU'
scene.cycles.samples = 64
scene.cycles.use_denoising = False
scene.render.resolution_x, scene.render.resolution_y = 800, 440
scene.view_settings.view_transform = 'Standard'
scene.render.image_settings.file_format = 'PNG'
scene.render.image_settings.color_mode = 'RGB'
scene.render.image_settings.compression = 100
scene.render.filepath = os.path.abspath(out)
bpy.ops.render.render(write_still=True)
print(f"wrote {out}: K colours over {model.polarview.report and __import__('json').loads(model.polarview.report)['colour_range']}")
