"""The strand's section data for the peer model, and the `continuous` law in plain Python.

The beam constants (EA, K_min, the traditional EI and EA, mass per length, helix radius, pitch,
eta) come from `strand section SCENE --json`, so both programs read one strand; the per-wire
constants follow from the scene file as in `strand_core::section`:

    k       = eta E_w A_w                 wire's axial stiffness projected on the strand axis (N)
    cap     = k cos^2(alpha)              friction limit per unit strand strain and unit gain (N)
    capstan = mu sin(alpha)
    phi_i(x) = phase + 2 pi i / m + s 2 pi x / P   (s = +1 right lay, -1 left lay), wrapped
    lever_i = -R_w sin(phi_i)             wire's bending strain per unit curvature kappa_z (m)
    gains   = exp(capstan |phi_i|) - 1 (stretched), 1 - exp(-capstan |phi_i|) (shortened)

and the planar `continuous` law is

    M(eps, kappa, x) = K_min kappa + sum_i lever_i clamp(k lever_i kappa, -c_neg_i, c_pos_i),
    c_pos_i = cap max(eps, 0) gain_pos_i,  c_neg_i = cap max(eps, 0) gain_neg_i.

`check_against_cli` compares this function with `strand section --law continuous` at strains,
curvatures and stations that stick, slip on either side and go slack, so a transcription error
here stops the benchmark before anything is timed.
"""

import json
import math
import subprocess
import sys


def setup_error(message):
    """Stops the benchmark before (or instead of) a result: exit status 2."""
    print(f"bench-peers: {message}", file=sys.stderr)
    sys.exit(2)


def cli_json(cmd):
    """Runs the strand command and reads its JSON output."""
    try:
        p = subprocess.run(cmd, capture_output=True, text=True)
    except OSError as e:
        setup_error(f"cannot run {cmd[0]}: {e}")
    if p.returncode != 0:
        setup_error(f"{' '.join(cmd)} failed: {p.stderr.strip()}")
    return json.loads(p.stdout)


def section_constants(strand_cli, scene_path):
    """Beam and wire constants of the scene's strand (SI units), as a plain dict."""
    sec = cli_json([strand_cli, "section", scene_path, "--json"])
    with open(scene_path) as f:
        scene = json.load(f)
    strand = scene["strand"]
    (layer,) = strand["layers"]
    alpha = math.radians(layer["lay_angle_deg"])
    wire_area = math.pi * layer["diameter"] ** 2 / 4.0
    k = sec["eta"] * layer["youngs_modulus"] * wire_area
    lay = layer.get("lay_direction", "right")
    return {
        "length": strand["length"],
        "gravity": scene["loads"]["gravity"],
        "duration": scene["analysis"]["duration"],
        "output_interval": scene["analysis"]["output_interval"],
        "mass_per_length": sec["mass_per_length"],
        "EA": sec["EA"],
        "K_min": sec["K_min"],
        "EI_traditional": sec["EI_traditional"],
        "EA_traditional": sec["EA_traditional"],
        "wires": layer["wires"],
        "radius": sec["R_w"],
        "pitch": sec["pitch"],
        "phase": math.radians(layer.get("phase_deg", 0.0)),
        "lay_sign": 1.0 if lay == "right" else -1.0,
        "k": k,
        "cap_per_strain": k * math.cos(alpha) ** 2,
        "capstan": strand.get("friction", 0.3) * math.sin(alpha),
    }


def wrap(phi):
    """Angle wrapped to (-pi, pi]."""
    w = math.fmod(phi, 2.0 * math.pi)
    if w < 0.0:
        w += 2.0 * math.pi
    return w - 2.0 * math.pi if w > math.pi else w


def station(c, x):
    """Per-wire (lever, gain_pos, gain_neg) at material coordinate x (m)."""
    m = c["wires"]
    wires = []
    for i in range(m):
        phi = wrap(c["phase"] + 2.0 * math.pi * i / m + c["lay_sign"] * 2.0 * math.pi * x / c["pitch"])
        theta = abs(phi)
        wires.append(
            (
                -c["radius"] * math.sin(phi),
                math.expm1(c["capstan"] * theta),
                -math.expm1(-c["capstan"] * theta),
            )
        )
    return tuple(wires)


def continuous_moment(c, wires, eps, kappa):
    """Bending moment (N m) of the `continuous` law at a station's wires."""
    m = c["K_min"] * kappa
    if eps <= 0.0:
        return m
    scale = c["cap_per_strain"] * eps
    k = c["k"]
    for lever, gain_pos, gain_neg in wires:
        f = k * lever * kappa
        cap_pos = scale * gain_pos
        if f > cap_pos:
            f = cap_pos
        else:
            cap_neg = -scale * gain_neg
            if f < cap_neg:
                f = cap_neg
        m += f * lever
    return m


def check_against_cli(strand_cli, scene_path, c):
    """Largest |M_python - M_strand| / max(|M_strand|, 1e-9 N m) over a grid; raises if above 1e-10."""
    worst = 0.0
    points = 0
    for x in (0.0, 0.0137, 0.31, 0.5, 0.977):
        for eps in (-1e-5, 0.0, 2e-6, 3e-5, 4e-4):
            for kappa in (-12.0, -0.4, -0.03, -0.002, 0.0, 0.002, 0.03, 0.4, 12.0):
                out = cli_json([
                    strand_cli, "section", scene_path, "--law", "continuous", "--json",
                    f"--strain={eps!r}", f"--curvature={kappa!r}", f"--at={x!r}",
                ])
                # The command's curvature is the signed kappa_z (positive turning
                # counter-clockwise seen from +Z), and its moment is M_z (README "Curvature sign").
                want = out["moment"]
                got = continuous_moment(c, station(c, x), eps, kappa)
                worst = max(worst, abs(got - want) / max(abs(want), 1e-9))
                points += 1
    if worst > 1e-10:
        setup_error(
            f"the Python `continuous` law differs from `strand section` by {worst:.2e} (relative): "
            "fix benchmarks/exudyn/strand_law.py before timing"
        )
    return {"points": points, "largest_relative_difference": worst}
