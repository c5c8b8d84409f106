"""The documentation runs: README's Python example and console output, and every ```python block in docs/."""

import re
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
DOCS = sorted((ROOT / "docs").rglob("*.md")) + [ROOT / "README.md"]


def blocks(path: Path, language: str) -> list[str]:
    return re.findall(rf"^```{language}\n(.*?)^```$", path.read_text(), flags=re.S | re.M)


@pytest.mark.parametrize("path", [p for p in DOCS if blocks(p, "python")], ids=lambda p: p.name)
def test_python_blocks_run(path, tmp_path, monkeypatch):
    monkeypatch.chdir(ROOT)
    for code in blocks(path, "python"):
        exec(compile(code, str(path), "exec"), {"__name__": "__doc__"})


def test_readme_console_example_matches_the_command():
    (block,) = [b for b in blocks(ROOT / "README.md", "console") if "erdesign size" in b]
    command, *expected = block.strip().splitlines()
    args = command.removeprefix("$ erdesign ").replace('"', "").split()
    # args: size examples/makris.toml --velocity 1 in/s --field 3 kV/mm  -> rejoin the values with spaces
    joined = " ".join(args)
    m = re.match(r"size (\S+) --velocity (.+) --field (.+)", joined)
    res = subprocess.run(
        [sys.executable, "-m", "erdesign", "size", str(ROOT / m[1]), "--velocity", m[2], "--field", m[3]],
        capture_output=True,
        text=True,
        cwd=ROOT,
        timeout=120,
    )
    assert res.returncode == 0, res.stderr
    assert res.stdout.strip().splitlines() == expected


def test_readme_starts_with_the_two_setup_commands():
    text = (ROOT / "README.md").read_text()
    first_two = blocks(ROOT / "README.md", "bash")[:2]
    assert "streamlit run app.py" in first_two[0] and "pytest" in first_two[1]
    assert text.index(first_two[0]) < text.index("##")  # before any section
    ci = (ROOT / ".ci" / "run").read_text()
    assert "second bash block" in ci


def test_images_in_docs_exist_and_are_png():
    # Every image a doc shows is committed (made by a script under docs/) and is a real PNG.
    for path in DOCS:
        for target in re.findall(r"!\[[^\]]*\]\(([^)]+)\)", path.read_text()):
            image = (path.parent / target).resolve()
            assert image.exists(), f"{path.name}: missing image {target}"
            assert image.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n", f"{path.name}: {target} is not a PNG"
