"""Friction and lay angle of a hanging nylon 1+8 cantilever: a sweep of the equivalent model.

Runs the statics of examples/nylon-1x8-hanging.json (equivalent model) at every combination
of wire-core friction and lay angle on local processes, keeps each point's files, and plots
the bending stiffness along the cantilever against its curvature (from each point's
centerline.csv), the section law's secant stiffness over the same curvatures at a strain of
1e-3 (strand.section over NumPy arrays, averaged over one pitch), and the tip deflection. Writes the picture to docs/book/src/figures/python-friction-sweep.png
(or the path given) and prints the sweep's table. A second run with the same folder reuses the
finished points.

    pip install ./crates/strand-py matplotlib
    python examples/python/friction_sweep.py [out.png]
"""

import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pandas as pd  # noqa: E402

import strand  # noqa: E402

ROOT = Path(__file__).resolve().parents[2]
FRICTION = [0.05, 0.15, 0.25, 0.4]
LAY_ANGLE = [12.0, 20.0]


def main() -> None:
    png = Path(sys.argv[1]) if len(sys.argv) > 1 else ROOT / "docs" / "book" / "src" / "figures" / "python-friction-sweep.png"
    base = strand.Scene.from_file(ROOT / "examples" / "nylon-1x8-hanging.json")
    out = ROOT / "out" / "friction-sweep"
    df = strand.sweep(
        base,
        {"strand.friction": FRICTION, "strand.layers[0].lay_angle_deg": LAY_ANGLE},
        models="equivalent",
        out_dir=out,
        keep_files=True,
    )
    cols = ["strand.friction", "strand.layers[0].lay_angle_deg", "status", "tip_x", "tip_y", "steps", "wall_time_s"]
    print(df[cols].to_string(index=False))

    fig, (ax, law, tip) = plt.subplots(1, 3, figsize=(15, 4.4), gridspec_kw={"width_ratios": [1.3, 1.3, 1]})
    styles = {12.0: "o", 20.0: "^"}
    lines = {12.0: "-", 20.0: "--"}
    colors = plt.cm.viridis([i / (len(FRICTION) - 1) * 0.85 for i in range(len(FRICTION))])
    kappa = np.geomspace(1e-3, 10.0, 200)
    for _, row in df[df.status == "ok"].iterrows():
        c = pd.read_csv(out / "points" / row.key / "equivalent" / "centerline.csv")
        mu, alpha = row["strand.friction"], row["strand.layers[0].lay_angle_deg"]
        color = colors[FRICTION.index(mu)]
        ax.plot(c.curvature.abs(), c.bending_stiffness, styles[alpha], ms=3, color=color,
                label=f"mu = {mu}, alpha = {alpha:g} deg")
        # The section law at the same friction and lay angle: the secant stiffness M/kappa,
        # averaged over 48 stations of one pitch (curvatures x stations broadcast).
        scene = base.with_values({"strand.friction": mu, "strand.layers[0].lay_angle_deg": alpha})
        pitch = scene.summary()["pitch"]
        x = (np.arange(48) + 0.5) / 48 * pitch
        r = strand.section(scene, kappa[:, None], 1e-3, x[None, :])
        law.plot(kappa, r["moment"].mean(axis=1) / kappa, lines[alpha], color=color)
    for alpha in LAY_ANGLE:
        s = base.with_values({"strand.layers[0].lay_angle_deg": alpha}).summary()
        for a in (ax, law):
            a.axhline(s["K_min"], color="grey", lw=0.8, ls=lines[alpha])
            a.axhline(s["K_max"], color="grey", lw=0.8, ls=lines[alpha])
    for a in (ax, law):
        a.set_xscale("log")
        a.set_ylabel("bending stiffness M/kappa (N m^2)")
    ax.set_xlabel("|curvature| along the cantilever (1/m)")
    ax.set_title("runs: centreline (grey: K_min, K_max)", fontsize=10)
    ax.legend(fontsize=7, ncol=2)
    law.set_xlabel("curvature (1/m)")
    law.set_title("section law at strain 1e-3, pitch mean", fontsize=10)
    for alpha in LAY_ANGLE:
        d = df[(df["strand.layers[0].lay_angle_deg"] == alpha) & (df.status == "ok")]
        tip.plot(d["strand.friction"], -d.tip_y, styles[alpha] + lines[alpha], label=f"alpha = {alpha:g} deg")
    tip.set_xlabel("friction mu")
    tip.set_ylabel("tip deflection -y (m)")
    tip.set_title("tip of the 2.5 m cantilever", fontsize=10)
    tip.legend(fontsize=8)
    fig.suptitle("nylon 1+8 cantilever under gravity, equivalent model: strand.sweep over friction and lay angle")
    fig.tight_layout()
    png.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(png, dpi=110)
    print(f"wrote {png}")


if __name__ == "__main__":
    main()
