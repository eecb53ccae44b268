"""Documentation that cannot drift from the code: links resolve, the commands the README shows
exist, the module map lists every module, the reference pages are what the code makes, and the
README stays a front door (short, no commit hashes)."""

from __future__ import annotations

import contextlib
import io
import re
from pathlib import Path

import pytest

import arteleop
from arteleop.cli.main import main
from arteleop.cli.reference import command_names, command_reference, study_file_reference

ROOT = Path(__file__).resolve().parent.parent
PAGES = sorted([ROOT / "README.md", ROOT / "CHANGELOG.md", ROOT / "benchmarks" / "README.md",
                *(ROOT / "docs").rglob("*.md")])  # fmt: skip
LINK = re.compile(r"\]\(([^)\s]+)\)")


def _slug(heading: str) -> str:
    """GitHub's anchor for a heading."""
    text = re.sub(r"[`*]", "", heading.strip().lower())
    return re.sub(r"\s", "-", re.sub(r"[^\w\s-]", "", text))


def _anchors(page: Path) -> set[str]:
    return {
        _slug(line.lstrip("#")) for line in page.read_text().splitlines() if line.startswith("#")
    }


@pytest.mark.parametrize("page", PAGES, ids=lambda p: str(p.relative_to(ROOT)))
def test_every_relative_link_resolves(page: Path) -> None:
    text = re.sub(r"```.*?```", "", page.read_text(), flags=re.DOTALL)
    for target in LINK.findall(text):
        if re.match(r"[a-z]+:", target):
            continue  # a web address
        path, _, anchor = target.partition("#")
        linked = (page.parent / path).resolve() if path else page
        assert linked.exists(), f"{page.relative_to(ROOT)}: {target} does not exist"
        if anchor and linked.suffix == ".md":
            assert anchor in _anchors(linked), f"{page.relative_to(ROOT)}: no heading #{anchor}"


def test_every_docs_path_the_code_names_exists() -> None:
    """Docstrings and messages point to pages of docs/ and benchmarks/: each one is there."""
    named = set()
    for source in [*(ROOT / "arteleop").rglob("*.py"), *(ROOT / "benchmarks").glob("*.py")]:
        named |= set(re.findall(r"(?:docs|benchmarks)/[\w./-]*\w", source.read_text()))
    missing = sorted(path for path in named if not (ROOT / path).exists())
    assert missing == []


def _readme_commands() -> set[str]:
    """Every ``arteleop ...`` command the README shows, as the words that name it."""
    text = (ROOT / "README.md").read_text()
    found = set()
    for match in re.finditer(r"arteleop ((?:[a-z]+)(?: [a-z]+)?)", text):
        words = match.group(1).split()
        if words[0] in {"study", "operator"} and len(words) > 1:
            found.add(" ".join(words[:2]))
        else:
            found.add(words[0])
    return found


def test_every_command_the_readme_shows_exists() -> None:
    shown = _readme_commands()
    assert {"trial", "study run", "teleop"} <= shown
    known = set(command_names()) | {"COMMAND"}
    for command in sorted(shown):
        if command.split()[0] not in {c.split()[0] for c in known}:
            continue  # prose: "arteleop is released..."
        assert command in known, f"the README shows 'arteleop {command}', which does not exist"
        with contextlib.redirect_stdout(io.StringIO()), pytest.raises(SystemExit) as done:
            main([*command.split(), "--help"])
        assert done.value.code == 0, command


def test_the_module_map_lists_every_module() -> None:
    """docs/explanation/architecture.md names every module of the package in its package's row."""
    page = (ROOT / "docs" / "explanation" / "architecture.md").read_text()
    rows = dict(re.findall(r"^\| `([\w/]+)`[^|]*\| (.*) \|$", page, re.MULTILINE))
    package = Path(arteleop.__file__).parent
    missing = []
    for module in sorted(package.rglob("*.py")):
        if module.name.startswith("__"):
            continue
        relative = module.relative_to(package)
        room = relative.parts[0] + "/" if len(relative.parts) > 1 else "arteleop/"
        if f"`{module.stem}`" not in rows.get(room, ""):
            missing.append(str(relative))
    assert missing == []


@pytest.mark.parametrize(
    ("page", "make"),
    [("commands.md", command_reference), ("study-file.md", study_file_reference)],
)
def test_the_reference_pages_are_what_the_code_makes(page: str, make) -> None:
    committed = (ROOT / "docs" / "reference" / page).read_text()
    assert committed == make(), (
        f"docs/reference/{page} is out of date: python docs/make_reference.py"
    )


def test_the_readme_is_a_front_door() -> None:
    text = (ROOT / "README.md").read_text()
    assert len(text.splitlines()) <= 200
    hashes = re.findall(r"\b(?=[0-9a-f]*[a-f])(?=[0-9a-f]*[0-9])[0-9a-f]{7,40}\b", text)
    assert hashes == [], "commit hashes belong in docs/results/ and the changelog"


MOVED_PAGES = {
    "study.md": "explanation/study.md",
    "operator-model.md": "explanation/operator-model.md",
    "data-format.md": "reference/data-format.md",
    "recording-format.md": "reference/recording-format.md",
}
"""Pages of docs/ that moved in 0.4, by old path: links from elsewhere still land."""


@pytest.mark.parametrize(("old", "new"), MOVED_PAGES.items())
def test_a_page_that_moved_answers_at_its_old_path(old: str, new: str) -> None:
    assert f"]({new})" in (ROOT / "docs" / old).read_text()
    assert (ROOT / "docs" / new).read_text().startswith("# ")
