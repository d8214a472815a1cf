"""The batch journal (issue 10 items 5 and 6): SHA-256 digests of every
input, each line checked before a resume trusts it, every write checked."""
import hashlib
import os
import shutil
import subprocess

import numpy as np
import pytest
import xarray as xr

from conftest import program, run_program
from test_batch import make_batch, same_contents

SHA256_VECTORS = {          # FIPS 180-4 / NIST examples
    b"": "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855",
    b"abc": "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad",
    b"abcdbcdecdefdefgefghfghighijhijkijkljklmklmnlmnomnopnopq":
        "248d6a61d20638b8e5c026930c3e6039a33ce45964ff2167f6ecedd419db06c1",
    b"a" * 1_000_000: "cdc76e5c9914fb9281a1c7e284d73e67f1809a48a497200e046d39ccc7112cd0",
}


def journal_lines(path):
    """The journal's profile lines as (checksum, body, digest, values, message)."""
    out = []
    for line in path.read_text().split("\n")[1:]:
        if not line.startswith("P "):
            continue
        checksum, body = line[2:66], line[67:]
        values, message = body[64:].split(" ;", 1)
        out.append((checksum, body, body[:64], values.split(), message))
    return out


def make_line(digest, values, message=""):
    """A journal line as pavefric writes it, with a correct checksum."""
    body = digest + "".join(f" {v:>25s}" for v in values) + " ;" + message
    return "P " + hashlib.sha256(body.encode()).hexdigest() + " " + body


def test_sha256_of_profile_files_matches_the_standard_vectors(tmp_path):
    # the journal records the SHA-256 of each profile file's bytes, even of
    # a file that is not a profile: the FIPS vectors, then lengths around the
    # 55/56/64-byte padding boundaries against hashlib
    rng = np.random.default_rng(3)
    contents = list(SHA256_VECTORS) + [rng.bytes(n) for n in (1, 55, 56, 57, 63, 64, 65, 119,
                                                               120, 128, 65537)]
    d = tmp_path / "files"
    d.mkdir()
    names = []
    for k, data in enumerate(contents):
        (d / f"f{k:02d}.txt").write_bytes(data)
        names.append(f"files/f{k:02d}.txt")
    (tmp_path / "list.txt").write_text("\n".join(names + ["files/zz_last.txt"]) + "\n")
    (d / "zz_last.txt").write_text("height_mm\n" + "\n".join("0.1"
                                                              for _ in range(64)) + "\n")
    scene = tmp_path / "s.nml"
    scene.write_text("&batch profile_list = 'list.txt' /\n&surface closed = .false. /\n"
                     "&operation speeds_kmh = 20 /\n")
    r = run_program(scene, "-o", tmp_path / "o.nc", "--max-profiles", str(len(contents)))
    assert r.returncode == 3, r.stderr
    lines = journal_lines(tmp_path / "o.nc.journal")
    assert len(lines) == len(contents)
    for (checksum, body, digest, values, _), data in zip(lines, contents):
        assert digest == hashlib.sha256(data).hexdigest()
        assert checksum == hashlib.sha256(body.encode()).hexdigest()
    for (_, _, digest, _, _), data in zip(lines, contents):
        if data in SHA256_VECTORS:
            assert digest == SHA256_VECTORS[data]


def test_profile_edited_between_stop_and_resume_is_recomputed(tmp_path):
    scene = make_batch(tmp_path, n=10)
    out = tmp_path / "o.nc"
    assert run_program(scene, "-o", out, "--max-profiles", "6").returncode == 3
    # swap two heights of profile 3 (same bytes, other order: the old
    # Adler-32 of paths only never saw it)
    p = tmp_path / "profiles" / "seg_0003.txt"
    lines = p.read_text().splitlines()
    lines[10], lines[11] = lines[11], lines[10]
    p.write_text("\n".join(lines) + "\n")
    r = run_program(scene, "-o", out)
    assert r.returncode == 0, r.stderr
    assert "resuming: 5 of 10 profiles already done" in r.stderr
    assert "1 profile file(s) changed since the journal (recomputed)" in r.stderr
    assert "5 done in this run (failed included), 5 taken from the journal" in r.stdout
    clean = tmp_path / "clean.nc"
    assert run_program(scene, "-o", clean).returncode == 0
    same_contents(clean, out)


