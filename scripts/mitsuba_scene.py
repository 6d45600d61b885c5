#!/usr/bin/env python3
"""Converts a wavepath scene (docs/scene-format.md) to a Mitsuba 3 scene dictionary.

Mitsuba 3 is the project's independent oracle (tests/oracle/) and its peer in
the benchmark (bench/run.py): it shares no code with wavepath's estimator, so
an image that agrees with Mitsuba's is right for a reason other than the
wavepath code agreeing with itself. The mapping (docs/mitsuba.md):

- camera: `perspective`, `fov_axis` y, looking from `position` at `look_at`;
  `hdrfilm` with the camera's `filter` as its `rfilter` (`box` by default:
  one pixel wide; tent and gaussian with their radius and stddev), RGB float;
- render: `path` integrator with Mitsuba's `max_depth` = ours + 1 (Mitsuba
  counts path segments, we count scattering events), `rr_depth` = ours (both
  play the roulette first at the rr_depth-th surface hit);
  `independent` sampler. `nee`, `mis`, `hemisphere` and `sampler` choose
  wavepath's estimator, not the image, and have no counterpart;
- diffuse: `twosided` `diffuse`; mirror: `twosided` `conductor` of material
  `none` (reflectance 1) scaled by `specular_reflectance`; conductor,
  roughconductor, plastic and roughplastic: `twosided` around Mitsuba's plugin
  of the same name and parameters (wavepath's materials are two-sided); dielectric, roughdielectric
  and thindielectric: Mitsuba's plugin of the same name; glass: `dielectric`
  with `int_ior` = ior and `ext_ior` 1 (the outside is the normal's side in
  both); emitter: black `diffuse`; emission: a one-sided `area` emitter on the
  shape, a two-sided one as a second, flipped copy of the shape just behind it
  (quads and spheres only);
- textures: Mitsuba's `bitmap` and `checkerboard` of the same parameters,
  `to_uv` as a 3x3 transform, in place of a textured colour parameter (a
  diffuse `reflectance`, a plastic's `diffuse_reflectance`, a conductor's or
  plastic's `specular_reflectance`, a roughconductor's or roughdielectric's
  `alpha`, `alpha_u` or `alpha_v`), a normalmap's `normalmap` and a bumpmap's
  `bumpmap`;
- normalmap: `twosided` around Mitsuba's `normalmap` around the nested
  material's plugin (twosided outside, so that the nested BSDF is black to an
  arrival below the perturbed normal, as in wavepath); bumpmap: the same with
  Mitsuba's `bumpmap` and its `scale`; mask: Mitsuba's `mask` with the same
  `opacity` (a number or a texture) around the nested material's BSDF;
- shapes: spheres as `sphere`; quads as two-triangle PLY meshes written into
  the work directory (Mitsuba's `rectangle` is orthogonal only, and quads may
  be sheared), with uvs (0, 0) at the corner, (1, 0) at corner + edge1 and
  (0, 1) at corner + edge2, as wavepath's quads have them; planes as a square quad `PLANE_EXTENT` times the scene's extent
  around the camera's foot point (Mitsuba has no infinite plane); meshes as
  Mitsuba `obj`/`ply` shapes of the same file with our transform as
  `to_world` (`objects` of an OBJ file: those objects written as a PLY
  first); `face_normals` unless the file has vertex normals and the scene
  keeps them (Mitsuba would otherwise smooth the normals of files that have
  none);
- background: a `constant` emitter when not black;
- lights: `directional` emitters of the same `direction` and `irradiance`;
  `envmap` emitters of the same file, `scale` and `to_world`; `point`
  emitters of the same `position` and `intensity`; `spot` emitters of the
  same `intensity`, `cutoff_angle` and `beam_width`, a look-at `to_world`
  from the position along the direction.

Everything is rebased to the camera as wavepath's loader does (the camera at
the origin), so that Mitsuba's float arithmetic sees the same small numbers.

What Mitsuba cannot express, or this converter does not know, is refused by
name: `MitsubaSceneError` with `<scene>: <JSON path>: <problem>`.

The dictionary is plain Python (transforms as 4x4 nested lists under
`to_world`) and can be printed as JSON; `load(mi, scene_dict)` makes Mitsuba
objects of it under the variant already set.

Usage: scripts/mitsuba_scene.py SCENE [--workdir DIR] [--width W --height H --spp N --max-depth D --seed S]
prints the dictionary as JSON.
"""
import argparse
import json
import math
import os
import struct
import sys

