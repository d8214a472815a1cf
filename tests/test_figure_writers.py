"""The figures (`plot -o`, `run --plot`, `profile --plot`, `prony --plot`) and
`profile --export` follow the rule of every pavefric writer: they replace
only a file pavefric wrote. Before 2026-12-07 they wrote with matplotlib's
savefig and numpy's savetxt straight onto their paths: `profile scan.txt
--export scan.txt` overwrote the measured profile it had read, and `plot -o`
replaced a user's own figure (or any file) at its path. A figure pavefric
draws now carries 'pavefric <version>' in its PNG text chunk 'Software',
and the core (check_png_replaceable, through check_output's 'png' kind)
replaces an existing PNG only if that chunk, before the image data, says so.
"""
from __future__ import annotations

import struct
import subprocess
import sys
import zlib

import numpy as np
import pytest

import pavefric
from conftest import write_scene

TIMEOUT = 300


def cli(*args, cwd):
    return subprocess.run([sys.executable, "-m", "pavefric", *map(str, args)],
                          capture_output=True, text=True, cwd=cwd, timeout=TIMEOUT)


def chunk(kind: bytes, data: bytes) -> bytes:
    return struct.pack(">I", len(data)) + kind + data + struct.pack(
        ">I", zlib.crc32(kind + data) & 0xFFFFFFFF)


def png(*before_image: bytes, after_image: bytes = b"") -> bytes:
    """A 1x1 grey PNG with the given chunks between its header and its image
    data (and after it)."""
    header = chunk(b"IHDR", struct.pack(">IIBBBBB", 1, 1, 8, 0, 0, 0, 0))
    image = chunk(b"IDAT", zlib.compress(b"\x00\x80"))
    return (b"\x89PNG\r\n\x1a\n" + header + b"".join(before_image) + image + after_image
            + chunk(b"IEND", b""))


def software(path) -> str | None:
    """The PNG's 'Software' text, read independently of the core (tEXt)."""
    data = path.read_bytes()
    assert data[:8] == b"\x89PNG\r\n\x1a\n"
    at = 8
    while at + 8 <= len(data):
        length, kind = struct.unpack(">I4s", data[at:at + 8])
        body = data[at + 8:at + 8 + length]
        if kind == b"tEXt" and body.startswith(b"Software\x00"):
            return body[9:].decode("latin-1")
        if kind in (b"IDAT", b"IEND"):
            return None
        at += 12 + length
    return None


