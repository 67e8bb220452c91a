# Runs inside Blender (background mode): what Blender's bundled glTF importer makes of quasiflat's
# files, and an EEVEE or Cycles render of one of them from `qf-render eval --cameras` views.
#
#   blender -b --factory-startup --python-exit-code 1 -P blender_check.py -- import CASES.json
#   blender -b --factory-startup --python-exit-code 1 -P blender_check.py -- render FILE.glb CAMERAS.json OUTDIR eevee|cycles SAMPLES
#
# import: CASES.json is a list of {"file", "expect", "nodes"}: expect "imports" (the file must import
# with no error or warning, and every fact below must hold), or "ktx2" / "webp" / "draco" (Blender 3.4
# cannot decode KHR_texture_basisu, its importer does not know EXT_texture_webp, and Debian ships no
# Draco decoder for it: the import must either be
# refused with an error that names what is missing, or succeed and pass the same checks); "nodes":
# node names that must arrive exactly (the `_LODn` names of a combined file), or absent.
# Every fact is read from the .glb itself (its JSON chunk), so what is checked is what the file says.
# render: draws FILE with EEVEE (surfaceless EGL) or Cycles on the CPU, lit like the engine method
# (engine_scene.h EngineLights: a white directional headlight and ambient light, no shadows), and
# writes view_I_black.png and view_I_white.png as `qf-render eval --external` reads them.
# Exit status 1 (with FAIL lines) when a check fails; messages name the file and the fact.
import io
import json
import logging
import math
import os
import struct
import sys
import zlib
from contextlib import redirect_stdout

import bpy
import numpy
from mathutils import Matrix, Vector

# Debian 12's Blender 3.4.1 importer builds its polygon flags with `numpy.bool`, an alias numpy 1.24
# (Debian 12's python3-numpy) removed: every mesh import fails with "module 'numpy' has no attribute
# 'bool'" (glTF-Blender-IO issue 1844, fixed in Blender 3.5, not backported). The alias is restored
# here, as a user of Debian's Blender has to (docs/engines.md), so that the rest can be checked.
NUMPY_BOOL_RESTORED = not hasattr(numpy, "bool")
if NUMPY_BOOL_RESTORED:
    numpy.bool = numpy.bool_

GL_CLAMP_TO_EDGE, GL_NEAREST = 33071, 9728


def glb_json(path):
    with open(path, "rb") as f:
        data = f.read()
    if data[:4] != b"glTF":
        raise SystemExit(f"FAIL {path}: not a .glb file")
    length, kind = struct.unpack_from("<II", data, 12)
    if kind != 0x4E4F534A:
        raise SystemExit(f"FAIL {path}: first chunk is not JSON")
    return json.loads(data[20:20 + length])


class Capture(logging.Handler):
    """Collects the importer's log records of level WARNING and above."""

    def __init__(self):
        super().__init__(logging.WARNING)
        self.messages = []

    def emit(self, record):
        self.messages.append(record.getMessage())


def import_file(path):
    """Imports into an empty scene. Returns (error or None, warnings): the importer reports through
    the 'glTFImporter' logger and through print() lines tagged WARNING / ERROR, so both are read."""
    bpy.ops.wm.read_factory_settings(use_empty=True)
    capture = Capture()
    logging.getLogger("glTFImporter").addHandler(capture)
    out = io.StringIO()
    error = None
    # The importer sets its logger's level from Blender's debug value: 0 (the default) lets only
    # CRITICAL through, 2 lets warnings and errors through to the handler above.
    bpy.app.debug_value = 2
    try:
        with redirect_stdout(out):
            result = bpy.ops.import_scene.gltf(filepath=path)
        if "FINISHED" not in result:
            error = f"import returned {sorted(result)}"
    except Exception as e:  # the operator raises RuntimeError with the importer's message
        # A Python error inside the importer arrives as its whole traceback: its last line says what.
        lines = [l.strip() for l in str(e).splitlines() if l.strip() and not l.strip().startswith("Location:")]
        error = lines[-1] if lines else type(e).__name__
    finally:
        bpy.app.debug_value = 0
        logging.getLogger("glTFImporter").removeHandler(capture)
    sys.stdout.write(out.getvalue())
    printed = [l for l in out.getvalue().splitlines() if "| WARNING:" in l or "| ERROR:" in l]
    return error, capture.messages + printed


