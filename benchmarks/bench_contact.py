"""Contact solver speed: a sphere on a 128 x 128 grid, cold and warm-started (issue 2)."""

from __future__ import annotations

import time

import numpy as np

from taxel.mechanics import ElasticMaterial, Sphere, hertz_sphere, solve_contact

SHAPE, SPACING, RADIUS, FORCE = (128, 128), 0.1e-3, 10e-3, 1.0
COVER = ElasticMaterial(1e6, 0.5)


def _median_time(call, repeats: int) -> tuple[float, object]:
    times, result = [], None
    for _ in range(repeats):
        started = time.perf_counter()
        result = call()
        times.append(time.perf_counter() - started)
    return float(np.median(times)), result


def run(quick: bool = False) -> str:
    repeats = 5 if quick else 40
    heights = Sphere(RADIUS).on_grid(SHAPE, SPACING)
    first = solve_contact(heights, SPACING, COVER, normal_force=FORCE)  # builds the kernels
    cold_time, cold = _median_time(
        lambda: solve_contact(heights, SPACING, COVER, normal_force=FORCE), repeats
    )
    warm_time, warm = _median_time(
        lambda: solve_contact(heights, SPACING, COVER, normal_force=1.05 * FORCE, initial=first),
        repeats,
    )
    # a whole press: 20 frames, force rising by 5 % per frame, each warm-started from the last
    frame_times, previous = [], first
    for step in range(1, 21):
        started = time.perf_counter()
        previous = solve_contact(
            heights, SPACING, COVER, normal_force=FORCE * 1.05**step, initial=previous
        )
        frame_times.append(time.perf_counter() - started)
    hertz = hertz_sphere(FORCE, RADIUS, COVER.plane_strain_modulus)
    cells = hertz.contact_radius / SPACING
    rows = [
        ("cold start", cold_time, cold, 40.0),
        ("warm start, next frame (force +5 %)", warm_time, warm, 8.0),
        ("press sequence, median of 20 frames", float(np.median(frame_times)), previous, 8.0),
    ]
    lines = [
        "## Contact solver (`solve_contact`)",
        "",
        f"Rigid sphere R = {RADIUS * 1e3:g} mm on a half-space (E = 1 MPa, nu = 0.5), "
        f"{SHAPE[0]} x {SHAPE[1]} grid of {SPACING * 1e3:g} mm cells, F = {FORCE:g} N "
        f"(contact radius {cells:.1f} cells), relative tolerance 1e-8, one core.",
        "",
        "| case | median time [ms] | iterations | target [ms] | meets target |",
        "|---|---|---|---|---|",
    ]
    for name, seconds, result, target in rows:
        verdict = "yes" if seconds * 1e3 <= target else "no"
        lines.append(
            f"| {name} | {seconds * 1e3:.1f} | {result.n_iterations} | {target:g} | {verdict} |"
        )
    error = abs(cold.indentation / hertz.indentation - 1)
    lines += [
        "",
        f"Accuracy of the cold solve: indentation {error:.2e} from Hertz (exact spherical cap, "
        "so a small part of this is the sphere/paraboloid difference), force balance "
        f"{abs(cold.normal_force / FORCE - 1):.1e}.",
    ]
    return "\n".join(lines)


if __name__ == "__main__":
    print(run())
