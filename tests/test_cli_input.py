"""The command line as a new user meets it: help, progress, bad input, Ctrl-C.

Every bad input ends with one line naming the option and what it expects, exit code 2, never a
traceback or a hang.
"""

from __future__ import annotations

import collections
import ipaddress
import os
import re
import select
import signal
import socket
import subprocess
import sys
import time
import urllib.request
from pathlib import Path
from typing import get_args

import pandas as pd
import psutil
import pytest

from arteleop import cli
from arteleop.ar_features import MODALITIES, OperatorView, ViewConfig
from arteleop.cli import main
from arteleop.study import FORMAT_VERSION
from tests.helpers import ctrl_c_reaches_it

ARTELEOP = [sys.executable, "-m", "arteleop.cli"]


def _error(capsys: pytest.CaptureFixture[str], argv: list[str]) -> str:
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert err.startswith("arteleop: error: ") and "Traceback" not in err
    return err.removeprefix("arteleop: error: ").strip()


def test_bare_command_and_help_list_every_command(capsys: pytest.CaptureFixture[str]) -> None:
    assert main([]) == 2
    bare = capsys.readouterr().err
    assert main(["--help"]) == 0
    helped = capsys.readouterr().out
    for text in (bare, helped):
        for command in ("trial", "teleop", "scene", "operator synth", "operator check", "analyze"):
            assert f"\n  {command} " in text, command


def test_modality_is_offered_as_its_six_choices(capsys: pytest.CaptureFixture[str]) -> None:
    assert get_args(cli.Modality) == tuple(MODALITIES)
    with pytest.raises(SystemExit):
        main(["trial", "--help"])
    out = capsys.readouterr().out
    assert "{none,manipulation,embodiment,task,full,predictive}" in out
    for option in ("--seed", "--timeout-s", "--delay-ms", "--operator", "--quiet"):
        line = next(line for line in out.splitlines() if option in line)
        assert "(default" in line or line.strip() != option  # each has its description


@pytest.mark.parametrize(
    "command", [["trial"], ["teleop"], ["scene"], ["operator", "synth"], ["study", "run"]]
)
def test_negative_seed_is_refused(capsys: pytest.CaptureFixture[str], command: list[str]) -> None:
    assert _error(capsys, [*command, "--seed", "-1"]) == (
        "--seed -1: a seed is a whole number, 0 or more."
    )


def test_study_run_seed_replaces_the_definitions(
    monkeypatch: pytest.MonkeyPatch, tmp_path: Path
) -> None:
    """--seed N runs the definition with seed N (the run folder records what it ran)."""
    import arteleop.study
    from arteleop.errors import ConfigurationError

    ran = []

    def fake_run(study, out, workers, progress=None):
        ran.append(study)
        raise ConfigurationError("stopped here")

    monkeypatch.setattr(arteleop.study, "run_study", fake_run)
    assert main(["study", "run", "--seed", "3", "--out", str(tmp_path / "run")]) == 2
    assert ran[0].seed == 3 and ran[0].cohort == arteleop.study.StudyConfig().cohort


