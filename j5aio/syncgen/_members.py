"""Telling the members of a core class apart: coroutines, getters and setters; docstrings."""

from __future__ import annotations

import inspect
from collections.abc import Callable
from typing import Any

__all__ = []


def _docstring(doc: str | None, indent: str, fallback: str) -> list[str]:
    text = (doc or fallback).strip()
    quote = '"""'
    prefix = "r" if "\\" in text else ""
    text = text.replace('"""', '\\"\\"\\"')
    lines = text.splitlines()
    if len(lines) == 1:
        return [f"{indent}{prefix}{quote}{lines[0]}{quote}"]
    body = [f"{indent}{prefix}{quote}{lines[0]}"]
    body += [f"{indent}{line}".rstrip() for line in lines[1:]]
    body.append(f"{indent}{quote}")
    return body


def _is_coroutine_function(obj: Any) -> bool:
    return inspect.iscoroutinefunction(obj) or inspect.iscoroutinefunction(
        getattr(obj, "__wrapped__", None),
    )


def _required_params(func: Callable[..., Any]) -> list[inspect.Parameter]:
    params = list(inspect.signature(func).parameters.values())[1:]
    return [
        p
        for p in params
        if p.default is p.empty and p.kind not in (p.VAR_POSITIONAL, p.VAR_KEYWORD)
    ]


def _getter_property_name(name: str, func: Any) -> str | None:
    if (
        inspect.isfunction(func)
        and name.startswith("get_")
        and name.isidentifier()
        and _is_coroutine_function(func)
        and not _required_params(func)
    ):
        return name[4:]
    return None


def _is_setter(func: Any) -> bool:
    if not (inspect.isfunction(func) and _is_coroutine_function(func)):
        return False
    params = list(inspect.signature(func).parameters.values())[1:]
    positional = [p for p in params if p.kind in (p.POSITIONAL_ONLY, p.POSITIONAL_OR_KEYWORD)]
    return len(_required_params(func)) == 1 and len(positional) >= 1
