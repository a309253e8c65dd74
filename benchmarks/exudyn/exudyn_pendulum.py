"""One timed run of the pinned strand pendulum in Exudyn, printed as JSON (the peer side of
`cargo xtask bench-peers`; `peer_pendulum` is the strand side and prints the same keys).

    python3 exudyn_pendulum.py CONSTANTS.json --law constant|continuous --step H
        [--spectral-radius R] [--relative-tolerance TOL] [--absolute-tolerance TOL]
        [--full-newton] [--elements N] [--scale-ei F]

CONSTANTS.json is written by bench_peers.py from `strand section` and the scene
(`strand_law.section_constants`). The model: N ObjectANCFCable2D elements (default
quadrature: 5 Gauss points for the axial term, 3 for bending), node 0's position held by two
CoordinateConstraints, gravity as LoadMassProportional on every element. `constant` gives the
elements the traditional beam's EI and EA; `continuous` gives them EA_eq and the law as a
Python bendingMomentUserFunction of (curvature, axial strain, material coordinate). Exudyn's
generalized-alpha at step H with its defaults otherwise (modified Newton, relative tolerance
1e-8 of the step's first residual, absolute 1e-10, adaptive step halving when Newton fails).

`setup_s` is building and assembling the system, `solve_s` the solver's SolveSystem (its own
start, the steps and its finish), by the monotonic clock. `--scale-ei` multiplies the bending
stiffness (both laws): a deliberately wrong model, to see the agreement check fail.
"""

import argparse
import json
import sys
import time

sys.exudynFast = True  # Exudyn's build without range checks (its documented fast mode)
import exudyn as exu  # noqa: E402
from exudyn.itemInterface import (  # noqa: E402
    CoordinateConstraint,
    LoadMassProportional,
    MarkerBodyMass,
    MarkerNodeCoordinate,
    NodePoint2DSlope1,
    NodePointGround,
    ObjectANCFCable2D,
    SensorNode,
    VObjectANCFCable2D,
)

import strand_law  # noqa: E402


def build(c, law, elements, scale_ei):
    """The system, the tip sensor and the element objects' start coordinates."""
    sc = exu.SystemContainer()
    mbs = sc.AddSystem()
    length = c["length"]
    l = length / elements
    ground = mbs.AddNode(NodePointGround(referenceCoordinates=[0.0, 0.0, 0.0]))
    nodes = [
        mbs.AddNode(NodePoint2DSlope1(referenceCoordinates=[i * l, 0.0, 1.0, 0.0]))
        for i in range(elements + 1)
    ]
    if law == "constant":
        ei, ea, uf = c["EI_traditional"], c["EA_traditional"], 0
    else:
        ei, ea = c["K_min"], c["EA"]
        uf = ContinuousMoment(c, l, scale_ei)
    start_of = {}
    for e in range(elements):
        obj = mbs.AddObject(
            ObjectANCFCable2D(
                length=l,
                massPerLength=c["mass_per_length"],
                bendingStiffness=scale_ei * ei,
                axialStiffness=ea,
                nodeNumbers=[nodes[e], nodes[e + 1]],
                bendingMomentUserFunction=uf,
                visualization=VObjectANCFCable2D(show=False),
            )
        )
        start_of[int(obj)] = e * l
        marker = mbs.AddMarker(MarkerBodyMass(bodyNumber=obj))
        mbs.AddLoad(LoadMassProportional(markerNumber=marker, loadVector=c["gravity"]))
    if law != "constant":
        uf.start_of.update(start_of)
    held = mbs.AddMarker(MarkerNodeCoordinate(nodeNumber=ground, coordinate=0))
    for coordinate in (0, 1):
        m = mbs.AddMarker(MarkerNodeCoordinate(nodeNumber=nodes[0], coordinate=coordinate))
        mbs.AddObject(CoordinateConstraint(markerNumbers=[held, m]))
    tip = [
        mbs.AddSensor(
            SensorNode(
                nodeNumber=nodes[-1],
                outputVariableType=v,
                storeInternal=True,
                writeToFile=False,
            )
        )
        for v in (exu.OutputVariableType.Position, exu.OutputVariableType.Velocity)
    ]
    mbs.Assemble()
    return sc, mbs, tip


class ContinuousMoment:
    """The `continuous` law as Exudyn's bendingMomentUserFunction. Exudyn passes the position
    inside the element (0..1) and the object's number, so the wire constants of each Gauss
    point are computed once and kept by (object, position), as strand keeps its stations."""

    def __init__(self, c, l, scale):
        self.c = c
        self.l = l
        self.scale = scale
        self.start_of = {}
        self.stations = {}

    def __call__(self, mbs, t, item, xi, curvature, curvature_t, curvature_ref, ei, damping,
                 strain, strain_t, strain_ref):
        key = (item, xi)
        wires = self.stations.get(key)
        if wires is None:
            wires = strand_law.station(self.c, self.start_of[item] + xi * self.l)
            self.stations[key] = wires
        m = strand_law.continuous_moment(self.c, wires, strain - strain_ref, curvature - curvature_ref)
        return self.scale * m


