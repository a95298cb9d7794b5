"""Draws the speed-vs-error curves of `ladarsim bench --json FILE`: beams/s against the error of a
drone's point count and energy, adaptive tolerances against fixed sub-ray counts, at each distance.

usage: /usr/bin/python3 scripts/plot_bench.py bench.json [out.png]   (or: ladarsim bench --plot out.png)
"""
import json
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt


def main():
    path = sys.argv[1]
    out = sys.argv[2] if len(sys.argv) > 2 else path.rsplit(".", 1)[0] + ".png"
    bench = json.load(open(path))
    curves = bench["accuracy"]["curves"]
    fig, axes = plt.subplots(1, 2, figsize=(12, 4.8))
    colours = {200.0: "tab:blue", 1000.0: "tab:orange", 2000.0: "tab:red"}
    for ax, key, label in ((axes[0], "count_error_pct", "|point-count error| (%)"),
                           (axes[1], "energy_error_pct", "|received-energy error| (%)")):
        for curve in curves:
            d = curve["distance_m"]
            for method, marker, style in (("adaptive", "o", "-"), ("fixed", "s", "--")):
                pts = [p for p in curve["points"] if p["method"] == method]
                xs = [max(abs(p[key]), 0.05) for p in pts]
                ys = [p["beams_per_s"] for p in pts]
                ax.plot(xs, ys, style, marker=marker, color=colours.get(d, "k"),
                        label=f"{int(d)} m, {method}")
                for p, x, y in zip(pts, xs, ys):
                    tag = f'{p["footprint_tolerance"]:g}' if method == "adaptive" else str(p["footprint_samples"])
                    ax.annotate(tag, (x, y), textcoords="offset points", xytext=(3, 3), fontsize=7)
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel(label + f' vs {bench["accuracy"]["reference_samples"]} sub-rays')
        ax.set_ylabel("beams per second (2 cores)")
        ax.axhline(bench["realtime"]["sensor_beams_per_s"], color="grey", lw=0.8)
        ax.grid(True, which="both", alpha=0.3)
    axes[0].legend(fontsize=7)
    fig.suptitle("0.3 m drone in front of terrain: speed against error "
                 "(labels: tolerance for adaptive, sub-rays per beam for fixed; grey: the sensor's real time)")
    fig.tight_layout()
    tmp = out + ".tmp.png"
    fig.savefig(tmp, dpi=110)
    os.replace(tmp, out)
    print(f"wrote {out}")


if __name__ == "__main__":
    main()
