"""``erdesign vehicle (--damper D.toml | --model NAME --params P) [--road ...] [--control ...] [--json] [--out H.csv]``.

The quarter vehicle of Butz and von Stryk (2002) section 4 with the damper of a damper file or a registered model,
passive or under semi-active control, and its ride figures (docs/vehicle.md; JSON keys in docs/cli.md).
"""

from __future__ import annotations

import click

from .main import SEED, as_flags, cli, emit_json, json_number

__all__ = ["vehicle"]

_EXAMPLES = """
\b
Examples:
  erdesign vehicle --model bouc_wen_modified --params butz_vonstryk2002 --road step
  erdesign vehicle --model bingham --params "c0=6000 N*s/m, f_c=0 N" --road bump   # their conventional damper
  erdesign vehicle --damper mr_valve --road random --road-class C --speed "72 km/h" --control skyhook
  erdesign vehicle --model bouc_wen_modified --params spencer1997 --max-field "2.25 V" \\
      --control clipped-optimal --road random --json --out history.csv
"""

_CONTROLS = ("passive", "skyhook", "groundhook", "clipped-optimal")


@cli.command(epilog=_EXAMPLES)
@click.option(
    "--damper",
    default=None,
    metavar="DAMPER.toml",
    help="Damper file or bundled example name: its physics damper is the vehicle's damper.",
)
@click.option("--effects", default="", help="Comma-separated effects of the physics damper (with --damper).")
@click.option("--model", "model_name", default=None, metavar="NAME", help="Registry model instead of a damper file.")
@click.option(
    "--params",
    default=None,
    metavar="P",
    help="The model's parameters: a published set (e.g. "
    'butz_vonstryk2002), "name=value unit, ..." or an identify --json file.',
)
@click.option(
    "--road",
    type=click.Choice(["step", "bump", "random"]),
    default="step",
    show_default=True,
    help="Road input: a step and a (1 - cos) bump as Butz and von Stryk, or an ISO 8608 random road.",
)
@click.option("--height", default="0.1 m", show_default=True, help="Height of the step or bump.")
@click.option("--bump-duration", default="0.5 s", show_default=True, help="Time the wheel takes over the bump.")
@click.option("--road-class", default="C", show_default=True, help="ISO 8608 class A-H of the random road.")
@click.option("--speed", default="20 m/s", show_default=True, help="Vehicle speed on the random road.")
@click.option("--seed", default=0, show_default=True, type=SEED, help="Seed of the random road's phases.")
@click.option(
    "--control",
    "control",
    type=click.Choice(_CONTROLS),
    default="passive",
    show_default=True,
    help="Control law (semi-active laws act through the damper's inverse model or switch it on/off).",
)
@click.option(
    "--gain",
    default=None,
    metavar="C",
    help='Skyhook / groundhook damping, e.g. "20 kN*s/m" '
    "(default 2 sqrt(k m2), the body's critical damping; clipped-optimal takes none).",
)
@click.option("--field", default=None, metavar="E", help="Control a passive damper holds (default 0).")
@click.option(
    "--max-field",
    default=None,
    metavar="E",
    help="Top of the semi-active control range [0, E] "
    '(default: the damper file\'s reference_field; with --model its unit gives the kind, e.g. "2.25 V").',
)
@click.option(
    "--vehicle",
    "vehicle_text",
    default=None,
    metavar='"m2=1300 kg, ..."',
    help="Vehicle values replacing Butz and von Stryk's: m1, m2 [kg], K, k [N/m], C [N s/m].",
)
@click.option("--duration", default=None, help="Simulated time (default 3 s; 5 s on a random road).")
@click.option("--dt", default=None, help="Time step (default 0.25 ms; 1 ms for a model with internal states).")
@click.option("--out", default=None, metavar="HISTORY.csv", help="Write the time history (CSV with units).")
@click.option("--force", "overwrite", is_flag=True, help="Let --out replace an existing file.")
@click.option("--json", "as_json", is_flag=True, help="Print one JSON object (SI units) instead of a table.")
def vehicle(
    damper,
    effects,
    model_name,
    params,
    road,
    height,
    bump_duration,
    road_class,
    speed,
    seed,
    control,
    gain,
    field,
    max_field,
    vehicle_text,
    duration,
    dt,
    out,
    overwrite,
    as_json,
) -> None:
    """Quarter vehicle with the damper, passive or semi-active: ride figures (Butz and von Stryk 2002)."""
    import warnings

    from .._util import check_output_path
    from ..errors import ErdesignError
    from ..simulation.roads import make_road
    from ..simulation.vehicle import simulate_vehicle, write_history
    from ..simulation.vehicle_setup import quarter_car, vehicle_damper
    from ..units import to_si
    from .size import quantity_option

    if (damper is None) == (model_name is None):
        raise click.UsageError("give --damper DAMPER.toml or --model NAME --params P (one of them)")
    if model_name is not None and params is None:
        raise click.UsageError(f"--model {model_name} needs --params P")
    if out is not None:
        out, _ = check_output_path(
            out,
            force=overwrite,
            formats={".csv": "csv"},
            inputs={"the damper file": damper, "the parameter file": params},
        )
    options = {"height": to_si(quantity_option(height, "m", "--height"), "m", "--height")}
    if road == "bump":
        options["duration"] = to_si(quantity_option(bump_duration, "s", "--bump-duration"), "s", "--bump-duration")
    elif road == "random":
        options = {
            "road_class": road_class,
            "seed": seed,
            "speed": to_si(quantity_option(speed, "m/s", "--speed"), "m/s", "--speed"),
        }
    track = make_road(road, **options)
    d = vehicle_damper(
        damper=damper,
        effects=tuple(e for e in effects.split(",") if e),
        model=model_name,
        params=params,
        field=field,
        max_field=max_field,
    )
    car = quarter_car(vehicle_text)
    seconds = (
        (5.0 if road == "random" else 3.0)
        if duration is None
        else to_si(quantity_option(duration, "s", "--duration"), "s", "--duration")
    )
    step = None if dt is None else to_si(quantity_option(dt, "s", "--dt"), "s", "--dt")
    c = None if gain is None else to_si(quantity_option(gain, "N*s/m", "--gain"), "N*s/m", "--gain")
    try:
        r = simulate_vehicle(d, track, control, gain=c, car=car, duration=seconds, dt=step)
    except ErdesignError as exc:  # the library names its arguments; the message names the options
        raise type(exc)(as_flags(str(exc))) from None
    if out is not None:
        write_history(out, r, overwrite=overwrite, option="--out")
    figures = r.ride()
    notes = [*r.notes]
    if figures["unreachable_fraction"] > 0.5:
        notes.append(
            f"the damper could not give the {control} force at {100 * figures['unreachable_fraction']:.0f} % "
            "of the samples (a semi-active damper only dissipates, and within its control range)"
        )
    for w in notes if not as_json else ():
        warnings.warn(w)
    if as_json:
        emit_json(
            {
                "damper": r.damper,
                "model": d.model.name,
                "control": r.controller,
                "road": track.description,
                "gain_N_s_per_m": r.gain,
                "control_kind": r.control_kind,
                "control_range": list(d.control_range),
                "duration_s": float(r.time[-1]),
                "dt_s": float(r.time[1] - r.time[0]),
                "samples": int(r.time.size),
                "vehicle": {
                    "m1_kg": car.m1,
                    "m2_kg": car.m2,
                    "K_N_per_m": car.K,
                    "C_N_s_per_m": car.C,
                    "k_N_per_m": car.k,
                },
                **{key: json_number(v) for key, v in figures.items()},
                "warnings": notes,
            }
        )
        return
    click.echo(_table(r, figures, track, out))


