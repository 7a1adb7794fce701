"""Every Python snippet of README.md and the book (docs/*.md) runs with the installed package,
in a temporary directory holding a link to the repository's `examples/` (the shell snippets run
in crates/polbrdf-cli/tests/doc_snippets.rs, by the same rules). A block that must not run has
`<!-- snippet: skip (reason) -->` on the line before its fence; one that needs an optional peer
has `<!-- snippet: needs MODULE -->` and skips, saying so, when MODULE is not installed."""

from __future__ import annotations

import json
import re
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
MARKER = re.compile(r"^<!-- snippet: (.+) -->$")


def documents() -> list[Path]:
    docs = sorted(p for p in (ROOT / "docs").glob("*.md") if p.name != "cli.md")
    return [ROOT / "README.md", *docs]


def python_blocks() -> list[tuple[str, int, str | None, str]]:
    """(file, line of the fence, marker, code) of every ```python block."""
    out = []
    for path in documents():
        lines = path.read_text().splitlines()
        i = 0
        while i < len(lines):
            if not lines[i].lstrip().startswith("```"):
                i += 1
                continue
            lang = lines[i].strip()[3:].strip()
            before = [line.strip() for line in lines[:i] if line.strip()]
            found = MARKER.match(before[-1]) if before else None
            start = i
            i += 1
            code = []
            while i < len(lines) and not lines[i].lstrip().startswith("```"):
                code.append(lines[i])
                i += 1
            i += 1
            if lang == "python":
                name = str(path.relative_to(ROOT))
                out.append((name, start + 1, found.group(1) if found else None, "\n".join(code)))
    return out


BLOCKS = python_blocks()
FILES = sorted({f for f, _, _, _ in BLOCKS})

# Runs the blocks of one page in order in one interpreter, as a reader would in one session (a
# page's later blocks use the names its first ones define); names the block that fails.
DRIVER = """
import json, sys, traceback
blocks = json.load(sys.stdin)
env = {"__name__": "__main__"}
for file, line, code in blocks:
    try:
        exec(compile(code, f"{file}:{line}", "exec"), env)
    except BaseException:
        traceback.print_exc()
        sys.exit(f"the snippet at {file}:{line} failed")
"""


def test_the_extractor_finds_the_snippets() -> None:
    assert len(BLOCKS) >= 5


@pytest.mark.parametrize("file", FILES)
def test_python_snippets_run(file: str, tmp_path: Path) -> None:
    run = []
    for f, line, marker, code in BLOCKS:
        if f != file:
            continue
        if marker is not None:
            if marker.startswith("skip (") and marker.endswith(")") and len(marker) > 7:
                continue
            module = marker.removeprefix("needs ")
            assert module != marker and module.isidentifier(), f"{f}:{line}: bad marker {marker!r}"
            pytest.importorskip(module, reason=f"{f}:{line} needs {module}")
        run.append((f, line, code))
    if not run:
        pytest.skip(f"{file}: every Python snippet is marked skip")
    (tmp_path / "examples").symlink_to(ROOT / "examples")
    result = subprocess.run(
        [sys.executable, "-c", DRIVER],
        input=json.dumps(run),
        cwd=tmp_path,
        check=False,
        capture_output=True,
        text=True,
        timeout=900,
    )
    assert result.returncode == 0, result.stderr