@pytest.fixture()
def run_dir(tmp_path, profile_m):
    scene = write_scene(tmp_path, profile=profile_m)
    r = cli("run", scene, "-o", tmp_path / "out.nc", cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    return tmp_path


def own_figure(tmp_path) -> bytes:
    """A figure of the user's, drawn by matplotlib (its own 'Software')."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots()
    ax.plot([0, 1], [1, 0])
    fig.savefig(tmp_path / "mine.png")
    plt.close(fig)
    return (tmp_path / "mine.png").read_bytes()


def no_temporaries(d):
    assert sorted(p.name for p in d.iterdir() if ".tmp" in p.name) == []


def test_plot_replaces_only_a_figure_pavefric_drew(run_dir):
    mine = own_figure(run_dir)
    r = cli("plot", "out.nc", "-o", "mine.png", cwd=run_dir)
    assert r.returncode == 1
    assert "'mine.png': exists and is not a figure pavefric drew" in r.stderr
    assert "replaces only its own outputs" in r.stderr
    assert (run_dir / "mine.png").read_bytes() == mine
    # its own figure is replaced, and says who drew it
    assert cli("plot", "out.nc", "-o", "mu.png", cwd=run_dir).returncode == 0
    assert software(run_dir / "mu.png") == f"pavefric {pavefric.__version__}"
    before = (run_dir / "mu.png").stat().st_ino
    r = cli("plot", "out.nc", "-o", "mu.png", "--title", "again", cwd=run_dir)
    assert r.returncode == 0, r.stderr
    assert (run_dir / "mu.png").stat().st_ino != before          # through a rename
    # an empty file is replaced; a text file named .png is refused
    (run_dir / "empty.png").touch()
    assert cli("plot", "out.nc", "-o", "empty.png", cwd=run_dir).returncode == 0
    (run_dir / "notes.png").write_text("the user's notes\n")
    assert cli("plot", "out.nc", "-o", "notes.png", cwd=run_dir).returncode == 1
    assert (run_dir / "notes.png").read_text() == "the user's notes\n"
    no_temporaries(run_dir)


def test_a_figure_path_must_end_in_png_and_never_be_an_input(run_dir):
    nc = (run_dir / "out.nc").read_bytes()
    for target in ("out.nc", "scene.nml", "figure.pdf"):
        before = (run_dir / target).read_bytes() if (run_dir / target).exists() else None
        r = cli("plot", "out.nc", "-o", target, cwd=run_dir)
        assert r.returncode == 1
        assert f"'{target}': pavefric draws its figures as PNG" in r.stderr
        after = (run_dir / target).read_bytes() if (run_dir / target).exists() else None
        assert after == before
    assert (run_dir / "out.nc").read_bytes() == nc
    # a NetCDF output renamed .png is still the plot's input
    (run_dir / "out.png").write_bytes(nc)
    r = cli("plot", "out.png", "-o", "out.png", cwd=run_dir)
    assert r.returncode == 1
    assert "is an input" in r.stderr
    assert (run_dir / "out.png").read_bytes() == nc
    no_temporaries(run_dir)


def test_run_plot_is_checked_before_the_run(run_dir):
    mine = own_figure(run_dir)
    r = cli("run", "scene.nml", "-o", "again.nc", "--plot", "mine.png", cwd=run_dir)
    assert r.returncode == 1
    assert "'mine.png': exists and is not a figure pavefric drew" in r.stderr
    assert not (run_dir / "again.nc").exists()                   # no run was made
    assert (run_dir / "mine.png").read_bytes() == mine
    r = cli("run", "scene.nml", "-o", "again.nc", "--plot", "again.png", cwd=run_dir)
    assert r.returncode == 0, r.stderr
    assert software(run_dir / "again.png").startswith("pavefric ")


@pytest.mark.parametrize("chunks, after, ours", [
    ((chunk(b"tEXt", b"Software\x00pavefric 9.9"),), b"", True),
    ((chunk(b"tEXt", b"Title\x00x"), chunk(b"tEXt", b"Software\x00pavefric")), b"", True),
    ((chunk(b"iTXt", b"Software\x00\x00\x00en\x00Software\x00pavefric 1"),), b"", True),
    ((chunk(b"tEXt", b"Software\x00Matplotlib version3.8"),), b"", False),
    ((chunk(b"tEXt", b"Comment\x00pavefric"),), b"", False),               # another key
    ((chunk(b"tEXt", b"Software\x00not pavefric"),), b"", False),          # not its start
    ((), chunk(b"tEXt", b"Software\x00pavefric"), False),                  # after the image
    ((chunk(b"zTXt", b"Software\x00\x00" + zlib.compress(b"pavefric")),), b"", False),
    ((chunk(b"iTXt", b"Software\x00\x01\x00\x00\x00" + zlib.compress(b"pavefric")),), b"",
     False),                                                                # compressed
], ids=["tEXt", "second", "iTXt", "matplotlib", "other-key", "not-start", "after-image",
        "zTXt", "iTXt-compressed"])
def test_the_core_reads_the_software_chunk(tmp_path, chunks, after, ours):
    path = tmp_path / "f.png"
    path.write_bytes(png(*chunks, after_image=after))
    if ours:
        pavefric.check_output(path, replaces="png")
    else:
        with pytest.raises(pavefric.PavefricError, match="not a figure pavefric drew"):
            pavefric.check_output(path, replaces="png")


@pytest.mark.parametrize("data", [
    b"\x89PNG\r\n\x1a\n",                                       # the magic alone
    png(chunk(b"tEXt", b"Software\x00pavefric"))[:40],          # cut inside the chunk
    b"\x89PNG\r\n\x1a\n" + b"\xff\xff\xff\xfftEXtSoftware\x00pavefric",   # a length past the end
    b"\x89PNG\r\n\x1a\n" + b"\x00\x00\x00\x00tEXt" * 20000,     # many empty chunks
    b"GIF89a" + b"Software\x00pavefric",                        # not a PNG
], ids=["magic", "truncated", "huge-length", "many-chunks", "not-png"])
def test_forged_or_cut_pngs_are_refused(tmp_path, data):
    path = tmp_path / "f.png"
    path.write_bytes(data)
    with pytest.raises(pavefric.PavefricError, match="not a figure pavefric drew"):
        pavefric.check_output(path, replaces="png")
    assert path.read_bytes() == data


def test_profile_export_never_replaces_the_profile_it_read(tmp_path, profile_m):
    """The reproducer: `profile scan.txt --export scan.txt` overwrote the
    measured profile with its cleaned copy."""
    scan = tmp_path / "scan.txt"
    np.savetxt(scan, profile_m * 1e3)
    before = scan.read_bytes()
    r = cli("profile", scan, "--export", scan, cwd=tmp_path)
    assert r.returncode == 1
    assert "is an input" in r.stderr
    assert scan.read_bytes() == before
    # nor a file it did not write; its own export is replaced
    notes = tmp_path / "notes.txt"
    notes.write_text("0.1\n0.2\n")
    r = cli("profile", scan, "--export", notes, cwd=tmp_path)
    assert r.returncode == 1
    assert "is not a file this command wrote" in r.stderr
    assert notes.read_text() == "0.1\n0.2\n"
    clean = tmp_path / "clean.txt"
    assert cli("profile", scan, "--export", clean, cwd=tmp_path).returncode == 0
    assert clean.read_text().startswith("# pavefric profile: cleaned from ")
    assert cli("profile", scan, "--export", clean, cwd=tmp_path).returncode == 0
    heights = np.loadtxt(clean)[:, 1] * 1e-3
    np.testing.assert_allclose(heights, profile_m, rtol=0, atol=1e-15)
    # the figure is checked first: a refused one leaves the export unwritten
    mine = own_figure(tmp_path)
    r = cli("profile", scan, "--plot", "mine.png", "--export", "other.txt", cwd=tmp_path)
    assert r.returncode == 1
    assert not (tmp_path / "other.txt").exists()
    assert (tmp_path / "mine.png").read_bytes() == mine
    no_temporaries(tmp_path)


def test_prony_plot_is_checked_before_the_fit(tmp_path):
    from test_rubber import _prony_data

    data = _prony_data(tmp_path, 3e6, [4e8, 5e7], [1e-6, 1e-3], [-10.0, 10.0, 30.0])
    mine = own_figure(tmp_path)
    r = cli("prony", data, "-o", "c.nml", "--plot", "mine.png", cwd=tmp_path)
    assert r.returncode == 1
    assert "'mine.png': exists and is not a figure pavefric drew" in r.stderr
    assert not (tmp_path / "c.nml").exists()
    assert (tmp_path / "mine.png").read_bytes() == mine
    r = cli("prony", data, "-o", "c.png", "--plot", "c.png", cwd=tmp_path)
    assert r.returncode == 1 and "is the -o path" in r.stderr
    assert not (tmp_path / "c.png").exists()
    r = cli("prony", data, "-o", "c.nml", "--plot", "fit.png", cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    assert software(tmp_path / "fit.png").startswith("pavefric ")
    no_temporaries(tmp_path)
