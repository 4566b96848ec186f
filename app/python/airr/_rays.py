"""The ray file's reader (format: docs/ray-file.md)."""
import os

import numpy as np

_HEADER = np.dtype([("magic", "S8"), ("version", "<u4"), ("width", "<u4"), ("height", "<u4"), ("flags", "<u4"),
                    ("first_sample", "<u8"), ("spp", "<u8"), ("selected", "<u8"), ("paths", "<u8"),
                    ("segments", "<u8"), ("expression_bytes", "<u4")])
PATH = np.dtype([("x", "<u4"), ("y", "<u4"), ("sample", "<u8"), ("first_segment", "<u4"), ("segment_count", "<u4"),
                 ("contribution", "<f4", 3), ("reserved", "<u4")])
SEGMENT = np.dtype([("start", "<f4", 3), ("direction", "<f4", 3), ("length", "<f4"), ("radiance", "<f4", 3),
                    ("kind", "u1"), ("taken", "u1"), ("front", "u1"), ("reserved", "u1"), ("index", "<u2"),
                    ("reserved2", "<u2")])
EVENT_KINDS = ("display", "eye", "half_mirror", "sheet", "prop", "ambient")


def read_rays(path):
    """Read a ray file that `airr render --rays` or airr.record_rays wrote.

    Returns a dict: "width", "height", "first_sample", "spp", "selected" (paths the expression
    selected), "complete" (all of them are in the file), "expression", "paths" (a numpy structured
    array: x, y, sample, first_segment, segment_count, contribution (RGB)) and "segments" (start,
    direction, length (mm), radiance (RGB), the event the segment leaves: kind (an index into
    EVENT_KINDS), taken, front, index). A pixel's value in the render without its control variate
    is the sum of its paths' contributions over spp. Raises ValueError naming the file and what is
    wrong when it is not a whole ray file.
    """
    path = os.fspath(path)
    with open(path, "rb") as f:
        data = f.read()

    def bad(what):
        return ValueError(f"{path}: {what}")

    if len(data) < _HEADER.itemsize or data[:8] != b"AIRRRAYS":
        raise bad("not a ray file (no AIRRRAYS header)")
    head = np.frombuffer(data, _HEADER, count=1)[0]
    if head["version"] != 1:
        raise bad(f"ray file version {int(head['version'])}; this reader reads version 1")
    offset = _HEADER.itemsize + int(head["expression_bytes"])
    paths, segments = int(head["paths"]), int(head["segments"])
    end = offset + paths * PATH.itemsize + segments * SEGMENT.itemsize
    if len(data) != end:
        raise bad(f"{len(data)} bytes where the header announces {end}")
    expression = data[_HEADER.itemsize:offset].decode("utf-8")
    path_records = np.frombuffer(data, PATH, count=paths, offset=offset)
    segment_records = np.frombuffer(data, SEGMENT, count=segments, offset=offset + paths * PATH.itemsize)
    if paths and int((path_records["first_segment"].astype(np.uint64) +
                      path_records["segment_count"]).max()) > segments:
        raise bad("a path's segments run past the file's")
    return {"width": int(head["width"]), "height": int(head["height"]), "first_sample": int(head["first_sample"]),
            "spp": int(head["spp"]), "selected": int(head["selected"]), "complete": bool(head["flags"] & 1),
            "expression": expression, "paths": path_records, "segments": segment_records}
