#!/usr/bin/python3
"""Writes a campaign's dataset card: what its sequences hold, per split, at a glance.

Usage: plot_campaign.py DIR/campaign.json DIR/card.md

Beside card.md: card-targets.png (each target's range and points, frame by frame, by class),
card-balance.png (targets seen and returns by class) and card-visibility.png (the weather drawn).
A target is an object of class drone, bird or plane; "seen" means with at least one return in a
frame. Ranges come from ground_truth.json (the box centre in the sensor frame).
"""
import json
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

SPLITS = ["train", "val", "test"]
TARGETS = ["drone", "bird", "plane"]
COLOURS = {"drone": "tab:red", "bird": "tab:blue", "plane": "tab:green"}


def target_frames(campaign_dir, sequence):
    """(class, range_m, returns) of every target in every frame of a sequence."""
    with open(os.path.join(campaign_dir, sequence["directory"], "ground_truth.json")) as f:
        truth = json.load(f)
    rows = []
    for frame in truth["frames"]:
        for o in frame["objects"]:
            if o["class"] in TARGETS:
                rows.append((o["class"], math.hypot(*o["box_sensor"]["centre_m"]), o["returns"]))
    return rows


def draw_targets(rows_by_split, path):
    fig, axes = plt.subplots(2, 3, figsize=(13, 7), sharex=True, sharey="row")
    # One set of bins for every class and split, so that their histograms compare.
    farthest = max([r for split in SPLITS for _, r, _ in rows_by_split[split]], default=1.0)
    bins = [farthest * k / 20 for k in range(21)]
    for column, split in enumerate(SPLITS):
        rows = rows_by_split[split]
        top, bottom = axes[0][column], axes[1][column]
        top.set_title(f"{split}: {len(rows)} target-frames")
        for c in TARGETS:
            ranges = [r for k, r, _ in rows if k == c]
            if ranges:
                top.hist(ranges, bins=bins, histtype="step", color=COLOURS[c], label=f"{c} ({len(ranges)})")
            seen = [(r, n) for k, r, n in rows if k == c and n > 0]
            if seen:
                bottom.scatter([r for r, _ in seen], [n for _, n in seen], s=6, color=COLOURS[c], label=c)
        top.set_ylabel("target-frames")
        bottom.set_ylabel("returns on the target (seen only)")
        bottom.set_xlabel("range (m)")
        bottom.set_ylim(bottom=0)
        for ax in (top, bottom):
            ax.grid(alpha=0.3)
            if ax.get_legend_handles_labels()[0]:
                ax.legend(fontsize=8)
            else:
                ax.text(0.5, 0.5, "none", transform=ax.transAxes, ha="center", color="grey")
    fig.suptitle("Range and points per target, by class and split")
    fig.tight_layout()
    fig.savefig(path, dpi=90)
    plt.close(fig)


def draw_balance(seen, returns, classes, path):
    fig, (left, right) = plt.subplots(1, 2, figsize=(13, 4.5))
    width = 0.8 / len(SPLITS)
    for i, split in enumerate(SPLITS):
        xs = [k + (i - 1) * width for k in range(len(classes))]
        left.bar(xs[: len(TARGETS)], [seen[split].get(c, 0) for c in TARGETS], width, label=split)
        right.bar(xs, [returns[split].get(c, 0) for c in classes], width, label=split)
    left.set_xticks(range(len(TARGETS)), TARGETS)
    left.set_ylabel("target-frames with returns")
    left.set_title("Targets seen, by class")
    right.set_xticks(range(len(classes)), classes, rotation=30)
    right.set_yscale("log")
    right.set_ylim(bottom=0.8)
    right.set_ylabel("returns")
    right.set_title("Returns by class")
    for ax in (left, right):
        ax.legend()
        ax.grid(alpha=0.3, axis="y")
    fig.tight_layout()
    fig.savefig(path, dpi=90)
    plt.close(fig)


