"""VTK files of sable and LIGGGHTS (dump custom/vtk, dump mesh/vtk): a legacy text file's POINTS
block and a cell or point field, LIGGGHTS' (FIELD arrays) or sable's (SCALARS) layout; every
array of an XML file (ascii, base64 or appended raw) or of a legacy ASCII or BINARY POLYDATA."""
import base64
import re
import xml.etree.ElementTree as ET

import numpy as np


def points(path):
    """The POINTS block of a legacy VTK file as an array [n, 3]."""
    with open(path) as f:
        lines = f.read().split('\n')
    i = next(k for k, l in enumerate(lines) if l.startswith('POINTS '))
    n = int(lines[i].split()[1])
    nums = []
    for line in lines[i + 1:]:
        if len(nums) >= 3 * n:
            break
        nums += [float(x) for x in line.split()]
    return np.array(nums[:3 * n]).reshape(-1, 3)


def field(text, name):
    """The values of the field `name` in a VTK file's text (a FIELD array 'name 1 N float' or
    'SCALARS name float 1' with its LOOKUP_TABLE), as a list of floats; None when absent."""
    m = re.search(r'^(?:SCALARS )?' + re.escape(name) + r' .*\n(?:LOOKUP_TABLE default\n)?((?:[-+0-9.eE ]+\n)+)',
                  text, re.M)
    return [float(x) for x in m.group(1).split()] if m else None


# VTK's names of XML data types -> numpy's (byte order added from the file).
_XML_TYPES = {"Int8": "i1", "UInt8": "u1", "Int16": "i2", "UInt16": "u2", "Int32": "i4", "UInt32": "u4",
              "Int64": "i8", "UInt64": "u8", "Float32": "f4", "Float64": "f8"}


def _b64_block(text, off, header):
    """The data of the base64 block at `off` (a byte count, then the data) as bytes. VTK
    encodes the count on its own (padded) or with the data in one stream: both are read."""
    hchars = 4 * -(-header.itemsize // 3)
    head = base64.b64decode(text[off:off + hchars])
    size = int(np.frombuffer(head[:header.itemsize], header)[0])
    if text[off + hchars - 1:off + hchars] == b"=":
        return base64.b64decode(text[off + hchars:off + hchars + 4 * -(-size // 3)])[:size]
    total = header.itemsize + size
    return base64.b64decode(text[off:off + 4 * -(-total // 3)])[header.itemsize:total]


def xml_arrays(path):
    """Every DataArray of an uncompressed VTK XML file (.vtu, .vtp, .vtr, the pieces of .pvtu and
    .pvtp) by Name, as arrays [tuples, components] (components > 1) or [tuples]: ascii, inline
    binary (base64) and appended (raw or base64) data, either byte order, UInt32 or UInt64 headers."""
    with open(path, "rb") as f:
        raw = f.read()
    appended, encoding = b"", "raw"
    start = raw.find(b"<AppendedData")
    if start >= 0:  # raw bytes are no XML: cut them out before parsing
        tag_end = raw.index(b">", start)
        encoding = re.search(rb'encoding="(\w+)"', raw[start:tag_end]).group(1).decode()
        end = raw.rindex(b"</AppendedData>")
        appended = raw[raw.index(b"_", tag_end) + 1:end]
        raw = raw[:start] + raw[end + len(b"</AppendedData>"):]
    root = ET.fromstring(raw)
    if root.get("compressor"):
        raise ValueError(f"{path}: compressed VTK XML ({root.get('compressor')}) is not read here")
    order = "<" if root.get("byte_order", "LittleEndian") == "LittleEndian" else ">"
    header = np.dtype(order + ("u8" if root.get("header_type") == "UInt64" else "u4"))
    out = {}
    for el in root.iter("DataArray"):
        dtype = np.dtype(order + _XML_TYPES[el.get("type")])
        fmt = el.get("format", "ascii")
        if fmt == "ascii":
            values = np.array((el.text or "").split(), dtype=dtype)
        elif fmt == "binary":
            values = np.frombuffer(_b64_block("".join((el.text or "").split()).encode(), 0, header), dtype)
        elif encoding == "raw":
            off = int(el.get("offset"))
            size = int(np.frombuffer(appended[off:off + header.itemsize], header)[0])
            values = np.frombuffer(appended[off + header.itemsize:off + header.itemsize + size], dtype)
        else:  # appended base64: offsets count encoded characters
            values = np.frombuffer(_b64_block(appended, int(el.get("offset")), header), dtype)
        nc = int(el.get("NumberOfComponents", "1"))
        out[el.get("Name")] = values.astype(dtype.newbyteorder("=")).reshape(-1, nc) if nc > 1 else \
            values.astype(dtype.newbyteorder("="))
    return out


def legacy_arrays(path):
    """A legacy POLYDATA file of dump custom/vtk, ASCII or BINARY (big-endian): {'Points':
    [n, 3], 'VERTICES': the cell list, and each FIELD array by name ([n] or [n, components])}."""
    with open(path, "rb") as f:
        data = f.read()
    pos = 0

    def line():
        nonlocal pos
        end = data.index(b"\n", pos)
        text, pos = data[pos:end].decode(), end + 1
        return text

    def values(count, typ):
        nonlocal pos
        dtype = {"double": "f8", "float": "f4", "int": "i4", "long": "i8", "vtktypeint64": "i8"}[typ]
        if not binary:
            tokens = []
            while len(tokens) < count:
                tokens += line().split()
            return np.array(tokens, dtype=dtype)
        a = np.frombuffer(data, ">" + dtype, count, pos)
        pos += a.nbytes
        if data[pos:pos + 1] == b"\n":
            pos += 1
        return a.astype(dtype)

    line(), line()
    binary = line().strip() == "BINARY"
    out = {}
    while pos < len(data):
        words = line().split()
        if not words or words[0] in ("DATASET", "POINT_DATA"):
            continue
        if words[0] == "POINTS":
            out["Points"] = values(3 * int(words[1]), words[2]).reshape(-1, 3)
        elif words[0] == "VERTICES":
            out["VERTICES"] = values(int(words[2]), "int")
        elif words[0] == "FIELD":
            for _ in range(int(words[2])):
                name, nc, n, typ = line().split()
                v = values(int(nc) * int(n), typ)
                out[name] = v.reshape(-1, int(nc)) if int(nc) > 1 else v
        else:
            raise ValueError(f"{path}: unexpected legacy VTK line {' '.join(words)!r}")
    return out