PLANE_EXTENT = 1000.0  # a plane's half-size as a multiple of the scene's extent
# Distance of a two-sided emitter's back copy behind the front, relative to the scene's extent: well above
# Mitsuba's float ray offsets (about 5e-6 of the coordinates), else rays from outside hit the hidden copy.
TWO_SIDED_GAP = 1e-4
MESH_FORMATS = (".obj", ".ply")  # what Mitsuba's mesh plugins read
LIBLLVM = "/usr/lib/x86_64-linux-gnu/libLLVM-19.so"


class MitsubaSceneError(Exception):
    """A scene the converter refuses: one line naming the scene, the JSON path and the problem."""


# The keys each part of a scene may have (docs/scene-format.md); any other key is refused,
# so that a feature added to wavepath is never silently dropped from Mitsuba's image.
TOP_KEYS = {"camera", "render", "background", "lights", "textures", "materials", "shapes"}
LIGHT_KEYS = {"directional": {"type", "direction", "irradiance"}, "envmap": {"type", "filename", "scale", "to_world"},
              "point": {"type", "position", "intensity"},
              "spot": {"type", "position", "direction", "intensity", "cutoff_angle", "beam_width"}}
CAMERA_KEYS = {"position", "look_at", "up", "fov_y", "width", "height"}
RENDER_KEYS = {"spp", "max_depth", "rr_depth", "seed", "nee", "mis", "hemisphere", "sampler"}
MATERIAL_KEYS = {
    "diffuse": {"type", "albedo", "emission", "two_sided", "one_sided"},
    "mirror": {"type", "reflectance", "one_sided"},
    "glass": {"type", "ior"},
    "emitter": {"type", "radiance", "two_sided"},
    "conductor": {"type", "material", "eta", "k", "specular_reflectance", "one_sided"},
    "roughconductor": {"type", "material", "eta", "k", "specular_reflectance", "distribution", "alpha", "alpha_u",
                       "alpha_v", "one_sided"},
    "dielectric": {"type", "int_ior", "ext_ior"},
    "roughdielectric": {"type", "int_ior", "ext_ior", "distribution", "alpha", "alpha_u", "alpha_v"},
    "thindielectric": {"type", "int_ior", "ext_ior"},
    "plastic": {"type", "diffuse_reflectance", "specular_reflectance", "int_ior", "ext_ior", "nonlinear", "one_sided"},
    "roughplastic": {"type", "diffuse_reflectance", "specular_reflectance", "int_ior", "ext_ior", "nonlinear",
                     "distribution", "alpha", "one_sided"},
    "normalmap": {"type", "normalmap", "bsdf"},
    "bumpmap": {"type", "bumpmap", "scale", "bsdf"},
    "mask": {"type", "opacity", "bsdf"},
}
SHAPE_KEYS = {
    "sphere": {"type", "material", "center", "radius"},
    "plane": {"type", "material", "point", "normal"},
    "quad": {"type", "material", "corner", "edge1", "edge2"},
    "mesh": {"type", "material", "file", "transform", "face_normals", "objects"},
}
TRANSFORM_KEYS = {"scale", "rotate", "translate", "matrix"}
TEXTURE_KEYS = {
    "bitmap": {"type", "file", "filter_type", "wrap_mode", "raw", "to_uv"},
    "checkerboard": {"type", "color0", "color1", "to_uv"},
}


# Small vector and matrix helpers (3-vectors and 4x4 row-major lists, in double).
def sub(a, b):
    return [x - y for x, y in zip(a, b)]


def add(a, b):
    return [x + y for x, y in zip(a, b)]


