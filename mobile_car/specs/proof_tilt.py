"""The tilt proof: MuJoCo stands the robot on a floor that tilts slowly about a horizontal
axis, so that the slope falls towards an azimuth, its drive wheels braked, until it slides
or tips; the angle is compared with the computed one (docs/specs.md, "Statics, and their proofs").

Gravity turns instead of the floor (the same slope to the robot; the floor's contact
frame stays put). The slope rises at FAST_RATE to BEFORE below the computed angle, then
at SLOW_RATE, quasi-static, until the event or WINDOW past it. Events: it tips when a
part it stood on has risen LIFT (the angle taken is where that rise began: ONSET_LIFT);
it slides when a part it stands on that holds (no swivel castor) has slipped SLIDE over
the floor where it touches it (the velocity of its point at the contact: a wheel that
rolls, or a robot rocking over an edge, moves its centre but not that point), the
angle taken where the slip's speed rose past SLIDE_SPEED, unless it stopped for STILL
since (it slides in jerks, sticking for a few ms).
Brakes are a damping on the driven wheels' joints that lets them creep BRAKE_CREEP
(m/s at the rim under the whole weight). Each contact gets the friction the figure
assumed, and the friction cone is elliptic (Coulomb's: MuJoCo's default pyramid holds
less across its axes, and creeps 5 times as fast), with IMPRATIO and NOSLIP_ITERATIONS
of MuJoCo's noslip pass; the contacts as stiff as sim's drop makes them
(RESTING_SOLREF: at MuJoCo's default a wheel sinks ~3 mm under its load, and rises as
much as the slope unloads it, long before it tips).

Why noslip, and the slip measured so finely: MuJoCo's soft friction creeps, and a
contact that slips gets more normal force the faster it slips (in the elliptic cone's
middle zone the normal force grows with the tangential residual). A robot past its
slide angle then crept down at 0.5 mm/s on wheels whose loads had swollen to hold it:
MiR "held" 2-4° past its figure under the 5 mm/s a slide was once taken at. The noslip
pass takes the creep out while the friction holds (MiR: 0.23 mm/s to 0.0005 mm/s at 30°),
so a slip of SLIDE_SPEED is the slide itself; IMPRATIO 100 keeps the swelling small
(it goes as 1/impratio: at 10 Husky slid sideways 4.5° early, MiR's worst direction
held 1.4° long; at 100 a mecanum robot's diagonal 1.5° long: IMPRATIO)."""

from __future__ import annotations

import copy
import dataclasses
import math

from .figures import Proof

FAST_RATE = math.radians(10.0)   # rad/s
SLOW_RATE = math.radians(2.0)    # rad/s
WINDOW = math.radians(4.0)
BEFORE = math.radians(2.0)
SETTLE = 0.5                     # s on the level floor first
LIFT = 0.002                     # m
ONSET_LIFT = 0.0005              # m
SLIDE = 0.0002                   # m
SLIDE_SPEED = 0.00005            # m/s: with noslip a held robot creeps under 1e-6
STILL = 0.2                      # s
BRAKE_CREEP = 1e-5               # m/s
# MuJoCo's friction constraint this much stiffer than the normal one: at 1 a box held by
# its four braked wheels on μ 0.6 crept 8 mm/s at 30° of its 31° slide angle, at 10 0.9;
# and the normal force a slipping contact gains goes as 1 / IMPRATIO. That gain is taken
# from the contacts that do not slip: where all slip together (a box on four tyres) it
# moves nothing, but a mecanum robot tilted along a diagonal holds on the two wheels whose
# rollers' grip lies along it, the other two roll free down it, and at 100 the gripping
# pair drew load off them and held 1.5° past the figure (ROSbot XL 28.2° for 26.5°,
# linorobot2 28.6°); at 1000 0.1 to 0.8° (the eight robots of the docs within 0.1° of 100).
IMPRATIO = 1000.0
NOSLIP_ITERATIONS = 10
TOLERANCE = 1.0                  # deg
CHUNK = 5                        # steps between the checks (5 ms: 0.01° of slope)
GRAVITY = 9.81


@dataclasses.dataclass
class Tilt:
    azimuth: float         # deg
    event: str | None      # "tips", "slides", or None (neither by the run's end)
    angle: float | None    # deg
    seconds: float         # simulated


