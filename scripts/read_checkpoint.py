#!/usr/bin/env python3
"""Reads a seismpm checkpoint (docs/checkpoint.md) with the standard library only.

    python3 scripts/read_checkpoint.py FILE            # a summary: sections, clock, bodies, particles
    python3 scripts/read_checkpoint.py FILE FIELD ...  # also these particle members (x u v mass ...)

As a module: read_checkpoint(path) -> dict of section tag -> payload bytes (checked: magic, version,
CRC-32 of every section) and "version" -> the format version, and particles(sections, dim) -> dict of
member name -> list of values (a version 2 file's damping_stress as zeros).
"""
import struct
import sys
import zlib

MAGIC = b"SEISMPMCHK"
VERSIONS = (2, 3)  # 3 added Rayleigh damping (damping_stress; alpha, beta per deformable material)
# Particles::for_each_member's order; the element size comes from the file.
PARTICLE_MEMBERS = ["x", "u", "v", "affine", "mass", "volume", "half_width", "stress", "damping_stress", "strain",
                    "plastic_strain", "yield", "normal", "id", "body", "material"]
INTEGER_MEMBERS = {"yield": "B", "id": "i", "body": "H", "material": "H"}


class CheckpointError(Exception):
    pass


def read_checkpoint(path):
    data = open(path, "rb").read()
    if len(data) < 16:
        raise CheckpointError(f"{path}: too short for a checkpoint")
    if data[:10] != MAGIC:
        raise CheckpointError(f"{path}: not a seismpm checkpoint")
    (version,) = struct.unpack_from("<H", data, 10)
    if version not in VERSIONS:
        raise CheckpointError(f"{path}: format version {version}, this reader knows {VERSIONS}")
    sections, at = {"version": version}, 16
    while True:
        if len(data) - at < 20:
            raise CheckpointError(f"{path}: truncated (no END section)")
        tag = data[at:at + 8].rstrip(b"\0").decode("ascii")
        (length,) = struct.unpack_from("<Q", data, at + 8)
        if length > len(data) - at - 20:
            raise CheckpointError(f"{path}: truncated inside section {tag}")
        payload = data[at + 16:at + 16 + length]
        (crc,) = struct.unpack_from("<I", data, at + 16 + length)
        if zlib.crc32(data[at:at + 16 + length]) != crc:
            raise CheckpointError(f"{path}: section {tag} is corrupt (CRC-32 mismatch)")
        at += 20 + length
        if tag == "END":
            break
        sections[tag] = payload
    return sections


class Reader:
    def __init__(self, payload):
        self.data, self.at = payload, 0

    def take(self, fmt):
        values = struct.unpack_from("<" + fmt, self.data, self.at)
        self.at += struct.calcsize("<" + fmt)
        return values if len(values) > 1 else values[0]

    def text(self):
        n = self.take("I")
        s = self.data[self.at:self.at + n].decode("utf-8", "replace")
        self.at += n
        return s


def meta(sections):
    r = Reader(sections["META"])
    return {"program": r.text(), "dim": r.take("I"), "time": r.take("d"), "steps": r.take("q"), "phase": r.text()}


def bodies(sections):
    r = Reader(sections["BODIES"])
    out = []
    for _ in range(r.take("q")):
        out.append({"name": r.text(), "ppc": r.take("i"), "rigid": bool(r.take("B")), "material": r.take("i")})
    return out


def particles(sections, dim):
    r = Reader(sections["PARTICLE"])
    n = r.take("q")
    out = {}
    for name in PARTICLE_MEMBERS:
        if name == "damping_stress" and sections["version"] < 3:
            out[name] = [(0.0,) * 6] * n  # before Rayleigh damping: none
            continue
        count, size = r.take("q"), r.take("I")
        raw = r.data[r.at:r.at + count * size]
        r.at += count * size
        if name in INTEGER_MEMBERS:
            code = INTEGER_MEMBERS[name]
            out[name] = list(struct.unpack(f"<{count}{code}", raw))
        else:
            per = size // 8
            flat = struct.unpack(f"<{count * per}d", raw)
            out[name] = list(flat) if per == 1 else [flat[k * per:(k + 1) * per] for k in range(count)]
        assert count == n
    return out


def main(argv):
    if len(argv) < 2:
        print(__doc__)
        return 2
    try:
        sections = read_checkpoint(argv[1])
    except (OSError, CheckpointError) as e:
        print(f"read_checkpoint: {e}", file=sys.stderr)
        return 1
    m = meta(sections)
    print(f"{argv[1]}: {m['dim']}D model, t = {m['time']!r} s, step {m['steps']}, phase {m['phase']}")
    print(f"format version {sections['version']}; sections: " +
          ", ".join(f"{t} ({len(p)} bytes)" for t, p in sections.items() if t != "version"))
    for b in bodies(sections):
        print(f"body '{b['name']}': {'rigid' if b['rigid'] else 'deformable'}, ppc {b['ppc']}")
    p = particles(sections, m["dim"])
    print(f"particles: {len(p['id'])}")
    for name in argv[2:]:
        if name not in p:
            print(f"read_checkpoint: no particle member {name} ({' '.join(PARTICLE_MEMBERS)})", file=sys.stderr)
            return 1
        print(name + ": " + " ".join(repr(v) for v in p[name][:10]) + (" ..." if len(p[name]) > 10 else ""))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