def scaled(a, s):
    return [x * s for x in a]


def dot(a, b):
    return sum(x * y for x, y in zip(a, b))


def cross(a, b):
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


def norm(a):
    return math.sqrt(dot(a, a))


def normalized(a):
    return scaled(a, 1.0 / norm(a))


def matmul(a, b):
    return [[sum(a[i][k] * b[k][j] for k in range(4)) for j in range(4)] for i in range(4)]


def translation(t):
    return [[1, 0, 0, t[0]], [0, 1, 0, t[1]], [0, 0, 1, t[2]], [0, 0, 0, 1]]


def determinant3(m):
    return dot(m[0][:3], cross(m[1][:3], m[2][:3]))


def rotation(axis, degrees):
    """Right-handed rotation about `axis` (counter-clockwise seen from its tip), Rodrigues' formula."""
    x, y, z = normalized(axis)
    c, s = math.cos(math.radians(degrees)), math.sin(math.radians(degrees))
    t = 1.0 - c
    return [[t * x * x + c, t * x * y - s * z, t * x * z + s * y, 0],
            [t * x * y + s * z, t * y * y + c, t * y * z - s * x, 0],
            [t * x * z - s * y, t * y * z + s * x, t * z * z + c, 0], [0, 0, 0, 1]]


class Converter:
    def __init__(self, scene_path, workdir):
        self.scene_path = scene_path
        self.workdir = workdir
        self.written = 0  # PLY files written into workdir
        with open(scene_path) as f:
            self.scene = json.load(f)
        self.origin = self.scene["camera"]["position"]  # everything is rebased to the camera

    def fail(self, where, problem):
        raise MitsubaSceneError(f"{self.scene_path}: {where}: {problem}")

    def check_keys(self, obj, allowed, where):
        for key in obj:
            if key not in allowed:
                self.fail(f"{where}.{key}" if where else key,
                          "not expressible in Mitsuba: the converter (scripts/mitsuba_scene.py) does not know this key")

    def convert(self, overrides):
        scene = self.scene
        self.check_keys(scene, TOP_KEYS, "")
        self.check_keys(scene["camera"], CAMERA_KEYS, "camera")
        render = {"spp": 16, "max_depth": 8, "rr_depth": 3, "seed": 0, **scene.get("render", {})}
        self.check_keys(render, RENDER_KEYS, "render")
        camera = {"up": [0, 1, 0], **scene["camera"]}
        for key in ("width", "height"):
            if overrides.get(key) is not None:
                camera[key] = overrides[key]
        for key in ("spp", "max_depth", "seed"):
            if overrides.get(key) is not None:
                render[key] = overrides[key]
        out = {"type": "scene", "integrator": self.integrator(render), "sensor": self.sensor(camera, render)}
        background = scene.get("background", [0, 0, 0])
        if any(c > 0 for c in background):
            out["background"] = {"type": "constant", "radiance": rgb(background)}
        self.textures = {name: self.texture(texture, f"textures.{name}")
                         for name, texture in scene.get("textures", {}).items()}
        for i, light in enumerate(scene.get("lights", [])):
            out[f"light_{i}"] = self.light(light, f"lights[{i}]")
        materials = {name: self.material(material, f"materials.{name}")
                     for name, material in scene.get("materials", {}).items()}
        extent = self.extent()
        for i, shape in enumerate(scene.get("shapes", [])):
            for k, part in enumerate(self.shape(shape, f"shapes[{i}]", materials, extent)):
                out[f"shape_{i}_{k}"] = part
        return out

    def material(self, material, where):
        """The material with its textured parameters (and a normalmap's, bumpmap's or mask's map and nested
        material's) made Mitsuba's."""
        kind = material.get("type")
        if kind not in MATERIAL_KEYS:
            self.fail(f"{where}.type", f"material type {json.dumps(kind)} has no Mitsuba counterpart here")
        self.check_keys(material, MATERIAL_KEYS[kind], where)
        textured = {key: self.mitsuba_texture(value["texture"], key) for key, value in material.items()
                    if key in TEXTURABLE_KEYS + ("normalmap", "bumpmap", "opacity") and isinstance(value, dict)}
        if kind in ("normalmap", "bumpmap", "mask"):
            textured["bsdf"] = self.material(material["bsdf"], f"{where}.bsdf")
        return {**material, **textured}

    def mitsuba_texture(self, name, key):
        """Texture `name` as material key `key` takes it. Mitsuba 3.9.1's checkerboard reads color1 where its eval
        reads color0 when a BSDF takes it as a scalar (eval_1: a roughness, a mask's opacity), where wavepath's
        checkerboard is the same pattern for every parameter: for a scalar key the colours are swapped, so that
        Mitsuba renders the pattern the wavepath scene means."""
        texture = self.textures[name]
        if texture["type"] == "checkerboard" and key in SCALAR_KEYS:
            # Mitsuba's defaults where the scene gives none (wavepath's are the same: 0.4 and 0.2)
            return {**texture, "color0": texture.get("color1", rgb([0.2] * 3)),
                    "color1": texture.get("color0", rgb([0.4] * 3))}
        return texture

    def texture(self, texture, where):
        """Mitsuba's texture of the same type and parameters; a bitmap's file is found from the scene's directory."""
        kind = texture.get("type")
        if kind not in TEXTURE_KEYS:
            self.fail(f"{where}.type", f"texture type {json.dumps(kind)} has no Mitsuba counterpart here")
        self.check_keys(texture, TEXTURE_KEYS[kind], where)
        out = {"type": kind}
        for key, value in texture.items():
            if key == "file":
                out["filename"] = os.path.abspath(os.path.join(os.path.dirname(self.scene_path), value))
            elif key in ("color0", "color1"):
                out[key] = rgb([value] * 3 if isinstance(value, (int, float)) else value)
            elif key == "to_uv":
                out[key] = {"to_uv": [list(map(float, row)) for row in value] + [[0.0, 0.0, 1.0]]}
            elif key != "type":
                out[key] = value
        return out

    def light(self, light, where):
        kind = light.get("type")
        if kind not in LIGHT_KEYS:
            self.fail(f"{where}.type", f"light type {json.dumps(kind)} has no Mitsuba counterpart here")
        self.check_keys(light, LIGHT_KEYS[kind], where)
        if kind == "envmap":
            out = {"type": "envmap", "scale": float(light.get("scale", 1.0)),
                   "filename": os.path.abspath(os.path.join(os.path.dirname(self.scene_path), light["filename"]))}
            if "to_world" in light:
                out["to_world"] = self.transform(light["to_world"], f"{where}.to_world")
            return out
        if kind == "point":
            return {"type": "point", "position": sub(light["position"], self.origin),
                    "intensity": rgb(light.get("intensity", [1, 1, 1]))}
        if kind == "spot":
            position = sub(light["position"], self.origin)
            direction = normalized(light["direction"])
            up = [1.0, 0.0, 0.0] if abs(direction[1]) > 0.9 else [0.0, 1.0, 0.0]  # any up not along the axis
            cutoff = float(light.get("cutoff_angle", 20.0))
            return {"type": "spot", "to_world": {"look_at": [position, add(position, direction), up]},
                    "intensity": rgb(light.get("intensity", [1, 1, 1])), "cutoff_angle": cutoff,
                    "beam_width": float(light.get("beam_width", 0.75 * cutoff))}
        return {"type": "directional", "direction": light["direction"],
                "irradiance": rgb(light.get("irradiance", [1, 1, 1]))}

    def integrator(self, render):
        # Mitsuba counts path segments (1: emitters seen directly), wavepath scattering events (0: the same).
        # rr_depth counts the same in both: Mitsuba plays the roulette at a hit once its segment count (that hit's
        # included) reaches rr_depth, wavepath once its bounce index plus one does (tests/oracle/
        # roulette_variance_test.py checks it by the variance). It changes the variance only; Mitsuba stores it
        # as a 32-bit int.
        return {"type": "path", "max_depth": render["max_depth"] + 1,
                "rr_depth": min(render["rr_depth"], render["max_depth"] + 2)}

    def sensor(self, camera, render):
        return {
            "type": "perspective", "fov": camera["fov_y"], "fov_axis": "y",
            "to_world": {"look_at": [[0, 0, 0], sub(camera["look_at"], self.origin), camera["up"]]},
            "film": {"type": "hdrfilm", "width": camera["width"], "height": camera["height"],
                     "rfilter": rfilter(camera.get("filter", {"type": "box"})), "pixel_format": "rgb",
                     "component_format": "float32"},
            "sampler": {"type": "independent", "sample_count": render["spp"], "seed": render["seed"]},
        }

    def extent(self):
        """The largest distance from the camera of any point the scene's finite shapes name (planes' size)."""
        far = 1.0
        for shape in self.scene.get("shapes", []):
            for key in ("center", "corner", "point"):
                if key in shape:
                    far = max(far, norm(sub(shape[key], self.origin)) + shape.get("radius", 0.0) +
                              norm(shape.get("edge1", [0, 0, 0])) + norm(shape.get("edge2", [0, 0, 0])))
        return far

    def shape(self, shape, where, materials, extent):
        """The Mitsuba shapes of one of ours: a list (two for a two-sided emitter)."""
        kind = shape.get("type")
        if kind not in SHAPE_KEYS:
            self.fail(f"{where}.type", f"shape type {json.dumps(kind)} has no Mitsuba counterpart here")
        self.check_keys(shape, SHAPE_KEYS[kind], where)
        material = materials[shape["material"]]
        if kind == "sphere":
            front = {"type": "sphere", "center": sub(shape["center"], self.origin), "radius": shape["radius"]}
        elif kind == "quad":
            corner = sub(shape["corner"], self.origin)
            front = self.quad_mesh(corner, shape["edge1"], shape["edge2"])
        elif kind == "plane":
            front = self.plane_mesh(sub(shape["point"], self.origin), shape["normal"], extent)
        else:
            front = self.mesh(shape, where)
        front["bsdf"] = bsdf(material)
        radiance = emission(material)
        if radiance is None:
            return [front]
        front["emitter"] = {"type": "area", "radiance": rgb(radiance)}
        if not material.get("two_sided", False):
            return [front]
        # Mitsuba's area emitter emits from the front only: the back side is a
        # flipped copy a hair behind the front (which hides it from the front side).
        gap = TWO_SIDED_GAP * extent
        if kind == "sphere":
            back = {**front, "radius": shape["radius"] - min(gap, shape["radius"] / 2), "flip_normals": True}
        elif kind == "quad":
            e1, e2 = shape["edge1"], shape["edge2"]
            behind = scaled(normalized(cross(e1, e2)), -gap)
            back = {**self.quad_mesh(add(sub(shape["corner"], self.origin), behind), e2, e1),
                    "bsdf": front["bsdf"], "emitter": front["emitter"]}
        else:
            self.fail(f"{where}.material", "a two-sided emitting mesh has no Mitsuba counterpart here "
                      "(Mitsuba's area emitter is one-sided; only quads and spheres get a flipped copy)")
        return [front, back]

    def quad_mesh(self, corner, edge1, edge2):
        """The parallelogram corner + u edge1 + v edge2 as two counter-clockwise triangles (normal edge1 x edge2)."""
        points = [corner, add(corner, edge1), add(add(corner, edge1), edge2), add(corner, edge2)]
        uvs = [(0, 0), (1, 0), (1, 1), (0, 1)]  # wavepath's quad uv: corner + u edge1 + v edge2 (shared/texture.h)
        return {"type": "ply", "filename": self.write_ply(points, [(0, 1, 2), (0, 2, 3)], uvs), "face_normals": True}

    def plane_mesh(self, point, normal, extent):
        """A square of half-size PLANE_EXTENT * extent in the plane, centred on the camera's foot point."""
        n = normalized(normal)
        foot = scaled(n, dot(point, n))  # the camera is at the origin
        helper = [1.0, 0.0, 0.0] if abs(n[0]) < 0.9 else [0.0, 1.0, 0.0]
        u = scaled(normalized(cross(helper, n)), PLANE_EXTENT * extent)
        v = cross(n, u)  # u x v is along n: the quad's normal is the plane's
        corner = sub(sub(foot, u), v)
        return self.quad_mesh(corner, scaled(u, 2.0), scaled(v, 2.0))

    def mesh(self, shape, where):
        path = os.path.join(os.path.dirname(self.scene_path), shape["file"])
        extension = os.path.splitext(path)[1].lower()
        if extension not in MESH_FORMATS:
            self.fail(f"{where}.file", f"{shape['file']}: Mitsuba reads OBJ and PLY meshes only, not {extension or 'this'}")
        to_world = matmul(translation(scaled(self.origin, -1.0)), self.transform(shape.get("transform", {}), where))
        try:
            has_normals = file_has_vertex_normals(path, extension)
        except OSError as e:
            self.fail(f"{where}.file", f"{shape['file']}: cannot open: {e.strerror}")
        keeps_normals = has_normals and not shape.get("face_normals", False)
        if "objects" in shape:
            if extension != ".obj":
                self.fail(f"{where}.objects", f"{shape['file']}: objects can be picked from OBJ files only here")
            if keeps_normals:
                self.fail(f"{where}.objects", f"{shape['file']}: picked objects lose the file's vertex normals "
                          "here (set face_normals)")
            points, faces = read_obj_objects(path, shape["objects"], lambda problem: self.fail(f"{where}.objects", problem))
            path, extension = self.write_ply(points, faces), ".ply"
        out = {"type": extension[1:], "filename": os.path.abspath(path), "to_world": to_world,
               "face_normals": not keeps_normals}
        # wavepath keeps a mirroring transform's front side where the file meant it; Mitsuba's face normal
        # follows the transformed corners, so it flips: flip it back.
        if determinant3(to_world) < 0:
            out["flip_normals"] = True
        return out

    def transform(self, t, where):
        """File to scene coordinates: scale, then rotate, then translate; or `matrix` (docs/scene-format.md)."""
        self.check_keys(t, TRANSFORM_KEYS, f"{where}.transform")
        if "matrix" in t:
            return [list(map(float, row)) for row in t["matrix"]]
        s = t.get("scale", 1.0)
        s = [s, s, s] if isinstance(s, (int, float)) else s
        m = [[s[0], 0, 0, 0], [0, s[1], 0, 0], [0, 0, s[2], 0], [0, 0, 0, 1]]
        if "rotate" in t:
            m = matmul(rotation(t["rotate"][:3], t["rotate"][3]), m)
        return matmul(translation(t.get("translate", [0, 0, 0])), m)

    def write_ply(self, points, faces, uvs=None):
        """A binary little-endian PLY of float positions (and uvs) and triangles in the work directory; returns its
        path."""
        os.makedirs(self.workdir, exist_ok=True)
        path = os.path.join(self.workdir, f"mesh_{self.written}.ply")
        self.written += 1
        header = (f"ply\nformat binary_little_endian 1.0\nelement vertex {len(points)}\n"
                  "property float x\nproperty float y\nproperty float z\n"
                  + ("property float u\nproperty float v\n" if uvs else "") +
                  f"element face {len(faces)}\nproperty list uchar int vertex_indices\nend_header\n")
        with open(path, "wb") as f:
            f.write(header.encode("ascii"))
            for k, p in enumerate(points):
                f.write(struct.pack("<3f", *p) + (struct.pack("<2f", *uvs[k]) if uvs else b""))
            for face in faces:
                f.write(struct.pack("<B3i", 3, *face))
        return os.path.abspath(path)