@pytest.mark.parametrize(
    ("option", "message"),
    [
        (["--timeout-s", "0"], "--timeout-s 0.0: give the trial a positive simulated time (s)."),
        (["--delay-ms", "nan"], "--delay-ms nan: give a delay of 0 ms or more."),
        (
            ["--delay-ms", "100000"],
            "--delay-ms 100000: the operator would see the robot respond 200 s after moving (the "
            "round trip), after --timeout-s 120 s; no trial can finish. Shorten the delay or "
            "lengthen the timeout.",
        ),
        (
            ["--operator", "synthetc"],
            "--operator synthetc: no such file. Give 'synthetic' (a simulated participant) or "
            "the path of a wearable recording's CSV.",
        ),
        (["--confidence", "1"], "--confidence 1.0: expected 0.5-0.999 (a probability)."),
        (
            ["--task", "pick"],
            "--task 'pick': expected 'pick-and-place', 'pointing', or a task of your own as "
            "'package.module:NAME' (docs/guides/extending.md).",
        ),
        (
            ["--task", "pointing"],
            "--task pointing: a pointing trial's targets come from a pointing study's design; run "
            "one with 'arteleop study run docs/examples/fitts_lag.toml --out DIR', or a study file "
            'of your own with task = "pointing".',
        ),
        (
            ["--placement-criterion-m", "0.5"],
            "--placement-criterion-m 0.5: expected 0.001-0.1 (m).",
        ),
        (
            ["--filter-min-cutoff-hz", "0"],
            "--filter-min-cutoff-hz 0.0: expected a cutoff of 0.01-100 Hz.",
        ),
        (
            ["--filter-beta", "-1"],
            "--filter-beta -1.0: expected 0-1000 (Hz per m/s; 0 is a plain low-pass filter).",
        ),
    ],
)
def test_bad_trial_options_name_the_option(
    capsys: pytest.CaptureFixture[str], option: list[str], message: str
) -> None:
    assert _error(capsys, ["trial", *option]) == message


def test_teleop_offers_live_input(capsys: pytest.CaptureFixture[str]) -> None:
    assert _error(capsys, ["teleop", "--operator", "livee"]) == (
        "--operator livee: no such file. Give 'synthetic' (a simulated participant), 'live' "
        "(drive the robot from the page) or the path of a wearable recording's CSV."
    )
    assert _error(capsys, ["teleop", "--timeout-s", "-1"]) == (
        "--timeout-s -1.0: give the trial a positive simulated time (s)."
    )
    for command in (["teleop"], ["trial", "--view"]):
        assert _error(capsys, [*command, "--port", "70000"]) == (
            "--port 70000: expected a TCP port, 0-65535 (0: any free one)."
        )


def test_an_empty_recording_is_called_empty(
    capsys: pytest.CaptureFixture[str], tmp_path: Path
) -> None:
    (tmp_path / "r.csv").write_text("")
    message = _error(capsys, ["operator", "check", str(tmp_path / "r.csv")])
    assert message.startswith(f"{tmp_path / 'r.csv'} is empty: a recording has a header line")


def test_a_missing_recording_is_missing(capsys: pytest.CaptureFixture[str], tmp_path: Path) -> None:
    assert _error(capsys, ["operator", "check", str(tmp_path / "nope.csv")]) == (
        f"{tmp_path / 'nope.csv'}: no such file"
    )


@pytest.mark.parametrize("host", ["localhst", "10.255.255.1"])
@pytest.mark.parametrize("command", ["trial", "teleop"])
def test_a_host_that_cannot_be_bound_fails_at_once(
    host: str, command: str, capsys: pytest.CaptureFixture[str], monkeypatch: pytest.MonkeyPatch
) -> None:
    """Said before the robot is loaded (seconds on a fresh machine), not after."""

    def loaded(*_: object, **__: object) -> None:
        raise AssertionError("the robot was loaded before the host was checked")

    monkeypatch.setattr("arteleop.scene.RemoteSite.__init__", loaded)
    view = ["--view"] if command == "trial" else []
    assert _error(capsys, [command, *view, "--host", host]).startswith(f"--host {host}: ")


def test_other_hosts_warn_and_a_taken_port_moves_on() -> None:
    with socket.socket() as taken:
        taken.bind(("127.0.0.1", 0))
        taken.listen()
        port = taken.getsockname()[1]
        with OperatorView(ViewConfig(port=port)) as view:
            assert view.notices() == [f"port {port} is taken; serving on {port + 1}"]
    with OperatorView(ViewConfig(host="0.0.0.0", port=0)) as view:
        assert "anyone on that network can see it and drive the robot" in view.notices()[0]