def prove_tilt(sim, found, section, statics) -> list[Tilt]:
    """Tilt the robot towards forward, left, backward, right and the azimuths of its
    statics.stand and statics.slide figures; fill the figures' proofs. ``statics``: the
    computed angles (rad) by azimuth (deg), ``.tip(a)`` and ``.slide(a)``, the named
    ``.directions`` and the azimuths of the stand and slide figures (``.stand_at``,
    ``.slide_at``)."""
    value = {f.key: f for f in section.figures}
    stand_at, slide_at = statics.stand_at, statics.slide_at
    azimuths = dict.fromkeys([*statics.directions.values(), stand_at, slide_at])
    runs = {}
    for azimuth in azimuths:
        tip, slide = statics.tip(azimuth), statics.slide(azimuth)
        runs[azimuth] = tilt(sim, found, azimuth, math.degrees(min(tip, slide)))
    for name, azimuth in statics.directions.items():
        figure = value[f"statics.tip.{name}"]
        figure.proof = _tip_proof(runs[azimuth], figure.value,
                                  math.degrees(statics.slide(azimuth)))
    stand = value["statics.stand"]
    run = runs[stand_at]
    stand.proof = Proof(run.angle, run.angle is not None and
                        abs(run.angle - stand.value) <= TOLERANCE, f"±{TOLERANCE:g}°",
                        _said(run))
    slide = value["statics.slide"]
    slide.proof = _slide_proof(runs[slide_at], slide.value,
                               math.degrees(statics.tip(slide_at)))
    return list(runs.values())


def _tip_proof(run: Tilt, tip: float, slide: float) -> Proof:
    if run.event == "tips":
        return Proof(run.angle, abs(run.angle - tip) <= TOLERANCE, f"±{TOLERANCE:g}°",
                     _said(run))
    if run.event == "slides":  # it never got to tip: right if the figures said so
        agrees = slide < tip and abs(run.angle - slide) <= TOLERANCE
        return Proof(None, agrees, f"±{TOLERANCE:g}°",
                     f"{_said(run)}, before it could tip (slide computed {slide:.2f}°)",
                     instead=f"slid first at {run.angle:.3g}°")
    return Proof(None, False, f"±{TOLERANCE:g}°", _said(run))


def _slide_proof(run: Tilt, slide: float, tip: float) -> Proof:
    if run.event == "slides":
        return Proof(run.angle, abs(run.angle - slide) <= TOLERANCE, f"±{TOLERANCE:g}°",
                     _said(run))
    if run.event == "tips":
        agrees = tip < slide and abs(run.angle - tip) <= TOLERANCE
        return Proof(None, agrees, f"±{TOLERANCE:g}°",
                     f"{_said(run)}, before it could slide (tip computed {tip:.2f}°)")
    return Proof(None, False, f"±{TOLERANCE:g}°", _said(run))


def _said(run: Tilt) -> str:
    if run.event is None:
        return (f"tilted towards azimuth {run.azimuth:g}°: neither slid nor tipped by "
                f"{run.angle:.2f}°" if run.angle is not None else "the run went astray")
    return (f"tilted towards azimuth {run.azimuth:g}° it {run.event} at {run.angle:.2f}° "
            f"({run.seconds:.1f} s simulated)")


def proof_model(sim, found, resting: bool = True):
    """A copy of sim's model for a proof: each contact's friction as the figures assume
    it (above the floor's priority), Coulomb's elliptic cone, and the SimModel over it;
    ``resting``: the contacts as stiff as sim's drop makes them (a driving proof keeps
    sim's driving contacts)."""
    from ..sim.engine import mujoco
    from ..sim.model import RESTING_SOLREF

    mj = mujoco()
    model = copy.copy(sim.model)
    for contact in found.contacts:
        for g in range(model.ngeom):
            if model.geom_bodyid[g] == contact.body and g in sim.support_geoms:
                model.geom_friction[g][0] = max(contact.mu, 1e-5)
                model.geom_priority[g] = 2
                if resting:
                    model.geom_solref[g] = RESTING_SOLREF
    model.opt.cone, model.opt.impratio = mj.mjtCone.mjCONE_ELLIPTIC, IMPRATIO
    return model, dataclasses.replace(sim, model=model)


