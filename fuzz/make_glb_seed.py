#!/usr/bin/env python3
"""Packs a .gltf whose buffers are data URIs into a binary glTF (.glb): the fuzzers' GLB seed.

    python3 fuzz/make_glb_seed.py bench/scenes/cornell-sun.gltf fuzz/seeds/cornell-sun.glb
"""
import base64
import json
import struct
import sys


def pack(gltf_path: str, glb_path: str) -> None:
    with open(gltf_path, encoding="utf-8") as f:
        doc = json.load(f)
    blob = b""
    # GLB holds one BIN chunk: every data-URI buffer is appended to it and the bufferViews moved.
    offsets = []
    for buf in doc.get("buffers", []):
        data = base64.b64decode(buf["uri"].split(",", 1)[1])
        blob += b"\0" * (-len(blob) % 4)
        offsets.append(len(blob))
        blob += data
    for view in doc.get("bufferViews", []):
        view["byteOffset"] = view.get("byteOffset", 0) + offsets[view["buffer"]]
        view["buffer"] = 0
    blob += b"\0" * (-len(blob) % 4)
    doc["buffers"] = [{"byteLength": len(blob)}]
    text = json.dumps(doc, separators=(",", ":")).encode()
    text += b" " * (-len(text) % 4)
    total = 12 + 8 + len(text) + 8 + len(blob)
    with open(glb_path, "wb") as f:
        f.write(struct.pack("<III", 0x46546C67, 2, total))
        f.write(struct.pack("<II", len(text), 0x4E4F534A) + text)
        f.write(struct.pack("<II", len(blob), 0x004E4942) + blob)


if __name__ == "__main__":
    pack(sys.argv[1], sys.argv[2])