def test_served_on_every_interface_of_a_machine_no_other_reaches_says_so(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    # A laptop off its network: eth0 has an address but is down, lo is up.
    nic = collections.namedtuple("nic", "family address")
    up = collections.namedtuple("up", "isup")
    monkeypatch.setattr(
        psutil,
        "net_if_addrs",
        lambda: {
            "lo": [nic(socket.AF_INET, "127.0.0.1")],
            "eth0": [nic(socket.AF_INET, "192.0.2.7")],
        },
    )
    monkeypatch.setattr(psutil, "net_if_stats", lambda: {"lo": up(True), "eth0": up(False)})
    with OperatorView(ViewConfig(host="0.0.0.0", port=0)) as view:
        assert view.url.startswith("http://127.0.0.1:")
        assert view.notices()[1] == (
            "warning: no network interface other machines can reach is up, so the address "
            "printed, 127.0.0.1, opens only on this machine: bring a network up, or give study "
            "serve a --public-url (a tunnel's, say)"
        )


@pytest.mark.parametrize("host", ["0.0.0.0", "::"])
def test_served_on_every_interface_the_link_names_an_address_others_reach(host: str) -> None:
    # The machine's name resolves to 127.0.1.1 on Debian: links named it, or 127.0.0.1.
    family = socket.AF_INET6 if ":" in host else socket.AF_INET
    interfaces = {ipaddress.ip_address(a.address.split("%")[0]) for nic in
                  psutil.net_if_addrs().values() for a in nic if a.family == family}  # fmt: skip
    if not any(not (a.is_loopback or a.is_link_local) for a in interfaces):
        pytest.skip(f"this machine has no {family.name} address beyond itself")
    with OperatorView(ViewConfig(host=host, port=0)) as view:
        (address,) = re.fullmatch(r"http://\[?([^\]]+?)\]?:\d+", view.url).groups()
        ip = ipaddress.ip_address(address)
        assert ip in interfaces and not (ip.is_loopback or ip.is_link_local), view.url
        with urllib.request.urlopen(view.url, timeout=10) as page:  # it opens
            assert page.status == 200


def test_a_missing_libusb_is_named(
    capsys: pytest.CaptureFixture[str], monkeypatch: pytest.MonkeyPatch
) -> None:
    def missing(_: object) -> int:
        raise ImportError("libusb-1.0.so.0: cannot open shared object file")

    monkeypatch.setitem(cli.COMMANDS, "scene", (cli.SceneCommand, missing))
    assert "'apt-get install libusb-1.0-0'" in _error(capsys, ["scene"])


def test_pybullet_prints_no_banner() -> None:
    run = subprocess.run(
        [sys.executable, "-c", "import arteleop.teleop"], capture_output=True, text=True
    )
    assert run.stdout == run.stderr == ""


def test_ctrl_c_ends_a_trial_cleanly() -> None:
    proc = subprocess.Popen(
        [*ARTELEOP, "trial"],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        preexec_fn=ctrl_c_reaches_it,
    )
    # Into the trial, whatever the machine's speed: its progress shows a simulated second or
    # more (a whole trial takes 4 s of wall on a fast machine, so a fixed wait may be too late).
    progress = b""
    deadline = time.monotonic() + 60
    while not re.search(rb"\| *[1-9][0-9]*/120 ", progress) and time.monotonic() < deadline:
        if select.select([proc.stderr], [], [], 1.0)[0]:
            progress += os.read(proc.stderr.fileno(), 4096)
    assert re.search(rb"\| *[1-9][0-9]*/120 ", progress), progress
    proc.send_signal(signal.SIGINT)
    _, rest = proc.communicate(timeout=30)
    err = (progress + rest).decode()
    assert proc.returncode == 130, err
    assert err.splitlines()[-1] == "arteleop: interrupted", err


def test_ctrl_c_stops_a_parallel_study_at_once_and_resume_finishes_it(tmp_path) -> None:
    definition = tmp_path / "s.toml"
    # Without AR a trial takes 25-40 simulated seconds, cut at 30 (5-7 s of wall at today's
    # speed): the Ctrl-C, 3 s into the trials, comes while both run, not during the report.
    definition.write_text('modalities = ["none"]\ntimeout_s = 30.0\n[familiarization]\n'
                          "trials = 0\n[cohort]\nsize = 2\navr_experts = 0\n"
                          "games_experts = 0\nboth_experts = 0\n")  # fmt: skip
    run = tmp_path / "run"
    proc = subprocess.Popen(
        [*ARTELEOP, "study", "run", str(definition), "--out", str(run), "--workers", "2"],
        stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, start_new_session=True,
        preexec_fn=ctrl_c_reaches_it,
    )  # fmt: skip
    deadline = time.monotonic() + 120  # start-up and planning take longer on a busy machine
    while not (run / "trials.csv").exists() and time.monotonic() < deadline:
        time.sleep(0.1)
    time.sleep(3.0)  # both workers into their trial
    os.killpg(proc.pid, signal.SIGINT)  # a terminal's Ctrl-C reaches the whole group
    start = time.monotonic()
    _, err = proc.communicate(timeout=60)
    assert time.monotonic() - start < 10  # not after the trials under way
    assert proc.returncode == 130
    lines = [line for line in err.replace("\r", "\n").splitlines() if line.strip()]
    assert lines[-1] == f"arteleop: interrupted; 'arteleop study resume {run}' continues the run"
    assert not any("Traceback" in line for line in lines)
    done = subprocess.run([*ARTELEOP, "study", "resume", str(run), "--quiet", "--workers", "2"],
                          capture_output=True, text=True, timeout=300)  # fmt: skip
    assert done.returncode == 0, done.stderr
    assert done.stdout.startswith(f"2 trials in {run} (")


def test_ctrl_c_during_the_report_says_how_to_write_it(tmp_path, monkeypatch, capsys) -> None:
    """Once every trial is in, a Ctrl-C can only stop the report: the message says that resume
    writes it (the manifest says the report is not finished)."""
    from arteleop.cli import study
    from arteleop.study import StudyRun

    def interrupted(_: object) -> int:
        raise KeyboardInterrupt

    monkeypatch.setattr(study, "analyze", interrupted)
    trials = pd.DataFrame({"phase": ["experimental"], "outcome": ["success"], "modality": ["full"],
                           "completion_time_s": [20.0], "placement_error_m": [0.01]})  # fmt: skip
    with pytest.raises(KeyboardInterrupt) as stop:
        study._study_done(StudyRun(tmp_path, trials, 1, []))
    assert str(stop.value) == (
        f"the trials are all in {tmp_path}; 'arteleop study resume {tmp_path}' writes it"
    )


def test_a_studys_progress_times_its_first_trial_from_the_runs_start(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    """The bar appears at the first trial's end: timed from then, it gave that trial no time
    and a rate of 65536 trials a second."""
    import re
    from types import SimpleNamespace

    from arteleop.cli.study import _study_progress

    with _study_progress(tmp_path, quiet=False) as update:
        time.sleep(0.25)  # the first trial
        update(SimpleNamespace(participant="P01", trial_index=1), 1, 4)
    shown = capsys.readouterr().err
    # tqdm writes a rate under one a second as its inverse.
    rates = [float(r) for r in re.findall(r"([\d.]+)trial/s", shown)]
    rates += [1 / float(s) for s in re.findall(r"([\d.]+)s/trial", shown)]
    assert rates and all(0 < r <= 4.0 for r in rates), shown  # a trial in 0.25 s or more
    assert "last: P01 trial 1" in shown


def test_progress_is_shown_unless_quiet() -> None:
    args = [*ARTELEOP, "trial", "--timeout-s", "3", "--seed", "1"]
    loud = subprocess.run(args, capture_output=True, text=True, timeout=120)
    quiet = subprocess.run([*args, "--quiet"], capture_output=True, text=True, timeout=120)
    assert "trial" in loud.stderr and "s simulated" in loud.stderr
    assert quiet.stderr == ""
    assert loud.stdout == quiet.stdout and "outcome              timeout" in quiet.stdout
    assert "co-location" not in quiet.stdout  # a perfect registration: nothing to report


def test_the_view_keeps_serving_after_the_trial_until_ctrl_c() -> None:
    proc = subprocess.Popen(
        [*ARTELEOP, "trial", "--view", "--port", "0", "--timeout-s", "2", "--quiet",
         "--width-px", "160", "--height-px", "120"],
        stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, preexec_fn=ctrl_c_reaches_it,
    )  # fmt: skip
    assert proc.stdout is not None
    lines = []
    for line in proc.stdout:
        lines.append(line)
        if line.startswith("the trial is over"):
            break
    time.sleep(1.0)
    assert proc.poll() is None  # still serving
    proc.send_signal(signal.SIGINT)
    _, err = proc.communicate(timeout=30)
    assert proc.returncode == 1  # the trial's outcome: a timeout
    assert "Traceback" not in err
    assert any(line.startswith("outcome              timeout") for line in lines)


def test_trial_options_reach_the_operator_and_the_filter() -> None:
    from arteleop.cli.trial import TrialCommand, _operator_options
    from arteleop.operator import OperatorTraits
    from arteleop.teleop import HandFilterConfig

    traits, hand_filter = _operator_options(
        TrialCommand(confidence=0.9, placement_criterion_m=0.02, filter_beta=2.0, no_filter=True)
    )
    assert (traits.confidence, traits.placement_criterion_m) == (0.9, 0.02)
    assert (hand_filter.enabled, hand_filter.beta_per_m) == (False, 2.0)
    # The defaults are the model's median novice and the study's filter.
    assert _operator_options(TrialCommand()) == (OperatorTraits(), HandFilterConfig())


def test_study_serve_refuses_what_it_cannot_serve_into(
    capsys: pytest.CaptureFixture[str], tmp_path: Path
) -> None:
    """A file for the run folder, a folder of other files, a host it cannot bind or a port
    taken (before any folder is begun), a simulated run's folder."""
    (tmp_path / "file").write_text("x")
    (tmp_path / "notes").mkdir()
    (tmp_path / "notes" / "a.txt").write_text("mine")
    assert _error(capsys, ["study", "serve", "--out", str(tmp_path / "file")]) == (
        f"--out {tmp_path / 'file'}: a file, not a folder; give a new folder."
    )
    assert _error(capsys, ["study", "serve", "--out", str(tmp_path / "notes")]) == (
        f"{tmp_path / 'notes'} exists and is not empty: give --out a new or empty folder."
    )
    assert (tmp_path / "notes" / "a.txt").read_text() == "mine"
    out = tmp_path / "new"
    message = _error(capsys, ["study", "serve", "--out", str(out), "--host", "192.0.2.1"])
    assert message.startswith("--host 192.0.2.1: this machine cannot serve on 192.0.2.1")
    with socket.socket() as taken:
        taken.bind(("127.0.0.1", 0))
        taken.listen()
        port = taken.getsockname()[1]
        assert _error(capsys, ["study", "serve", "--out", str(out), "--port", str(port)]) == (
            f"--port {port}: taken on 127.0.0.1 (Address already in use). Stop what serves "
            "there, or give another port (0: any free one)."
        )
    assert _error(capsys, ["study", "serve", "--out", str(out), "--port", "70000"]) == (
        "--port 70000: expected a TCP port, 0-65535 (0: any free one)."
    )
    assert not out.exists()
    simulated = tmp_path / "simulated"
    simulated.mkdir()
    (simulated / "study.toml").write_text('name = "sim"\n')
    (simulated / "manifest.json").write_text(f'{{"format_version": {FORMAT_VERSION}}}\n')
    assert _error(capsys, ["study", "serve", "--out", str(simulated)]) == (
        f"{simulated} holds a simulated run: 'arteleop study resume {simulated}' continues it; "
        "give 'study serve' a new folder."
    )


def test_a_public_url_with_a_path_is_refused_before_the_run_begins(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    out = tmp_path / "people"
    argv = ["study", "serve", "--out", str(out), "--public-url", "https://proxy/study"]
    assert _error(capsys, argv).startswith("--public-url https://proxy/study: expected http")
    assert not out.exists()
