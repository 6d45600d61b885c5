#!/usr/bin/env python3
"""scripts/mitsuba_scene.py: the mapping of each part of a scene, and every refusal by name.

Pure Python (Mitsuba is not imported): the oracle test (mitsuba_oracle.py)
checks that the converted scenes render the same images; these tests pin the
conventions one at a time, so that a broken one names itself.
"""
import json
import math
import os
import struct
import sys
import tempfile
import unittest

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.join(ROOT, "scripts"))
import mitsuba_scene  # noqa: E402
from mitsuba_scene import MitsubaSceneError  # noqa: E402

CAMERA = {"position": [1, 2, 3], "look_at": [1, 2, 0], "fov_y": 40, "width": 8, "height": 6}
MATERIALS = {"white": {"type": "diffuse", "albedo": [0.5, 0.5, 0.5]}, "lamp": {"type": "emitter", "radiance": [2, 2, 2]}}
QUAD = {"type": "quad", "corner": [0, 0, 0], "edge1": [1, 0, 0], "edge2": [0, 1, 0], "material": "white"}


def apply(matrix, point):
    return [sum(matrix[i][k] * c for k, c in enumerate(point + [1.0])) for i in range(3)]


def read_ply(path, with_uvs=False):
    """Positions (and uvs) and triangles of a PLY file as mitsuba_scene writes it."""
    with open(path, "rb") as f:
        header = []
        while not header or header[-1] != "end_header":
            header.append(f.readline().decode().strip())
        vertices = int(next(line.split()[2] for line in header if line.startswith("element vertex")))
        faces = int(next(line.split()[2] for line in header if line.startswith("element face")))
        floats = sum(line.startswith("property float") for line in header)
        rows = [list(struct.unpack(f"<{floats}f", f.read(4 * floats))) for _ in range(vertices)]
        triangles = [struct.unpack("<B3i", f.read(13))[1:] for _ in range(faces)]
    points = [row[:3] for row in rows]
    return (points, [row[3:] for row in rows], triangles) if with_uvs else (points, triangles)