def rfilter(scene_filter):
    """The camera's pixel filter as Mitsuba's rfilter (the same names, parameters and defaults)."""
    kind = scene_filter["type"]
    if kind == "tent":
        return {"type": "tent", "radius": scene_filter.get("radius", 1.0)}
    if kind == "gaussian":
        return {"type": "gaussian", "stddev": scene_filter.get("stddev", 0.5)}
    return {"type": "box"}


def rgb(value):
    return {"type": "rgb", "value": list(map(float, value))}


def emission(material):
    """The material's emitted radiance, or None when it emits nothing."""
    radiance = material.get("radiance", material.get("emission"))
    return radiance if radiance is not None and any(c > 0 for c in radiance) else None


# The materials' parameters that may be {"texture": name} (docs/scene-format.md): colours, and
# the rough conductors' and dielectrics' roughness, which Mitsuba reads from the same texture plugins.
COLOUR_KEYS = ("albedo", "diffuse_reflectance", "specular_reflectance")
SCALAR_KEYS = ("alpha", "alpha_u", "alpha_v", "opacity")
TEXTURABLE_KEYS = COLOUR_KEYS + ("alpha", "alpha_u", "alpha_v")


def rgb_or_texture(value):
    """A constant colour, or a texture the converter already made Mitsuba's (Converter.texture)."""
    return value if isinstance(value, dict) else rgb(value)


