"""Reading the named ``list-table`` directives of a reStructuredText page, as rows of text."""

from __future__ import annotations

import re
from pathlib import Path

_DIRECTIVE = re.compile(r"^(\s*)\.\. list-table::")
_NAME = re.compile(r"^\s*:name:\s*(\S+)\s*$")
_OPTION = re.compile(r"^\s*:[\w-]+:")
_ROW = re.compile(r"^(\s*)\* - ?(.*)$")
_CELL = re.compile(r"^(\s*)- ?(.*)$")


def _clean(cell: list[str]) -> str:
    """One cell's text on one line, without the inline-literal marks."""
    return " ".join(part.strip() for part in cell if part.strip()).replace("``", "")


def _rows(body: list[str]) -> list[list[str]]:
    rows: list[list[list[str]]] = []
    for line in body:
        row = _ROW.match(line)
        cell = _CELL.match(line)
        if row is not None:
            rows.append([[row.group(2)]])
        elif cell is not None and rows:
            rows[-1].append([cell.group(2)])
        elif rows and line.strip():
            rows[-1][-1].append(line)  # a cell's text going on
    return [[_clean(cell) for cell in row] for row in rows]


def list_tables(page: Path) -> dict[str, list[dict[str, str]]]:
    """The list tables of ``page`` that have a ``:name:``, each as rows keyed by the header.

    :raises ValueError: a named table without a header row, or with a row of another width.
    """
    lines = page.read_text(encoding="utf-8").splitlines()
    tables: dict[str, list[dict[str, str]]] = {}
    index = 0
    while index < len(lines):
        directive = _DIRECTIVE.match(lines[index])
        index += 1
        if directive is None:
            continue
        indent = len(directive.group(1))
        name = None
        while index < len(lines) and _OPTION.match(lines[index]):
            found = _NAME.match(lines[index])
            if found is not None:
                name = found.group(1)
            index += 1
        body = []
        while index < len(lines) and (
            not lines[index].strip() or len(lines[index]) - len(lines[index].lstrip()) > indent
        ):
            body.append(lines[index])
            index += 1
        if name is None:
            continue
        header, *rows = _rows(body)
        if not rows or any(len(row) != len(header) for row in rows):
            raise ValueError(f"{page.name}: table {name} has rows that do not fit its header")
        tables[name] = [dict(zip(header, row, strict=True)) for row in rows]
    return tables