def on_grid(position, velocity, interval, duration):
    """[t, x, y] at every output time, by cubic Hermite interpolation of the tip's position and
    velocity between the two steps around it (its error is of order h^4 times the fourth time
    derivative: below 1e-9 m at 1 ms steps on this swing, against step errors of 1e-5 m and
    more)."""
    times = [float(r[0]) for r in position]
    out = []
    n = int(round(duration / interval))
    j = 0
    for i in range(n + 1):
        t = i * interval
        while j + 2 < len(times) and times[j + 1] < t:
            j += 1
        t0, t1 = times[j], times[j + 1]
        h = t1 - t0
        s = min(max((t - t0) / h, 0.0), 1.0) if h > 0 else 0.0
        h00, h10 = 2 * s**3 - 3 * s**2 + 1, s**3 - 2 * s**2 + s
        h01, h11 = -2 * s**3 + 3 * s**2, s**3 - s**2
        xy = [
            h00 * position[j][k] + h10 * h * velocity[j][k] + h01 * position[j + 1][k]
            + h11 * h * velocity[j + 1][k]
            for k in (1, 2)
        ]
        out.append([t, xy[0], xy[1]])
    return out


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("constants")
    p.add_argument("--law", choices=["constant", "continuous"], required=True)
    p.add_argument("--step", type=float, required=True)
    p.add_argument("--spectral-radius", type=float, default=0.9)
    p.add_argument("--relative-tolerance", type=float, default=None)
    p.add_argument("--absolute-tolerance", type=float, default=None)
    p.add_argument("--full-newton", action="store_true", help="a new Jacobian every iteration")
    p.add_argument("--elements", type=int, default=30)
    p.add_argument("--scale-ei", type=float, default=1.0)
    a = p.parse_args()
    with open(a.constants) as f:
        c = json.load(f)

    t0 = time.perf_counter()
    sc, mbs, tip = build(c, a.law, a.elements, a.scale_ei)
    setup = time.perf_counter() - t0

    s = exu.SimulationSettings()
    ti = s.timeIntegration
    ti.endTime = c["duration"]
    ti.numberOfSteps = int(round(c["duration"] / a.step))
    ti.generalizedAlpha.spectralRadius = a.spectral_radius
    if a.relative_tolerance is not None:
        ti.newton.relativeTolerance = a.relative_tolerance
    if a.absolute_tolerance is not None:
        ti.newton.absoluteTolerance = a.absolute_tolerance
    ti.newton.useModifiedNewton = not a.full_newton
    ti.verboseMode = 0
    s.solution.file.write = False
    # The tip at every step (Exudyn halves steps where Newton fails, so its steps need not
    # fall on the output times); `on_grid` interpolates them to the output times.
    s.solution.sensors.writePeriod = 0.5 * a.step / 64
    s.show.computationTime = False

    solver = exu.MainSolverImplicitSecondOrder()
    t0 = time.perf_counter()
    ok = solver.SolveSystem(mbs, s)
    solve = time.perf_counter() - t0
    if not ok:
        raise SystemExit(f"Exudyn's solver failed: {solver.GetErrorString()}")

    position, velocity = (mbs.GetSensorStoredData(x) for x in tip)
    it = solver.it
    out = {
        "program": "exudyn",
        "version": exu.config.Version(),
        "law": a.law,
        "elements": a.elements,
        "bending_points_per_element": 3,
        "dofs": mbs.systemData.ODE2Size() if hasattr(mbs.systemData, "ODE2Size") else None,
        "step": a.step,
        "spectral_radius": a.spectral_radius,
        "newton_relative_tolerance": ti.newton.relativeTolerance,
        "newton_absolute_tolerance": ti.newton.absoluteTolerance,
        # One sensor sample at the start and one after every step.
        "steps": len(position) - 1,
        "modified_newton": bool(ti.newton.useModifiedNewton),
        "step_halving": bool(ti.adaptiveStep),
        "newton_iterations": int(it.newtonStepsCount),
        "jacobians": int(it.newtonJacobiCount),
        "setup_s": setup,
        "solve_s": solve,
        "tip": on_grid(position, velocity, c["output_interval"], c["duration"]),
    }
    print(json.dumps(out))


if __name__ == "__main__":
    main()
