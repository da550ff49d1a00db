"""Tests of the meshvid Python module (run by ctest as python.pytest)."""
import os
import pydoc
import re
import struct
import warnings

import numpy as np
import pytest

import meshvid

GOLDEN = os.environ.get("MESHVID_GOLDEN_DIR", os.path.join(os.path.dirname(__file__), "..", "..", "tests", "golden"))
V1 = os.path.join(GOLDEN, "sphere.v1.mvid")  # 6 frames, levels 0..2, one key group
V2 = os.path.join(GOLDEN, "sphere.v2.mvid")  # 12 frames in key groups 0-4, 5-8, 9-11


def test_info_and_frames_from_a_path():
    f = meshvid.open(V1)
    info = f.info
    assert info["frame_count"] == 6 == len(f)
    assert info["levels"] == 2
    assert info["vertices_per_level"] == [18, 66, 258]
    vertices, triangles = f.frame(2, level=1)
    assert vertices.dtype == np.float32 and vertices.shape == (66, 3)
    assert triangles.dtype == np.int32 and triangles.shape == (info["triangles_per_level"][1], 3)
    assert triangles.min() >= 0 and triangles.max() < 66
    # The golden sphere stays near the unit sphere.
    radii = np.linalg.norm(vertices, axis=1)
    assert 0.8 < radii.min() and radii.max() < 1.3


def test_bytes_and_path_decode_the_same():
    with open(V2, "rb") as stream:
        data = stream.read()
    from_bytes, from_path = meshvid.open(data), meshvid.open(V2)
    for t in (0, 7, 11):
        a, b = from_bytes.frame(t), from_path.frame(t)
        np.testing.assert_array_equal(a[0], b[0])
        np.testing.assert_array_equal(a[1], b[1])


def test_key_groups_and_iteration():
    f = meshvid.open(V2)
    assert f.key_groups == [(0, 5), (5, 4), (9, 3)]
    assert [f.key_group_of(t) for t in (0, 4, 5, 8, 9, 11)] == [0, 0, 1, 1, 2, 2]
    frames = list(f)
    assert len(frames) == 12
    # One connectivity within a key group, another across.
    np.testing.assert_array_equal(frames[5][1], frames[8][1])
    assert frames[4][1].shape != frames[5][1].shape or not np.array_equal(frames[4][1], frames[5][1])
    coarse = list(f.frames(level=0))
    assert coarse[0][0].shape[0] < frames[0][0].shape[0]


def test_errors_carry_the_library_message(tmp_path):
    with pytest.raises(meshvid.Error, match="no such file|cannot open|not found"):
        meshvid.open(str(tmp_path / "missing.mvid"))
    with pytest.raises(meshvid.Error):
        meshvid.open(b"not an mvid file at all")
    f = meshvid.open(V1)
    with pytest.raises(IndexError):
        f.frame(6)
    with pytest.raises(meshvid.Error, match="level"):
        f.frame(0, level=7)
    with pytest.raises(meshvid.Error, match="shape"):
        meshvid.encode([[(np.zeros((3, 2)), np.array([[0, 1, 2]]))]])
    with pytest.raises(meshvid.Error, match="vertex 5"):
        meshvid.encode([[(np.zeros((3, 3)), np.array([[0, 1, 5]]))]])


def test_version_context_manager_repr_and_metadata():
    assert re.fullmatch(r"\d+\.\d+\.\d+", meshvid.__version__)
    with meshvid.open(V2) as f:
        assert len(f) == 12
        text = repr(f)
        assert "sphere.v2.mvid" in text and "12 frames" in text and "3 key groups" in text
        assert isinstance(f.metadata, dict) and isinstance(f.info["metadata"], dict)
        assert f.partial is False
    assert "closed" in repr(f)
    with pytest.raises(ValueError, match="closed"):
        f.frame(0)
    with pytest.raises(ValueError, match="closed"):
        len(f)


def test_docstrings_name_no_cpp_types():
    text = pydoc.render_doc(meshvid, renderer=pydoc.plaintext)
    assert "meshvid::" not in text and "std::" not in text and "anonymous" not in text


def crc32c(data):
    """CRC-32C (Castagnoli), the container's chunk checksum."""
    crc = 0xFFFFFFFF
    for byte in data:
        crc ^= byte
        for _ in range(8):
            crc = (crc >> 1) ^ (0x82F63B78 if crc & 1 else 0)
    return crc ^ 0xFFFFFFFF


def promising(data, frames):
    """`data` with its HEAD chunk promising `frames` frames, its CRC recomputed. HEAD follows the
    8-byte preamble: a 16-byte chunk header (payload size at +8), then the payload, whose
    frame_count follows the frame rate's numerator and denominator; the CRC after the payload
    covers the chunk header and payload (spec/mvid-container.md)."""
    head, header = 8, 16
    size = struct.unpack_from("<Q", data, head + 8)[0]
    out = bytearray(data)
    struct.pack_into("<I", out, head + header + 8, frames)
    end = head + header + size
    struct.pack_into("<I", out, end, crc32c(bytes(out[head:end])))
    return bytes(out)


