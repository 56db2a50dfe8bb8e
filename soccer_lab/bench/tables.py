"""The plain-text tables of ``soccer-env bench``: the step rates of :func:`run_benchmarks
<soccer_lab.bench.steps.run_benchmarks>` (:func:`format_table`) and the table layout they and
the profiles share (:func:`table`, :func:`table_rows`)."""

from __future__ import annotations

from typing import Any

__all__ = ["format_table", "table_rows", "table"]


def format_table(res: dict[str, Any]) -> str:
    """A plain-text table of :func:`~soccer_lab.bench.steps.run_benchmarks` results."""
    rows = [("task", "steps/s", "bare pymunk", "env/bare", "rSoccer ref", "x rSoccer",
             "target")]
    for key, label in (("goalkeeper", "Goalkeeper-v0 (1 robot)"),
                       ("match_6v6_div_b", "match 6 vs 6, Div B")):
        r = res[key]
        rows.append((label, f"{r['steps_per_s']:,.0f}", f"{r['bare_pymunk_steps_per_s']:,.0f}",
                     f"{r['ratio_to_bare_pymunk']:.2f}", f"{r['rsoccer_steps_per_s']:,}",
                     f"{r['ratio_to_rsoccer']:.1f}", f"{r['target_steps_per_s']:,}"))
    text = table(rows)
    if res.get("perceived"):
        rows = [("obs_mode='perceived'", "Goalkeeper steps/s", "cost vs truth",
                 "6v6 steps/s", "cost vs truth")]
        for preset, r in res["perceived"].items():
            rows.append((f"perception={preset!r}", f"{r['goalkeeper_steps_per_s']:,.0f}",
                         f"{r['goalkeeper_cost_vs_truth']:.2f}", f"{r['match_steps_per_s']:,.0f}",
                         f"{r['match_cost_vs_truth']:.2f}"))
        text += "\n\n" + table(rows)
    if res.get("humanoid"):
        h = res["humanoid"]
        text += "\n\n" + table(table_rows(
            h, (f"humanoids ({h['robot']}, camera {h['camera']})", "truth steps/s",
                "perceived steps/s", "cost vs truth"),
            (("goalkeeper", "Goalkeeper-v0 + 3 team-mates (4 robots)"),
             ("match", "match 3 vs 3")),
            (("truth_steps_per_s", ",.0f"), ("perceived_steps_per_s", ",.0f"),
             ("cost_vs_truth", ".2f"))))
    if res.get("batched"):
        b = res["batched"]
        text += "\n\n" + table(table_rows(
            b, (f"batched ({b['batch']} environments, one process)", "single env-steps/s",
                "batched env-steps/s", "ratio"),
            (("goalkeeper", "Goalkeeper-v0, truth"),
             ("match_2v2_scripted", "match 2 vs 2 VecEnv, scripted yellow")),
            (("single_env_steps_per_s", ",.0f"), ("batched_env_steps_per_s", ",.0f"),
             ("ratio", ".2f"))))
    return text


def table_rows(block: dict[str, Any], head: tuple[str, ...],
               cases: tuple[tuple[str, str], ...], fields: tuple[tuple[str, str], ...]
               ) -> list[tuple[str, ...]]:
    """A table's rows: ``head``, then per ``(key, label)`` of ``cases`` the label and
    ``block[key]``'s ``fields`` (``(name, format spec)``)."""
    return [head] + [(label, *(format(block[key][name], spec) for name, spec in fields))
                     for key, label in cases]


def table(rows: list[tuple[str, ...]]) -> str:
    """``rows`` of cells as aligned columns (the first left-aligned, the others
    right-aligned, two spaces apart) with a rule of dashes under the first row."""
    widths = [max(len(row[i]) for row in rows) for i in range(len(rows[0]))]
    lines = ["  ".join(c.ljust(w) if i == 0 else c.rjust(w) for i, (c, w) in
                       enumerate(zip(row, widths))) for row in rows]
    lines.insert(1, "  ".join("-" * w for w in widths))
    return "\n".join(lines)
