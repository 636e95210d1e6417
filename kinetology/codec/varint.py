"""Unsigned LEB128 numbers (7 bits a byte, the high bit saying "more"): the one coder of the
integers that both the ``KIN2`` container and the residual layer write.
"""

from __future__ import annotations

from psgs.errors import ValidationError

__all__ = ["VarintError", "encode", "decode"]


class VarintError(ValidationError):
    """Bytes that do not hold a number; ``pos`` is where reading stopped.

    Examples
    --------
    >>> try:
    ...     decode(b"\\xff" * 10, 0)
    ... except VarintError as exc:
    ...     print(exc, exc.pos)
    number too long 10
    """

    def __init__(self, message: str, pos: int) -> None:
        super().__init__(message)
        self.pos = pos


def encode(numbers) -> bytes:
    """The varint bytes of ``numbers`` (non-negative integers), one after another.

    Examples
    --------
    >>> encode([0, 127, 128, 300]).hex()
    '007f8001ac02'
    """
    out = bytearray()
    for n in numbers:
        n = int(n)
        if n < 0:
            raise ValidationError("varints are unsigned")
        while n >= 0x80:
            out.append((n & 0x7F) | 0x80)
            n >>= 7
        out.append(n)
    return bytes(out)


def decode(data: bytes, pos: int) -> tuple[int, int]:
    """The number that starts at ``data[pos]`` and the position after it.

    Raises
    ------
    VarintError
        When the data ends inside the number, or it runs past 64 bits.

    Examples
    --------
    >>> decode(bytes.fromhex("ac02ff"), 0)
    (300, 2)
    >>> decode(b"\\x80", 0)
    Traceback (most recent call last):
    ...
    kinetology.codec.varint.VarintError: data ends inside a number
    """
    shift = result = 0
    while True:
        if pos >= len(data):
            raise VarintError("data ends inside a number", pos)
        byte = data[pos]
        pos += 1
        result |= (byte & 0x7F) << shift
        if byte < 0x80:
            return result, pos
        shift += 7
        if shift > 63:
            raise VarintError("number too long", pos)
