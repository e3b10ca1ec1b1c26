"""``stgen demo --out D`` never overwrites a file stgen did not write, never writes through a
symbolic link out of D, and says what it wrote (issue 9)."""

from __future__ import annotations

import pytest

from stgen import cli
from stgen.commands import demo
from stgen.scenarios import definitions, platforms


@pytest.fixture()
def one_short_wave(monkeypatch):
    monkeypatch.setattr(demo, "QUICK_WAVE_SECONDS", 0.2)
    monkeypatch.setattr(definitions, "SCENARIOS", (definitions.AIRY_WAVE,))
    monkeypatch.setattr(platforms, "PLATFORM_SCENARIOS", ())
    monkeypatch.setattr(demo, "_path_scenarios", lambda quick, scratch: [])  # no path or playback either


def test_a_symlink_in_d_to_a_file_outside_is_refused_before_any_run(tmp_path, capsys):
    victim = tmp_path / "victim.txt"
    victim.write_text("precious\n", encoding="utf-8")
    out = tmp_path / "D"
    out.mkdir()
    (out / "random_wave.csv").symlink_to("../victim.txt")
    assert cli.main(["demo", "--quick", "--out", str(out)]) == 1
    captured = capsys.readouterr()
    assert "random_wave.csv: is a symbolic link" in captured.err and "Traceback" not in captured.err
    assert "Generated the controller" not in captured.out  # refused before generating or running
    assert victim.read_text(encoding="utf-8") == "precious\n"


def test_the_users_csv_and_png_in_d_are_not_overwritten(tmp_path, capsys):
    (tmp_path / "airy_wave.csv").write_text("my,data\n1,2\n", encoding="utf-8")
    (tmp_path / "point_to_point.png").write_bytes(b"my picture")
    assert cli.main(["demo", "--quick", "--out", str(tmp_path)]) == 1
    err = capsys.readouterr().err
    assert "airy_wave.csv: exists and was not written by stgen" in err
    assert "point_to_point.png: exists and was not written by stgen" in err
    assert (tmp_path / "airy_wave.csv").read_text(encoding="utf-8") == "my,data\n1,2\n"
    assert (tmp_path / "point_to_point.png").read_bytes() == b"my picture"


def test_a_symlinked_generated_folder_leading_out_of_d_is_refused(tmp_path, capsys):
    elsewhere = tmp_path / "elsewhere"
    elsewhere.mkdir()
    out = tmp_path / "D"
    out.mkdir()
    (out / "generated").symlink_to(elsewhere)
    assert cli.main(["demo", "--quick", "--out", str(out)]) == 1
    assert "generated: is a symbolic link" in capsys.readouterr().err
    assert list(elsewhere.iterdir()) == []


def test_a_second_demo_replaces_its_own_files_and_says_what_it_wrote(tmp_path, one_short_wave, capsys):
    assert cli.main(["demo", "--quick", "--out", str(tmp_path)]) == 0
    capsys.readouterr()
    (tmp_path / "notes.txt").write_text("mine\n", encoding="utf-8")
    assert cli.main(["demo", "--quick", "--out", str(tmp_path)]) == 0
    out = capsys.readouterr().out
    assert f"Wrote 2 traces and figures in {tmp_path}/ (--quick: each CSV keeps one scan in 10): airy_wave.csv, airy_wave.png" in out
    assert (tmp_path / "notes.txt").read_text(encoding="utf-8") == "mine\n"


@pytest.mark.parametrize("command", ["generate", "demo"])
def test_an_empty_out_path_is_refused(tmp_path, monkeypatch, capsys, command):
    monkeypatch.chdir(tmp_path)
    assert cli.main([command, "--out", ""]) == 2
    assert "--out: empty path" in capsys.readouterr().err
    assert list(tmp_path.iterdir()) == []
