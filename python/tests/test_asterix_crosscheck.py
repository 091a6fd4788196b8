"""argus-asterix against an independent ASTERIX decoder: the `asterix-decoder` PyPI package
(a C++ extension, GPL; a test tool only, installed into the test venv from
python/requirements-test.txt, never vendored or linked).

(a) Argus-written CAT048/034/021/062 samples decode, in that package, to the values Argus
    decodes from them (field by field: every field Argus interprets).
(b) Argus decodes the package's own sample captures, fetched from its sdist at test time, to
    the values the package prints, and where the package cannot parse a record (a capture of
    another CAT062 edition) Argus reports a typed skip too.

Argus's side comes from the `asterix_json` example of crates/asterix (built by
`cargo xtask test`; path in ARGUS_ASTERIX_JSON), which names the fields as the package does and
gives them in the wire's physical units. The pcap samples are unpacked to their UDP payloads
here (classic pcap, Ethernet or Linux cooked, IPv4/UDP); that is the test's own extraction,
not Argus's pcap reader.
"""

from __future__ import annotations

import json
import os
import pathlib
import struct
import subprocess
import sys
import tarfile

import asterix
import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
KNOWN = {21, 34, 48, 62}


@pytest.fixture(scope="session")
def tool() -> str:
    path = os.environ.get("ARGUS_ASTERIX_JSON")
    if not path:
        target = pathlib.Path(os.environ.get("CARGO_TARGET_DIR", ROOT / "target"))
        path = str(target / "debug" / "examples" / "asterix_json")
    assert os.path.exists(path), (
        "the asterix_json example is needed "
        f"(cargo build -p argus-asterix --example asterix_json): {path}"
    )
    return path


def argus(tool: str, raw: bytes, tmp: pathlib.Path) -> dict:
    f = tmp / "input.raw"
    f.write_bytes(raw)
    done = subprocess.run([tool, "decode", str(f)], capture_output=True, check=True)
    return json.loads(done.stdout)


def same(a, d) -> bool:
    # Floats: both sides scale the same integer count; the package multiplies by its
    # configuration's decimal scale (≥ 16 significant digits), so 1e-12 relative is ample
    # and still far below every LSB here (the finest, I021/131, is 1.7e-7 °).
    if isinstance(a, float) or isinstance(d, float):
        return abs(a - d) <= 1e-12 * max(1.0, abs(a))
    return a == d


def compare(a_rec: dict, d_rec: dict) -> int:
    """Asserts every field Argus decoded equals the package's; returns the fields compared."""
    assert a_rec["category"] == d_rec["category"]
    n = 0
    for item, fields in a_rec["items"].items():
        cat = a_rec["category"]
        assert item in d_rec, f"CAT{cat:03} {item}: not in the package's record {d_rec}"
        for field, value in fields.items():
            theirs = d_rec[item][field]["val"]
            assert same(value, theirs), (
                f"CAT{cat:03} {item}/{field}: Argus {value!r}, package {theirs!r}"
            )
            n += 1
    return n


def has_items(rec: dict) -> bool:
    return any(k.startswith("I") for k in rec)


def cross_check(tool: str, raw: bytes, tmp: pathlib.Path) -> tuple[int, int, int]:
    """One UDP payload or raw file. Returns (records compared, fields compared, payloads both
    refuse)."""
    ours = argus(tool, raw, tmp)
    theirs = [r for r in asterix.parse(raw, verbose=False) if r["category"] in KNOWN]
    failed = [i for i, r in enumerate(theirs) if r.get("hexdata") is None]
    if failed:
        # The package lost the framing (and resynchronises on what follows, which Argus
        # does not): Argus must report a typed skip, and the records before agree.
        assert ours["skipped"], "the package failed on this payload but Argus reported nothing"
        assert all(s["offset"] <= len(raw) for s in ours["skipped"])
        before = [r for r in theirs[: failed[0]] if has_items(r)]
        assert len(ours["records"]) >= len(before)
        fields = sum(compare(a, d) for a, d in zip(ours["records"], before))
        return len(before), fields, 1
    # An empty FSPEC: a record without items for the package, a typed EmptyRecord skip for Argus.
    empty = sum(1 for r in theirs if not has_items(r))
    assert sum(1 for s in ours["skipped"] if s["reason"] == "EmptyRecord") == empty
    full = [r for r in theirs if has_items(r)]
    assert len(ours["records"]) == len(full), (ours["skipped"], len(full))
    return len(full), sum(compare(a, d) for a, d in zip(ours["records"], full)), 0


