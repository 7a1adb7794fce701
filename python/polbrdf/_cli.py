"""The ``polbrdf`` command installed with the Python package (``pip install ./python``).

It is the Rust command line itself (``polbrdf_cli::main_with_args``), compiled into the
extension module: the same commands, options, outputs and exit codes as the ``polbrdf`` binary.
"""

from __future__ import annotations

import sys

from polbrdf import _polbrdf


def main(argv: list[str] | None = None) -> int:
    """Run ``polbrdf`` with ``argv`` (default: this process's arguments); exit with its code."""
    args = sys.argv[1:] if argv is None else argv
    sys.stdout.flush()
    sys.stderr.flush()
    code = _polbrdf.cli_main(["polbrdf", *args])
    raise SystemExit(code)


if __name__ == "__main__":
    main()