def bsdf(material):
    """Mitsuba's BSDF for the material: inside a twosided, as wavepath's reflecting materials reflect on both sides,
    unless the material is one_sided (Mitsuba's BSDFs are black from the back)."""
    plugin = two_sided_bsdf(material)
    if material.get("one_sided") and plugin.get("type") == "twosided":
        return plugin["bsdf"]
    return plugin


def adapter_outside(adapter, nested):
    """A normalmap or bumpmap plugin inside a twosided, unless its nested material is one-sided."""
    return adapter if nested.get("one_sided") else {"type": "twosided", "bsdf": adapter}


def two_sided_bsdf(material):
    """Mitsuba's BSDF for the material, a reflecting one inside a twosided."""
    kind = material["type"]
    if kind == "diffuse":
        return {"type": "twosided", "bsdf": {"type": "diffuse", "reflectance": rgb_or_texture(material["albedo"])}}
    if kind == "mirror":
        return {"type": "twosided",
                "bsdf": {"type": "conductor", "material": "none", "specular_reflectance": rgb(material["reflectance"])}}
    if kind == "glass":
        return {"type": "dielectric", "int_ior": float(material["ior"]), "ext_ior": 1.0}
    if kind in ("conductor", "roughconductor", "plastic", "roughplastic"):
        # The same names and parameters: wavepath's materials are Mitsuba's, two-sided.
        plugin = {"type": kind}
        for key, value in material.items():
            if key in COLOUR_KEYS:
                plugin[key] = rgb_or_texture([value] * 3 if isinstance(value, (int, float)) else value)
            elif key in ("eta", "k"):
                plugin[key] = rgb([value] * 3 if isinstance(value, (int, float)) else value)
            elif key not in ("type", "one_sided"):
                plugin[key] = value
        return {"type": "twosided", "bsdf": plugin}
    if kind == "normalmap":
        # twosided outside: Mitsuba's nested BSDF is then black to an arrival
        # below the perturbed normal, as wavepath's (shared/normal_map.h)
        nested = two_sided_bsdf(material["bsdf"])
        return adapter_outside({"type": "normalmap", "normalmap": material["normalmap"], "bsdf": nested["bsdf"]},
                               material["bsdf"])
    if kind == "bumpmap":
        # twosided outside, as a normalmap's
        nested = two_sided_bsdf(material["bsdf"])
        return adapter_outside({"type": "bumpmap", "bumpmap": material["bumpmap"],
                                "scale": float(material.get("scale", 1.0)), "bsdf": nested["bsdf"]}, material["bsdf"])
    if kind == "mask":
        # the same plugin around the nested material's BSDF (twosided inside, as wavepath's materials are)
        opacity = material.get("opacity", 0.5)
        return {"type": "mask", "opacity": opacity if isinstance(opacity, dict) else float(opacity),
                "bsdf": bsdf(material["bsdf"])}
    if kind in ("dielectric", "roughdielectric", "thindielectric"):
        # The same names and parameters; a dielectric has two sides of its own (inside and outside).
        return dict(material)
    return {"type": "diffuse", "reflectance": rgb([0, 0, 0])}  # an emitter reflects nothing


