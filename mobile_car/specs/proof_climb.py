"""The climb proof: MuJoCo drives the robot straight up a slope MARGIN under its computed
climb angle, where it must climb, and MARGIN over it, where it must not (docs/specs.md,
"Statics, and their proofs"). As in the tilt proof gravity is turned, not the floor, and
the contacts are the proof model's (:func:`.proof_tilt.proof_model`), as soft as sim
drives on (on the tilt's stiff resting contacts Husky's tyres chattered and slid back 1°
under its limit). The wheels are sim's motors: their velocity servos, limited to their
effort, commanded a crawl (CRAWL at the rim, sim's speed where that is slower) after
sim's ramp; the robot climbs when, over the last MEASURE s of DRIVE s, it goes up the
slope at PROGRESS of r·ω or more. A crawl, because 1° under its limit a robot has ~0.17
m/s² to spare: at sim's speed it was still catching up after its ramp (a 10 kg box at
0.25 m/s: 64%), which says nothing of the slope. The servos are SERVO_STIFFER times sim's
gain: at sim's, Husky's wheels lagged their command by a third under the torque a 39°
slope asks (kv·Δω = τ), which is the servo's droop, not the slope; their effort limits
are sim's. A mecanum robot's are SERVO_STIFFER_MECANUM times sim's: at SERVO_STIFFER
its four wheels, held at one speed, bounced on their gripping capsules once the lightly
loaded (uphill) pair neared its grip (loads of 0-34 N where the figures' 16 N and 26 N
rest) and a 10 kg X-pattern robot whose figure is 35.3° slid back at 31° and 33° but
climbed at 32°; at 5 times it climbed at 95% of r·ω up to 34.3° and slid back at 35°
and 36.3°, as its braked tilt proof holds it to 35.3°: the figure, every wheel at its
grip along its rollers, is right (tests/specs/test_mecanum_proofs.py).

MuJoCo's driven mecanum wheels push with a share of that grip: their contact is
Coulomb's (a block and a gripping capsule slide where the law says, to 0.005°), but a
lone driven wheel of the robot's climbs with 0.96-0.97 of its grip (tan θ)
(:mod:`.proof_grip`), and linorobot2, ROSbot XL and Ridgeback, whose figure is 35.3°,
slid back at 34.3°. A mecanum robot climbs 1° under the slope the statics give at that
share (the rig is run for the robot's own wheel, load and servo), and not 1° over its
figure: a figure of twice the grip (54.7°) is still refuted.

So does any robot whose climb its tyres' grip binds, not its motors (the figure "limited
by traction"): Leo Rover and Husarion Panther, 45° at μ 1, slid back at 44°. Their figure
is right (MuJoCo loads their wheels as the statics do, to 0.5 N, and the braked robot
slides at 45.03°), but at SERVO_STIFFER four wheels held at one speed bounce once the
uphill pair slips (Leo's rear loads swung 0-36 N where the statics' 17 N rest) and the
robot gives out at 40.8° (Panther 42°, a 20 kg skid-steer box 40.8°); at
SERVO_STIFFER_GRIP, as for mecanum wheels (3 to 10 times give the same within 0.7°), at
44.1°, 42.7° and 43.1°. A lone tyre, like a lone mecanum wheel, pushes with a share of its
grip that falls with its load (Panther's: 0.977 under its quarter of the weight, 0.943
under the 25 kg a rear wheel carries at 45°), so the proof runs the rig
(:func:`.proof_grip.tyre_share`) for the most loaded driven wheel at the figure's slope
and drives the robot 1° under the statics at that share. A robot its motors bind is
proven as before: its servos are SERVO_STIFFER times sim's, the share changes nothing,
no rig runs."""

from __future__ import annotations

import math

from .figures import Proof

MARGIN = 1.0        # deg
CRAWL = 0.05        # m/s
DRIVE = 2.5         # s after the settle
MEASURE = 0.5       # s: the speed is averaged over the run's last
PROGRESS = 0.8      # of r·ω·t
STEEPEST = 88.0     # deg: no slope over it is tried
SERVO_STIFFER = 20.0
SERVO_STIFFER_MECANUM = 5.0
SERVO_STIFFER_GRIP = 5.0  # a robot whose climb its grip binds: as a mecanum one's
GRAVITY = 9.81


