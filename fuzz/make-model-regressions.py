#!/usr/bin/env python3
"""Writes fuzz/regressions/models/: one small model file per way a file from a stranger
once broke glint (issue 44), each named after its cause. They are replayed by the model
harnesses (fuzz.gltf, fuzz.mesh_parts, fuzz.model_file) and through the commands and
glint.load_mesh (tests/reliability/hostile_models_test.cpp), which also makes the files too
big to keep here (100,000-deep JSON, a 100,000-node chain, a 100,000-property PLY) and the
ones git cannot hold (symbolic links, names that are not UTF-8).

    fuzz/make-model-regressions.py [DIR]     (default: fuzz/regressions/models)
"""
import base64
import json
import os
import struct
import sys

OUT = sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(os.path.abspath(__file__)), "regressions", "models")

# A triangle (positions, normals, uvs, indices) as one buffer.
POSITIONS = [0, 0, 0, 1, 0, 0, 0, 1, 0]
NORMALS = [0, 0, 1] * 3
UVS = [0, 0, 1, 0, 0, 1]
INDICES = [0, 1, 2]
PNG_1x1 = base64.b64decode(
    "iVBORw0KGgoAAAANSUhEUgAAAAEAAAABCAIAAACQd1PeAAAADElEQVR4nGP4z8AAAAMBAQDJ/pLvAAAAAElFTkSuQmCC")


def triangle_bin():
    return (struct.pack("<9f", *POSITIONS) + struct.pack("<9f", *NORMALS) + struct.pack("<6f", *UVS)
            + struct.pack("<3I", *INDICES))


