"""``erdesign app [--port N] [--headless] [-- STREAMLIT OPTIONS]``: run the Streamlit design app."""

from __future__ import annotations

import subprocess
import sys

import click

from ..app import APP_FILE
from .main import WholeNumber, cli

__all__ = ["app", "streamlit_command"]


def streamlit_command(port: int | None = None, headless: bool = False, extra: tuple[str, ...] = ()) -> list[str]:
    """The command line that runs the app: ``python -m streamlit run <erdesign/app/main.py> ...``.

    >>> cmd = streamlit_command(port=8502, headless=True)
    >>> cmd[3], cmd[4].endswith("main.py"), cmd[5:]
    ('run', True, ['--server.port', '8502', '--server.headless', 'true'])
    """
    cmd = [sys.executable, "-m", "streamlit", "run", str(APP_FILE)]
    if port is not None:
        cmd += ["--server.port", str(port)]
    if headless:
        cmd += ["--server.headless", "true"]
    return cmd + list(extra)


_EXAMPLES = """
\b
Examples:
  erdesign app
  erdesign app --port 8600 --headless
"""


@cli.command(context_settings={"ignore_unknown_options": True}, epilog=_EXAMPLES)
@click.option("--port", type=WholeNumber(1, 65535), default=None, help="Port to serve on (default: Streamlit's, 8501).")
@click.option("--headless", is_flag=True, help="Do not open a browser.")
@click.argument("streamlit_args", nargs=-1, type=click.UNPROCESSED)
def app(port: int | None, headless: bool, streamlit_args: tuple[str, ...]) -> None:
    """Open the design app (Size, Simulate, Compare and diagnose, Report) in the browser.

    Further arguments go to ``streamlit run`` (e.g. ``--server.address 0.0.0.0``).
    """
    code = subprocess.call(streamlit_command(port, headless, streamlit_args))
    if code:
        raise click.ClickException(f"streamlit exited with code {code}")
