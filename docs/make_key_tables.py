"""Write the key tables of docs/file_formats.md from the files' schemas, so that the docs cannot drift from the code.

Each table sits between two marker lines naming the schema (a :class:`erdesign.schema.Table` by its dotted path)::

    <!-- keys: erdesign.damper.files.GeometryTable -->
    | key | value | required / default | meaning |
    ...
    <!-- end keys -->

and is made by :func:`erdesign.schema.key_table`.  Run from the repository root:  python docs/make_key_tables.py.
tests/badinput/test_files_schema.py checks that the file is current.
"""

from __future__ import annotations

import importlib
import re
import sys
from pathlib import Path

from erdesign.schema import key_table

DOCS = [Path(__file__).resolve().parent / "file_formats.md"]
_BLOCK = re.compile(r"(<!-- keys: ([\w.]+) -->\n)(.*?)(<!-- end keys -->)", re.S)


def _model(path: str):
    module, name = path.rsplit(".", 1)
    return getattr(importlib.import_module(module), name)


def render(text: str) -> str:
    """``text`` with every key table block made again from its schema."""
    return _BLOCK.sub(lambda m: m.group(1) + key_table(_model(m.group(2))) + m.group(4), text)


def main(check: bool = False) -> int:
    stale = []
    for doc in DOCS:
        text = doc.read_text(encoding="utf-8")
        new = render(text)
        if new != text:
            stale.append(doc)
            if not check:
                doc.write_text(new, encoding="utf-8")
    if check and stale:
        print(f"out of date: {', '.join(map(str, stale))}; run python docs/make_key_tables.py", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main(check="--check" in sys.argv[1:]))
