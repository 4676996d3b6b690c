"""Progress of a sweep, in a terminal (one line on stderr, redrawn) or in Jupyter (an updated
output cell; no widget library needed), or as occasional lines when stderr is a log file."""

from __future__ import annotations

import sys
import time
from typing import Optional

__all__ = ["Progress"]


def _in_notebook() -> bool:
    try:
        from IPython import get_ipython  # noqa: WPS433
    except ImportError:
        return False
    shell = get_ipython()
    return shell is not None and type(shell).__name__ == "ZMQInteractiveShell"


class Progress:
    """``done`` of ``total`` points, elapsed time and an estimate of the time left."""

    def __init__(self, total: int, label: str = "sweep", enabled: bool = True):
        self.total = max(int(total), 0)
        self.label = label
        self.enabled = enabled
        self.start = time.monotonic()
        self.shown = -1
        self._handle = None
        self._notebook = enabled and _in_notebook()
        self._tty = enabled and not self._notebook and sys.stderr.isatty()
        self._last_line = 0.0

    def _text(self, done: int) -> str:
        elapsed = time.monotonic() - self.start
        left = ""
        if 0 < done < self.total:
            left = f", about {elapsed / done * (self.total - done):.0f} s left"
        width = 30
        filled = int(width * done / self.total) if self.total else width
        bar = "#" * filled + "-" * (width - filled)
        return f"clr {self.label} [{bar}] {done}/{self.total} points, {elapsed:.0f} s{left}"

    def update(self, done: int) -> None:
        """Show ``done`` finished points (redrawn only when it changed)."""
        if not self.enabled or done == self.shown:
            return
        self.shown = done
        text = self._text(done)
        if self._notebook:
            from IPython.display import display  # noqa: WPS433

            if self._handle is None:
                self._handle = display({"text/plain": text}, raw=True, display_id=True)
            else:
                self._handle.update({"text/plain": text}, raw=True)
        elif self._tty:
            sys.stderr.write("\r" + text)
            sys.stderr.flush()
        else:
            now = time.monotonic()
            # a log file gets a line every 10 s at most, and the last one
            if done == self.total or now - self._last_line >= 10.0:
                self._last_line = now
                sys.stderr.write(text + "\n")
                sys.stderr.flush()

    def close(self, done: Optional[int] = None) -> None:
        """Draw the final state and end the line."""
        if done is not None:
            self.update(done)
        if self._tty and self.enabled:
            sys.stderr.write("\n")
            sys.stderr.flush()
