#!/usr/bin/env python3
"""Checkpoint snapshots (format 5, include/pounding/study/checkpoint.hpp) for cli.study_reductions.

  snapshot.py overlap SRC DST   writes DST: SRC with its done bits replaced by one unit SRC holds and one it does not
                                (a file sharing part of its units with SRC: files of two runs mixed), re-checksummed
XXH64 in pure Python, checked against the reference vectors of tests/study/test_checkpoint.cpp and against SRC's own
checksum before anything is written."""
import struct
import sys

M = (1 << 64) - 1
P1, P2, P3, P4, P5 = (11400714785074694791, 14029467366897019727, 1609587929392839161, 9650029242287828579,
                      2870177450012600261)


def rotl(x, r):
    return ((x << r) | (x >> (64 - r))) & M


def rnd(acc, v):
    return (rotl((acc + v * P2) & M, 31) * P1) & M


def xxh64(b, seed=0):
    n, i = len(b), 0
    if n >= 32:
        v = [(seed + P1 + P2) & M, (seed + P2) & M, seed, (seed - P1) & M]
        lanes = struct.unpack_from("<%dQ" % ((n // 32) * 4), b, 0)
        for k in range(0, len(lanes), 4):
            v = [rnd(v[j], lanes[k + j]) for j in range(4)]
        i = (n // 32) * 32
        h = (rotl(v[0], 1) + rotl(v[1], 7) + rotl(v[2], 12) + rotl(v[3], 18)) & M
        for x in v:
            h = ((h ^ rnd(0, x)) * P1 + P4) & M
    else:
        h = (seed + P5) & M
    h = (h + n) & M
    while i + 8 <= n:
        h ^= rnd(0, struct.unpack_from("<Q", b, i)[0])
        h = (rotl(h, 27) * P1 + P4) & M
        i += 8
    if i + 4 <= n:
        h ^= (struct.unpack_from("<I", b, i)[0] * P1) & M
        h = (rotl(h, 23) * P2 + P3) & M
        i += 4
    while i < n:
        h ^= (b[i] * P5) & M
        h = (rotl(h, 11) * P1) & M
        i += 1
    h ^= h >> 33
    h = (h * P2) & M
    h ^= h >> 29
    h = (h * P3) & M
    return h ^ (h >> 32)


assert xxh64(b"") == 0xef46db3751d8e999 and xxh64(b"123456789") == 0x8cb841db40e6ae83
assert xxh64(bytes((i * 131 + 7) % 256 for i in range(6403))) == 0xaf2f37993e7d7128


def done_range(b):
    """(offset, length) of the done bytes of snapshot bytes b."""
    assert b[:8] == b"PNDCKPT5", "not a snapshot"
    blen = struct.unpack_from("<Q", b, 32)[0]
    at = 40 + blen
    nc, ns, nd = struct.unpack_from("<3Q", b, at)
    return at + 24 + 8 * nc + 8 * ns, nd


def main():
    _, cmd, src, dst = sys.argv
    assert cmd == "overlap"
    b = bytearray(open(src, "rb").read())
    assert xxh64(bytes(b[:-8])) == struct.unpack_from("<Q", b, len(b) - 8)[0], "SRC's checksum does not match"
    at, nd = done_range(b)
    units = struct.unpack_from("<Q", b, 16)[0]
    have = [u for u in range(units) if b[at + u // 8] >> (u % 8) & 1]
    other = next(u for u in range(units) if not b[at + u // 8] >> (u % 8) & 1)
    assert have, "SRC holds no unit"
    b[at:at + nd] = bytes(nd)
    for u in (have[0], other):
        b[at + u // 8] |= 1 << (u % 8)
    struct.pack_into("<Q", b, len(b) - 8, xxh64(bytes(b[:-8])))
    open(dst, "wb").write(b)
    print(f"{dst}: units {have[0]} (also in {src}) and {other}")


if __name__ == "__main__":
    main()