def triangle_doc(byte_length):
    return {
        "asset": {"version": "2.0", "generator": "glint fuzz/make-model-regressions.py"},
        "buffers": [{"byteLength": byte_length}],
        "bufferViews": [
            {"buffer": 0, "byteOffset": 0, "byteLength": 36},
            {"buffer": 0, "byteOffset": 36, "byteLength": 36},
            {"buffer": 0, "byteOffset": 72, "byteLength": 24},
            {"buffer": 0, "byteOffset": 96, "byteLength": 12},
        ],
        "accessors": [
            {"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0]},
            {"bufferView": 1, "componentType": 5126, "count": 3, "type": "VEC3"},
            {"bufferView": 2, "componentType": 5126, "count": 3, "type": "VEC2"},
            {"bufferView": 3, "componentType": 5125, "count": 3, "type": "SCALAR"},
        ],
        "meshes": [{"name": "tri", "primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1, "TEXCOORD_0": 2}, "indices": 3}]}],
        "nodes": [{"name": "tri", "mesh": 0}],
        "scenes": [{"nodes": [0]}],
        "scene": 0,
    }


def embedded(doc, data):
    doc["buffers"][0]["uri"] = "data:application/octet-stream;base64," + base64.b64encode(data).decode()
    return doc


def glb(doc, data):
    text = json.dumps(doc, separators=(",", ":")).encode()
    text += b" " * (-len(text) % 4)
    data = data + b"\0" * (-len(data) % 4)
    body = struct.pack("<II", len(text), 0x4E4F534A) + text + struct.pack("<II", len(data), 0x004E4942) + data
    return struct.pack("<III", 0x46546C67, 2, 12 + len(body)) + body


def write(name, content):
    path = os.path.join(OUT, name)
    with open(path, "wb") as f:
        f.write(content if isinstance(content, bytes) else content.encode())


def gltf(name, doc):
    write(name, json.dumps(doc, separators=(",", ":")))


def main():
    os.makedirs(OUT, exist_ok=True)
    data = triangle_bin()

    # 1. References outside the model's folder (read, embedded in an exported page).
    for name, uri in [("uri-parent-image.gltf", "../../../secret.png"),
                      ("uri-percent-encoded-parent-image.gltf", "..%2F..%2Fsecret.png"),
                      ("uri-absolute-image.gltf", "/etc/passwd"),
                      ("uri-file-scheme-image.gltf", "file:///etc/passwd")]:
        doc = embedded(triangle_doc(len(data)), data)
        doc["images"] = [{"uri": uri}]
        doc["textures"] = [{"source": 0}]
        doc["materials"] = [{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}}]
        doc["meshes"][0]["primitives"][0]["material"] = 0
        gltf(name, doc)
    for name, uri in [("uri-parent-buffer.gltf", "../secret.bin"), ("uri-percent-encoded-parent-buffer.gltf", "%2E%2E/secret.bin"),
                      ("uri-http-buffer.gltf", "http://example.com/tri.bin")]:
        doc = triangle_doc(len(data))
        doc["buffers"][0]["uri"] = uri
        gltf(name, doc)

    # 2. A texture glint does not read, which a browser would fetch from the network.
    doc = triangle_doc(len(data) + len(PNG_1x1))
    doc["bufferViews"].append({"buffer": 0, "byteOffset": len(data), "byteLength": len(PNG_1x1)})
    doc["images"] = [{"bufferView": 4, "mimeType": "image/png"}, {"uri": "http://example.com/emissive.png"}]
    doc["textures"] = [{"source": 0}, {"source": 1}]
    doc["materials"] = [{"name": "lamp", "pbrMetallicRoughness": {"baseColorTexture": {"index": 0}},
                         "emissiveTexture": {"index": 1}, "emissiveFactor": [1, 1, 1]}]
    doc["meshes"][0]["primitives"][0]["material"] = 0
    write("export-http-emissive-texture.glb", glb(doc, data + PNG_1x1))

    # 3. glint's own reader: offsets that wrap, indices past arrays, odd colour types,
    #    node cycles, wrong JSON types in a bake asset's extras.
    doc = triangle_doc(len(data))
    doc["accessors"][0]["byteOffset"] = 2**64 - 8
    write("accessor-byte-offset-wraps.glb", glb(doc, data))
    doc = triangle_doc(len(data))
    doc["bufferViews"][0]["byteOffset"] = 2**63
    write("buffer-view-offset-past-2-63.glb", glb(doc, data))
    doc = triangle_doc(len(data))
    doc["meshes"][0]["primitives"][0]["material"] = 7
    write("material-index-past-materials.glb", glb(doc, data))
    for t, n in [("SCALAR", 1), ("VEC2", 2), ("MAT4", 16)]:
        doc = triangle_doc(len(data))
        doc["accessors"].append({"bufferView": 0, "componentType": 5126, "count": 3, "type": t})
        doc["meshes"][0]["primitives"][0]["attributes"]["COLOR_0"] = 4
        write("color-of-type-%s.glb" % t.lower(), glb(doc, data))
    doc = triangle_doc(len(data))
    doc["nodes"][0]["children"] = [0]
    write("node-its-own-child.glb", glb(doc, data))
    doc = triangle_doc(len(data))
    doc["nodes"] = [{"mesh": 0, "children": [1]}, {"children": [0]}]
    write("node-cycle-of-two.glb", glb(doc, data))
    doc = triangle_doc(len(data))
    doc["nodes"] = [{"mesh": 0}, {"children": [0]}, {"children": [0]}]
    doc["scenes"] = [{"nodes": [1, 2]}]
    write("node-with-two-parents.glb", glb(doc, data))
    doc = triangle_doc(len(data))
    doc["extras"] = {"glint_bake": {"high": 5, "low": [1, 2], "samples": "four", "hard_edge_vertices": {"a": None}}}
    write("extras-glint-bake-wrong-types.glb", glb(doc, data))
    doc = triangle_doc(len(data))
    doc["materials"] = [{"extras": {"glint_maps": {"normal": {"texture": "zero", "order": -1}}}}]
    doc["meshes"][0]["primitives"][0]["material"] = 0
    write("extras-glint-maps-wrong-types.glb", glb(doc, data))
    doc = triangle_doc(len(data))
    doc["accessors"][3]["count"] = 2**40
    write("index-count-past-file.glb", glb(doc, data))
    doc = embedded(triangle_doc(len(data)), data)  # found by fuzz/gltf.cpp: a memcpy from null (UBSan)
    doc["accessors"][0]["count"] = 0
    doc["accessors"][1]["count"] = 0
    gltf("accessor-count-zero.gltf", doc)

    # 4. What TinyGLTF, stb, Assimp or Embree cannot take.
    doc = triangle_doc(len(data) + len(PNG_1x1))
    doc["bufferViews"].append({"buffer": 0, "byteOffset": 2**31 + 5, "byteLength": len(PNG_1x1)})
    doc["images"] = [{"bufferView": 4, "mimeType": "image/png"}]
    doc["textures"] = [{"source": 0}]
    doc["materials"] = [{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}}]
    doc["meshes"][0]["primitives"][0]["material"] = 0
    write("image-buffer-view-offset-past-2-31.glb", glb(doc, data + PNG_1x1))
    doc = triangle_doc(len(data))
    doc["accessors"][0]["sparse"] = {"count": 1, "indices": {"bufferView": 3, "componentType": 5125},
                                     "values": {"bufferView": 0}}
    del doc["accessors"][0]["bufferView"]
    write("sparse-accessor-without-buffer-view.glb", glb(doc, data))
    doc = triangle_doc(len(data))
    doc["accessors"][0]["sparse"] = {"count": 1, "indices": {"componentType": 5125}, "values": {}}
    write("sparse-indices-without-buffer-view.glb", glb(doc, data))
    nested = {}
    for level in range(30):  # linear in size; Assimp's time doubled per level
        nested = {"level": level, "a": nested, "pad": "x" * 300}
    doc = embedded(triangle_doc(len(data)), data)
    doc["extras"] = json.loads(json.dumps(nested))
    gltf("extras-nested-30-levels.gltf", doc)
    write("coordinate-1e38.obj", "v 0 0 0\nv 1e38 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nf 1/1 2/2 3/3\n")
    write("coordinate-inf.obj", "v 0 0 0\nv inf 0 0\nv 0 1 0\nf 1 2 3\n")

    # 5. PLY through every path: a bit-flipped binary file, a truncated one.
    header = b"ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n" \
             b"element face 1\nproperty list uchar int vertex_indices\nend_header\n"
    body = struct.pack("<9f", *POSITIONS) + struct.pack("<B3i", 3, 0, 1, 2)
    flipped = bytearray(header + body)
    flipped[len(header) + 36] ^= 0x80  # the face's corner count: 3 → 131
    write("ply-bit-flipped-corner-count.ply", bytes(flipped))
    write("ply-truncated-body.ply", header + body[:20])
    write("ply-header-only.ply", header)

    # 6. Odd JSON at the top: not an object, a .glb whose JSON chunk lies.
    write("json-array-not-object.gltf", "[1, 2, 3]")
    doc = triangle_doc(len(data))
    bad = bytearray(glb(doc, data))
    struct.pack_into("<I", bad, 12, 0x7FFFFFF0)
    write("glb-json-chunk-length-past-end.glb", bytes(bad))


if __name__ == "__main__":
    main()
