"""The card's upload box: a file input that checks a file's size in the browser and sends
the file in pieces, each its own websocket message.

The server closes a connection whose message exceeds 512 KiB (`app.serve.SESSION`),
and Panel's `FileInput` sends a whole file base64-encoded in one message; `CsvUpload`
never sends a message near that size.  It is Panel's public `ReactiveHTML` (its scripts
run under the page's Content-Security-Policy, which allows `new Function` but no `blob:`
module, what a `JSComponent` is loaded as; and it loads nothing from elsewhere):

- a file over `max_bytes` is never read: the browser reports its size (`refused`) and
  the card says why under the box;
- a smaller one is read in slices of `chunk_bytes` and each slice is sent base64-encoded
  as `chunk` ("serial:index:count:size:base64"), the next one only once the server has
  acknowledged the last (`ack`), so that no message exceeds the cap and none is merged
  with another by Panel's batching of a widget's changes;
- the server checks every piece again (`parse_chunk`: its place, the declared size
  against `max_bytes`) and hands the whole file, in memory, to `on_file`; a refusal goes
  to `on_refused` as a sentence.  Nothing is written to disk.

A line under the input (a polite live region) says what became of the file chosen:
"NAME: sending, 2 of 8", "NAME: sent", "NAME: not sent" (over the cap).
"""

from __future__ import annotations

import base64
import binascii
import math
import re
from collections.abc import Callable
from dataclasses import dataclass
from typing import ClassVar

import panel as pn
import param

from app.dem.data import too_big

#: The bytes of file in one message (a multiple of 3: its base64 has no padding but at
#: the end), 384 KiB of base64: well under the server's 512 KiB cap with the envelope.
CHUNK_BYTES = 288 * 1024

_CHUNK = re.compile(r"([a-z0-9]{1,16}):(\d{1,6}):(\d{1,6}):(-?\d{1,12}):([A-Za-z0-9+/=]*)")
_REFUSED = re.compile(r"([a-z0-9]{1,16}):(-?\d{1,15})")


@dataclass(frozen=True)
class Chunk:
    """One piece of a file as the browser sent it: the upload's `serial`, the piece's
    `index` of `count`, the file's `size` in bytes and the piece's bytes."""

    serial: str
    index: int
    count: int
    size: int
    payload: bytes


def parse_chunk(text: str, max_bytes: int, chunk_bytes: int) -> Chunk:
    """The piece `text` ("serial:index:count:size:base64") of a file of at most
    `max_bytes` sent in pieces of `chunk_bytes`; ValueError if it is malformed or does
    not fit such a file (its size above `max_bytes`, too many pieces, a piece of the
    wrong length)."""
    m = _CHUNK.fullmatch(text)
    if m is None:
        raise ValueError("the browser sent a piece of the file that could not be read")
    serial, index, count, size = m[1], int(m[2]), int(m[3]), int(m[4])
    if not 0 <= size <= max_bytes:
        raise ValueError(too_big(size, max_bytes))
    if count != max(1, math.ceil(size / chunk_bytes)) or not 0 <= index < count:
        raise ValueError("the browser sent the pieces of the file out of order")
    try:
        payload = base64.b64decode(m[5], validate=True)
    except binascii.Error:
        raise ValueError("the browser sent a piece of the file that could not be read") \
            from None
    expected = min(chunk_bytes, size - index * chunk_bytes)
    if len(payload) != expected:
        raise ValueError("the browser sent a piece of the file of the wrong length")
    return Chunk(serial, index, count, size, payload)


def refusal(text: str, max_bytes: int) -> str:
    """The sentence for the browser's refusal `text` ("serial:size"; size -1: the
    browser could not read the file)."""
    m = _REFUSED.fullmatch(text)
    size = int(m[2]) if m else -1
    if size < 0:
        return "your file could not be read by the browser: choose it again"
    return too_big(size, max_bytes)


