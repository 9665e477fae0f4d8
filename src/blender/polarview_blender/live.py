"""Live mode: a control mesh with Live on is subdivided again after it was edited. A depsgraph
handler notes which control meshes changed; a timer, restarted with every change (debounced),
remakes their surfaces once the edits pause. A control mesh whose points and faces are what its
surface was made of is skipped, so the result's own updates cause no loop."""
import hashlib

import bpy

# Seconds without edits before the surface is made again.
DEBOUNCE = 0.3

_pending = set()      # names of control meshes edited since the last update
_made_from = {}       # control mesh name -> digest of the arrays and settings its surface was made of


def digest(obj):
    """A digest of what the surface depends on: points, faces and the settings."""
    from .surface import control_arrays
    settings = obj.polarview
    h = hashlib.blake2b(digest_size=16)
    for array in control_arrays(obj):
        h.update(array.tobytes())
    h.update(f"{settings.scheme} {settings.level} {settings.samples} {settings.ngon_to_fan}".encode())
    return h.digest()


def remember(obj):
    """Records that obj's surface was just made from its current state."""
    _made_from[obj.name] = digest(obj)


def changed(obj):
    """Live was switched on or off for obj: on, it is brought up to date at once (after the delay)."""
    if obj.polarview.live:
        _pending.add(obj.name)
        _schedule()


def on_depsgraph_update(scene, depsgraph):
    for update in depsgraph.updates:
        if not update.is_updated_geometry or not isinstance(update.id, bpy.types.Object):
            continue
        obj = update.id.original
        if obj.type == 'MESH' and obj.polarview.live:
            _pending.add(obj.name)
    if _pending:
        _schedule()


def _schedule():
    if bpy.app.timers.is_registered(flush):
        bpy.app.timers.unregister(flush)
    bpy.app.timers.register(flush, first_interval=DEBOUNCE)


def pending():
    """The control meshes waiting for an update (names)."""
    return set(_pending)


def flush():
    """Remakes the surfaces of the edited live control meshes whose state changed (the timer's
    callback; tests call it directly, as a background Blender runs no timers). An error is kept on
    the control mesh (the panel shows it) instead of raised."""
    from .surface import subdivide
    names = sorted(_pending)
    _pending.clear()
    for name in names:
        obj = bpy.data.objects.get(name)
        if obj is None or obj.type != 'MESH' or not obj.polarview.live:
            continue
        try:
            state = digest(obj)
            if _made_from.get(name) == state and obj.polarview.result is not None:
                continue
            s = obj.polarview
            subdivide(bpy.context, obj, s.scheme, s.level, s.samples, s.ngon_to_fan)
            _made_from[name] = state
        except (ValueError, MemoryError, TypeError, RuntimeError) as error:
            from .operators import refusal
            obj.polarview.error = refusal(obj, error)
    return None  # a one-shot timer


def register():
    if on_depsgraph_update not in bpy.app.handlers.depsgraph_update_post:
        bpy.app.handlers.depsgraph_update_post.append(on_depsgraph_update)


def unregister():
    if on_depsgraph_update in bpy.app.handlers.depsgraph_update_post:
        bpy.app.handlers.depsgraph_update_post.remove(on_depsgraph_update)
    if bpy.app.timers.is_registered(flush):
        bpy.app.timers.unregister(flush)
    _pending.clear()
    _made_from.clear()
