"""docs/regenerate on a scratch tree of its own: rewriting a block, --check
finding a stale one, the normalisation of machine-dependent fields, claims,
expensive blocks and their stamp, figures.

    /usr/bin/python3 -m pytest -q tests/test_docs_regenerate.py
"""
import shutil
import subprocess
import sys
import textwrap
from pathlib import Path

import pytest

SCRIPT = Path(__file__).resolve().parent.parent / "docs" / "regenerate"


@pytest.fixture
def tree(tmp_path):
    """A repository of one README.md, the script, and a fake `chaosweep`."""
    (tmp_path / "docs").mkdir()
    shutil.copy(SCRIPT, tmp_path / "docs" / "regenerate")
    fake = tmp_path / "fake-chaosweep"
    fake.write_text(textwrap.dedent("""\
        #!/bin/sh
        case "$1" in
          --version) echo "chaosweep 9.9.9 (git 0123456789abcdef0123456789abcdef01234567)";;
          sweep) echo "sweep 'x': 3 runs on $THREADS threads, avx2 kernels"; echo "best CT     $CT s";;
          draw) mkdir -p out; echo png > out/f.png; echo "wrote out/f.png";;
        esac
        """))
    fake.chmod(0o755)
    return tmp_path


def readme(tree, body):
    (tree / "README.md").write_text(textwrap.dedent(body))


def run(tree, *args, **env):
    import os
    e = dict(os.environ, THREADS="2", CT="12.5")
    e.update(env)
    return subprocess.run([sys.executable, str(tree / "docs" / "regenerate"), "--binary", str(tree / "fake-chaosweep"),
                           *args], capture_output=True, text=True, env=e)


BLOCK = """\
    # demo
    <!-- regenerate
    value ct = ^best CT +([\\d.]+) s
    claim ct < 20 # "fast" below
    -->
    ```sh
    chaosweep sweep
    ```
    <!-- /regenerate -->
    """


def test_rewrites_a_block_then_check_passes(tree):
    readme(tree, BLOCK)
    r = run(tree)
    assert r.returncode == 0, r.stderr
    text = (tree / "README.md").read_text()
    assert "```text\nsweep 'x': 3 runs on 2 threads, avx2 kernels\nbest CT     12.5 s\n```" in text
    assert run(tree, "--check").returncode == 0


def test_check_fails_on_a_stale_number_and_changes_nothing(tree):
    readme(tree, BLOCK)
    run(tree)
    before = (tree / "README.md").read_text()
    r = run(tree, "--check", CT="13.5")
    assert r.returncode == 1
    assert "-best CT     12.5 s" in r.stderr and "+best CT     13.5 s" in r.stderr
    assert (tree / "README.md").read_text() == before


def test_thread_count_and_simd_target_are_normalised(tree):
    readme(tree, BLOCK)
    run(tree)
    before = (tree / "README.md").read_text()
    assert run(tree, "--check", THREADS="64").returncode == 0
    assert run(tree, THREADS="64").returncode == 0
    assert (tree / "README.md").read_text() == before, "only volatile fields differ: keep the committed text"


def test_a_claim_that_no_longer_holds_is_named(tree):
    readme(tree, BLOCK)
    r = run(tree, CT="25")
    assert r.returncode == 1
    assert "claim 'ct < 20' no longer holds (ct = 25.0): \"fast\" below" in r.stderr


def test_failing_commands_are_reported_with_their_stderr(tree):
    readme(tree, BLOCK.replace("chaosweep sweep", "echo oops >&2; false"))
    r = run(tree)
    assert r.returncode == 1 and "exited 1" in r.stderr and "oops" in r.stderr


def test_expensive_blocks_run_only_with_the_flag_and_carry_a_stamp(tree):
    readme(tree, BLOCK.replace("<!-- regenerate\n", "<!-- regenerate expensive\n"))
    r = run(tree, "--check")
    assert r.returncode == 1 and "without its stamp line" in r.stderr
    assert run(tree).returncode == 1  # not rerun without --expensive, still unstamped
    assert "best CT     " not in (tree / "README.md").read_text()
    r = run(tree, "--expensive")
    assert r.returncode == 0, r.stderr
    text = (tree / "README.md").read_text()
    assert "with chaosweep 9.9.9 at commit 0123456789ab on " in text and "best CT     12.5 s" in text
    assert run(tree, "--check", CT="99").returncode == 0, "--check does not rerun an expensive block"
    bad = text.replace("12.5 s", "25 s")
    (tree / "README.md").write_text(bad)
    r = run(tree, "--check")
    assert r.returncode == 1 and "claim 'ct < 20'" in r.stderr, "claims hold on the committed output too"


def test_figures_are_copied_when_regenerating_not_when_checking(tree):
    readme(tree, """\
        <!-- regenerate
        figure out/f.png -> img.png
        -->
        ```sh
        chaosweep draw
        ```
        <!-- /regenerate -->
        """)
    assert run(tree).returncode == 0
    assert (tree / "img.png").read_text() == "png\n"
    (tree / "img.png").unlink()
    assert run(tree, "--check").returncode == 0
    assert not (tree / "img.png").exists()


def test_a_malformed_block_is_refused_naming_the_line(tree):
    readme(tree, "text\n<!-- regenerate -->\nno sh block\n<!-- /regenerate -->\n")
    r = run(tree, "--check")
    assert r.returncode == 1 and "README.md:2: a regenerate block must begin with a ```sh block" in r.stderr