def same_value(blender_value, json_value):
    """A custom property (an IDPropertyArray, a number, a string) against the JSON value it came from."""
    if isinstance(json_value, list):
        return len(blender_value) == len(json_value) and all(same_value(a, b) for a, b in zip(blender_value, json_value))
    if isinstance(json_value, (int, float)) and not isinstance(json_value, bool):
        return abs(float(blender_value) - json_value) <= 1e-6 * max(1.0, abs(json_value))
    return blender_value == json_value


def linked_from(socket):
    """The node feeding an input socket, or None."""
    return socket.links[0].from_node if socket.is_linked else None


def check_material(gm, gltf, problems, facts):
    name = gm.get("name")
    mat = bpy.data.materials.get(name)
    if mat is None:
        problems.append(f"material {name!r} did not arrive (materials: {[m.name for m in bpy.data.materials]})")
        return
    mode = gm.get("alphaMode", "OPAQUE")
    want = {"OPAQUE": "OPAQUE", "MASK": "CLIP", "BLEND": "BLEND"}[mode]
    if mat.blend_method != want:
        problems.append(f"material {name}: alphaMode {mode} arrived as blend_method {mat.blend_method}, not {want}")
    if mode == "MASK":
        cutoff = gm.get("alphaCutoff", 0.5)
        # Blender stores the threshold as a 32-bit float, as the file does.
        if abs(mat.alpha_threshold - cutoff) > 1e-6:
            problems.append(f"material {name}: alpha_threshold {mat.alpha_threshold} is not the file's alphaCutoff {cutoff}")
        elif mat.blend_method == "CLIP":
            facts.add(f"MASK -> blend_method CLIP, alpha_threshold = alphaCutoff ({cutoff:.3g})")
        # Not a check (glTF has no shadows): what EEVEE's shadow maps see of the cut-out texels.
        facts.add(f"MASK -> shadow_method {mat.shadow_method}"
                  + (" (EEVEE shadows of whole quads)" if mat.shadow_method == "OPAQUE" else ""))
    if mat.use_backface_culling == bool(gm.get("doubleSided", False)):
        problems.append(f"material {name}: doubleSided {gm.get('doubleSided', False)} arrived as "
                        f"use_backface_culling {mat.use_backface_culling}")
    elif gm.get("doubleSided"):
        facts.add("doubleSided -> use_backface_culling off")
    if not mat.use_nodes:
        problems.append(f"material {name}: no node tree")
        return
    bsdfs = [n for n in mat.node_tree.nodes if n.bl_idname == "ShaderNodeBsdfPrincipled"]
    if len(bsdfs) != 1:
        problems.append(f"material {name}: {len(bsdfs)} Principled BSDF nodes, not 1")
        return
    bsdf = bsdfs[0]
    pbr = gm.get("pbrMetallicRoughness", {})
    base = linked_from(bsdf.inputs["Base Color"])
    if "baseColorTexture" in pbr:
        tex = gltf["textures"][pbr["baseColorTexture"]["index"]]
        gimage = gltf["images"][tex["source"]]
        if base is None or base.bl_idname != "ShaderNodeTexImage" or base.image is None:
            problems.append(f"material {name}: no image texture on the Principled BSDF's Base Color "
                            f"(linked: {base.bl_idname if base else None})")
        else:
            img = base.image
            if img.name != gimage.get("name", img.name):
                problems.append(f"material {name}: base colour image {img.name!r}, not the file's {gimage.get('name')!r}")
            if img.size[0] == 0 or img.packed_file is None:
                problems.append(f"material {name}: base colour image {img.name} is empty or not packed (size {tuple(img.size)})")
            if img.colorspace_settings.name != "sRGB":
                problems.append(f"material {name}: base colour image in {img.colorspace_settings.name}, not sRGB")
            sampler = gltf["samplers"][tex["sampler"]] if "sampler" in tex else {}
            if sampler.get("wrapS") == GL_CLAMP_TO_EDGE and base.extension != "EXTEND":
                problems.append(f"material {name}: CLAMP_TO_EDGE arrived as extension {base.extension}, not EXTEND")
            if sampler.get("magFilter") not in (None, GL_NEAREST) and base.interpolation != "Linear":
                problems.append(f"material {name}: linear filtering arrived as {base.interpolation}")
            facts.add(f"base colour texture -> Image Texture node on Base Color ({img.size[0]}x{img.size[1]}, "
                      f"packed, extension {base.extension})")
            if mode != "OPAQUE":
                alpha = linked_from(bsdf.inputs["Alpha"])
                # bpy wrappers are made per access: == compares the nodes themselves, `is` would not.
                if alpha != base or not any(l.from_socket.name == "Alpha" for l in bsdf.inputs["Alpha"].links):
                    problems.append(f"material {name}: the base colour texture's alpha is not on the BSDF's Alpha")
                else:
                    facts.add("texture alpha -> Principled Alpha")
    if "normalTexture" in gm:
        nmap = linked_from(bsdf.inputs["Normal"])
        if nmap is None or nmap.bl_idname != "ShaderNodeNormalMap":
            problems.append(f"material {name}: no Normal Map node on the BSDF's Normal")
        else:
            tex = linked_from(nmap.inputs["Color"])
            if tex is None or tex.bl_idname != "ShaderNodeTexImage" or tex.image is None:
                problems.append(f"material {name}: the Normal Map node has no image")
            elif tex.image.colorspace_settings.name != "Non-Color":
                problems.append(f"material {name}: normal image in {tex.image.colorspace_settings.name}, not Non-Color")
            else:
                facts.add(f"normalTexture -> Normal Map node ({nmap.space}), image Non-Color")
    if "metallicFactor" in pbr and abs(bsdf.inputs["Metallic"].default_value - pbr["metallicFactor"]) > 1e-6 \
            and not bsdf.inputs["Metallic"].is_linked:
        problems.append(f"material {name}: Metallic {bsdf.inputs['Metallic'].default_value}, not {pbr['metallicFactor']}")


