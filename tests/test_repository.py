"""The repository stands alone: no machine paths, and the shipped test records are the ones
their README describes (a plain clone with nothing beside it runs every test)."""

import hashlib
import re
from pathlib import Path

from conftest import DATA

ROOT = Path(__file__).resolve().parents[1]
# absolute paths of particular machines, and the old shared folder beside the checkout
_MACHINE_PATH = re.compile(r"(?<![\w.])/(?:work|check|root|home)/|\.\./shared\b")
_TEXT = {".py", ".md", ".toml", ".txt", ".cfg", ".ini", ".yml", ".yaml", ""}


def _text_files():
    for top in ("femoat", "tests", "benchmarks", "studies", "meshes", ".ci"):
        for path in (ROOT / top).rglob("*"):
            if path.is_file() and path.suffix in _TEXT and "__pycache__" not in path.parts \
                    and DATA not in path.parents:
                yield path
    yield ROOT / "README.md"
    yield ROOT / "pyproject.toml"


def test_no_absolute_machine_paths():
    hits = []
    for path in _text_files():
        for lineno, line in enumerate(path.read_text(errors="replace").splitlines(), 1):
            if _MACHINE_PATH.search(line) and path != Path(__file__):
                hits.append(f"{path.relative_to(ROOT)}:{lineno}: {line.strip()}")
    assert not hits, "machine paths in the repository:\n" + "\n".join(hits)


def test_shipped_records_match_their_readme_checksums():
    # every row "| `file` | `sha256` | ..." of data/README.md names a file whose sha256 it gives
    rows = re.findall(r"^\| `([^`]+)` \| `([0-9a-f]{64})` \|", (DATA / "README.md").read_text(),
                      re.MULTILINE)
    listed = {name for name, _ in rows}
    shipped = {str(p.relative_to(DATA)) for p in DATA.rglob("*") if p.is_file()} - {"README.md"}
    assert listed == shipped
    for name, digest in rows:
        assert hashlib.sha256((DATA / name).read_bytes()).hexdigest() == digest, name