def draw_visibility(visibility, path):
    fig, ax = plt.subplots(figsize=(7, 4))
    values = [v for split in SPLITS for v in visibility[split]]
    if values:
        lo, hi = min(values), max(values)
        bins = [lo * (hi / lo) ** (k / 15) for k in range(16)] if hi > lo else 5
        ax.hist([visibility[s] for s in SPLITS], bins=bins, label=SPLITS, stacked=True)
        if hi > lo:
            ax.set_xscale("log")
        ax.legend()
    else:
        ax.text(0.5, 0.5, "visibility not drawn: the scenario default (23 km) throughout",
                transform=ax.transAxes, ha="center", color="grey")
    ax.set_xlabel("visibility (km)")
    ax.set_ylabel("sequences")
    ax.set_title("Visibility drawn, by split")
    ax.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(path, dpi=90)
    plt.close(fig)


def table(header, rows):
    lines = ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    lines += ["| " + " | ".join(str(x) for x in row) + " |" for row in rows]
    return "\n".join(lines)


def main(index_path, card_path):
    with open(index_path) as f:
        index = json.load(f)
    campaign_dir = os.path.dirname(os.path.abspath(index_path))
    out_dir = os.path.dirname(os.path.abspath(card_path))
    sequences = index["sequences"]

    rows_by_split = {s: [] for s in SPLITS}
    seen = {s: {} for s in SPLITS}
    returns = {s: {} for s in SPLITS}
    visibility = {s: [] for s in SPLITS}
    sensors = {s: {} for s in SPLITS}
    for seq in sequences:
        split = seq["split"]
        rows = target_frames(campaign_dir, seq)
        rows_by_split[split] += rows
        for c, _, n in rows:
            seen[split][c] = seen[split].get(c, 0) + (n > 0)
        for c, n in seq["returns_by_class"].items():
            returns[split][c] = returns[split].get(c, 0) + n
        if "visibility_km" in seq["sampled"]["atmosphere"]:
            visibility[split].append(seq["sampled"]["atmosphere"]["visibility_km"])
        sensor = seq["sampled"]["sensor"]
        name = f"{sensor.get('preset', sensor.get('file', '?'))} (choice {sensor['choice']})"
        sensors[split][name] = sensors[split].get(name, 0) + 1
    classes = sorted({c for s in SPLITS for c in returns[s]})

    draw_targets(rows_by_split, os.path.join(out_dir, "card-targets.png"))
    draw_balance(seen, returns, classes, os.path.join(out_dir, "card-balance.png"))
    draw_visibility(visibility, os.path.join(out_dir, "card-visibility.png"))

    count = {s: sum(1 for q in sequences if q["split"] == s) for s in SPLITS}
    frames = index["frames"]
    lines = [
        "# Dataset card",
        "",
        f"Campaign `{index['spec_file']}`, seed {index['seed']}: {len(sequences)} sequences of {frames} frames "
        f"({len(sequences) * frames} frames), rendered by ladarsim {index['software']['version']}. "
        "Each sequence is a dataset in `sequences/NNNNNN/` beside its scenario; `campaign.json` indexes them.",
        "",
        "## Splits",
        "",
        table(["split", "sequences", "frames"], [[s, count[s], count[s] * frames] for s in SPLITS]),
        "",
        "## Targets (frames in which each is seen, of frames it is in)",
        "",
        table(["class"] + SPLITS,
              [[c] + [f"{seen[s].get(c, 0)} / {sum(1 for k, _, _ in rows_by_split[s] if k == c)}" for s in SPLITS]
               for c in TARGETS]),
        "",
        "![range and points per target](card-targets.png)",
        "",
        "## Returns by class",
        "",
        table(["class"] + SPLITS, [[c] + [returns[s].get(c, 0) for s in SPLITS] for c in classes]),
        "",
        "![class balance](card-balance.png)",
        "",
        "## Sensors and weather",
        "",
        table(["sensor"] + SPLITS,
              [[name] + [sensors[s].get(name, 0) for s in SPLITS]
               for name in sorted({n for s in SPLITS for n in sensors[s]})]),
        "",
        table(["visibility (km)"] + SPLITS,
              [["range"] + [f"{min(visibility[s]):.1f}-{max(visibility[s]):.1f}" if visibility[s] else "-"
                            for s in SPLITS]]),
        "",
        "![visibility](card-visibility.png)",
        "",
    ]
    with open(card_path + ".tmp", "w") as f:
        f.write("\n".join(lines))
    os.replace(card_path + ".tmp", card_path)


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    main(sys.argv[1], sys.argv[2])
