#!/usr/bin/env python3
"""Writes the glTF test scenes of this folder (tests/scene/gltf_scene_test.cpp):
each value a float32 exactly (dyadic), so that the glTF reader and the JSON
written by hand beside each (<name>.json) make the same Scene.

    python3 scenes/test/gltf/make_gltf.py
"""
import base64
import json
import os
import struct

HERE = os.path.dirname(os.path.abspath(__file__))


def quad(corner, edge1, edge2):
    """Four corners and two triangles whose front is edge1 x edge2."""
    c = corner
    p = [c, [c[i] + edge1[i] for i in range(3)], [c[i] + edge1[i] + edge2[i] for i in range(3)],
         [c[i] + edge2[i] for i in range(3)]]
    return p, [0, 1, 2, 0, 2, 3]


def gltf(meshes, nodes, materials, extra_nodes, extensions=None, cameras=None, image=None):
    """meshes: (positions, indices, material[, uvs]) each; nodes: (name, mesh, matrix or None);
    image: texture 0's image, {"uri": file} or {"bytes": the file's bytes, "mimeType": ...} (embedded)."""
    blob = b""
    accessors, views, gmeshes = [], [], []
    for positions, indices, material, *uvs in meshes:
        attributes = {}
        if uvs:
            start = len(blob)
            for uv in uvs[0]:
                blob += struct.pack("<2f", *uv)
            views.append({"buffer": 0, "byteOffset": start, "byteLength": len(blob) - start})
            accessors.append({"bufferView": len(views) - 1, "componentType": 5126, "count": len(uvs[0]),
                              "type": "VEC2"})
            attributes["TEXCOORD_0"] = len(accessors) - 1
        start = len(blob)
        for p in positions:
            blob += struct.pack("<3f", *p)
        views.append({"buffer": 0, "byteOffset": start, "byteLength": len(blob) - start})
        accessors.append({"bufferView": len(views) - 1, "componentType": 5126, "count": len(positions),
                          "type": "VEC3", "min": [min(p[i] for p in positions) for i in range(3)],
                          "max": [max(p[i] for p in positions) for i in range(3)]})
        start = len(blob)
        for i in indices:
            blob += struct.pack("<H", i)
        blob += b"\0" * (-len(blob) % 4)
        views.append({"buffer": 0, "byteOffset": start, "byteLength": 2 * len(indices)})
        accessors.append({"bufferView": len(views) - 1, "componentType": 5123, "count": len(indices),
                          "type": "SCALAR"})
        gmeshes.append({"primitives": [{"attributes": dict(attributes, POSITION=len(accessors) - 2),
                                        "indices": len(accessors) - 1, "material": material, "mode": 4}]})
    gnodes = []
    for name, mesh, matrix in nodes:
        node = {"name": name, "mesh": mesh}
        if matrix:
            node["matrix"] = matrix
        gnodes.append(node)
    gnodes += extra_nodes
    images = []
    if image and "bytes" in image:
        start = len(blob)
        blob += image["bytes"] + b"\0" * (-len(image["bytes"]) % 4)
        views.append({"buffer": 0, "byteOffset": start, "byteLength": len(image["bytes"])})
        images.append({"bufferView": len(views) - 1, "mimeType": image["mimeType"]})
    elif image:
        images.append({"uri": image["uri"]})
    out = {"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": list(range(len(gnodes)))}],
           "nodes": gnodes, "meshes": gmeshes, "materials": materials, "accessors": accessors,
           "bufferViews": views,
           "buffers": [{"byteLength": len(blob),
                        "uri": "data:application/octet-stream;base64," + base64.b64encode(blob).decode()}]}
    if images:
        out["textures"] = [{"source": 0}]
        out["images"] = images
    if cameras:
        out["cameras"] = cameras
    if extensions:
        out["extensions"] = extensions
        out["extensionsUsed"] = sorted(extensions.keys()) + ["KHR_materials_emissive_strength"]
    return out