class ConverterTest(unittest.TestCase):
    def setUp(self):
        self.dir = tempfile.TemporaryDirectory(prefix="mitsuba-scene-test-")
        self.addCleanup(self.dir.cleanup)

    def write(self, name, text):
        path = os.path.join(self.dir.name, name)
        with open(path, "w") as f:
            f.write(text)
        return path

    def convert(self, shapes=(), materials=None, **top):
        scene = {"camera": CAMERA, "materials": materials or MATERIALS, "shapes": list(shapes), **top}
        path = self.write("scene.json", json.dumps(scene))
        return mitsuba_scene.convert(path, os.path.join(self.dir.name, "meshes"))

    def refused(self, expected, shapes=(), materials=None, **top):
        with self.assertRaises(MitsubaSceneError) as caught:
            self.convert(shapes, materials, **top)
        self.assertIn(expected, str(caught.exception))
        return str(caught.exception)

    def shapes(self, converted):
        return [v for k, v in converted.items() if k.startswith("shape_")]  # in the scene's order

    # Settings, camera and film.
    def test_depths_count_segments_in_mitsuba(self):
        out = self.convert(render={"max_depth": 5, "rr_depth": 2})
        self.assertEqual(out["integrator"], {"type": "path", "max_depth": 6, "rr_depth": 2})
        self.assertEqual(self.convert()["integrator"]["max_depth"], 9)  # the default max_depth 8

    def test_huge_rr_depth_fits_mitsubas_int(self):
        out = self.convert(render={"max_depth": 4, "rr_depth": 2147483647})
        self.assertEqual(out["integrator"]["rr_depth"], 6)  # beyond max_depth: roulette never starts

    def test_camera_is_rebased_and_fov_is_vertical(self):
        sensor = self.convert()["sensor"]
        self.assertEqual(sensor["to_world"], {"look_at": [[0, 0, 0], [0, 0, -3], [0, 1, 0]]})
        self.assertEqual((sensor["fov"], sensor["fov_axis"]), (40, "y"))
        film = sensor["film"]
        self.assertEqual((film["width"], film["height"], film["rfilter"]), (8, 6, {"type": "box"}))

    def test_overrides_replace_size_spp_depth_and_seed(self):
        path = self.write("scene.json", json.dumps({"camera": CAMERA}))
        out = mitsuba_scene.convert(path, self.dir.name, width=3, height=2, spp=7, max_depth=1, seed=9)
        self.assertEqual((out["sensor"]["film"]["width"], out["sensor"]["film"]["height"]), (3, 2))
        self.assertEqual(out["sensor"]["sampler"], {"type": "independent", "sample_count": 7, "seed": 9})
        self.assertEqual(out["integrator"]["max_depth"], 2)

    def test_background_is_a_constant_emitter_only_when_not_black(self):
        self.assertNotIn("background", self.convert())
        out = self.convert(background=[0.5, 0, 0])
        self.assertEqual(out["background"], {"type": "constant", "radiance": {"type": "rgb", "value": [0.5, 0, 0]}})

    def test_directional_lights_are_directional_emitters(self):
        out = self.convert(lights=[{"type": "directional", "direction": [0, -1, 0.5], "irradiance": [2, 1, 0.5]},
                                   {"type": "directional", "direction": [1, 0, 0]}])
        self.assertEqual(out["light_0"], {"type": "directional", "direction": [0, -1, 0.5],
                                          "irradiance": {"type": "rgb", "value": [2, 1, 0.5]}})
        self.assertEqual(out["light_1"]["irradiance"], {"type": "rgb", "value": [1, 1, 1]})
        self.refused("lights[0].type: light type \"area\" has no Mitsuba counterpart here", lights=[{"type": "area"}])
        self.refused("lights[0].angle: not expressible in Mitsuba",
                     lights=[{"type": "directional", "direction": [0, -1, 0], "angle": 1}])

    def test_point_and_spot_lights_are_point_and_spot_emitters(self):
        origin = CAMERA["position"]
        out = self.convert(lights=[{"type": "point", "position": [1, 2, 3], "intensity": [2, 1, 0.5]},
                                   {"type": "spot", "position": [0, 3, 0], "direction": [0, -2, 0],
                                    "intensity": [4, 4, 4], "cutoff_angle": 30, "beam_width": 10},
                                   {"type": "spot", "position": [0, 3, 0], "direction": [1, 0, 0]}])
        self.assertEqual(out["light_0"], {"type": "point", "position": [1 - origin[0], 2 - origin[1], 3 - origin[2]],
                                          "intensity": {"type": "rgb", "value": [2, 1, 0.5]}})
        spot = out["light_1"]
        self.assertEqual((spot["type"], spot["cutoff_angle"], spot["beam_width"]), ("spot", 30.0, 10.0))
        at, target, up = spot["to_world"]["look_at"]  # from the position along the unit direction, up not along it
        self.assertEqual(at, [0 - origin[0], 3 - origin[1], 0 - origin[2]])
        self.assertEqual(mitsuba_scene.sub(target, at), [0.0, -1.0, 0.0])
        self.assertEqual(up, [1.0, 0.0, 0.0])
        self.assertEqual((out["light_2"]["cutoff_angle"], out["light_2"]["beam_width"]), (20.0, 15.0))  # Mitsuba's
        self.assertEqual(out["light_2"]["intensity"], {"type": "rgb", "value": [1, 1, 1]})
        self.refused("lights[0].to_world: not expressible in Mitsuba",
                     lights=[{"type": "spot", "position": [0, 1, 0], "direction": [0, -1, 0], "to_world": {}}])

    def test_envmap_lights_are_envmap_emitters(self):
        out = self.convert(lights=[{"type": "envmap", "filename": "sky.exr", "scale": 2,
                                    "to_world": {"rotate": [0, 1, 0, 90]}}])
        self.assertEqual(out["light_0"]["type"], "envmap")
        self.assertEqual(out["light_0"]["filename"], os.path.join(self.dir.name, "sky.exr"))  # beside the scene
        self.assertEqual(out["light_0"]["scale"], 2.0)
        to_world = out["light_0"]["to_world"]  # +x turned 90 degrees about +y: -z
        self.assertAlmostEqual(to_world[2][0], -1.0)
        self.assertAlmostEqual(to_world[0][0], 0.0)
        self.assertNotIn("to_world", self.convert(lights=[{"type": "envmap", "filename": "sky.exr"}])["light_0"])
        self.refused("lights[0].irradiance: not expressible in Mitsuba",
                     lights=[{"type": "envmap", "filename": "sky.exr", "irradiance": [1, 1, 1]}])

    # Materials.
    def test_materials(self):
        materials = {"d": {"type": "diffuse", "albedo": [0.1, 0.2, 0.3]}, "m": {"type": "mirror", "reflectance": [0.9, 0.8, 0.7]},
                     "g": {"type": "glass", "ior": 1.33}, "e": {"type": "emitter", "radiance": [1, 2, 3]}}
        shapes = [{**QUAD, "material": name} for name in "dmge"]
        d, m, g, e = self.shapes(self.convert(shapes, materials))
        self.assertEqual(d["bsdf"], {"type": "twosided", "bsdf": {"type": "diffuse", "reflectance": {"type": "rgb", "value": [0.1, 0.2, 0.3]}}})
        self.assertEqual(m["bsdf"]["bsdf"], {"type": "conductor", "material": "none",
                                             "specular_reflectance": {"type": "rgb", "value": [0.9, 0.8, 0.7]}})
        self.assertEqual(g["bsdf"], {"type": "dielectric", "int_ior": 1.33, "ext_ior": 1.0})
        self.assertEqual(e["bsdf"]["reflectance"]["value"], [0, 0, 0])
        self.assertEqual(e["emitter"], {"type": "area", "radiance": {"type": "rgb", "value": [1, 2, 3]}})
        self.assertNotIn("emitter", d)

    def test_plastics_are_twosided_around_mitsubas_plugins(self):
        materials = {"p": {"type": "plastic", "diffuse_reflectance": [0.7, 0.2, 0.1], "int_ior": "bk7", "nonlinear": True},
                     "r": {"type": "roughplastic", "diffuse_reflectance": 0.4, "specular_reflectance": [0.9, 0.8, 0.7],
                           "distribution": "ggx", "alpha": 0.3, "ext_ior": 1.2}}
        p, r = self.shapes(self.convert([{**QUAD, "material": "p"}, {**QUAD, "material": "r"}], materials))
        self.assertEqual(p["bsdf"], {"type": "twosided", "bsdf": {
            "type": "plastic", "diffuse_reflectance": {"type": "rgb", "value": [0.7, 0.2, 0.1]}, "int_ior": "bk7",
            "nonlinear": True}})
        self.assertEqual(r["bsdf"], {"type": "twosided", "bsdf": {
            "type": "roughplastic", "diffuse_reflectance": {"type": "rgb", "value": [0.4, 0.4, 0.4]},
            "specular_reflectance": {"type": "rgb", "value": [0.9, 0.8, 0.7]}, "distribution": "ggx", "alpha": 0.3,
            "ext_ior": 1.2}})

    def test_textures_become_mitsubas_plugins_of_the_same_names(self):
        textures = {"c": {"type": "checkerboard", "color0": 0.5, "color1": [0.1, 0.2, 0.3], "to_uv": [[2, 0, 1], [0, 3, 0]]},
                    "b": {"type": "bitmap", "file": "t.png", "filter_type": "nearest", "wrap_mode": "mirror", "raw": True}}
        materials = {"dc": {"type": "diffuse", "albedo": {"texture": "c"}}, "db": {"type": "diffuse", "albedo": {"texture": "b"}}}
        dc, db = self.shapes(self.convert([{**QUAD, "material": "dc"}, {**QUAD, "material": "db"}], materials, textures=textures))
        self.assertEqual(dc["bsdf"]["bsdf"]["reflectance"],
                         {"type": "checkerboard", "color0": {"type": "rgb", "value": [0.5, 0.5, 0.5]},
                          "color1": {"type": "rgb", "value": [0.1, 0.2, 0.3]},
                          "to_uv": {"to_uv": [[2.0, 0.0, 1.0], [0.0, 3.0, 0.0], [0.0, 0.0, 1.0]]}})
        self.assertEqual(db["bsdf"]["bsdf"]["reflectance"],
                         {"type": "bitmap", "filename": os.path.join(self.dir.name, "t.png"), "filter_type": "nearest",
                          "wrap_mode": "mirror", "raw": True})
        self.refused("textures.n.type: texture type \"noise\" has no Mitsuba counterpart here",
                     textures={"n": {"type": "noise"}})

    def test_textured_plastic_and_conductor_parameters_become_their_textures(self):
        textures = {"c": {"type": "checkerboard"}}
        materials = {"p": {"type": "roughplastic", "diffuse_reflectance": {"texture": "c"}, "specular_reflectance": 0.5},
                     "m": {"type": "conductor", "material": "Au", "specular_reflectance": {"texture": "c"}}}
        p, m = self.shapes(self.convert([{**QUAD, "material": "p"}, {**QUAD, "material": "m"}], materials,
                                        textures=textures))
        self.assertEqual(p["bsdf"]["bsdf"]["diffuse_reflectance"]["type"], "checkerboard")
        self.assertEqual(p["bsdf"]["bsdf"]["specular_reflectance"], {"type": "rgb", "value": [0.5, 0.5, 0.5]})
        self.assertEqual(m["bsdf"]["bsdf"]["specular_reflectance"]["type"], "checkerboard")
        self.assertEqual(m["bsdf"]["bsdf"]["material"], "Au")

    def test_textured_roughness_becomes_its_texture_and_a_number_stays_one(self):
        materials = {"r": {"type": "roughconductor", "alpha_u": {"texture": "c"}, "alpha_v": 0.2},
                     "g": {"type": "roughdielectric", "alpha": {"texture": "c"}}}
        r, g = self.shapes(self.convert([{**QUAD, "material": "r"}, {**QUAD, "material": "g"}], materials,
                                        textures={"c": {"type": "checkerboard"}}))
        self.assertEqual(r["bsdf"]["bsdf"]["alpha_u"]["type"], "checkerboard")
        self.assertEqual(r["bsdf"]["bsdf"]["alpha_v"], 0.2)
        self.assertEqual(g["bsdf"]["alpha"]["type"], "checkerboard")

    def test_mask_is_mask_around_the_nested_plugin_and_a_checkerboard_opacity_swaps_its_colours(self):
        # Mitsuba 3.9.1's checkerboard read as a number (eval_1) gives color1 where its colour lookup gives color0
        textures = {"c": {"type": "checkerboard", "color0": 1, "color1": 0}}
        materials = {"m": {"type": "mask", "opacity": {"texture": "c"},
                           "bsdf": {"type": "diffuse", "albedo": {"texture": "c"}}},
                     "h": {"type": "mask", "bsdf": {"type": "dielectric", "int_ior": 1.5, "ext_ior": 1.0}}}
        m, h = self.shapes(self.convert([{**QUAD, "material": "m"}, {**QUAD, "material": "h"}], materials,
                                        textures=textures))
        self.assertEqual(m["bsdf"]["type"], "mask")
        one, zero = {"type": "rgb", "value": [1, 1, 1]}, {"type": "rgb", "value": [0, 0, 0]}
        self.assertEqual((m["bsdf"]["opacity"]["color0"], m["bsdf"]["opacity"]["color1"]), (zero, one))
        nested = m["bsdf"]["bsdf"]
        self.assertEqual(nested["type"], "twosided")
        self.assertEqual((nested["bsdf"]["reflectance"]["color0"], nested["bsdf"]["reflectance"]["color1"]),
                         (one, zero))  # a colour: as it is
        self.assertEqual(h["bsdf"]["opacity"], 0.5)  # Mitsuba's default, written out
        self.assertEqual(h["bsdf"]["bsdf"]["type"], "dielectric")

    def test_normalmap_is_twosided_around_normalmap_around_the_nested_plugin(self):
        textures = {"n": {"type": "bitmap", "file": "n.png", "raw": True}, "c": {"type": "checkerboard"}}
        materials = {"m": {"type": "normalmap", "normalmap": {"texture": "n"},
                           "bsdf": {"type": "roughplastic", "diffuse_reflectance": {"texture": "c"}}}}
        m, = self.shapes(self.convert([{**QUAD, "material": "m"}], materials, textures=textures))
        self.assertEqual(m["bsdf"]["type"], "twosided")
        self.assertEqual(m["bsdf"]["bsdf"]["type"], "normalmap")
        self.assertEqual(m["bsdf"]["bsdf"]["normalmap"],
                         {"type": "bitmap", "filename": os.path.join(self.dir.name, "n.png"), "raw": True})
        nested = m["bsdf"]["bsdf"]["bsdf"]
        self.assertEqual(nested["type"], "roughplastic")
        self.assertEqual(nested["diffuse_reflectance"]["type"], "checkerboard")

    def test_bumpmap_is_twosided_around_bumpmap_with_its_scale_around_the_nested_plugin(self):
        textures = {"h": {"type": "bitmap", "file": "h.png", "raw": True}}
        materials = {"m": {"type": "bumpmap", "bumpmap": {"texture": "h"}, "scale": 0.25,
                           "bsdf": {"type": "diffuse", "albedo": [0.5, 0.5, 0.5]}},
                     "d": {"type": "bumpmap", "bumpmap": {"texture": "h"}, "bsdf": {"type": "conductor"}}}
        m, d = self.shapes(self.convert([{**QUAD, "material": "m"}, {**QUAD, "material": "d"}], materials,
                                        textures=textures))
        self.assertEqual(m["bsdf"]["type"], "twosided")
        bump = m["bsdf"]["bsdf"]
        self.assertEqual(bump["type"], "bumpmap")
        self.assertEqual(bump["scale"], 0.25)
        self.assertEqual(bump["bumpmap"],
                         {"type": "bitmap", "filename": os.path.join(self.dir.name, "h.png"), "raw": True})
        self.assertEqual(bump["bsdf"]["type"], "diffuse")
        self.assertEqual(d["bsdf"]["bsdf"]["scale"], 1.0)  # Mitsuba's default
        self.assertEqual(d["bsdf"]["bsdf"]["bsdf"]["type"], "conductor")

    def test_diffuse_emission_makes_an_area_emitter(self):
        materials = {"glow": {"type": "diffuse", "albedo": [0.5, 0.5, 0.5], "emission": [0, 0.5, 0]},
                     "dark": {"type": "diffuse", "albedo": [0.5, 0.5, 0.5], "emission": [0, 0, 0]}}
        glow, dark = self.shapes(self.convert([{**QUAD, "material": "glow"}, {**QUAD, "material": "dark"}], materials))
        self.assertEqual(glow["emitter"]["radiance"]["value"], [0, 0.5, 0])
        self.assertNotIn("emitter", dark)

    # Shapes.
    def test_sphere_is_rebased(self):
        (sphere,) = self.shapes(self.convert([{"type": "sphere", "center": [1, 2, 0], "radius": 0.5, "material": "white"}]))
        self.assertEqual((sphere["type"], sphere["center"], sphere["radius"]), ("sphere", [0, 0, -3], 0.5))

    def test_quad_is_two_counter_clockwise_triangles_about_edge1_cross_edge2(self):
        sheared = {**QUAD, "corner": [1, 2, 1], "edge1": [2, 0, 0], "edge2": [1, 1, 0]}
        (quad,) = self.shapes(self.convert([sheared]))
        points, uvs, triangles = read_ply(quad["filename"], with_uvs=True)
        self.assertEqual(points, [[0, 0, -2], [2, 0, -2], [3, 1, -2], [1, 1, -2]])
        self.assertEqual(uvs, [[0, 0], [1, 0], [1, 1], [0, 1]])  # wavepath's quad uvs (shared/texture.h)
        for a, b, c in triangles:
            normal = mitsuba_scene.cross(mitsuba_scene.sub(points[b], points[a]), mitsuba_scene.sub(points[c], points[a]))
            self.assertGreater(normal[2], 0)  # edge1 x edge2 = +z
        self.assertEqual(sorted(v for t in triangles for v in t), [0, 0, 1, 2, 2, 3])

    def test_plane_is_a_large_square_through_the_plane_facing_its_normal(self):
        plane = {"type": "plane", "point": [5, 0, 0], "normal": [0, 2, 0], "material": "white"}
        quad = self.shapes(self.convert([plane, {**QUAD, "corner": [1, 2, -7]}]))[0]
        points, triangles = read_ply(quad["filename"])
        self.assertTrue(all(abs(p[1] + 2) < 1e-3 for p in points))  # y = 0, rebased by the camera's y = 2
        xs, zs = [p[0] for p in points], [p[2] for p in points]
        self.assertLess(max(xs), -min(xs) * 1.0001)  # centred on the camera's foot point
        self.assertGreater(max(xs) - min(xs), 1000 * 10)  # far beyond the scene (extent ~10 from the camera)
        self.assertGreater(max(zs) - min(zs), 1000 * 10)
        a, b, c = triangles[0]
        normal = mitsuba_scene.cross(mitsuba_scene.sub(points[b], points[a]), mitsuba_scene.sub(points[c], points[a]))
        self.assertGreater(normal[1], 0)

    def test_two_sided_quad_gets_a_flipped_copy_behind_it(self):
        materials = {"lamp": {"type": "emitter", "radiance": [1, 1, 1], "two_sided": True}}
        front, back = self.shapes(self.convert([{**QUAD, "material": "lamp"}], materials))
        front_points, _ = read_ply(front["filename"])
        back_points, back_triangles = read_ply(back["filename"])
        self.assertTrue(all(p[2] < -3 and p[2] > -3.01 for p in back_points))  # behind: along -(edge1 x edge2)
        a, b, c = back_triangles[0]
        normal = mitsuba_scene.cross(mitsuba_scene.sub(back_points[b], back_points[a]),
                                     mitsuba_scene.sub(back_points[c], back_points[a]))
        self.assertLess(normal[2], 0)
        self.assertEqual(back["emitter"], front["emitter"])

    def test_two_sided_sphere_gets_a_flipped_copy_inside_it(self):
        materials = {"lamp": {"type": "emitter", "radiance": [1, 1, 1], "two_sided": True}}
        front, back = self.shapes(self.convert([{"type": "sphere", "center": [1, 2, 0], "radius": 1, "material": "lamp"}],
                                               materials))
        self.assertTrue(back["flip_normals"])
        self.assertLess(back["radius"], 1)
        self.assertGreater(back["radius"], 0.99)
        self.assertNotIn("flip_normals", front)

    # Meshes.
    def test_mesh_transform_scales_then_rotates_then_translates(self):
        self.write("tri.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n")
        mesh = {"type": "mesh", "file": "tri.obj", "material": "white",
                "transform": {"translate": [1, 0, 0], "rotate": [0, 1, 0, 90], "scale": [2, 3, 4]}}
        (out,) = self.shapes(self.convert([mesh]))
        self.assertEqual(out["type"], "obj")
        self.assertEqual(out["filename"], os.path.join(self.dir.name, "tri.obj"))
        # (1, 0, 0): scaled to (2, 0, 0) (a rotation first would give (0, 0, -4)), turned counter-clockwise about +y to (0, 0, -2), moved to (1, 0, -2),
        # rebased by the camera (1, 2, 3)
        for got, want in zip(apply(out["to_world"], [1.0, 0.0, 0.0]), [0, -2, -5]):
            self.assertAlmostEqual(got, want, places=12)
        self.assertNotIn("flip_normals", out)

    def test_mesh_matrix_transform(self):
        self.write("tri.ply", "ply\nformat ascii 1.0\nelement vertex 0\nproperty float x\nend_header\n")
        matrix = [[0, -1, 0, 4], [1, 0, 0, 5], [0, 0, 1, 6], [0, 0, 0, 1]]
        (out,) = self.shapes(self.convert([{"type": "mesh", "file": "tri.ply", "material": "white",
                                            "transform": {"matrix": matrix}}]))
        self.assertEqual(out["type"], "ply")
        self.assertEqual(apply(out["to_world"], [1.0, 0.0, 0.0]), [3, 4, 3])

    def test_mirroring_transform_flips_normals_back(self):
        self.write("tri.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n")
        mesh = {"type": "mesh", "file": "tri.obj", "material": "white", "transform": {"scale": [1, -1, 1]}}
        (out,) = self.shapes(self.convert([mesh]))
        self.assertTrue(out["flip_normals"])

    def test_face_normals_unless_the_file_has_vertex_normals_and_keeps_them(self):
        self.write("plain.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n")
        self.write("smooth.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nf 1//1 2//1 3//1\n")
        self.write("smooth.ply", "ply\nformat ascii 1.0\nelement vertex 0\nproperty float x\nproperty float nx\nend_header\n")
        shapes = [{"type": "mesh", "file": "plain.obj", "material": "white"},
                  {"type": "mesh", "file": "smooth.obj", "material": "white"},
                  {"type": "mesh", "file": "smooth.obj", "material": "white", "face_normals": True},
                  {"type": "mesh", "file": "smooth.ply", "material": "white"}]
        self.assertEqual([s["face_normals"] for s in self.shapes(self.convert(shapes))], [True, False, True, False])

    def test_objects_are_picked_from_an_obj_file(self):
        self.write("parts.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\no a\nf 1 2 3\no b\nf 2 4 3\nf 1 2 4 3\n")
        (out,) = self.shapes(self.convert([{"type": "mesh", "file": "parts.obj", "objects": ["b"], "material": "white"}]))
        self.assertEqual(out["type"], "ply")
        self.assertEqual(read_ply(out["filename"])[1], [(1, 3, 2), (0, 1, 3), (0, 3, 2)])  # the quad fanned

    # Refusals, each naming the scene, the JSON path and the problem.
    def test_unknown_keys_are_refused_by_name(self):
        message = self.refused("materials.white.roughness: not expressible in Mitsuba",
                               materials={"white": {"type": "diffuse", "albedo": [1, 1, 1], "roughness": 0.1}})
        self.assertTrue(message.startswith(os.path.join(self.dir.name, "scene.json") + ": "))
        self.refused("shapes[0].uv: not expressible", shapes=[{**QUAD, "uv": [0, 1]}])
        self.refused("render.tonemap: not expressible", render={"tonemap": True})
        self.refused("fog: not expressible", fog=1)

    def test_unknown_types_are_refused(self):
        self.refused('materials.x.type: material type "metal" has no Mitsuba counterpart',
                     materials={"x": {"type": "metal"}})
        self.refused('shapes[0].type: shape type "disk" has no Mitsuba counterpart',
                     shapes=[{"type": "disk", "material": "white"}])

    def test_mesh_formats_mitsuba_cannot_read_are_refused(self):
        self.write("box.stl", "solid box\nendsolid box\n")
        self.refused("shapes[0].file: box.stl: Mitsuba reads OBJ and PLY meshes only, not .stl",
                     shapes=[{"type": "mesh", "file": "box.stl", "material": "white"}])

    def test_missing_mesh_file_is_refused(self):
        self.refused("shapes[0].file: gone.obj: cannot open: No such file or directory",
                     shapes=[{"type": "mesh", "file": "gone.obj", "material": "white"}])

    def test_objects_only_from_obj_files_and_by_existing_names(self):
        self.write("parts.ply", "ply\nformat ascii 1.0\nelement vertex 0\nproperty float x\nend_header\n")
        self.refused("shapes[0].objects: parts.ply: objects can be picked from OBJ files only",
                     shapes=[{"type": "mesh", "file": "parts.ply", "objects": ["a"], "material": "white"}])
        self.write("parts.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\no a\nf 1 2 3\n")
        self.refused('shapes[0].objects: no object named "z" (objects: a)',
                     shapes=[{"type": "mesh", "file": "parts.obj", "objects": ["z"], "material": "white"}])
        self.write("smooth.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\no a\nf 1//1 2//1 3//1\n")
        self.refused("shapes[0].objects: smooth.obj: picked objects lose the file's vertex normals",
                     shapes=[{"type": "mesh", "file": "smooth.obj", "objects": ["a"], "material": "white"}])

    def test_two_sided_emitting_mesh_is_refused(self):
        self.write("tri.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n")
        self.refused("shapes[0].material: a two-sided emitting mesh has no Mitsuba counterpart",
                     shapes=[{"type": "mesh", "file": "tri.obj", "material": "lamp"}],
                     materials={"lamp": {"type": "emitter", "radiance": [1, 1, 1], "two_sided": True}})

    def test_every_shipped_scene_converts(self):
        for folder in ("scenes", os.path.join("scenes", "test")):
            for name in sorted(os.listdir(os.path.join(ROOT, folder))):
                if name.endswith(".json"):
                    with self.subTest(scene=name):
                        out = mitsuba_scene.convert(os.path.join(ROOT, folder, name), self.dir.name)
                        self.assertTrue(any(k.startswith("shape_") for k in out))

    def test_rotation_is_right_handed(self):
        r = mitsuba_scene.rotation([0, 0, 2], 90)  # about +z: x to y
        for got, want in zip(apply(r, [1.0, 0.0, 0.0]), [0, 1, 0]):
            self.assertAlmostEqual(got, want, places=12)
        self.assertAlmostEqual(mitsuba_scene.determinant3(r), 1.0, places=12)
        self.assertAlmostEqual(math.hypot(*apply(r, [0.6, 0.8, 0.0])), 1.0, places=12)


if __name__ == "__main__":
    unittest.main()
