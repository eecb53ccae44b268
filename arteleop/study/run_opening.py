"""A run's plan and manifest when it begins, and the checks a run folder passes when it is
opened again (to resume it, or to serve its next participant): its definition unedited, its
manifest able to vouch for it, its plan the one this version makes."""

from __future__ import annotations

import dataclasses
import hashlib
import platform
from collections.abc import Callable, Sequence
from datetime import UTC, datetime
from importlib import metadata
from typing import Any

from arteleop.blas_kernel import SAME_AS_PINNED, blas_description
from arteleop.errors import RunFolderError, StudyDefinitionError
from arteleop.numpy_loops import (
    ANY_AVX512_TARGET,
    numpy_loops_description,
    running_avx512_targets,
)
from arteleop.scene.gl_renderer import renderer_description, resolve_renderer
from arteleop.study.cohort import participants
from arteleop.study.definition import StudyConfig
from arteleop.study.participants import ParticipantSpec
from arteleop.study.plan import TrialSpec, plan_study
from arteleop.study.run_folder import FORMAT_VERSION, STUDY_FILE, RunFolder
from arteleop.study.sites import StudySite
from arteleop.study.study_file import first_difference, parse_study

PACKAGES = ("arteleop", "pybullet", "pin", "mink", "mujoco", "ruckig", "numpy", "scipy",
            "pandas", "statsmodels", "open3d", "moderngl")  # fmt: skip
"""Packages whose versions the manifest records: each can change the numbers."""


def new_manifest(
    study: StudyConfig, text: str, plan: Sequence[Any], participants: int
) -> dict[str, object]:
    """A new run's manifest.json: what it is and what it ran on. ``plan``: its trials, or a
    pointing study's blocks (frozen dataclasses)."""
    return {
        "format_version": FORMAT_VERSION,
        "seed": study.seed,
        "trials_planned": len(plan),
        "participants": participants,
        **machine_record(),
        "started": utc_now(),
        "finished": None,
        # What the run is, so that resume can refuse a folder whose definition was edited or
        # whose plan this arteleop would make otherwise.
        "definition": text,
        "definition_sha256": _digest(text),
        "plan_sha256": _plan_digest(plan),
        "report_finished": None,
    }


def machine_record() -> dict[str, object]:
    """What this machine computes a trial with, as a manifest records it."""
    return {
        "packages": _versions(),
        "python": platform.python_version(),
        # OpenBLAS's kernels round in their own way: trials differ between them.
        "blas": blas_description(),
        # So do numpy's AVX-512 math loops and its others.
        "numpy_loops": numpy_loops_description(),
        # The final tracker looks are rendered: a GPU and Mesa may differ in a pixel's last bit.
        "head_camera": renderer_description(resolve_renderer("auto")),
    }


def record_resume(folder: RunFolder, trials_in: int) -> None:
    """Adds a resume begun on this machine, before its first trial, to the manifest's
    ``resumed`` list: when, the trials already in then, and what the trials it runs are
    computed with (a run resumed elsewhere mixes two machines' trials; :func:`arithmetic_notes`
    tells the user)."""
    manifest = folder.manifest()
    resumed = manifest.get("resumed", [])
    if not isinstance(resumed, list):
        raise RunFolderError(
            f"{folder.path / 'manifest.json'}: 'resumed' is {resumed!r}, expected a list of "
            "the run's resumes; restore manifest.json from a backup, or delete the key."
        )
    entry = {"started": utc_now(), "trials_in": trials_in, **machine_record()}
    manifest["resumed"] = [*resumed, entry]
    folder.write_manifest(manifest)


def open_run(
    folder: RunFolder, study: StudyConfig | None = None, site: StudySite | None = None
) -> tuple[StudyConfig, list[TrialSpec], list[ParticipantSpec], dict[str, object]]:
    """A run folder to continue, checked: its definition, plan and participants, and its
    manifest. With ``study``, refuses a folder made from another definition; ``site`` plans
    it (see :func:`plan_run`). The caller holds the folder's lock."""
    recorded, manifest = opened_definition(folder, study)
    plan, people = plan_run(recorded, site)
    check_plan(folder, manifest, plan)
    return recorded, plan, people, manifest