def file_has_vertex_normals(path, extension):
    """Whether the file gives vertex normals (OBJ: `vn` lines; PLY: nx, ny, nz on its vertices)."""
    if extension == ".obj":
        with open(path, errors="replace") as f:
            return any(line.startswith("vn ") for line in f)
    with open(path, "rb") as f:
        header = []
        for line in f:
            header.append(line.decode("ascii", "replace").split())
            if header[-1] == ["end_header"]:
                break
    return any(words[:1] == ["property"] and words[-1] == "nx" for words in header)


def read_obj_objects(path, names, fail):
    """The positions and triangles of the named `o`/`g` objects of an OBJ file (polygons fanned)."""
    positions, faces, current, found = [], [], None, set()
    with open(path, errors="replace") as f:
        for line in f:
            words = line.split()
            if not words:
                continue
            if words[0] == "v":
                positions.append(list(map(float, words[1:4])))
            elif words[0] in ("o", "g"):
                current = " ".join(words[1:])
                found.add(current)
            elif words[0] == "f" and current in names:
                corners = [int(w.split("/")[0]) for w in words[1:]]
                corners = [c - 1 if c > 0 else len(positions) + c for c in corners]
                faces += [(corners[0], corners[k], corners[k + 1]) for k in range(1, len(corners) - 1)]
    for name in names:
        if name not in found:
            fail(f"no object named {json.dumps(name)} (objects: {', '.join(sorted(found)) or 'none'})")
    return positions, faces


