"""Example damper files (TOML), installed with the package as ``erdesign.examples``.

Load one with :func:`erdesign.load_example` (``load_example("makris")``) or give its path to the command line.
"""