def opened_definition(
    folder: RunFolder, study: StudyConfig | None = None
) -> tuple[StudyConfig, dict[str, object]]:
    """A run folder's definition and manifest, checked before it is continued: no symbolic
    link, study.toml as the run began it (and, with ``study``, the same), this arteleop's
    format, and the manifest's digests there. The caller holds the folder's lock."""
    require_run_folder(folder)
    for entry in folder.path.iterdir():
        if entry.is_symlink():  # it would be read, or appended to, wherever it points
            raise RunFolderError(
                f"{entry}: a symbolic link in a run folder, which reads and writes only its own "
                "files; put the file itself there, or start a new run in another folder."
            )
    manifest = folder.manifest()
    recorded = recorded_definition(folder, manifest, study)
    if manifest.get("format_version") != FORMAT_VERSION:
        raise RunFolderError(
            f"{folder.path / 'manifest.json'}: format_version "
            f"{manifest.get('format_version')!r}, this arteleop writes {FORMAT_VERSION}; "
            "resume it with the version that began it "
            f"({_get(manifest, 'packages', {}).get('arteleop', 'unknown')})."
        )
    began = manifest.get("definition")
    if (not isinstance(began, str) or manifest.get("definition_sha256") != _digest(began)
            or not isinstance(manifest.get("plan_sha256"), str)):  # fmt: skip
        raise RunFolderError(
            f"{folder.path / 'manifest.json'}: its 'definition', 'definition_sha256' or "
            "'plan_sha256' is missing, null or edited, so the run cannot be checked against "
            "what it began with. Restore manifest.json from a backup."
        )
    return recorded, manifest


def arithmetic_notes(folder: RunFolder, manifest: dict[str, object]) -> list[str]:
    """What a run resumed here computes otherwise than where it began, or, if not, than where it
    was last resumed (the manifest's ``resumed``), as its manifest recorded it (a key it lacks
    is not compared): numpy's BLAS kernel or whether its AVX-512 loops ran (what
    ``OPENBLAS_CORETYPE`` and ``NPY_DISABLE_CPU_FEATURES`` set), and the packages' versions
    (what an install sets). Not a refusal: the trials left run as this machine computes them,
    each a trial of the same design, not the one the first machine would have written."""
    path = folder.path / "manifest.json"
    resumed = manifest.get("resumed")
    last = resumed[-1] if isinstance(resumed, list) and resumed else None
    sources = (("began", manifest), ("was last resumed", last))
    checks = (
        (_arithmetic_differences, "on a machine that computes otherwise",
         "the trials run now are this machine's, and differ from those that one would have "
         "written as another seed's do (docs/results/reproducibility.md). For a run computed "
         "alike throughout, resume it where it began, or set OPENBLAS_CORETYPE and "
         "NPY_DISABLE_CPU_FEATURES as there."),
        (_version_differences, "with other versions",
         "the trials run now may differ from those it would have written. For a run computed "
         "alike throughout, install the versions its 'packages' lists."),
    )  # fmt: skip
    notes = []
    for differences, how, consequence in checks:
        if found := _first_difference(sources, differences):
            where, differ = found
            notes.append(f"{path}: the run {where} {how} ({'; '.join(differ)}): {consequence}")
    return notes


def _first_difference(
    sources: Sequence[tuple[str, object]], differences: Callable[[dict[str, object]], list[str]]
) -> tuple[str, list[str]] | None:
    """The first of ``sources`` (where the run began, then its last resume, as the manifest
    records them) whose record ``differences`` finds this machine differs from, and how."""
    for where, record in sources:
        if isinstance(record, dict) and (found := differences(record)):
            return where, found
    return None


def _arithmetic_differences(record: dict[str, object]) -> list[str]:
    """How this machine's arithmetic differs from a manifest's (or a resume's) record of it."""
    blas, loops = record.get("blas"), record.get("numpy_loops")
    differ = []
    if isinstance(blas, str) and blas.split():
        there, here = blas.split()[-1], blas_description().split()[-1]
        if here != there and not {here, there} <= SAME_AS_PINNED:
            differ.append(f"BLAS kernel {there} there, {here} here")
    if isinstance(loops, str):
        there_on, here_on = _avx512_named(loops), bool(running_avx512_targets())
        if there_on != here_on:
            differ.append(f"numpy's AVX-512 loops {_on(there_on)} there, {_on(here_on)} here")
    return differ