def convert(scene_path, workdir, width=None, height=None, spp=None, max_depth=None, seed=None):
    """The Mitsuba scene dictionary of a wavepath scene file; meshes it writes go to `workdir`."""
    overrides = {"width": width, "height": height, "spp": spp, "max_depth": max_depth, "seed": seed}
    return Converter(scene_path, workdir).convert(overrides)


def open_mitsuba(variant):
    """The mitsuba module with `variant` set. Its LLVM variants get Debian's libLLVM 19 (scripts/setup.sh
    installs libllvm19): Dr.Jit crashes with Debian's default LLVM 15."""
    if variant.startswith("llvm"):
        os.environ.setdefault("DRJIT_LIBLLVM_PATH", LIBLLVM)
    import mitsuba as mi
    mi.set_variant(variant)
    return mi


def load(mi, scene_dict):
    """mi.load_dict of a converted dictionary, its transforms made Mitsuba transforms (variant already set)."""

    def to_mitsuba(value):
        if isinstance(value, dict):
            if set(value) == {"to_uv"}:  # a texture's to_uv, a 3x3 matrix (Converter.texture)
                return mi.ScalarTransform3f(value["to_uv"])
            return {k: to_world(v) if k == "to_world" else to_mitsuba(v) for k, v in value.items()}
        return value

    def to_world(value):
        if isinstance(value, dict):  # {"look_at": [origin, target, up]}
            origin, target, up = value["look_at"]
            return mi.ScalarTransform4f().look_at(origin=origin, target=target, up=up)
        return mi.ScalarTransform4f(value)

    return mi.load_dict(to_mitsuba(scene_dict))


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("scene")
    parser.add_argument("--workdir", default="mitsuba-meshes", help="where quads and picked objects go as PLY")
    for flag in ("width", "height", "spp", "max-depth", "seed"):
        parser.add_argument(f"--{flag}", type=int)
    args = parser.parse_args()
    try:
        out = convert(args.scene, args.workdir, args.width, args.height, args.spp, args.max_depth, args.seed)
    except MitsubaSceneError as e:
        print(f"mitsuba_scene: error: {e}", file=sys.stderr)
        return 3
    json.dump(out, sys.stdout, indent=1)
    print()
    return 0


if __name__ == "__main__":
    sys.exit(main())