def prove_climb(sim, found, section, statics) -> None:
    """Fill statics.climb's proof (nothing to prove without a figure; a robot that tips
    backward first cannot show it: a note says so, the tilt proved the tip). A mecanum
    robot, and a robot its grip binds, climbs under the slope its wheels reach at the
    share of their grip a lone one pushes with in MuJoCo (:mod:`.proof_grip`), the
    statics' own sum (``statics``, the figures' :class:`.statics.Statics`) at that
    share."""
    figure = section.figure("statics.climb")
    if figure is None or figure.value is None:
        return
    angle = figure.value
    back = section.figure("statics.tip.backward")
    if back is not None and back.value is not None and angle + MARGIN >= back.value:
        section.notes.append(f"statics.climb not proven: the robot tips over backward at "
                             f"{back.value:.1f}° (W502), before the {angle:.1f}° its motors "
                             "climb")
        return
    reach, under_what = angle, ""
    gripped = sim.drive.kind != "mecanum" and statics.grip_binds
    if sim.drive.kind == "mecanum" or gripped:
        share, whose = ((_mecanum_share(sim, found), "a lone one") if not gripped else
                        (_tyre_share(sim, found, statics, angle), "its most loaded one alone"))
        reach = round(math.degrees(statics.climb_angle(grip_share=share)), 4)
        under_what = (f" the {reach:.1f}° its wheels reach at the {share:.3f} of their grip"
                      f" {whose} pushes with in MuJoCo")
    lines, agrees = [], True
    under = reach - MARGIN
    if under > 0:
        ratio = climb(sim, found, under, gripped)
        agrees &= ratio >= PROGRESS
        lines.append(f"at {under:.1f}° it went up at {100 * ratio:.0f}% of r·ω")
    if angle + MARGIN < STEEPEST:
        ratio = climb(sim, found, angle + MARGIN, gripped)
        agrees &= ratio < PROGRESS
        lines.append(f"at {angle + MARGIN:.1f}° {100 * ratio:.0f}%")
    if not lines:
        return
    figure.proof = Proof(under if agrees and under > 0 else None, bool(agrees),
                         f"climbs {MARGIN:g}° under{under_what}, not {MARGIN:g}° over "
                         f"(≥ {100 * PROGRESS:.0f}% of r·ω up it after {DRIVE:g} s)",
                         "; ".join(lines))


def _mecanum_share(sim, found) -> float:
    """The least share of its grip a lone driven wheel of the robot pushes with, each
    carrying its part of the weight, driven as :func:`climb` drives them."""
    from .proof_grip import least_share
    from .proof_tilt import proof_model

    gripping = [w for w in sim.drive.driven if w.grip is not None]  # (their capsules)
    if not gripping:
        return 1.0
    model, _ = proof_model(sim, found, resting=False)
    omega = _crawl_speed(sim)
    return least_share(model, gripping, found.mass / len(sim.drive.driven), omega,
                       SERVO_STIFFER_MECANUM, (DRIVE, MEASURE, PROGRESS))


def _tyre_share(sim, found, statics, angle: float) -> float:
    """The share of its grip the most loaded driven wheel (at the figure's slope, as the
    statics load it) pushes with alone, carrying that load, driven as :func:`climb`
    drives it (:func:`.proof_grip.tyre_share`)."""
    from .proof_grip import tyre_share
    from .proof_tilt import proof_model

    loads: dict[int, float] = {}
    for contact, share in zip(found.contacts, statics.loads_at(math.radians(angle)),
                              strict=True):
        if contact.role == "driven":
            loads[contact.body] = loads.get(contact.body, 0.0) + share * found.mass
    loaded = [w for w in sim.drive.driven if loads.get(w.body_id, 0.0) > 0]
    if not loaded:
        return 1.0
    wheel = max(loaded, key=lambda w: loads[w.body_id])
    model, _ = proof_model(sim, found, resting=False)
    omega = _crawl_speed(sim)
    gain = float(model.actuator_gainprm[wheel.actuator_id][0]) * SERVO_STIFFER_GRIP
    return tyre_share(model, sim, wheel, loads[wheel.body_id], omega, gain,
                      (DRIVE, MEASURE, PROGRESS))


def _crawl_speed(sim) -> float:
    """The wheels' command up the slope (rad/s): sim's, at most CRAWL at the rim."""
    from ..sim.run import command_speed

    return min(command_speed(sim), CRAWL / sim.drive.radius)


def climb(sim, found, slope_deg: float, gripped: bool = False) -> float:
    """The robot's speed up a slope of ``slope_deg`` at the end of the drive, as a share
    of r·ω (negative: it went down); ``gripped``: a robot whose climb its grip binds,
    its servos SERVO_STIFFER_GRIP times sim's gain."""
    from ..sim.run import SETTLE_TIME, Run, forward_sign, ramped
    from .proof_tilt import proof_model

    model, copied = proof_model(sim, found, resting=False)
    theta = math.radians(slope_deg)
    model.opt.gravity[:] = [-GRAVITY * math.sin(theta), 0.0, -GRAVITY * math.cos(theta)]
    stiffer = SERVO_STIFFER_MECANUM if sim.drive.kind == "mecanum" else \
        SERVO_STIFFER_GRIP if gripped else SERVO_STIFFER
    for wheel in sim.drive.driven:
        model.actuator_gainprm[wheel.actuator_id][0] *= stiffer
        model.actuator_biasprm[wheel.actuator_id][2] *= stiffer
    run = Run(copied)
    omega = _crawl_speed(sim)
    commands = [(w.actuator_id, forward_sign(run, w) * omega) for w in sim.drive.driven]
    control = ramped(run, commands)
    run.step(SETTLE_TIME + DRIVE - MEASURE, control)
    start = float(run.position[0])
    run.step(MEASURE, control)
    expected = sim.drive.radius * omega * MEASURE
    gone = float(run.position[0]) - start
    return gone / expected if expected > 0 and math.isfinite(gone) else 0.0