def tilt(sim, found, azimuth: float, expected: float) -> Tilt:
    """One tilt towards ``azimuth`` (deg), slowing near ``expected`` (deg)."""
    from ..sim.run import Run

    model, copied = proof_model(sim, found)
    weight = found.mass * GRAVITY
    for wheel in sim.drive.driven:  # braked
        dof = model.jnt_dofadr[wheel.joint_id]
        model.dof_damping[dof] = weight * wheel.radius ** 2 / BRAKE_CREEP
    run = Run(copied)
    run.step(SETTLE)
    bodies = sorted({c.body for c in found.contacts})
    start_heights = run.data.xpos[bodies, 2].copy()
    slip = Slip(model, sim.floor_geom, sim.root_body, found.contacts, bodies)
    a = math.radians(azimuth)
    slow_from = max(0.0, math.radians(expected) - BEFORE)
    end = min(math.radians(expected) + WINDOW, math.radians(89.0))
    theta, elapsed = 0.0, 0.0
    onset_lift = onset_slide = None
    slid = still = 0.0
    step = model.opt.timestep * CHUNK
    while theta < end:
        slow = theta >= slow_from
        theta += (SLOW_RATE if slow else FAST_RATE) * step
        model.opt.noslip_iterations = NOSLIP_ITERATIONS if slow else 0
        elapsed += step
        model.opt.gravity[:] = [GRAVITY * math.sin(theta) * math.cos(a),
                                GRAVITY * math.sin(theta) * math.sin(a),
                                -GRAVITY * math.cos(theta)]
        run.step(step)
        lift = float((run.data.xpos[bodies, 2] - start_heights).max())
        if lift > ONSET_LIFT:
            onset_lift = theta if onset_lift is None else onset_lift
        else:
            onset_lift = None
        if lift > LIFT:
            return Tilt(azimuth, "tips", math.degrees(onset_lift), elapsed)
        speed = slip.speed(run.data)
        if speed > SLIDE_SPEED:
            if onset_slide is None:  # (what crept before does not count)
                onset_slide, slid = theta, 0.0
            still = 0.0
            slid += speed * step
            if slid > SLIDE:
                return Tilt(azimuth, "slides", math.degrees(onset_slide), elapsed)
        elif onset_slide is not None:
            still += step
            if still > STILL:
                onset_slide = None
        if not math.isfinite(lift):
            return Tilt(azimuth, None, None, elapsed)
    return Tilt(azimuth, None, math.degrees(theta), elapsed)


class Slip:
    """How fast the parts that hold slip over the floor where they touch it (m/s): the
    velocity of the body's point at the contact, along the floor (a wheel that rolls,
    or a robot that rocks over an edge, moves its body's centre; its contact stays put);
    along its axle only for a part that holds only along it (a mecanum wheel's rollers
    roll across it). Not a castor wheel on a swivel: pulled sideways it swivels round,
    its wheel moving by its trail (MiR's 5 mm at 5°, its robot standing still)."""

    def __init__(self, model, floor: int, root: int, contacts, bodies):
        import numpy as np

        holds = {c.body: c.axis if c.hold == "axle" else (0.0, 0.0)
                 for c in contacts if c.hold != "free"} or dict.fromkeys(bodies, (0.0, 0.0))
        self.floor = floor
        self.holds = np.zeros(model.ngeom, dtype=bool)  # by geom
        self.axis = np.zeros((model.ngeom, 2))
        for g in range(model.ngeom):
            body = int(model.geom_bodyid[g])
            if body in holds:
                self.holds[g], self.axis[g] = True, holds[body]
        self.along = self.axis.any(axis=1)
        self.root = int(model.body_rootid[root])
        self.body = model.geom_bodyid

    def speed(self, data) -> float:
        import numpy as np

        n = data.ncon
        if n == 0:
            return 0.0
        contact = data.contact
        geoms = contact.geom[:n]
        other = geoms.sum(axis=1) - self.floor  # (the robot touches nothing but the floor)
        mask = self.holds[other] & (geoms == self.floor).any(axis=1)
        if not mask.any():
            return 0.0
        other = other[mask]
        # (rotation, translation) at the centre of the root's subtree
        velocity = data.cvel[self.body[other]]
        r = contact.pos[:n][mask] - data.subtree_com[self.root]
        vx = velocity[:, 3] + velocity[:, 1] * r[:, 2] - velocity[:, 2] * r[:, 1]
        vy = velocity[:, 4] + velocity[:, 2] * r[:, 0] - velocity[:, 0] * r[:, 2]
        axis = self.axis[other]
        speed = np.where(self.along[other], np.abs(vx * axis[:, 0] + vy * axis[:, 1]),
                         np.hypot(vx, vy))
        return float(speed.max())
