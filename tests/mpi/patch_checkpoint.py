#!/usr/bin/env python3
"""Damages a checkpoint file the ways a restart must refuse (common/io/checkpoint_file.h):
  patch_checkpoint.py FILE truncate        keep the first half
  patch_checkpoint.py FILE flip            flip one bit in the middle (checksum now wrong)
  patch_checkpoint.py FILE format N        set the format version (checksum left as is:
                                           the version is read before the checksum)
  patch_checkpoint.py FILE protocol N      set the protocol version and fix the checksum,
                                           so only the version is wrong"""
import struct
import sys


def fnv1a(data):
    h = 1469598103934665603
    for b in data:
        h = ((h ^ b) * 1099511628211) & 0xFFFFFFFFFFFFFFFF
    return h


path, mode = sys.argv[1], sys.argv[2]
with open(path, "rb") as f:
    data = bytearray(f.read())
if mode == "truncate":
    data = data[: len(data) // 2]
elif mode == "flip":
    data[len(data) // 2] ^= 0x10
elif mode == "format":
    data[8:12] = struct.pack("<I", int(sys.argv[3]))
elif mode == "protocol":
    data[12:14] = struct.pack("<H", int(sys.argv[3]))
    data[-8:] = struct.pack("<Q", fnv1a(bytes(data[:-8])))
else:
    sys.exit(f"unknown mode {mode}")
with open(path, "wb") as f:
    f.write(data)
