"""A power analysis written to a folder, whole: ``power.csv``, ``power.md`` and the power
curves' figure."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pandas as pd

from arteleop.analysis.output import whole_folder
from arteleop.analysis.power import Pool, PowerOptions, smallest_n

TARGETS = (0.8, 0.9)


def write_power_report(
    pool: Pool,
    options: PowerOptions,
    table: pd.DataFrame,
    out_dir: Path,
    simulated: bool,
    interrupted: bool = False,
) -> dict[str, Path]:
    """Write the power table, its report and figure into ``out_dir`` (replacing it); returns the
    files by name. ``simulated`` says the pool holds simulated participants."""
    with whole_folder(out_dir) as partial:
        table.to_csv(partial / "power.csv", index=False, float_format="%.6g")
        _figure(table, options, partial / "power_curves.png")
        text = _markdown(pool, options, table, simulated, interrupted)
        (partial / "power.md").write_text(text, encoding="utf-8")
    return {name: out_dir / name for name in ("power.csv", "power.md", "power_curves.png")}


def _figure(table: pd.DataFrame, options: PowerOptions, path: Path) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    measures = list(dict.fromkeys(table["measure"])) if len(table) else []
    cols = min(max(len(measures), 1), 3)
    rows = -(-max(len(measures), 1) // cols)
    fig, grid = plt.subplots(rows, cols, figsize=(4.2 * cols, 3.2 * rows), squeeze=False,
                             sharey=True)  # fmt: skip
    axes = grid.ravel()
    for ax in axes[len(measures) :]:
        ax.set_visible(False)
    for ax, measure in zip(axes, measures, strict=False):
        part = table[table["measure"] == measure]
        for comparison, group in part.groupby("comparison", sort=False):
            ax.plot(group["n"], group["power"], marker="o", label=comparison)
            ax.fill_between(group["n"], group["ci_low"], group["ci_high"], alpha=0.15)
        for target in TARGETS:
            ax.axhline(target, color="grey", lw=0.8, ls="--")
        ax.set_title(measure)
        ax.set_xlabel("participants")
        ax.set_ylim(0, 1)
    for row in grid:
        row[0].set_ylabel(f"power at alpha = {options.alpha:g}")
    if measures:
        axes[0].legend(fontsize=7, loc="lower right")
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def _tests(options: PowerOptions) -> str:
    """The tests run on each resampled study, in words."""
    if options.method == "yuen":
        return ("the paired differences' 20 % trimmed mean against zero" if options.paired
                else "Yuen's test of 20 % trimmed means")  # fmt: skip
    tests = ("paired tests (paired t-test, or Wilcoxon's signed-rank test where Lilliefors "
             "rejects the differences' normality)" if options.paired else
             "tests between independent groups (Student's t-test, or Mann-Whitney's U where "
             "Lilliefors rejects a group's normality)")  # fmt: skip
    if options.method == "thesis":
        tests += (", each group first trimmed of its largest and smallest value as the "
                  "thesis did (a procedure that rejects a true null about twice as often as "
                  "alpha)")  # fmt: skip
    return tests


def _markdown(
    pool: Pool, options: PowerOptions, table: pd.DataFrame, simulated: bool, interrupted: bool
) -> str:
    kind = "simulated" if simulated else "real, or of unknown kind"
    tests = _tests(options)
    lines = [
        "# Power by resampling participants", "",
        f"**The pool**: {len(pool.participants)} participants ({kind}), from:", "",
        *(f"- {line}" for line in pool.sources), "",
        f"Conditions: {', '.join(pool.conditions)}. Each resampled study draws n participants "
        "from the pool with replacement, each one's trials together, and runs the tests "
        f"`arteleop analyze --method {options.method}` runs: {tests}"
        f"{', Holm-corrected within each family of pairwise tests' if options.holm else ''}, "
        f"at alpha = {options.alpha:g}; {options.resamples} resampled studies per n "
        f"(seed {options.seed}). Power is the share that reject, with its 95 % Wilson interval.",
        "",
        "**What this is.** Resampling a pilot estimates the power to find an effect *like the "
        "pilot's*: an effect the pool overstates by chance is found more often here than it "
        "will be. A pool of simulated participants gives the simulated participant's power, "
        "not people's; a pool smaller than the sizes asked for is resampled far beyond itself, "
        "and its estimate is only as good as the pool.", "",
    ]  # fmt: skip
    if interrupted:
        done = sorted(set(table["n"])) if len(table) else []
        lines += [f"**Interrupted**: only n = {', '.join(map(str, done)) or 'none'} done.", ""]
    if not len(table):
        return "\n".join(lines) + "\n"
    reached = {t: smallest_n(table, t).set_index(["comparison", "measure"])["n"] for t in TARGETS}
    lines += ["## The smallest n that reaches each power", "",
              "| comparison | measure | 80 % | 90 % |", "| --- | --- | ---: | ---: |"]  # fmt: skip
    for (comparison, measure), n80 in reached[0.8].items():
        n90 = reached[0.9][(comparison, measure)]
        said = [f"{n:.0f}" if n is not None and not np.isnan(n) else "not within the sizes"
                for n in (n80, n90)]  # fmt: skip
        lines.append(f"| {comparison} | {measure} | {said[0]} | {said[1]} |")
    lines += ["", "## Power per n", "", "| comparison | measure | n | power | 95 % CI |",
              "| --- | --- | ---: | ---: | --- |"]  # fmt: skip
    for _, r in table.iterrows():
        lines.append(f"| {r['comparison']} | {r['measure']} | {r['n']} | {r['power']:.3f} | "
                     f"{r['ci_low']:.3f}-{r['ci_high']:.3f} |")  # fmt: skip
    lines += ["", "![power curves](power_curves.png)"]
    return "\n".join(lines) + "\n"