def test_package_decodes_argus_written_samples(tool, tmp_path):
    raw_file = tmp_path / "samples.raw"
    subprocess.run([tool, "samples", str(raw_file)], check=True)
    raw = raw_file.read_bytes()
    ours = argus(tool, raw, tmp_path)
    # The unknown-category block is the only skip.
    assert [s["reason"] for s in ours["skipped"]] == ["UnknownCategory"]
    theirs = [r for r in asterix.parse(raw, verbose=False) if r["category"] in KNOWN]
    assert [r["category"] for r in theirs] == [r["category"] for r in ours["records"]]
    per_cat: dict[int, int] = {}
    for a, d in zip(ours["records"], theirs):
        per_cat[a["category"]] = per_cat.get(a["category"], 0) + compare(a, d)
    print(f"Argus-written samples: fields compared per category {per_cat}", file=sys.stderr)
    # Every category present, every field Argus writes (samples.rs: 18 + 2 + 6 + 4 records;
    # CAT021: 6 × 17 fields less the 6 left out on purpose).
    assert per_cat == {48: 404, 34: 10, 21: 96, 62: 40}


def network_failure(text: str) -> bool:
    signs = (
        "NewConnectionError",
        "Temporary failure in name resolution",
        "Network is unreachable",
        "Connection refused",
        "timed out",
        "No matching distribution found",
        "ProxyError",
    )
    return any(s in text for s in signs)


@pytest.fixture(scope="session")
def sdist(tmp_path_factory) -> pathlib.Path:
    """The package's sdist (the installed version), downloaded and unpacked; its sample
    captures are the ones decoded (not committed to this repository)."""
    d = tmp_path_factory.mktemp("asterix-sdist")
    cmd = [sys.executable, "-m", "pip", "download", "-q", "--no-deps", "--no-binary", ":all:"]
    cmd += [f"asterix-decoder=={asterix.__version__}", "-d", str(d)]
    done = subprocess.run(cmd, capture_output=True, text=True, timeout=600, check=False)
    if done.returncode != 0:
        if network_failure(done.stderr + done.stdout):
            why = done.stderr.strip()[-200:]
            pytest.skip(f"no network: PyPI unreachable, the asterix-decoder sdist not downloaded ({why})")
        pytest.fail(f"pip download of the asterix-decoder sdist failed: {done.stderr}")
    (archive,) = d.glob("asterix_decoder-*.tar.gz")
    with tarfile.open(archive) as t:
        # The "data" filter (no absolute paths, links out of the tree) where Python has it.
        if hasattr(tarfile, "data_filter"):
            t.extractall(d, filter="data")
        else:
            t.extractall(d)
    (tree,) = d.glob("asterix_decoder-*/")
    return tree


def udp_payloads(path: pathlib.Path) -> list[bytes]:
    """UDP payloads of a classic pcap (Ethernet with optional VLAN tags, or Linux cooked)."""
    data = path.read_bytes()
    end = "<" if data[:4] in (b"\xd4\xc3\xb2\xa1", b"\x4d\x3c\xb2\xa1") else ">"
    (linktype,) = struct.unpack(end + "I", data[20:24])
    pos, out = 24, []
    while pos + 16 <= len(data):
        _, _, incl, _ = struct.unpack(end + "IIII", data[pos : pos + 16])
        frame = data[pos + 16 : pos + 16 + incl]
        pos += 16 + incl
        if linktype == 1:
            eth = 14
            (etype,) = struct.unpack(">H", frame[12:14])
            while etype == 0x8100:
                (etype,) = struct.unpack(">H", frame[eth + 2 : eth + 4])
                eth += 4
            if etype != 0x0800:
                continue
            ip = frame[eth:]
        elif linktype == 113:
            ip = frame[16:]
        else:
            pytest.fail(f"{path.name}: link type {linktype} not handled by the test")
        if ip[9] != 17:
            continue
        ihl = (ip[0] & 15) * 4
        (total,) = struct.unpack(">H", ip[2:4])
        out.append(ip[ihl + 8 : total])
    return out


# (file, records compared, fields compared, payloads both refuse), package 0.7.11.
SAMPLES = [
    ("asterix/sample_data/cat048.raw", 1, 30, 0),
    ("asterix/sample_data/cat034.raw", 1, 5, 0),
    ("asterix/sample_data/cat062cat065.raw", 2, 20, 0),
    ("install/sample_data/cat_034_048.pcap", 162, 3858, 0),  # 128 CAT048 + 34 CAT034
    ("install/sample_data/cat_062_065.pcap", 2, 20, 0),
    # CAT062 of another edition: 72 of its 100 payloads neither decoder frames with 1.18's
    # I062/390; the 28 both frame agree.
    ("install/sample_data/asterix.pcap", 48, 384, 72),
]


@pytest.mark.parametrize(("name", "records", "fields", "refused"), SAMPLES)
def test_argus_decodes_package_samples(tool, sdist, tmp_path, name, records, fields, refused):
    path = sdist / name
    payloads = udp_payloads(path) if name.endswith(".pcap") else [path.read_bytes()]
    totals = [0, 0, 0]
    for p in payloads:
        for i, v in enumerate(cross_check(tool, p, tmp_path)):
            totals[i] += v
    print(f"{name}: {len(payloads)} payloads; records, fields compared, both refuse: {totals}",
          file=sys.stderr)
    assert totals == [records, fields, refused]