def check_import(case, problems, facts):
    path = case["file"]
    gltf = glb_json(path)
    error, warnings = import_file(path)
    expect = case.get("expect", "imports")
    if error is not None:
        # The refusals Blender 3.4 is known for must name what is missing; anything else is a failure.
        named = {"ktx2": "KHR_texture_basisu", "webp": "EXT_texture_webp", "draco": "draco"}.get(expect)
        if named and named.lower() in error.lower():
            facts.add(f"refused, with: {error}")
            return "refused"
        problems.append(f"import failed: {error}")
        return "failed"
    if warnings:
        problems.append(f"importer warned: {warnings}")

    # Nodes: every node of the file (also those only MSFT_lod refers to) arrives as an object of its name.
    objects = {o.name: o for o in bpy.data.objects}
    for node in gltf.get("nodes", []):
        o = objects.get(node.get("name"))
        if o is None:
            problems.append(f"node {node.get('name')!r} did not arrive as an object (objects: {sorted(objects)})")
            continue
        if "mesh" in node:
            gmesh = gltf["meshes"][node["mesh"]]
            if o.type != "MESH" or o.data.name != gmesh.get("name", o.data.name):
                problems.append(f"object {o.name}: data {o.data.name if o.data else None}, not mesh {gmesh.get('name')!r}")
                continue
            # Sizes: a triangle list arrives as as many faces, a point list as loose vertices.
            tris = points = 0
            for prim in gmesh["primitives"]:
                mode = prim.get("mode", 4)
                acc = gltf["accessors"][prim["indices"]] if "indices" in prim else gltf["accessors"][prim["attributes"]["POSITION"]]
                if mode == 4:
                    tris += acc["count"] // 3
                elif mode == 0:
                    points += gltf["accessors"][prim["attributes"]["POSITION"]]["count"]
                else:
                    problems.append(f"object {o.name}: primitive mode {mode} not checked by this test")
            if len(o.data.polygons) != tris:
                problems.append(f"object {o.name}: {len(o.data.polygons)} faces, the file has {tris} triangles")
            if points and (len(o.data.vertices) != points or len(o.data.polygons) != 0):
                problems.append(f"object {o.name}: {len(o.data.vertices)} vertices / {len(o.data.polygons)} faces, "
                                f"the file has {points} points")
            if points:
                facts.add(f"POINTS -> loose vertices ({points}), no faces (Cycles/EEVEE draw nothing)")
            if any("COLOR_0" in p["attributes"] for p in gmesh["primitives"]):
                if not o.data.color_attributes:
                    problems.append(f"object {o.name}: COLOR_0 did not arrive as a colour attribute")
                else:
                    # Our vertex-coloured files have no base colour texture: the colours alone feed Base Color.
                    mats = [m for m in o.data.materials if m and m.use_nodes]
                    bsdf = [n for m in mats for n in m.node_tree.nodes if n.bl_idname == "ShaderNodeBsdfPrincipled"]
                    feed = linked_from(bsdf[0].inputs["Base Color"]) if bsdf else None
                    if feed is None or feed.bl_idname != "ShaderNodeVertexColor":
                        problems.append(f"object {o.name}: Base Color is fed by {feed.bl_idname if feed else None}, "
                                        f"not a Color Attribute node (COLOR_0)")
                    else:
                        facts.add("COLOR_0 -> colour attribute, Color Attribute node on Base Color")
        extras = node.get("extras", {})
        for key, value in extras.items():
            if key not in o.keys():
                problems.append(f"object {o.name}: extras {key} did not arrive as a custom property")
            elif not same_value(o[key], value):
                problems.append(f"object {o.name}: custom property {key} {list(o[key])}, the file has {value}")
            else:
                facts.add(f"node extras {key} -> custom property")
    for name in case.get("nodes", []):
        if name not in objects:
            problems.append(f"expected node {name!r} did not arrive (objects: {sorted(objects)})")
    lods = sorted(n for n in objects if "_LOD" in n)
    if lods:
        top = [n for n in lods if objects[n].parent is None]
        shown = [n for n in lods if not objects[n].hide_render and not objects[n].hide_get()]
        facts.add(f"_LODn names kept: {', '.join(lods)} ({len(top)} top-level, {len(shown)} shown and rendered)")
    meshes = len(gltf.get("meshes", []))
    if len(bpy.data.meshes) != meshes:
        problems.append(f"{len(bpy.data.meshes)} Blender meshes, the file has {meshes}")
    for gm in gltf.get("materials", []):
        check_material(gm, gltf, problems, facts)
    return "imported"