def test_a_partial_file_is_refused_unless_allowed():
    with open(V2, "rb") as stream:
        whole = stream.read()
    cut = promising(whole, 12)[:10750]
    with pytest.raises(meshvid.Error, match="partial file: only 8 of the 12 frames"):
        meshvid.open(cut)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        f = meshvid.open(cut, allow_partial=True)
    assert any("partial file" in str(w.message) for w in caught)
    assert f.partial is True and len(f) == 8
    assert f.info["declared_frame_count"] == 12
    assert "(partial)" in repr(f)


def sphere(radius, rings=24, segments=48):
    """A closed UV sphere: (vertices (V, 3), triangles (F, 3))."""
    theta = np.linspace(0, np.pi, rings + 1)[1:-1]
    phi = np.linspace(0, 2 * np.pi, segments, endpoint=False)
    t, p = np.meshgrid(theta, phi, indexing="ij")
    body = np.stack([np.sin(t) * np.cos(p), np.cos(t), np.sin(t) * np.sin(p)], -1).reshape(-1, 3)
    vertices = np.vstack([[0, 1, 0], body, [0, -1, 0]]) * radius
    tris = []
    last = len(vertices) - 1
    for s in range(segments):
        n = (s + 1) % segments
        tris.append([0, 1 + n, 1 + s])
        tris.append([last, 1 + (rings - 2) * segments + s, 1 + (rings - 2) * segments + n])
    for r in range(rings - 2):
        for s in range(segments):
            n = (s + 1) % segments
            a, b = 1 + r * segments + s, 1 + r * segments + n
            c, d = a + segments, b + segments
            tris += [[a, b, d], [a, d, c]]
    return vertices.astype(np.float32), np.array(tris, dtype=np.int32)


def test_encode_from_arrays_round_trips(tmp_path):
    vertices, triangles = sphere(1.0)
    # A bump on top: a plain sphere gives the rigid tracking nothing to hold on to.
    bump = np.exp(-((vertices[:, 0] - 0.5) ** 2 + vertices[:, 2] ** 2) / 0.03) * (vertices[:, 1] > 0)
    vertices[:, 1] += 0.15 * bump
    centres = vertices[triangles].mean(axis=1)[:, 2]
    frames = []
    for t in range(4):
        moved = vertices + np.array([0.03 * t, 0, 0], dtype=np.float32)
        # Two views, each the half of the surface facing it.
        frames.append([(moved, triangles[centres > -0.02]), (moved, triangles[centres < 0.02])])
    # A folder that does not exist is created, as `meshvid encode -o` does.
    path = tmp_path / "new" / "folder" / "blob.mvid"
    stages = set()
    data = meshvid.encode(frames, path=str(path), quality=60, levels=1,
                          progress=lambda stage, done, total: stages.add(stage))
    assert "detail" in stages
    assert path.read_bytes() == data
    f = meshvid.open(data)
    assert len(f) == 4 and f.info["levels"] == 1
    for t in (0, 3):
        decoded, triangles_out = f.frame(t)
        assert triangles_out.shape[0] > 100
        radii = np.linalg.norm(decoded - np.array([0.03 * t, 0, 0]), axis=1)
        # The decoded surface lies on the captured one: the unit sphere away from the bump.
        assert abs(np.median(radii) - 1.0) < 0.02


def test_encode_takes_the_encoders_internals_by_key():
    vertices, triangles = sphere(1.0)
    frames = [[(vertices, triangles)]] * 2
    plain = meshvid.encode(frames)
    # Explicit defaults give the same file; a changed knob another one.
    assert meshvid.encode(frames, tune={"base_ahead": True, "window": 256}) == plain
    assert meshvid.encode(frames, tune={"base_position_bits": 14}) != plain
    with pytest.raises(meshvid.Error, match="unknown tuning key 'nodes'"):
        meshvid.encode(frames, tune={"nodes": 3})
    with pytest.raises(meshvid.Error, match="proxy_fraction must be in"):
        meshvid.encode(frames, tune={"proxy_fraction": 2})


def test_encode_can_be_cancelled_and_callback_errors_propagate():
    vertices, triangles = sphere(1.0)
    frames = [[(vertices, triangles)]] * 2
    with pytest.raises(meshvid.Error, match="cancel"):
        meshvid.encode(frames, progress=lambda stage, done, total: False)

    def failing(stage, done, total):
        raise ValueError("stop here")

    with pytest.raises(ValueError, match="stop here"):
        meshvid.encode(frames, progress=failing)