@pytest.mark.parametrize("change", ["speeds_kmh = 20, 60|speeds_kmh = 60, 20",
                                    "depths = 0.0, 1.0e-3|depths = 1.0e-3, 0.0"])
def test_swapped_speeds_or_depths_refuse_the_journal(tmp_path, change):
    scene = make_batch(tmp_path, n=6)
    out = tmp_path / "o.nc"
    assert run_program(scene, "-o", out, "--max-profiles", "2").returncode == 3
    old, new = change.split("|")
    scene.write_text(scene.read_text().replace(old, new))
    r = run_program(scene, "-o", out)
    assert r.returncode == 1 and "belongs to another batch" in r.stderr


def test_adler32_collision_no_longer_resumes_a_journal(tmp_path):
    # the old fingerprint, Adler-32 of the scene text and paths, is blind to
    # two speeds swapped when a comment changes to match: here both texts
    # have the same Adler-32, and the old code resumed with swapped results
    import zlib

    scene = make_batch(tmp_path, n=6)
    base = scene.read_text()
    first = base + "! note: " + "b" + "a" * 15 + "a" + "\n"
    second = (base.replace("speeds_kmh = 20, 60", "speeds_kmh = 60, 20") +
              "! note: " + "a" + "a" * 15 + "b" + "\n")
    assert zlib.adler32(first.encode()) == zlib.adler32(second.encode())
    scene.write_text(first)
    out = tmp_path / "o.nc"
    assert run_program(scene, "-o", out, "--max-profiles", "3").returncode == 3
    scene.write_text(second)
    r = run_program(scene, "-o", out)
    assert r.returncode == 1 and "belongs to another batch" in r.stderr, r.stdout + r.stderr