_RENDER = """
title.textContent = data.label;
state.serial = "";
state.say = (text) => { status.textContent = text; };
state.send = (serial, index) => {
  const file = state.file;
  if (file == null || serial !== state.serial) return;
  const start = index * data.chunk_bytes;
  file.slice(start, start + data.chunk_bytes).arrayBuffer().then((buffer) => {
    if (serial !== state.serial) return;
    const bytes = new Uint8Array(buffer);
    let text = "";
    for (let i = 0; i < bytes.length; i += 0x8000) {
      text += String.fromCharCode.apply(null, bytes.subarray(i, i + 0x8000));
    }
    state.say(`${file.name}: sending, ${index + 1} of ${state.count}`);
    data.chunk = `${serial}:${index}:${state.count}:${file.size}:${btoa(text)}`;
  }, () => {
    state.file = null;
    state.say(`${file.name}: not read`);
    data.refused = `${serial}:-1`;
  });
};
"""

_PICK = """
const file = input.files && input.files[0];
input.value = "";
if (file == null) return;
const serial = Math.random().toString(36).slice(2, 12) || "0";
state.serial = serial;
if (file.size > data.max_bytes) {
  state.file = null;
  state.say(`${file.name}: not sent`);
  data.refused = `${serial}:${file.size}`;
  return;
}
state.file = file;
state.count = Math.max(1, Math.ceil(file.size / data.chunk_bytes));
state.send(serial, 0);
"""

_ACK = """
const [serial, index] = data.ack.split(":");
if (serial !== state.serial || state.file == null) return;
const next = Number(index) + 1;
if (next < state.count) {
  state.send(serial, next);
} else {
  state.say(`${state.file.name}: sent`);
  state.file = null;
}
"""


class CsvUpload(pn.reactive.ReactiveHTML):
    """A labelled file input for one file of at most `max_bytes`, sent in pieces of
    `chunk_bytes` (see the module's docstring); `on_file(bytes)` receives each whole
    file, `on_refused(sentence)` each refusal."""

    label = param.String(default="File")
    accept = param.String(default="")
    max_bytes = param.Integer(default=0, bounds=(0, None))
    chunk_bytes = param.Integer(default=CHUNK_BYTES, bounds=(3, None))
    chunk = param.String(default="", doc="from the browser: the last piece sent")
    ack = param.String(default="", doc="to the browser: the last piece received")
    refused = param.String(default="", doc="from the browser: a file not sent")

    _template = (
        '<label id="box" class="box">'
        '<span id="title" class="title"></span>'
        '<input type="file" id="input" accept="${accept}" '
        'onchange="${script(\'pick\')}"></input></label>'
        '<div id="status" class="status" aria-live="polite"></div>')

    _scripts: ClassVar[dict[str, str]] = {"render": _RENDER, "pick": _PICK, "ack": _ACK}

    CSS = (".box { display: flex; flex-direction: column; gap: 4px; }"
           "input { min-height: 24px; } .status { font-size: 0.9em; color: #444; }")

    def __init__(self, on_file: Callable[[bytes], None],
                 on_refused: Callable[[str], None], **params) -> None:
        params["stylesheets"] = [self.CSS, *params.get("stylesheets", [])]
        super().__init__(**params)
        self._on_file = on_file
        self._on_refused = on_refused
        self._serial = ""
        self._parts: list[bytes] = []

    @param.depends("chunk", watch=True)
    def _receive(self) -> None:
        if not self.chunk:
            return
        try:
            piece = parse_chunk(self.chunk, self.max_bytes, self.chunk_bytes)
        except ValueError as err:
            self._drop()
            self._on_refused(str(err))
            return
        if piece.index == 0:
            self._serial, self._parts = piece.serial, []
        if piece.serial != self._serial or piece.index != len(self._parts):
            self._drop()
            return
        self._parts.append(piece.payload)
        self.param.update(chunk="", ack=f"{piece.serial}:{piece.index}")
        if len(self._parts) == piece.count:
            whole = b"".join(self._parts)
            self._drop()
            self._on_file(whole)

    @param.depends("refused", watch=True)
    def _refuse(self) -> None:
        if self.refused:
            self._drop()
            self._on_refused(refusal(self.refused, self.max_bytes))
            self.refused = ""

    def _drop(self) -> None:
        self._serial, self._parts = "", []