def gltf_importer_version():
    import addon_utils
    for mod in addon_utils.modules():
        if mod.__name__ == "io_scene_gltf2":
            return mod.bl_info["version"]
    return ("?",)


def cmd_import(cases_path):
    cases = json.load(open(cases_path))
    failed = 0
    for case in cases:
        problems, facts = [], set()
        outcome = check_import(case, problems, facts)
        label = os.path.join(os.path.basename(os.path.dirname(case["file"])), os.path.basename(case["file"]))
        # A fresh line: Blender's own report of a refusal ends without one.
        print(f"\n{'FAIL' if problems else 'ok  '} {label}: {outcome}"
              + "".join(f"\n   - {f}" for f in sorted(facts))
              + "".join(f"\n   ! FAIL {p}" for p in problems), flush=True)
        failed += bool(problems)
    if NUMPY_BOOL_RESTORED:
        print("note: numpy.bool restored for Blender 3.4's importer (numpy >= 1.24 removed it)")
    print(f"blender import: {len(cases) - failed} of {len(cases)} files as expected (Blender {bpy.app.version_string}, "
          f"importer {'.'.join(map(str, gltf_importer_version()))})")
    return 1 if failed else 0


def gl_matrix(values):
    """A column-major 4x4 (OpenGL, as the cameras JSON stores it) as a mathutils Matrix."""
    return Matrix([[values[c * 4 + r] for c in range(4)] for r in range(4)])


def write_png(path, rgba, width, height):
    """8-bit RGBA PNG, rows top first: written here so that no colour management touches the bytes."""
    raw = b"".join(b"\x00" + rgba[y * width * 4:(y + 1) * width * 4] for y in range(height))

    def chunk(tag, body):
        return struct.pack(">I", len(body)) + tag + body + struct.pack(">I", zlib.crc32(tag + body) & 0xFFFFFFFF)

    with open(path, "wb") as f:
        f.write(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 6, 0, 0, 0))
                + chunk(b"IDAT", zlib.compress(raw, 6)) + chunk(b"IEND", b""))