def test_damaged_journal_lines_are_recomputed_never_trusted(tmp_path):
    scene = make_batch(tmp_path, n=10)
    out = tmp_path / "o.nc"
    clean = tmp_path / "clean.nc"
    assert run_program(scene, "-o", clean).returncode == 0
    assert run_program(scene, "-o", out, "--max-profiles", "9").returncode == 3
    journal = tmp_path / "o.nc.journal"
    text = journal.read_text().split("\n")
    header, rows = text[0], text[1:10]
    parsed = journal_lines(journal)
    assert len(parsed) == 9 and len(rows) == 9

    def with_value(k, pos, value):
        _, _, digest, values, message = parsed[k]
        values = list(values)
        values[pos] = value
        return make_line(digest, values, message)

    mu = 18                                            # first mu value (0-based)
    flipped = rows[0][:200] + ("1" if rows[0][200] != "1" else "2") + rows[0][201:]
    rows[0] = flipped                                  # a flipped digit: checksum fails
    rows[1] = with_value(1, mu, "NaN")                 # valid checksum, NaN
    rows[2] = with_value(2, mu, "Infinity")            # valid checksum, Infinity
    rows[3] = with_value(3, 0, "1.10000000000000000E+001")   # index 11 of 10
    rows[4] = with_value(4, 1, "3.00000000000000000E+000")   # status 3
    rows[5] = with_value(5, 0, "2.50000000000000000E+000")   # index 2.5
    _, _, digest, values, message = parsed[6]
    rows[6] = make_line("0" * 64, values, message)     # another file's content
    rows[7] = rows[7][:len(rows[7]) // 2]              # cut in the middle
    journal.write_text("\n".join([header] + rows) + "\n")
    r = run_program(scene, "-o", out)
    assert r.returncode == 0, r.stderr
    assert "resuming: 1 of 10 profiles already done" in r.stderr
    assert "7 damaged journal line(s) ignored" in r.stderr
    assert "1 profile file(s) changed since the journal (recomputed)" in r.stderr
    same_contents(clean, out)
    with xr.open_dataset(out) as ds:
        assert np.all(np.isfinite(ds["mu"].values))


def test_line_cut_by_a_kill_does_not_swallow_the_next(tmp_path):
    # a kill leaves a line without its newline; the resumed run must end it
    # before appending, or its first line is lost (recomputed on a later resume)
    scene = make_batch(tmp_path, n=10)
    out = tmp_path / "o.nc"
    assert run_program(scene, "-o", out, "--max-profiles", "4").returncode == 3
    journal = tmp_path / "o.nc.journal"
    text = journal.read_text()
    journal.write_text(text[:-300])                    # the 4th line cut short
    assert run_program(scene, "-o", out, "--max-profiles", "3").returncode == 3
    r = run_program(scene, "-o", out, "--max-profiles", "1")
    assert "resuming: 6 of 10 profiles already done; 1 damaged journal line(s)" in r.stderr


SHIM = r"""
#define _GNU_SOURCE
#include <dlfcn.h>
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
/* write(2) on a file named *.journal fails with ENOSPC (a full disk) once
   FAIL_JOURNAL_AFTER bytes have been written to such files. */
static long written = 0;
ssize_t write(int fd, const void *buf, size_t n)
{
    static ssize_t (*real)(int, const void *, size_t);
    char link[64], path[4096];
    ssize_t k;
    if (!real) real = (ssize_t (*)(int, const void *, size_t))dlsym(RTLD_NEXT, "write");
    snprintf(link, sizeof link, "/proc/self/fd/%d", fd);
    k = readlink(link, path, sizeof path - 1);
    if (k > 8) {
        path[k] = 0;
        if (strcmp(path + k - 8, ".journal") == 0) {
            const char *limit = getenv("FAIL_JOURNAL_AFTER");
            if (limit && written + (long)n > atol(limit)) { errno = ENOSPC; return -1; }
            written += (long)n;
        }
    }
    return real(fd, buf, n);
}
"""


@pytest.fixture(scope="module")
def full_disk_shim(tmp_path_factory):
    """An LD_PRELOAD library that makes the journal's disk full."""
    d = tmp_path_factory.mktemp("shim")
    (d / "shim.c").write_text(SHIM)
    cc = shutil.which("cc") or shutil.which("gcc")
    assert cc, "a C compiler is needed (the build needs one too)"
    subprocess.run([cc, "-shared", "-fPIC", "-o", str(d / "shim.so"), str(d / "shim.c"), "-ldl"],
                   check=True, timeout=120)
    return d / "shim.so"


def test_journal_write_failure_stops_the_batch(tmp_path, full_disk_shim):
    # the old code computed all 300 profiles with the journal stuck at 10
    # and exited 0
    scene = make_batch(tmp_path, n=40)
    out = tmp_path / "o.nc"
    env = {**os.environ, "LD_PRELOAD": str(full_disk_shim), "FAIL_JOURNAL_AFTER": "6000"}
    r = subprocess.run([program(), str(scene), "-o", str(out)], capture_output=True, text=True,
                       env=env, timeout=600)
    assert r.returncode == 1, r.stdout + r.stderr
    assert "writing the journal" in r.stderr and "No space left on device" in r.stderr
    assert not out.exists()
    kept = len(journal_lines(tmp_path / "o.nc.journal"))
    assert 1 <= kept < 10
    # once the disk has room, the same command resumes from what was kept
    r = run_program(scene, "-o", out)
    assert r.returncode == 0, r.stderr
    assert f"resuming: {kept} of 40 profiles already done" in r.stderr
    clean = tmp_path / "clean.nc"
    assert run_program(scene, "-o", clean).returncode == 0
    same_contents(clean, out)


def test_journal_write_failure_under_mpi_ends_every_rank(tmp_path, full_disk_shim):
    from test_mpi_batch import mpirun, rank_exits

    scene = make_batch(tmp_path, n=40)
    r = mpirun(scene, "-o", tmp_path / "o.nc", wrap_exit=True,
               env_extra={"LD_PRELOAD": str(full_disk_shim), "FAIL_JOURNAL_AFTER": "6000"})
    assert rank_exits(r) == ["1", "1"], r.stdout + r.stderr
    assert r.stderr.count("writing the journal") == 1
    assert not (tmp_path / "o.nc").exists()
