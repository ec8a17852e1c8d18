"""Columns that travel inside the update message instead of beside it.

Bokeh sends each numpy column of a ColumnDataSource change as a binary buffer of its
own, after the message: two websocket frames per column (a reference, then the bytes).
A psi move changes some twenty float columns, so the browser took some forty frames,
each a task of its own, to receive one update.  An `InlineColumn` serialises itself
into the message (base64 of a gzip stream: the representation Bokeh uses when buffers
are not deferred, which BokehJS always gunzips), so the whole update is one message of
three frames; the browser decodes the same float64 bytes, so the values it plots are
bit for bit those computed here.

The gzip stream is stored, not compressed: float64 curves hardly compress, and
compressing them costs server CPU on every move (`python -m benchmarks.app.wire_cost`
prints the bytes and the CPU of each compression level on the columns of one psi move).
The stored stream is written here (`stored_gzip`: the gzip header, the bytes in stored
deflate blocks, their CRC-32 and length; RFCs 1951 and 1952) without setting up a
compressor for each column (zlib allocates its state on every call); for a column of up
to 8,000 floats it is byte for byte what `gzip.compress(data, compresslevel=0,
mtime=1)` gives (zlib cuts longer data into blocks of other sizes).  What it changes in
the browser: `python -m benchmarks.app.app_latency --revs`.

Large one-off payloads (the player's frame store) keep Bokeh's binary buffers: base64
is a third larger.
"""

from __future__ import annotations

import base64
import struct
import sys
import zlib
from collections.abc import Mapping
from typing import Any

import numpy as np
from bokeh.core.serialization import NDArrayRep, Serializable, Serializer

#: The gzip header of `stored_gzip`: magic, deflate, no flags, mtime 1 (fixed, as Bokeh's
#: for equal output), no extra flags, OS unknown (255): what `gzip.compress` writes.
GZIP_HEADER = b"\x1f\x8b\x08\x00\x01\x00\x00\x00\x00\xff"
#: The most bytes of one stored deflate block (RFC 1951, 3.2.4).
STORED_BLOCK = 0xFFFF


def stored_gzip(data: bytes) -> bytes:
    """`data` as a gzip stream of stored (uncompressed) deflate blocks: the header, each
    block's final flag, length and its one's complement, then the CRC-32 and the
    length of `data` modulo 2**32 (RFC 1952).  Up to 64,000 bytes, byte for byte
    `gzip.compress(data, compresslevel=0, mtime=1)`."""
    n = len(data)
    parts = [GZIP_HEADER]
    for start in range(0, n, STORED_BLOCK) if n else [0]:
        size = min(STORED_BLOCK, n - start)
        parts.append(struct.pack("<BHH", start + size >= n, size, size ^ 0xFFFF))
        parts.append(data[start:start + size])
    parts.append(struct.pack("<II", zlib.crc32(data), n & 0xFFFFFFFF))
    return b"".join(parts)


def encode(data: np.ndarray) -> str:
    """The bytes of a contiguous array as BokehJS decodes an inline buffer: base64 of a
    gzip stream (`stored_gzip`)."""
    return base64.b64encode(stored_gzip(data.tobytes())).decode("ascii")


class InlineColumn(np.ndarray, Serializable):
    """A float64 column that Bokeh serialises inline (base64) rather than as a buffer."""

    def to_serializable(self, serializer: Serializer) -> NDArrayRep:
        """Bokeh's ndarray representation with the bytes in the message itself."""
        data = np.ascontiguousarray(self, dtype=np.float64).view(np.ndarray)
        return NDArrayRep(type="ndarray", array={"type": "bytes", "data": encode(data)},
                          shape=list(data.shape), dtype="float64", order=sys.byteorder)


def inline(columns: Mapping[str, Any]) -> dict[str, Any]:
    """The columns with every 1-d numeric array made an `InlineColumn` (others as given).

    Values are converted to float64 (exactly, for the float64 arrays core returns).
    """
    out: dict[str, Any] = {}
    for name, values in columns.items():
        if isinstance(values, np.ndarray) and values.ndim == 1 and values.dtype.kind in "fiu":
            out[name] = np.asarray(values, dtype=np.float64).view(InlineColumn)
        else:
            out[name] = values
    return out


def column(values: np.ndarray) -> np.ndarray | list:
    """An array's values, in order, as one column of a source: numbers as a contiguous
    1-d array, text (an object array) as a list of str."""
    v = np.ravel(values)
    return v.tolist() if v.dtype == object else v