def cmd_render(path, cams_path, outdir, engine, samples):
    cams = json.load(open(cams_path))
    error, warnings = import_file(path)
    if error is not None:
        print(f"FAIL render {path}: import failed: {error}")
        return 1
    scene = bpy.context.scene
    if engine == "eevee":
        # EEVEE draws what Blender's viewport shows: blend_method CLIP cuts at alpha_threshold. One
        # sample a pixel (no temporal antialiasing), as the engine method draws without MSAA. In
        # background mode Blender gets its OpenGL context from surfaceless EGL (Mesa llvmpipe here).
        scene.render.engine = "BLENDER_EEVEE"
        scene.eevee.taa_render_samples = samples
        scene.render.filter_size = 0.0
    else:
        scene.render.engine = "CYCLES"
    scene.cycles.device = "CPU"
    scene.cycles.samples = samples
    scene.cycles.use_denoising = False
    scene.cycles.use_adaptive_sampling = False
    scene.cycles.seed = 0
    # Direct light only, as a rasteriser lights: no bounces, and (below) no object casts shadows. A
    # MASK texel's alpha is transparency to Cycles (blend_method is an EEVEE setting), so stacked
    # quads need transparent bounces.
    scene.cycles.max_bounces = 0
    scene.cycles.transparent_max_bounces = 64
    # A narrow pixel filter: one surface point per pixel, as the engine method draws without MSAA.
    scene.cycles.filter_width = 0.01
    scene.render.film_transparent = True
    scene.view_settings.view_transform = "Standard"  # Blender 3.4's default, Filmic, is not sRGB
    scene.view_settings.look = "None"
    scene.render.image_settings.file_format = "PNG"
    scene.render.image_settings.color_mode = "RGBA"
    scene.render.image_settings.color_depth = "8"
    for o in scene.objects:
        o.visible_shadow = False
    # Engine lights (three.js units): outgoing diffuse = albedo * (directional * cos / pi + ambient / pi).
    # A Cycles sun of strength S gives albedo * S * cos / pi; a uniform world of radiance L gives albedo * L.
    world = bpy.data.worlds.new("engine_ambient")
    world.use_nodes = True
    background = world.node_tree.nodes["Background"]
    a = cams["lights"]["ambient"] / math.pi
    background.inputs["Color"].default_value = (a, a, a, 1.0)
    background.inputs["Strength"].default_value = 1.0
    scene.world = world
    sun = bpy.data.objects.new("headlight", bpy.data.lights.new("headlight", "SUN"))
    sun.data.energy = cams["lights"]["directional"]
    sun.data.angle = 0.0
    sun.data.use_shadow = False  # EEVEE's shadow maps (Cycles: objects' visible_shadow, above)
    scene.collection.objects.link(sun)
    camera = bpy.data.objects.new("camera", bpy.data.cameras.new("camera"))
    scene.collection.objects.link(camera)
    scene.camera = camera
    # The importer turns glTF's +Y up into Blender's +Z up, (x, y, z) -> (x, -z, y): the cameras, given
    # in glTF's frame, are turned the same way.
    y_up_to_z_up = Matrix(((1, 0, 0, 0), (0, 0, -1, 0), (0, 1, 0, 0), (0, 0, 0, 1)))
    os.makedirs(outdir, exist_ok=True)
    for i, v in enumerate(cams["views"]):
        w, h = v["width"], v["height"]
        scene.render.resolution_x, scene.render.resolution_y = w, h
        scene.render.resolution_percentage = 100
        camera.matrix_world = y_up_to_z_up @ gl_matrix(v["view"]).inverted()
        proj = gl_matrix(v["projection"])
        camera.data.sensor_fit = "VERTICAL"
        camera.data.angle_y = 2.0 * math.atan(1.0 / proj[1][1])
        camera.data.clip_start, camera.data.clip_end = v["near"], v["far"]
        direction = y_up_to_z_up.to_3x3() @ (Vector(v["target"]) - Vector(v["eye"]))
        sun.rotation_euler = direction.to_track_quat("-Z", "Y").to_euler()
        shot = os.path.join(outdir, f"blender_{i}.png")
        scene.render.filepath = shot
        bpy.ops.render.render(write_still=True)
        # Over black and over white, as the web engines' renders are read (straight alpha, 8 bits).
        img = bpy.data.images.load(shot)
        px = numpy.array(img.pixels[:], dtype=numpy.float64).reshape(h, w, 4)[::-1]
        bpy.data.images.remove(img)
        rgb, alpha = px[..., :3], px[..., 3:4]
        for bg, name in ((0.0, "black"), (1.0, "white")):
            out = numpy.concatenate([rgb * alpha + bg * (1.0 - alpha), numpy.ones_like(alpha)], axis=2)
            write_png(os.path.join(outdir, f"view_{i}_{name}.png"),
                      (numpy.clip(out, 0, 1) * 255 + 0.5).astype(numpy.uint8).tobytes(), w, h)
    print(f"blender render: {len(cams['views'])} views of {os.path.basename(path)} ({engine}, {samples} samples) in {outdir}")
    return 0


def main():
    args = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    if len(args) == 2 and args[0] == "import":
        return cmd_import(args[1])
    if len(args) == 6 and args[0] == "render" and args[4] in ("eevee", "cycles"):
        return cmd_render(args[1], args[2], args[3], args[4], int(args[5]))
    print("usage: blender -b --factory-startup --python-exit-code 1 -P blender_check.py -- "
          "import CASES.json | render FILE.glb CAMERAS.json OUTDIR eevee|cycles SAMPLES")
    return 2


sys.exit(main())