def write(name, document):
    with open(os.path.join(HERE, name), "w") as f:
        json.dump(document, f, indent=1)
        f.write("\n")


def write_glb(name, document):
    """The binary container: the JSON chunk, then the buffer as the BIN chunk (buffer 0 without a uri)."""
    document = json.loads(json.dumps(document))
    buffer = document["buffers"][0]
    blob = base64.b64decode(buffer.pop("uri").split(",", 1)[1])
    text = json.dumps(document).encode()
    text += b" " * (-len(text) % 4)
    blob += b"\0" * (-len(blob) % 4)
    chunks = struct.pack("<I4s", len(text), b"JSON") + text + struct.pack("<I4s", len(blob), b"BIN\0") + blob
    with open(os.path.join(HERE, name), "wb") as f:
        f.write(struct.pack("<4sII", b"glTF", 2, 12 + len(chunks)) + chunks)


def pbr(name, base, metallic, roughness, **extra):
    m = {"name": name, "pbrMetallicRoughness": {"baseColorFactor": base + [1.0], "metallicFactor": metallic,
                                                  "roughnessFactor": roughness}}
    m.update(extra)
    return m


def main():
    floor = quad([-2, 0, 2], [4, 0, 0], [0, 0, -4])
    block = quad([-0.5, 0, 0], [1, 0, 0], [0, 1, 0])
    coat = quad([-1.5, 0, -0.5], [1, 0, 0], [0, 1, 0])
    lamp = quad([-0.5, 2.5, -0.5], [1, 0, 0], [0, 0, 1])  # (1, 0, 0) x (0, 0, 1) = (0, -1, 0): it faces down
    materials = [
        pbr("red", [0.75, 0.25, 0.25], 0.0, 1.0),
        pbr("gold", [1.0, 0.75, 0.375], 1.0, 0.5),
        pbr("coat", [0.25, 0.5, 0.75], 0.0, 0.25),
        dict(pbr("lamp", [0.5, 0.5, 0.5], 0.0, 1.0), emissiveFactor=[1.0, 1.0, 0.5],
             extensions={"KHR_materials_emissive_strength": {"emissiveStrength": 4.0}}),
    ]
    rotate_y_90 = [0, 0, -1, 0, 0, 1, 0, 0, 1, 0, 0, 0, 0.5, 0, 0, 1]  # column-major, then translate x 0.5
    down = [1, 0, 0, 0, 0, 0, -1, 0, 0, 1, 0, 0, 0, 0, 0, 1]  # -z to -y
    nodes = [("Floor", 0, None), ("Block", 1, rotate_y_90), ("Coat", 2, None), ("Lamp", 3, None)]
    extra = [{"name": "Camera", "camera": 0, "translation": [0, 1, 5]},
             {"name": "Sun", "matrix": down, "extensions": {"KHR_lights_punctual": {"light": 0}}}]
    cameras = [{"type": "perspective", "perspective": {"yfov": 0.5, "aspectRatio": 1.5, "znear": 0.01}}]
    lights = {"KHR_lights_punctual": {"lights": [{"name": "Sun", "type": "directional", "color": [1, 1, 0.75],
                                                  "intensity": 2}]}}
    meshes = [(floor[0], floor[1], 0), (block[0], block[1], 1), (coat[0], coat[1], 2), (lamp[0], lamp[1], 3)]
    write("materials.gltf", gltf(meshes, nodes, materials, extra, lights, cameras))
    write_glb("materials.glb", gltf(meshes, nodes, materials, extra, lights, cameras))
    # A grey floor 1 below a point light of intensity 1, seen from 3 above it (GltfCli's irradiance test).
    grey = [pbr("grey", [0.5, 0.5, 0.5], 0.0, 1.0)]
    look_down = [1, 0, 0, 0, 0, 0, -1, 0, 0, 1, 0, 0, 0, 3, 0, 1]  # -z to -y, then up 3
    bulb = [{"name": "Bulb", "translation": [0, 1, 0], "extensions": {"KHR_lights_punctual": {"light": 0}}},
            {"name": "Camera", "camera": 0, "matrix": look_down}]
    square = [{"type": "perspective", "perspective": {"yfov": 0.25, "aspectRatio": 1.0, "znear": 0.01}}]
    point = {"KHR_lights_punctual": {"lights": [{"name": "Bulb", "type": "point", "intensity": 1}]}}
    write("point_light.gltf", gltf([(floor[0], floor[1], 0)], [("Floor", 0, None)], grey, bulb, point, square))
    # The grey floor under a spot 2 above it, pointing down (the node's -z; innerConeAngle and
    # outerConeAngle its beam width and cutoff angle), and a coloured point light beside it
    # (GltfScene.PointAndSpotLightsMakeTheSceneOfTheirHandWrittenJson).
    spot_down = [1, 0, 0, 0, 0, 0, -1, 0, 0, 1, 0, 0, 0, 2, 0, 1]  # -z to -y, then up 2
    lamps = [{"name": "Spot", "matrix": spot_down, "extensions": {"KHR_lights_punctual": {"light": 0}}},
             {"name": "Bulb", "translation": [1, 0.5, -1], "extensions": {"KHR_lights_punctual": {"light": 1}}},
             bulb[1]]
    spot = {"KHR_lights_punctual": {"lights": [
        {"name": "Spot", "type": "spot", "color": [1, 0.75, 0.5], "intensity": 4,
         "spot": {"innerConeAngle": 0.25, "outerConeAngle": 0.5}},
        {"name": "Bulb", "type": "point", "color": [0.5, 0.5, 1], "intensity": 2, "range": 8}]}}
    write("spot_light.gltf", gltf([(floor[0], floor[1], 0)], [("Floor", 0, None)], grey, lamps, spot, square))
    # A blue veil (BLEND, alpha 0.5: a mask) over a grey floor, lit by the point light: diffuse
    # materials only, the mask's pass the one delta lobe (GltfCli's backends test).
    veil = quad([-1, 0, 0.5], [2, 0, 0], [0, 1.5, 0])
    veiled = grey + [dict(pbr("veil", [0.25, 0.5, 1.0], 0.0, 1.0), alphaMode="BLEND")]
    veiled[1]["pbrMetallicRoughness"]["baseColorFactor"][3] = 0.5
    lamp_above = [dict(bulb[0], translation=[0, 2, 1])]
    write("veil.gltf", gltf([(floor[0], floor[1], 0), (veil[0], veil[1], 1)], [("Floor", 0, None), ("Veil", 1, None)],
                            veiled, lamp_above, point))
    # The floor textured with ../textures/tiles.png: as that file, embedded in a .glb and as a
    # data: uri (GltfScene.AnEmbeddedImageReadsAsTheFileItHolds).
    with open(os.path.join(HERE, "..", "textures", "tiles.png"), "rb") as f:
        tiles = f.read()
    tiled = [pbr("tiles", [1.0, 1.0, 1.0], 0.0, 1.0)]
    tiled[0]["pbrMetallicRoughness"]["baseColorTexture"] = {"index": 0}
    tiled_floor = [(floor[0], floor[1], 0, [[0, 0], [2, 0], [2, 2], [0, 2]])]
    write("textured.gltf", gltf(tiled_floor, [("Floor", 0, None)], tiled, extra, lights, cameras,
                                {"uri": "../textures/tiles.png"}))
    write_glb("textured.glb", gltf(tiled_floor, [("Floor", 0, None)], tiled, extra, lights, cameras,
                                   {"bytes": tiles, "mimeType": "image/png"}))
    write("textured_data_uri.gltf", gltf(tiled_floor, [("Floor", 0, None)], tiled, extra, lights, cameras,
                                         {"uri": "data:image/png;base64," + base64.b64encode(tiles).decode()}))
    # Nothing but a red floor: the default camera and the default light.
    write("no_camera_no_light.gltf", gltf([(floor[0], floor[1], 0)], [("Floor", 0, None)], materials[:1], []))


if __name__ == "__main__":
    main()
