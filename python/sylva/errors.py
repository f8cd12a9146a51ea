"""Sylva's exceptions. The C binding raises them with the library's diagnostics as text
(`file:line:col: error: message`, the source line and a caret) and the SYL_* status."""
from __future__ import annotations

import re

_WHERE = re.compile(r"^(?P<path>.*?):(?P<line>\d+):(?P<col>\d+): error: (?P<msg>.*)$", re.M)


class SylvaError(Exception):
    """Base of Sylva's own errors; .status is the exit code `sylva` would give."""

    def __init__(self, text: str = "", status: int = 1):
        super().__init__(text)
        self.text = text.rstrip("\n")
        self.status = status

    def __str__(self) -> str:
        return self.text


class CompileError(SylvaError):
    """A wrong model: .path, .line, .col and .message of the first error; str() shows every
    message with its source line and caret, as `sylva check` prints them."""

    def __init__(self, text: str = "", status: int = 1):
        super().__init__(text, status)
        m = _WHERE.search(self.text)
        self.path = m["path"] if m else None
        self.line = int(m["line"]) if m else None
        self.col = int(m["col"]) if m else None
        self.message = m["msg"] if m else self.text.splitlines()[0] if self.text else ""


class LimitError(SylvaError):
    """A resource limit was hit (max_modules, max_memory, ...): the message names it."""

    def __init__(self, text: str = "", status: int = 3):
        super().__init__(text, status)
        self.message = self.text