def _table(r, figures, track, out) -> str:
    rows = [
        ("body acceleration, RMS", figures["body_acceleration_rms_m_per_s2"], "m/s^2"),
        ("body acceleration, ISO 2631 Wk-weighted RMS", figures["body_acceleration_weighted_rms_m_per_s2"], "m/s^2"),
        ("suspension travel, RMS", 1e3 * figures["suspension_travel_rms_m"], "mm"),
        ("suspension travel, peak", 1e3 * figures["suspension_travel_peak_m"], "mm"),
        ("dynamic tyre load, RMS", figures["tyre_load_rms_N"], "N"),
        ("dynamic tyre load, RMS / static load", 100 * figures["tyre_load_rms_relative"], "%"),
        ("dynamic tyre load, peak", figures["tyre_load_peak_N"], "N"),
        ("damper force, peak", figures["damper_force_peak_N"], "N"),
    ]
    if figures["settling_time_s"] is not None:
        rows.append(("body settling time (10 % band)", figures["settling_time_s"], "s"))
    width = max(len(name) for name, _, _ in rows)
    head = [
        f"quarter vehicle (Butz and von Stryk 2002), {r.damper}, {r.controller}"
        + (f" (gain {r.gain:.4g} N s/m)" if r.gain else ""),
        f"  road: {track.description}, {r.time[-1]:.4g} s in steps of {1e3 * (r.time[1] - r.time[0]):.4g} ms",
    ]
    lines = head + [f"  {name:<{width}}  {value:10.4g} {unit}" for name, value, unit in rows]
    if out is not None:
        lines.append(f"  history written to {out}")
    return "\n".join(lines)
