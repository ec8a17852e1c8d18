"""app.dem.upload (no browser): the pieces a browser sends are checked and put together
in order, in memory; a piece that does not fit a file under the cap, or comes out of
order, is refused or dropped; the browser's refusal of a large file is said in words."""

from __future__ import annotations

import base64
import math

import pytest

from app.dem import data
from app.dem.upload import CHUNK_BYTES, CsvUpload, parse_chunk, refusal
from app.serve import SESSION


def pieces(content: bytes, serial: str = "abc", chunk_bytes: int = CHUNK_BYTES) -> list[str]:
    """The pieces the browser's script sends for `content` ("serial:index:count:size:b64")."""
    count = max(1, math.ceil(len(content) / chunk_bytes))
    return [f"{serial}:{i}:{count}:{len(content)}:"
            + base64.b64encode(content[i * chunk_bytes:(i + 1) * chunk_bytes]).decode()
            for i in range(count)]


class Sink:
    """What a `CsvUpload` handed on: whole files and refusals."""

    def __init__(self) -> None:
        self.files: list[bytes] = []
        self.refusals: list[str] = []

    def upload(self, chunk_bytes: int = CHUNK_BYTES) -> CsvUpload:
        return CsvUpload(on_file=self.files.append, on_refused=self.refusals.append,
                         max_bytes=data.MAX_UPLOAD_BYTES, chunk_bytes=chunk_bytes)


def test_a_piece_fits_the_servers_websocket_message_cap() -> None:
    """Each piece is base64 (4/3 of its bytes) in a message with a small envelope; the
    server closes a connection whose message exceeds its cap."""
    assert CHUNK_BYTES % 3 == 0
    assert 4 * CHUNK_BYTES // 3 + 16 * 1024 < SESSION["websocket_max_message_size"]
    assert data.MAX_UPLOAD_BYTES > SESSION["websocket_max_message_size"]


def test_the_pieces_of_a_file_are_put_together_in_order() -> None:
    sink = Sink()
    upload = sink.upload(chunk_bytes=6)
    content = bytes(range(256)) * 3 + b"end"
    sent = pieces(content, chunk_bytes=6)
    assert len(sent) == 129
    for k, piece in enumerate(sent):
        upload.chunk = piece
        assert upload.ack == f"abc:{k}" and upload.chunk == ""
    assert sink.files == [content] and sink.refusals == []
    upload.chunk = pieces(b"", "e")[0]  # an empty file is one empty piece
    assert sink.files == [content, b""]


def test_a_new_file_replaces_one_half_sent_and_a_stray_piece_is_dropped() -> None:
    sink = Sink()
    upload = sink.upload(chunk_bytes=3)
    first, second = pieces(b"abcdefghi", "one", 3), pieces(b"xyz123", "two", 3)
    upload.chunk = first[0]
    upload.chunk = second[0]  # the visitor chose another file
    upload.chunk = first[1]   # (a piece of the first, late)
    assert upload.ack == "two:0"
    upload.chunk = second[1]
    assert sink.files == [] and sink.refusals == []  # the stray piece dropped the second
    for piece in second:
        upload.chunk = piece
    assert sink.files == [b"xyz123"]
    upload.chunk = first[2]  # a last piece without the ones before it
    assert sink.files == [b"xyz123"] and upload.ack == "two:1"


@pytest.mark.parametrize(("piece", "message"), [
    (f"abc:0:8:{data.MAX_UPLOAD_BYTES + 1}:AAAA", "your file has 2,097,153 bytes, more "
                                                   "than the 2,097,152 accepted"),
    ("abc:0:3:6:YWJj", "the browser sent the pieces of the file out of order"),
    ("abc:2:1:3:YWJj", "the browser sent the pieces of the file out of order"),
    ("abc:0:1:3:YWJ", "the browser sent a piece of the file that could not be read"),
    ("abc:0:2:4:YWI=", "the browser sent a piece of the file of the wrong length"),
    ("ABC:0:1:3:YWJj", "the browser sent a piece of the file that could not be read"),
    ("abc:0:1:3:YW Jj", "the browser sent a piece of the file that could not be read"),
])
def test_a_piece_that_does_not_fit_the_cap_is_refused(piece, message) -> None:
    with pytest.raises(ValueError, match=message):
        parse_chunk(piece, data.MAX_UPLOAD_BYTES, 3)
    sink = Sink()
    upload = sink.upload(chunk_bytes=3)
    upload.chunk = "abc:0:2:6:YWJj"
    upload.chunk = piece
    assert sink.files == [] and len(sink.refusals) == 1
    assert sink.refusals[0].startswith(message)
    upload.chunk = "abc:1:2:6:ZGVm"  # the rest of the file: dropped with it
    assert sink.files == []


def test_the_browsers_refusal_is_said_in_words() -> None:
    sink = Sink()
    upload = sink.upload()
    upload.refused = f"k2:{3 * 1024 * 1024}"
    assert sink.refusals == ["your file has 3,145,728 bytes, more than the 2,097,152 "
                             "accepted: keep every k-th step"]
    assert upload.refused == ""
    assert refusal("k3:-1", 10) == "your file could not be read by the browser: choose it again"
    assert refusal("<b>", 10) == refusal("k3:-1", 10)
