#!/usr/bin/python3
"""Draws `ladarsim table1 --json` output: points on a 0.3 m target against range.

Usage: plot_table1.py TABLE1.json OUT.png
"""
import json
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    rows = json.load(open(sys.argv[1]))
    r = [row["range_m"] for row in rows]
    fig, ax = plt.subplots(figsize=(9, 5.5))
    ax.plot(r, [row["paper_tp"] for row in rows], "ks-", label="paper Table 1 (TP)")
    ax.plot(r, [row["analytic_tp_0p5deg"] for row in rows], "b^--", label="Eq. 8, stated 0.5 deg field")
    ax.plot(r, [row["analytic_tp_0p65deg"] for row in rows], "gv--", label="Eq. 8, 0.65 deg field (reproduces the table's columns)")
    for name, colour, label in (("rendered_plate", "tab:red", "rendered 0.3 m plate"),
                                ("rendered_drone", "tab:orange", "rendered 0.3 m quadcopter")):
        mean = [row[name + "_mean"] for row in rows]
        ax.plot(r, mean, "o-", color=colour, label=label + " (mean, min-max band)")
        ax.fill_between(r, [row[name + "_min"] for row in rows], [row[name + "_max"] for row in rows],
                        color=colour, alpha=0.2)
        ax.plot(r, [row[name + "_noiseless_mean"] for row in rows], ":", color=colour, label=label + ", noise off")
    ax.set_yscale("log")
    ax.set_xlabel("range (m)")
    ax.set_ylabel("3D points on the target per frame")
    ax.set_title("Table 1: points on a 0.3 m target, paper's LADAR preset, clear air")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    tmp = sys.argv[2] + ".tmp.png"
    fig.savefig(tmp, dpi=100)
    os.replace(tmp, sys.argv[2])


if __name__ == "__main__":
    main()
