"""Writing a paper benchmark's tables: one place for the Markdown, CSV and JSON files."""

from __future__ import annotations

import csv
import json
from pathlib import Path
from typing import Any

__all__ = ["write_csv", "write_report"]


def write_csv(path: Path, rows: list[dict[str, Any]]) -> None:
    """``rows`` (dicts) as a CSV file with a header: every key of any row, in order of first
    appearance (a row without a key leaves its cell empty)."""
    fields = list(dict.fromkeys(k for row in rows for k in row))
    with path.open("w", newline="") as fh:
        writer = csv.DictWriter(fh, fieldnames=fields)
        writer.writeheader()
        writer.writerows(rows)


def write_report(out: Path, stem: str, text: str, rows: list[dict[str, Any]],
                 data: dict[str, Any]) -> list[str]:
    """``out/stem.md`` (``text``), ``.csv`` (``rows``) and ``.json`` (``data``); returns
    their paths."""
    paths = [out / f"{stem}.md", out / f"{stem}.csv", out / f"{stem}.json"]
    paths[0].write_text(text + "\n")
    write_csv(paths[1], rows)
    paths[2].write_text(json.dumps(data, indent=1, default=str))
    return [str(p) for p in paths]
