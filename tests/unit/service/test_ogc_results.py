"""Presenting outputs: files are base64-encoded in pieces that join into one encoding."""

from __future__ import annotations

import base64
import random

from service.ogc.results import _base64_chunks


def test_base64_in_pieces_is_the_whole_encoding() -> None:
    rng = random.Random(7)
    data = rng.randbytes(3 * 1024 * 1024 + 17)
    cuts = sorted(rng.sample(range(1, len(data)), 40))
    chunks = [data[a:b] for a, b in zip([0, *cuts], [*cuts, len(data)], strict=True)]
    pieces = list(_base64_chunks(iter(chunks)))
    assert len(pieces) > 1 and all(len(p) % 4 == 0 for p in pieces[:-1])
    assert b"".join(pieces) == base64.b64encode(data)
    assert list(_base64_chunks(iter([]))) == []