def _version_differences(record: dict[str, object]) -> list[str]:
    """The packages whose versions here differ from a manifest's (or a resume's) record."""
    there = record.get("packages")
    if not isinstance(there, dict):
        return []
    return [f"{name} {there[name]} there, {version} here"
            for name, version in _versions().items()
            if name in there and there[name] != version]  # fmt: skip


def _avx512_named(loops: str) -> bool:
    """Whether a manifest's ``numpy_loops`` names an AVX-512 target."""
    return bool(set(loops.split()) & ANY_AVX512_TARGET)


def _on(on: bool) -> str:
    return "on" if on else "off"


def check_plan(folder: RunFolder, manifest: dict[str, object], plan: Sequence[Any]) -> None:
    """Refuse to continue a run whose ``plan`` (trials, or a pointing study's blocks: frozen
    dataclasses) this arteleop makes otherwise than the version that began it."""
    if manifest.get("plan_sha256") != _plan_digest(plan):
        raise RunFolderError(
            f"{folder.path}: this arteleop plans the run's definition otherwise than the "
            "version that began it (its plan's digest differs); resume it with that version "
            f"({_get(manifest, 'packages', {}).get('arteleop', 'unknown')})."
        )


def require_run_folder(folder: RunFolder) -> None:
    if not folder.is_run_folder():
        raise RunFolderError(
            f"{folder.path} is not a run folder (it has no {STUDY_FILE} and manifest.json): "
            "'arteleop study run --out DIR' starts one."
        )


def recorded_definition(
    folder: RunFolder, manifest: dict[str, object], study: StudyConfig | None = None
) -> StudyConfig:
    """The run's definition: study.toml, refused if it no longer says what the run began with
    (the manifest keeps the text it began with), or, given ``study``, if it is another."""
    path = folder.path / STUDY_FILE
    try:
        text = path.read_text(encoding="utf-8")
    except (OSError, UnicodeDecodeError) as err:
        raise RunFolderError(f"Cannot read {path}: {err}.") from err
    recorded = parse_study(text, str(path))
    began = manifest.get("definition")
    if isinstance(began, str) and text != began:
        original = parse_study(began, f"{folder.path / 'manifest.json'} (definition)")
        key = first_difference(original, recorded)
        if key is not None:
            raise RunFolderError(
                f"{path} was edited after the run began: its key {key!r} is "
                f"{_value(recorded, key)!r}, the run's {_value(original, key)!r}. Put it back "
                "(manifest.json keeps the run's definition as 'definition'), or start a new run "
                "in another folder."
            )
    if study is not None and (key := first_difference(study, recorded)) is not None:
        raise RunFolderError(
            f"{folder.path} was made from another definition: its key {key!r} is "
            f"{_value(recorded, key)!r}, the given one {_value(study, key)!r}. Resume it "
            "without a definition, or start a new run in another folder."
        )
    return recorded


def _digest(text: str) -> str:
    return hashlib.sha256(text.encode("utf-8")).hexdigest()


def _plan_digest(plan: Sequence[Any]) -> str:
    return _digest("\n".join(repr(dataclasses.astuple(spec)) for spec in plan))


def _get(manifest: dict[str, object], key: str, default: dict) -> dict:
    value = manifest.get(key, default)
    return value if isinstance(value, dict) else default


def plan_run(
    study: StudyConfig, site: StudySite | None = None
) -> tuple[list[TrialSpec], list[ParticipantSpec]]:
    """The run's plan and participants; ``site`` probes the practice points (a new one if
    none), and is closed after."""
    site = site or StudySite()
    problem = site.problem(study.start_xy_m, study.target_xy_m)
    if problem is not None:
        raise StudyDefinitionError(f"start_xy_m / target_xy_m: {problem}")
    points = site.practice_points(study.start_xy_m, study.target_xy_m)
    try:
        return plan_study(study, points), list(participants(study))
    finally:
        site.close()  # the probe of practice points; forked workers must not inherit it


def _versions() -> dict[str, str]:
    versions = {}
    for name in PACKAGES:
        try:
            versions[name] = metadata.version(name)
        except metadata.PackageNotFoundError:
            versions[name] = "not installed"
    return versions


def utc_now() -> str:
    return datetime.now(UTC).isoformat(timespec="seconds")


def _value(study: StudyConfig, dotted: str) -> object:
    value: object = study
    for part in dotted.split("."):
        value = getattr(value, part)
    return value
